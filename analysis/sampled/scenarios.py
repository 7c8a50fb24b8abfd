"""Simulation options and scenarios (frozen, validated, with ``to_dict``/``from_dict`` for profiles).

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
from dataclasses import dataclass, field, fields

import numpy as np

from analysis.errors import ValidationError
from analysis.sampled.terminations import FIRM_GRASP, PAPER_OBJECT_MASS, PAPER_WALL_STIFFNESS, RIGID_GRASP, Grasp

__all__ = ["SimulationOptions", "Scenario", "SCENARIOS", "hbfd_options", "scenario"]


def _num(name: str, value: object, *, positive: bool = False, allow_inf: bool = False,
         allow_negative: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValidationError(name, "a real number", value)
    x = float(value)
    if math.isnan(x) or (math.isinf(x) and not allow_inf):
        raise ValidationError(name, "a finite number" if not allow_inf else "a number", value)
    if not allow_negative and (x < 0 or (positive and x == 0)):
        raise ValidationError(name, "> 0" if positive else ">= 0", value)
    return x


def _int(name: str, value: object, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not (lo <= value <= hi):
        raise ValidationError(name, f"an integer in [{lo}, {hi}]", value)
    return int(value)


def _bool(name: str, value: object) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise ValidationError(name, "true or false", value)
    return bool(value)


def _json_float(x: float) -> float | str:
    return x if math.isfinite(x) else ("inf" if x > 0 else "-inf")


def _from_json_float(x: object) -> object:
    return {"inf": math.inf, "-inf": -math.inf}.get(x, x) if isinstance(x, str) else x


def _check_keys(cls_name: str, data: object, allowed: set[str]) -> dict:
    if not isinstance(data, dict):
        raise ValidationError(cls_name, "an object (JSON dictionary)", data)
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise ValidationError(unknown[0], f"one of the {cls_name} keys {sorted(allowed)}", data[unknown[0]])
    return data


@dataclass(frozen=True)
class SimulationOptions:
    """Nonlinear effects and numerics of the simulator (all off by default).

    ``encoder_resolution`` (m; the HBFD 0.015 mm) and ``force_resolution`` (N; 0.05 N) quantize
    the sensors (encoder truncation toward minus infinity, gauge rounding), 0 = off.
    ``friction`` is the Coulomb force (N) on each mass (empty = none), regularized as saturated
    viscous friction ``-sat(v F_c / stick_velocity, F_c)`` (Karnopp-style stick band) and
    integrated exactly between events (see :mod:`analysis.simulator`).
    Actuator saturation: ``force_peak`` (N) is an instantaneous clip; ``force_continuous`` (N)
    is enforced by an I^2 t (thermal) model -- the RMS of the applied force over the
    ``thermal_time_constant`` (first-order average of F^2) may not exceed it; while it does, the
    clip folds back to ``force_continuous`` (how servo drives protect their motors).  ``inf`` =
    off.  ``delay_samples`` is a computation delay; ``implementation_delay`` the one-sample
    delay between coupling and environment (explicit integration).  ``substeps`` sub-divide the
    sample for the friction forces (unused without friction: the step is then exact).
    """

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

    def __post_init__(self) -> None:
        object.__setattr__(self, "substeps", _int("substeps", self.substeps, 1, 4096))
        object.__setattr__(self, "encoder_resolution", _num("encoder_resolution", self.encoder_resolution))
        object.__setattr__(self, "force_resolution", _num("force_resolution", self.force_resolution))
        try:
            fr = tuple(self.friction)
        except TypeError as exc:
            raise ValidationError("friction", "a list of Coulomb forces (N), one per mass", self.friction) from exc
        for i, x in enumerate(fr):
            try:
                _num("friction", x)
            except ValidationError as exc:
                raise ValidationError("friction", ">= 0 and finite (N)", x, i) from exc
        object.__setattr__(self, "friction", tuple(float(x) for x in fr))
        object.__setattr__(self, "stick_velocity", _num("stick_velocity", self.stick_velocity, positive=True))
        fc = _num("force_continuous", self.force_continuous, positive=True, allow_inf=True)
        fp = _num("force_peak", self.force_peak, positive=True, allow_inf=True)
        if fp < fc:
            raise ValidationError("force_peak", f">= force_continuous = {fc}", fp)
        object.__setattr__(self, "force_continuous", fc)
        object.__setattr__(self, "force_peak", fp)
        object.__setattr__(self, "thermal_time_constant",
                           _num("thermal_time_constant", self.thermal_time_constant, positive=True))
        object.__setattr__(self, "delay_samples", _int("delay_samples", self.delay_samples, 0, 1000))
        object.__setattr__(self, "implementation_delay", _bool("implementation_delay", self.implementation_delay))

    def to_dict(self) -> dict:
        out: dict = {}
        for f in fields(self):
            v = getattr(self, f.name)
            out[f.name] = list(v) if isinstance(v, tuple) else (_json_float(v) if isinstance(v, float) else v)
        return out

    @classmethod
    def from_dict(cls, data: object) -> SimulationOptions:
        d = _check_keys("simulation options", data, {f.name for f in fields(cls)})
        return cls(**{k: _from_json_float(v) for k, v in d.items()})


def hbfd_options(**changes) -> SimulationOptions:
    """The HBFD's nonlinear effects (section V): 0.015 mm encoder, 0.05 N gauge, 100 N / 400 N.

    The friction values (1 N on the stage, 0.5 N on the motor) are illustrative: the paper
    notes Coulomb friction but gives no value.
    """
    base = dict(encoder_resolution=15e-6, force_resolution=0.05, friction=(0.0, 1.0, 0.0, 0.5),
                force_continuous=100.0, force_peak=400.0)
    base.update(changes)
    return SimulationOptions(**base)


_CAUS = ("impedance", "admittance")


@dataclass(frozen=True)
class Scenario:
    """What the human and the virtual world do in a simulation.

    Environment: ``causality`` (``"impedance"`` penalty or ``"admittance"`` god-object); when
    ``wall`` is true a unilateral wall occupies ``x > wall_position`` with stiffness
    ``wall_stiffness`` and damping ``wall_damping`` (penalty) or as a constraint
    (god-object); ``object_mass`` is the god-object/object mass m_e.
    Human: ``grasp`` on the handle until ``release_time`` (then hands-off), and a push force
    ``push_force`` on the handle from ``push_start`` to ``min(push_end, release_time)``.
    Initial state: every mass at ``initial_position`` with ``initial_velocity``, at rest
    otherwise.  ``duration`` in s.
    """

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
        if not isinstance(self.name, str):
            raise ValidationError("name", "a string", self.name)
        if self.causality not in _CAUS:
            raise ValidationError("causality", "impedance or admittance", self.causality)
        object.__setattr__(self, "wall", _bool("wall", self.wall))
        object.__setattr__(self, "wall_position", _num("wall_position", self.wall_position, allow_negative=True))
        object.__setattr__(self, "wall_stiffness", _num("wall_stiffness", self.wall_stiffness))
        object.__setattr__(self, "wall_damping", _num("wall_damping", self.wall_damping))
        object.__setattr__(self, "object_mass", _num("object_mass", self.object_mass, positive=True))
        if isinstance(self.grasp, dict):
            object.__setattr__(self, "grasp", Grasp.from_dict(self.grasp))
        if not isinstance(self.grasp, Grasp):
            raise ValidationError("grasp", "a Grasp (mass, damping, stiffness)", self.grasp)
        object.__setattr__(self, "release_time", _num("release_time", self.release_time, allow_inf=True))
        object.__setattr__(self, "push_force", _num("push_force", self.push_force, allow_negative=True))
        object.__setattr__(self, "push_start", _num("push_start", self.push_start))
        object.__setattr__(self, "push_end", _num("push_end", self.push_end, allow_inf=True))
        if self.push_end < self.push_start:
            raise ValidationError("push_end", f">= push_start = {self.push_start}", self.push_end)
        object.__setattr__(self, "initial_position",
                           _num("initial_position", self.initial_position, allow_negative=True))
        object.__setattr__(self, "initial_velocity",
                           _num("initial_velocity", self.initial_velocity, allow_negative=True))
        d = _num("duration", self.duration, positive=True)
        if d > 3600:
            raise ValidationError("duration", "(0, 3600] s", d)
        object.__setattr__(self, "duration", d)

    def replace(self, **changes) -> Scenario:
        data = {f.name: getattr(self, f.name) for f in fields(self)}
        data.update(changes)
        return Scenario(**data)

    def to_dict(self) -> dict:
        out: dict = {}
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, Grasp):
                v = v.to_dict()
            elif isinstance(v, float):
                v = _json_float(v)
            out[f.name] = v
        return out

    @classmethod
    def from_dict(cls, data: object) -> Scenario:
        d = _check_keys("scenario", data, {f.name for f in fields(cls)})
        d = {k: _from_json_float(v) for k, v in d.items()}
        if "grasp" in d:
            d["grasp"] = Grasp.from_dict(d["grasp"])
        return cls(**d)


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
    """A preset from :data:`SCENARIOS`, optionally modified (e.g. ``causality="admittance"``)."""
    if name not in SCENARIOS:
        raise ValidationError("scenario", ", ".join(SCENARIOS), name)
    return SCENARIOS[name].replace(**changes) if changes else SCENARIOS[name]
