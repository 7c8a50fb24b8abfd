"""Settings and result objects of the wall-controller design (Eom, Suh & Yi); see
:mod:`analysis.transparency` for the analysis itself.  Frozen dataclasses, nothing here computes."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields, replace

import numpy as np

from analysis.errors import ValidationError
from analysis.transparency.holds import HOLDS

__all__ = [
    "PLANTS",
    "WallSettings",
    "IndexResult",
    "RobustnessPeak",
    "OptimalDamping",
    "TradeoffCurves",
    "StepResponse",
]

PLANTS = ("rigid", "chain")


# ----------------------------------------------------------------------------------------------
# settings (stored in the profile)
# ----------------------------------------------------------------------------------------------
def _real(name: str, value, *, lo: float | None = None, lo_open: bool = False, hi: float | None = None,
          hi_open: bool = False, allowed: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValidationError(name, allowed, value)
    x = float(value)
    if not math.isfinite(x):
        raise ValidationError(name, allowed, value)
    if lo is not None and (x < lo or (lo_open and x == lo)):
        raise ValidationError(name, allowed, value)
    if hi is not None and (x > hi or (hi_open and x == hi)):
        raise ValidationError(name, allowed, value)
    return x


def _integer(name: str, value, lo: int, hi: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= int(value) <= hi:
        raise ValidationError(name, f"an integer in [{lo}, {hi}]", value)
    return int(value)


def _choice(name: str, value, options: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in options:
        raise ValidationError(name, "one of " + ", ".join(repr(o) for o in options), value)
    return value


@dataclass(frozen=True)
class WallSettings:
    """Every parameter of a wall-controller design (a profile section; ``to_dict``/``from_dict``).

    Units: kg, N s/m, N/m, s, rad/s, N.  ``controller_stiffness = None`` means ``K_c = K``.
    ``plant = "chain"`` uses the profile's device chain instead of ``mass``/``damping``.
    ``bc_min .. bc_max`` (``bc_count`` values, linear) is the range of the Fig. 8 curves and of
    the search for the optimum.
    """

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
        pos = "> 0 and finite"
        nonneg = ">= 0 and finite"
        s = object.__setattr__
        s(self, "mass", _real("mass", self.mass, lo=0.0, lo_open=True, allowed=pos + " (kg)"))
        s(self, "damping", _real("damping", self.damping, lo=0.0, allowed=nonneg + " (N s/m)"))
        s(self, "wall_stiffness", _real("wall_stiffness", self.wall_stiffness, lo=0.0, allowed=nonneg + " (N/m)"))
        s(self, "wall_damping", _real("wall_damping", self.wall_damping, lo=0.0, allowed=nonneg + " (N s/m)"))
        if self.wall_stiffness == 0.0 and self.wall_damping == 0.0:
            raise ValidationError("wall_damping", "> 0 when wall_stiffness = 0 (the wall needs K or B)", 0.0)
        if self.controller_stiffness is not None:
            s(self, "controller_stiffness", _real("controller_stiffness", self.controller_stiffness, lo=0.0,
                                                  allowed=nonneg + " (N/m) or null for K_c = K"))
        s(self, "sample_time", _real("sample_time", self.sample_time, lo=0.0, lo_open=True, allowed=pos + " (s)"))
        _choice("hold", self.hold, HOLDS)
        s(self, "lowpass_damping", _real("lowpass_damping", self.lowpass_damping, lo=0.0, lo_open=True,
                                         allowed=pos))
        s(self, "weight_order", _integer("weight_order", self.weight_order, 0, 8))
        s(self, "weight_cutoff", _real("weight_cutoff", self.weight_cutoff, lo=0.0, lo_open=True,
                                       allowed=pos + " (rad/s)"))
        s(self, "alpha", _real("alpha", self.alpha, lo=0.0, hi=1.0, hi_open=True, allowed="in [0, 1)"))
        s(self, "beta", _real("beta", self.beta, lo=0.0, hi=1.0, allowed="in [0, 1]"))
        s(self, "bc_min", _real("bc_min", self.bc_min, allowed="finite (N s/m)"))
        s(self, "bc_max", _real("bc_max", self.bc_max, allowed="finite (N s/m)"))
        if not self.bc_max > self.bc_min:
            raise ValidationError("bc_max", f"> bc_min = {self.bc_min}", self.bc_max)
        s(self, "bc_count", _integer("bc_count", self.bc_count, 2, 10000))
        _choice("plant", self.plant, PLANTS)
        s(self, "step_force", _real("step_force", self.step_force, allowed="finite (N)"))
        s(self, "step_duration", _real("step_duration", self.step_duration, lo=0.0, lo_open=True, hi=100.0,
                                       allowed="in (0, 100] s"))

    @property
    def kc(self) -> float:
        """``K_c`` (``K`` unless ``controller_stiffness`` is set)."""
        return self.wall_stiffness if self.controller_stiffness is None else self.controller_stiffness

    def to_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: Mapping) -> WallSettings:
        """Validated construction from a profile section; missing keys take the defaults."""
        if not isinstance(data, Mapping):
            raise ValidationError("transparency", "an object", data)
        known = {f.name for f in fields(cls)}
        for key in data:
            if key not in known:
                raise ValidationError(str(key), "a known field: " + ", ".join(sorted(known)), data[key])
        return cls(**dict(data))

    def replace(self, **changes) -> WallSettings:
        return replace(self, **changes)


# ----------------------------------------------------------------------------------------------
# results
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class IndexResult:
    """``J(B_c)`` of eq. (11) with how it was obtained.

    ``finite`` is False (and ``index = inf``) when the weighted error is not in H2; ``reason``
    says why.  ``method`` is ``"lyapunov"`` or ``"quadrature"``; ``nodes`` counts quadrature nodes.
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
    frequency axis could not be bounded below the reported peak (``zoh`` ripple)."""

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
    """``J(B_c)`` and ``||L||_inf(B_c)`` (Fig. 8); ``index`` is ``inf`` where ``J`` is not finite."""

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
    """

    t: np.ndarray
    force: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    human_force: np.ndarray
    wall_position: np.ndarray
    bc: float
