"""Settings and result objects of the wall-controller design (Eom, Suh & Yi); see
:mod:`analysis.transparency` for the analysis itself.  Frozen dataclasses, nothing here computes.

The settings records (:class:`WallSettings`, :class:`ObserverSettings`) are profile sections,
validated by :mod:`analysis.checks`; this module is light (no design or observer code) so that
the profile record can hold them without loading the wall-design stack."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.limits import DAMPING, GAIN_STIFFNESS, MASS, SAMPLE_TIME
from analysis.checks import Real, SettingsRecord, choice, integer, positive, real
from analysis.errors import ValidationError
from analysis.transparency.five_bar import FIVE_BAR_PRESETS
from analysis.transparency.holds import HOLDS

__all__ = [
    "PLANTS",
    "OBSERVER_PRESETS",
    "WallSettings",
    "ObserverSettings",
    "IndexResult",
    "RobustnessPeak",
    "OptimalDamping",
    "TradeoffCurves",
    "StepResponse",
]

PLANTS = ("rigid", "chain")
#: The two-axis devices of :class:`ObserverSettings` (:data:`~analysis.transparency.five_bar.FIVE_BAR_PRESETS`).
OBSERVER_PRESETS = tuple(FIVE_BAR_PRESETS)


# ----------------------------------------------------------------------------------------------
# settings (stored in the profile)
# ----------------------------------------------------------------------------------------------
_UNIT_INTERVAL_OPEN = Real(lo=0.0, hi=1.0, hi_open=True)  # "in [0, 1)"
_UNIT_INTERVAL = Real(lo=0.0, hi=1.0)  # "in [0, 1]"
_DURATION = Real(lo=0.0, lo_open=True, hi=100.0, allowed="in (0, 100] s")
_FORCE = Real(unit="N")  # "finite (N)"


@dataclass(frozen=True)
class WallSettings(SettingsRecord):
    """Every parameter of a wall-controller design (a profile section; ``to_dict``/``from_dict``).

    Units: kg, N s/m, N/m, s, rad/s, N.  ``controller_stiffness = None`` means ``K_c = K``.
    ``plant = "chain"`` uses the profile's device chain instead of ``mass``/``damping``.
    ``bc_min .. bc_max`` (``bc_count`` values, linear) is the range of the Fig. 8 curves and of
    the search for the optimum.

    Parameters
    ----------
    mass : float, optional
        Handle mass ``m`` of the rigid plant ``P(s) = 1/(m s + b)`` (eq. 7) [kg].
    damping : float, optional
        Device damping ``b`` of the rigid plant [N s/m].
    wall_stiffness : float, optional
        Virtual-wall stiffness ``K`` of ``V(s) = (K + B s)/s`` (eq. 8) [N/m], >= 0.
    wall_damping : float, optional
        Virtual-wall damping ``B`` [N s/m], >= 0; > 0 when ``wall_stiffness`` is 0.
    controller_stiffness : float or None, optional
        Controller stiffness ``K_c`` of eq. (12) [N/m], >= 0; ``None`` for ``K_c = K``.
    sample_time : float, optional
        Sample time ``T`` of the controller [s].
    hold : str, optional
        The hold model, one of :data:`~analysis.transparency.holds.HOLDS`.
    lowpass_damping : float, optional
        Damping ratio ``zeta`` of the ``lowpass2`` hold, > 0.
    weight_order : int, optional
        Order ``r`` of the weight ``w1 = (w_c/(s + w_c))^r`` of eq. (11), 0 .. 8.
    weight_cutoff : float, optional
        Cut-off ``w_c`` of the weight ``w1`` [rad/s], > 0.
    alpha : float, optional
        Mass uncertainty ``alpha`` of the weight ``W = alpha m s + beta b`` (eq. 15), in [0, 1).
    beta : float, optional
        Damping uncertainty ``beta`` of the weight ``W`` (eq. 15), in [0, 1].
    bc_min : float, optional
        Lower end of the ``B_c`` range [N s/m].
    bc_max : float, optional
        Upper end of the ``B_c`` range [N s/m], > ``bc_min``.
    bc_count : int, optional
        Number of ``B_c`` values of the range (linear spacing), 2 .. 10000.
    plant : str, optional
        ``"rigid"`` (``mass``/``damping``) or ``"chain"`` (the profile's device chain); see
        :data:`PLANTS`.
    step_force : float, optional
        Human-force step of the step response [N], finite.
    step_duration : float, optional
        Duration of the step response [s], in (0, 100].

    Raises
    ------
    ValidationError
        When a field is out of its range, ``wall_stiffness`` and ``wall_damping`` are both 0, or
        ``bc_max <= bc_min``.
    """

    record_name = "transparency"

    mass: float = 0.01
    damping: float = 0.022
    wall_stiffness: float = 1000.0
    wall_damping: float = 1.0
    controller_stiffness: float | None = None
    sample_time: float = 1e-3
    hold: str = "lowpass2"
    lowpass_damping: float = 0.7071
    weight_order: int = 1
    weight_cutoff: float = 100.0
    alpha: float = 0.5
    beta: float = 0.5
    bc_min: float = 0.5
    bc_max: float = 40.0
    bc_count: int = 100
    plant: str = "rigid"
    step_force: float = -5.0
    step_duration: float = 0.5

    def __post_init__(self) -> None:
        s = object.__setattr__
        s(self, "mass", MASS("mass", self.mass))
        s(self, "damping", DAMPING("damping", self.damping))
        s(self, "wall_stiffness", GAIN_STIFFNESS("wall_stiffness", self.wall_stiffness))
        s(self, "wall_damping", DAMPING("wall_damping", self.wall_damping))
        if self.wall_stiffness == 0.0 and self.wall_damping == 0.0:
            raise ValidationError("wall_damping", "> 0 when wall_stiffness = 0 (the wall needs K or B)", 0.0)
        if self.controller_stiffness is not None:
            s(self, "controller_stiffness", real("controller_stiffness", self.controller_stiffness, lo=0.0,
                                                 allowed=">= 0 and finite (N/m) or null for K_c = K"))
        s(self, "sample_time", SAMPLE_TIME("sample_time", self.sample_time))
        choice("hold", self.hold, HOLDS)
        s(self, "lowpass_damping", positive("lowpass_damping", self.lowpass_damping))
        s(self, "weight_order", integer("weight_order", self.weight_order, 0, 8))
        s(self, "weight_cutoff", positive("weight_cutoff", self.weight_cutoff, "rad/s"))
        s(self, "alpha", _UNIT_INTERVAL_OPEN("alpha", self.alpha))
        s(self, "beta", _UNIT_INTERVAL("beta", self.beta))
        s(self, "bc_min", real("bc_min", self.bc_min, unit="N s/m"))
        s(self, "bc_max", real("bc_max", self.bc_max, unit="N s/m"))
        if not self.bc_max > self.bc_min:
            raise ValidationError("bc_max", f"> bc_min = {self.bc_min}", self.bc_max)
        s(self, "bc_count", integer("bc_count", self.bc_count, 2, 10000))
        choice("plant", self.plant, PLANTS)
        s(self, "step_force", _FORCE("step_force", self.step_force))
        s(self, "step_duration", _DURATION("step_duration", self.step_duration))

    @property
    def kc(self) -> float:
        """``K_c`` (``K`` unless ``controller_stiffness`` is set)."""
        return self.wall_stiffness if self.controller_stiffness is None else self.controller_stiffness

@dataclass(frozen=True)
class ObserverSettings(SettingsRecord):
    """Disturbance-observer parameters (Eom, Suh & Yi, section 2; a profile section).

    ``nominal_mass``/``nominal_damping`` are the single-axis ``P_n`` of eq. (3); ``order``/``cutoff``
    the binomial ``Q``; ``alpha``, ``beta``, ``delta`` perturb the real single-axis plant (eq. 13);
    ``preset`` is the two-axis device (:data:`OBSERVER_PRESETS`); ``step_force`` (N, on x) and
    ``step_duration`` (s) the cross-coupling time response.  The observer itself is
    :mod:`analysis.transparency.observer`.

    Parameters
    ----------
    nominal_mass : float, optional
        Nominal mass ``M`` of ``P_n = 1/(M s + B)`` (eq. 3) [kg].
    nominal_damping : float, optional
        Nominal damping ``B`` of ``P_n`` [N s/m].
    order : int, optional
        Order ``r`` of the binomial low-pass ``Q = (w_Q/(s + w_Q))^r``, 1 .. 8.
    cutoff : float, optional
        Cut-off ``w_Q`` of ``Q`` [rad/s], > 0.
    alpha : float, optional
        Mass uncertainty of the real plant ``P~`` (eq. 13), in [0, 1).
    beta : float, optional
        Damping uncertainty of the real plant ``P~`` (eq. 13), in [0, 1].
    delta : float, optional
        The perturbation ``Delta`` of eq. (13), in [-1, 1].
    preset : str, optional
        The two-axis device, one of :data:`OBSERVER_PRESETS`.
    step_force : float, optional
        Commanded force step on x [N], finite.
    step_duration : float, optional
        Duration of the cross-coupling time response [s], in (0, 100].

    Raises
    ------
    ValidationError
        When a field is out of its range.
    """

    record_name = "observer"

    nominal_mass: float = 0.01
    nominal_damping: float = 0.022
    order: int = 2
    cutoff: float = 200.0
    alpha: float = 0.5
    beta: float = 0.5
    delta: float = 1.0
    preset: str = "five_bar_centre"
    step_force: float = 1.0
    step_duration: float = 0.2

    def __post_init__(self) -> None:
        s = object.__setattr__
        s(self, "nominal_mass", MASS("nominal_mass", self.nominal_mass))
        s(self, "nominal_damping", DAMPING("nominal_damping", self.nominal_damping))
        s(self, "order", integer("order", self.order, 1, 8))
        s(self, "cutoff", positive("cutoff", self.cutoff, "rad/s"))
        s(self, "alpha", _UNIT_INTERVAL_OPEN("alpha", self.alpha))
        s(self, "beta", _UNIT_INTERVAL("beta", self.beta))
        s(self, "delta", real("delta", self.delta, lo=-1.0, hi=1.0))
        choice("preset", self.preset, OBSERVER_PRESETS)
        s(self, "step_force", _FORCE("step_force", self.step_force))
        s(self, "step_duration", _DURATION("step_duration", self.step_duration))

# ----------------------------------------------------------------------------------------------
# results
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class IndexResult:
    """``J(B_c)`` of eq. (11) with how it was obtained.

    ``finite`` is False (and ``index = inf``) when the weighted error is not in H2; ``reason``
    says why.  ``method`` is ``"lyapunov"`` or ``"quadrature"``; ``nodes`` counts quadrature nodes.

    Parameters
    ----------
    bc : float
        The controller damping ``B_c`` [N s/m].
    index : float
        ``J(B_c)``, the squared H2 norm of eq. (11) [(m/s/N)^2 rad/s]; ``inf`` when not finite.
    finite : bool
        Whether ``J`` is finite.
    reason : str
        Why ``J`` is not finite; ``""`` when it is.
    method : str
        ``"lyapunov"`` or ``"quadrature"``.
    nodes : int, optional
        Number of quadrature nodes (0 for ``"lyapunov"``).
    """

    bc: float
    index: float
    finite: bool
    reason: str
    method: str
    nodes: int = 0


@dataclass(frozen=True)
class RobustnessPeak:
    """``||L||_inf`` of eq. (16-17): ``gain`` (absolute) at ``frequency`` (rad/s, ``inf`` when the
    supremum is the high-frequency limit ``limit``).  ``certified`` is False only if part of the
    frequency axis could not be bounded below the reported peak (``zoh`` ripple).

    Parameters
    ----------
    bc : float
        The controller damping ``B_c`` [N s/m].
    gain : float
        ``||L||_inf`` (absolute, dimensionless).
    frequency : float
        Frequency of the peak [rad/s]; ``inf`` when the supremum is ``limit``.
    alpha : float
        Mass uncertainty of the weight ``W`` (eq. 15).
    beta : float
        Damping uncertainty of the weight ``W`` (eq. 15).
    limit : float
        ``lim |L|`` as ``w -> inf`` (0 for the ``discrete`` hold).
    certified : bool, optional
        False if part of the frequency axis could not be bounded below ``gain``.
    """

    bc: float
    gain: float
    frequency: float
    alpha: float
    beta: float
    limit: float
    certified: bool = True

    @property
    def gain_db(self) -> float:
        return 20.0 * math.log10(self.gain) if self.gain > 0 else -math.inf

    @property
    def robust(self) -> bool:
        """Eq. (17): ``||L||_inf <= 1``."""
        return self.gain <= 1.0


@dataclass(frozen=True)
class OptimalDamping:
    """The ``B_c`` minimizing ``J`` subject to ``||L||_inf <= 1`` (section 3).

    ``constrained`` is True when the unconstrained minimizer (``unconstrained_bc``) violates
    eq. (17) and the optimum sits on the constraint.  ``feasible`` is False (``bc = nan``) when no
    ``B_c`` in the searched range satisfies it.

    Parameters
    ----------
    bc : float
        The optimal controller damping ``B_c`` [N s/m]; ``nan`` when not feasible.
    index : float
        ``J`` at ``bc`` (eq. 11); ``inf`` when not feasible.
    peak : float
        ``||L||_inf`` at ``bc`` (eq. 16-17); ``nan`` when not feasible.
    peak_frequency : float
        Frequency of that peak [rad/s] (``inf`` at the high-frequency limit).
    feasible : bool
        Whether some ``B_c`` of the range satisfies ``||L||_inf <= 1``.
    constrained : bool
        Whether the optimum sits on the constraint ``||L||_inf = 1``.
    unconstrained_bc : float
        The minimizer of ``J`` without the constraint [N s/m]; ``nan`` when ``J`` is nowhere finite.
    reason : str, optional
        Why there is no optimum; ``""`` when feasible.
    """

    bc: float
    index: float
    peak: float
    peak_frequency: float
    feasible: bool
    constrained: bool
    unconstrained_bc: float
    reason: str = ""


@dataclass(frozen=True)
class TradeoffCurves:
    """``J(B_c)`` and ``||L||_inf(B_c)`` (Fig. 8); ``index`` is ``inf`` where ``J`` is not finite.

    Parameters
    ----------
    bc : numpy.ndarray
        Controller dampings ``B_c`` [N s/m], shape (N,).
    index : numpy.ndarray
        ``J`` at each ``B_c`` (eq. 11), ``inf`` where not finite, shape (N,).
    peak : numpy.ndarray
        ``||L||_inf`` at each ``B_c`` (eq. 16-17), shape (N,).
    peak_frequency : numpy.ndarray
        Frequency of each peak [rad/s] (``inf`` at the high-frequency limit), shape (N,).
    alpha : float, optional
        Mass uncertainty of the weight ``W`` (eq. 15).
    beta : float, optional
        Damping uncertainty of the weight ``W`` (eq. 15).
    """

    bc: np.ndarray
    index: np.ndarray
    peak: np.ndarray
    peak_frequency: np.ndarray
    alpha: float = 0.5
    beta: float = 0.5


@dataclass(frozen=True)
class StepResponse:
    """Answer of the exact sampled loop to a human-force step (Figs. 7, 10).

    ``t`` (s), ``position`` (m) and ``velocity`` (m/s) of the handle, exact between samples too;
    ``force`` the actuator (wall) force command, held over each sample; ``human_force`` the step;
    ``wall_position`` the ideal virtual wall's answer ``F/K (1 - e^{-K t/B})``.

    Parameters
    ----------
    t : numpy.ndarray
        Times [s], ``substeps`` points per sample, shape (N,).
    force : numpy.ndarray
        Actuator (wall) force command, held over each sample [N], shape (N,).
    position : numpy.ndarray
        Handle position [m], shape (N,).
    velocity : numpy.ndarray
        Handle velocity [m/s], shape (N,).
    human_force : numpy.ndarray
        The human-force step [N], shape (N,).
    wall_position : numpy.ndarray
        Position of the ideal virtual wall under the same step [m], shape (N,).
    bc : float
        The controller damping ``B_c`` [N s/m].
    """

    t: np.ndarray
    force: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    human_force: np.ndarray
    wall_position: np.ndarray
    bc: float
