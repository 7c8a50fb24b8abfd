"""Simulation options and scenarios (frozen, validated, with ``to_dict``/``from_dict`` for profiles).

Both are settings records of :mod:`analysis.checks` (validators, ``record_to_dict`` and
``record_from_dict``); this module is light (no loop or simulator code).

Scenario presets (:data:`SCENARIOS`) follow Adams et al., section VI:

* ``impedance_worst_case``: the human pushes the handle into a rigid wall with a firm grasp,
  then lets go (grasp and force removed at ``release_time``) -- the worst case the paper used to
  tune the impedance display (rigid constraint, the operator releases the handle).


* ``admittance_worst_case``: free motion with a rigid grasp and a short push -- the paper's worst
  case for the admittance display.


* ``wall_push``: a force step pushing the handle into a wall and holding it there.
* ``free_sliding``: a push along free space, then coasting.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from analysis.chain.limits import DAMPING, GAIN_STIFFNESS, MASS
from analysis.checks import Real, SettingsRecord, boolean, check_elements, choice, integer, string
from analysis.errors import ValidationError
from analysis.sampled.terminations import (
    CAUSALITIES,
    FIRM_GRASP,
    PAPER_OBJECT_MASS,
    PAPER_WALL_STIFFNESS,
    RIGID_GRASP,
    Grasp,
)

__all__ = ["SimulationOptions", "Scenario", "SCENARIOS", "hbfd_options", "scenario"]

# The number rules of options and scenarios (their errors say "a real number", "a finite number",
# "> 0", ">= 0"; see analysis.checks.Real).
_ANY = Real(not_real="a real number", not_finite="a finite number")
_NONNEG = Real(lo=0.0, allowed=">= 0", not_real="a real number", not_finite="a finite number")
_POS = Real(lo=0.0, lo_open=True, allowed="> 0", not_real="a real number", not_finite="a finite number")
_NONNEG_OR_INF = Real(lo=0.0, allow_inf=True, allowed=">= 0", not_real="a real number", not_finite="a number")
_POS_OR_INF = Real(lo=0.0, lo_open=True, allow_inf=True, allowed="> 0", not_real="a real number",
                   not_finite="a number")


_FRICTION = Real(lo=0.0, unit="N")  # ">= 0 and finite (N)", per element


@dataclass(frozen=True)
class SimulationOptions(SettingsRecord):
    """Nonlinear effects and numerics of the simulator (all off by default).

    ``encoder_resolution`` (m; the HBFD 0.015 mm) and ``force_resolution`` (N; 0.05 N) quantize
    the sensors (encoder truncation toward minus infinity, gauge rounding), 0 = off.
    ``friction`` is the Coulomb force (N) on each mass (empty = none), regularized as saturated
    viscous friction ``-sat(v F_c / stick_velocity, F_c)`` (Karnopp-style stick band) and
    integrated exactly between events (see :mod:`analysis.sampled.simulator`).
    Actuator saturation: ``force_peak`` (N) is an instantaneous clip; ``force_continuous`` (N)
    is enforced by an I^2 t (thermal) model -- the RMS of the applied force over the
    ``thermal_time_constant`` (first-order average of F^2) may not exceed it; while it does, the
    clip folds back to ``force_continuous`` (how servo drives protect their motors).  ``inf`` =
    off.  ``delay_samples`` is a computation delay; ``implementation_delay`` the one-sample
    delay between coupling and environment (explicit integration).  ``substeps`` sub-divide the
    sample for the friction forces (unused without friction: the step is then exact).
    ``passivity_observer`` records the energy into the virtual environment port;
    ``passivity_control`` (implies the observer) adds Hannaford & Ryu's variable damping that
    removes an observed energy excess (conventions in :mod:`analysis.sampled.actuation`);
    ``passivity_max_damping`` (N s/m; 0 = off, Hannaford & Ryu's unbounded PC) caps that damping.

    Parameters
    ----------
    substeps : int, optional
        Sub-steps per sample for the friction forces, 1 to 4096.
    encoder_resolution : float, optional
        Encoder quantum [m], at least 0 (0 = off).
    force_resolution : float, optional
        Force-gauge quantum [N], at least 0 (0 = off).
    friction : tuple of float, optional
        Coulomb force [N] on each mass, each at least 0, shape (n,) or empty (none).
    stick_velocity : float, optional
        Width of the stick band [m/s], greater than 0.
    force_continuous : float, optional
        Continuous (RMS) force limit [N], greater than 0; ``inf`` = off.
    force_peak : float, optional
        Instantaneous force limit [N], at least ``force_continuous``; ``inf`` = off.
    thermal_time_constant : float, optional
        Time constant of the I^2 t model [s], greater than 0.
    delay_samples : int, optional
        Computation delay in samples, 0 to 1000.
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    passivity_observer : bool, optional
        Record the energy into the virtual environment port.
    passivity_control : bool, optional
        Hannaford & Ryu's passivity controller (implies the observer).
    passivity_max_damping : float, optional
        Cap of the controller's damping [N s/m], at least 0 (0 = unbounded).

    Raises
    ------
    ValidationError
        When a value is out of range, or ``force_peak < force_continuous``.
    """

    record_name = "simulation options"

    substeps: int = 2
    encoder_resolution: float = 0.0
    force_resolution: float = 0.0
    friction: tuple[float, ...] = ()
    stick_velocity: float = 1e-4
    force_continuous: float = math.inf
    force_peak: float = math.inf
    thermal_time_constant: float = 1.0
    delay_samples: int = 0
    implementation_delay: bool = False
    passivity_observer: bool = False
    passivity_control: bool = False
    passivity_max_damping: float = 0.0

    def __post_init__(self) -> None:
        s = object.__setattr__
        s(self, "passivity_observer", boolean("passivity_observer", self.passivity_observer))
        s(self, "passivity_control", boolean("passivity_control", self.passivity_control))
        s(self, "passivity_max_damping", _NONNEG("passivity_max_damping", self.passivity_max_damping))
        s(self, "substeps", integer("substeps", self.substeps, 1, 4096))
        s(self, "encoder_resolution", _NONNEG("encoder_resolution", self.encoder_resolution))
        s(self, "force_resolution", _NONNEG("force_resolution", self.force_resolution))
        try:
            fr = tuple(self.friction)
        except TypeError as exc:
            raise ValidationError("friction", "a list of Coulomb forces (N), one per mass", self.friction) from exc
        check_elements("friction", fr, _FRICTION)
        s(self, "friction", tuple(float(x) for x in fr))
        s(self, "stick_velocity", _POS("stick_velocity", self.stick_velocity))
        fc = _POS_OR_INF("force_continuous", self.force_continuous)
        fp = _POS_OR_INF("force_peak", self.force_peak)
        if fp < fc:
            raise ValidationError("force_peak", f">= force_continuous = {fc}", fp)
        s(self, "force_continuous", fc)
        s(self, "force_peak", fp)
        s(self, "thermal_time_constant", _POS("thermal_time_constant", self.thermal_time_constant))
        s(self, "delay_samples", integer("delay_samples", self.delay_samples, 0, 1000))
        s(self, "implementation_delay", boolean("implementation_delay", self.implementation_delay))

def hbfd_options(**changes) -> SimulationOptions:
    """The HBFD's nonlinear effects (section V): 0.015 mm encoder, 0.05 N gauge, 100 N / 400 N.

    The friction values (1 N on the stage, 0.5 N on the motor) are illustrative: the paper
    notes Coulomb friction but gives no value.

    Parameters
    ----------
    **changes
        Fields of :class:`SimulationOptions` that replace the HBFD's values.

    Returns
    -------
    SimulationOptions
        The HBFD's options with ``changes``.
    """
    base = dict(encoder_resolution=15e-6, force_resolution=0.05, friction=(0.0, 1.0, 0.0, 0.5),
                force_continuous=100.0, force_peak=400.0)
    base.update(changes)
    return SimulationOptions(**base)


@dataclass(frozen=True)
class Scenario(SettingsRecord):
    """What the human and the virtual world do in a simulation.

    Environment: ``causality`` (``"impedance"`` penalty or ``"admittance"`` god-object); when
    ``wall`` is true a unilateral wall occupies ``x > wall_position`` with stiffness
    ``wall_stiffness`` and damping ``wall_damping`` (penalty) or as a constraint
    (god-object); ``object_mass`` is the god-object/object mass m_e.
    Human: ``grasp`` on the handle until ``release_time`` (then hands-off), and a push force
    ``push_force`` on the handle from ``push_start`` to ``min(push_end, release_time)``.
    Initial state: every mass at ``initial_position`` with ``initial_velocity``, at rest
    otherwise.  ``duration`` in s.

    Parameters
    ----------
    name : str, optional
        Name of the scenario.
    causality : str, optional
        ``"impedance"`` (penalty) or ``"admittance"`` (god-object).
    wall : bool, optional
        Whether a unilateral wall occupies ``x > wall_position``.
    wall_position : float, optional
        Wall surface [m].
    wall_stiffness : float, optional
        Penalty wall stiffness ``k_obj`` [N/m], 0 to 1e9.
    wall_damping : float, optional
        Penalty wall damping ``b_obj`` [N s/m], 0 to 1e8.
    object_mass : float, optional
        God-object/object mass ``m_e`` [kg], 1e-6 to 1e3.
    grasp : Grasp or dict, optional
        The human grasp until ``release_time`` (a dict is read with ``Grasp.from_dict``).
    release_time : float, optional
        When grasp and push are removed [s], at least 0; ``inf`` = never.
    push_force : float, optional
        Push on the handle [N], positive toward the wall.
    push_start : float, optional
        Start of the push [s], at least 0.
    push_end : float, optional
        End of the push [s], at least ``push_start``; ``inf`` = never.
    initial_position : float, optional
        Initial position of every mass [m].
    initial_velocity : float, optional
        Initial velocity of every mass [m/s].
    duration : float, optional
        Simulated time [s], in (0, 3600].

    Raises
    ------
    ValidationError
        When a value is out of range or of the wrong type.
    """

    record_name = "scenario"

    name: str = "custom"
    causality: str = "impedance"
    wall: bool = True
    wall_position: float = 0.0
    wall_stiffness: float = PAPER_WALL_STIFFNESS
    wall_damping: float = 0.0
    object_mass: float = PAPER_OBJECT_MASS
    grasp: Grasp = field(default_factory=Grasp)
    release_time: float = math.inf
    push_force: float = 0.0
    push_start: float = 0.0
    push_end: float = math.inf
    initial_position: float = 0.0
    initial_velocity: float = 0.0
    duration: float = 2.0

    def __post_init__(self) -> None:
        s = object.__setattr__
        string("name", self.name)
        choice("causality", self.causality, CAUSALITIES, allowed="impedance or admittance")
        s(self, "wall", boolean("wall", self.wall))
        s(self, "wall_position", _ANY("wall_position", self.wall_position))
        s(self, "wall_stiffness", GAIN_STIFFNESS("wall_stiffness", self.wall_stiffness))
        s(self, "wall_damping", DAMPING("wall_damping", self.wall_damping))
        s(self, "object_mass", MASS("object_mass", self.object_mass))
        if isinstance(self.grasp, dict):
            s(self, "grasp", Grasp.from_dict(self.grasp))
        if not isinstance(self.grasp, Grasp):
            raise ValidationError("grasp", "a Grasp (mass, damping, stiffness)", self.grasp)
        s(self, "release_time", _NONNEG_OR_INF("release_time", self.release_time))
        s(self, "push_force", _ANY("push_force", self.push_force))
        s(self, "push_start", _NONNEG("push_start", self.push_start))
        s(self, "push_end", _NONNEG_OR_INF("push_end", self.push_end))
        if self.push_end < self.push_start:
            raise ValidationError("push_end", f">= push_start = {self.push_start}", self.push_end)
        s(self, "initial_position", _ANY("initial_position", self.initial_position))
        s(self, "initial_velocity", _ANY("initial_velocity", self.initial_velocity))
        d = _POS("duration", self.duration)
        if d > 3600:
            raise ValidationError("duration", "(0, 3600] s", d)
        s(self, "duration", d)

SCENARIOS: dict[str, Scenario] = {
    "impedance_worst_case": Scenario(
        name="impedance_worst_case", causality="impedance", wall=True, wall_position=0.0,
        grasp=FIRM_GRASP, push_force=20.0, push_start=0.0, release_time=0.5, initial_position=-1e-3,
        duration=2.0),
    "admittance_worst_case": Scenario(
        name="admittance_worst_case", causality="impedance", wall=False, grasp=RIGID_GRASP,
        push_force=5.0, push_start=0.05, push_end=0.2, duration=2.0),
    "wall_push": Scenario(
        name="wall_push", causality="impedance", wall=True, wall_position=2e-3, grasp=FIRM_GRASP,
        push_force=10.0, push_start=0.1, duration=2.0),
    "free_sliding": Scenario(
        name="free_sliding", causality="impedance", wall=False, grasp=Grasp(mass=1.0, damping=5.0),
        push_force=3.0, push_start=0.1, push_end=0.6, duration=2.0),
}


def scenario(name: str, **changes) -> Scenario:
    """A preset from :data:`SCENARIOS`, optionally modified (e.g. ``causality="admittance"``).

    Parameters
    ----------
    name : str
        A key of :data:`SCENARIOS`.
    **changes
        Fields of :class:`Scenario` to replace.

    Returns
    -------
    Scenario
        The preset, or a modified copy.
    """
    choice("scenario", name, SCENARIOS, allowed=", ".join(SCENARIOS))
    return SCENARIOS[name].replace(**changes) if changes else SCENARIOS[name]
