"""Terminations of the haptic interface: the human grasp and the virtual environment.

The human is a passive one-port attached to the handle (mass 0 of the chain): a grasp of
mass ``m_h`` (added to the handle), damping ``b_h`` and stiffness ``k_h`` to ground (the
shoulder).  Hands-off is all zero.  Adams, Moreyra & Hannaford (section III) name the worst
cases: low human impedance with a rigid environment for impedance displays, high human
impedance with free motion for admittance displays.

The environment is one of the paper's two causalities (section VI):

* ``"impedance"`` (penalty): a massless object ``O_e`` and a wall force
  ``F_e = k_obj p + b_obj p'`` with penetration ``p`` (eq. 29); ``k_obj = 0`` is free motion.
  The paper's rigid wall is ``k_obj = 500 kN/m``.
* ``"admittance"`` (constraint / god-object): an object of small mass ``m_e`` (the paper:
  0.02 kg) with optional damping ``b_e`` to ground, integrated by backward Euler; when
  ``wall`` is true the object is held on the wall surface (``v_e = 0``), the god-object
  constraint of Zilles & Salisbury.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.errors import ValidationError

__all__ = [
    "Grasp",
    "Environment",
    "Termination",
    "HANDS_OFF",
    "FIRM_GRASP",
    "RIGID_GRASP",
    "CLAMPED",
    "PAPER_WALL_STIFFNESS",
    "PAPER_OBJECT_MASS",
    "penalty_wall",
    "god_object_wall",
    "free_motion",
    "default_grasps",
    "default_environments",
    "default_terminations",
]

PAPER_WALL_STIFFNESS = 500e3  # N/m, the paper's "rigid" penalty wall (section VI)
PAPER_OBJECT_MASS = 0.02  # kg, the paper's admittance-environment object O_e


def _nonneg(name: str, value: object, allow_inf: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValidationError(name, ">= 0 (a real number)", value)
    x = float(value)
    if math.isnan(x) or x < 0 or (math.isinf(x) and not allow_inf):
        raise ValidationError(name, ">= 0 and finite" if not allow_inf else ">= 0", value)
    return x


@dataclass(frozen=True)
class Grasp:
    """A passive human grasp on the handle: mass (kg), damping (N s/m), stiffness (N/m)."""

    mass: float = 0.0
    damping: float = 0.0
    stiffness: float = 0.0

    def __post_init__(self) -> None:
        for name in ("mass", "damping", "stiffness"):
            object.__setattr__(self, name, _nonneg(name, getattr(self, name)))

    @property
    def hands_off(self) -> bool:
        return self.mass == 0 and self.damping == 0 and self.stiffness == 0

    def to_dict(self) -> dict:
        return {"mass": self.mass, "damping": self.damping, "stiffness": self.stiffness}

    @classmethod
    def from_dict(cls, data: dict) -> Grasp:
        if not isinstance(data, dict):
            raise ValidationError("grasp", "an object with mass, damping, stiffness", data)
        unknown = set(data) - {"mass", "damping", "stiffness"}
        if unknown:
            raise ValidationError("grasp", "keys mass, damping, stiffness", sorted(unknown))
        return cls(**data)


HANDS_OFF = Grasp()
#: A firm human grasp (upper range of arm impedance measurements): the top of the default sweep.
FIRM_GRASP = Grasp(mass=2.0, damping=50.0, stiffness=2e3)
#: A rigid grasp: a strong two-handed grip braced against the body (high stiffness, still finite).
RIGID_GRASP = Grasp(mass=3.0, damping=200.0, stiffness=2e4)
#: The handle clamped to ground: the infinite-impedance termination of the two-port theory.
CLAMPED = Grasp(mass=0.0, damping=0.0, stiffness=1e8)


_CAUSALITIES = ("impedance", "admittance")


@dataclass(frozen=True)
class Environment:
    """A virtual environment seen through the coupling (see module docstring).

    ``causality``: ``"impedance"`` (penalty) or ``"admittance"`` (constraint/god-object).
    ``stiffness``/``damping``: penalty wall ``k_obj``/``b_obj`` (impedance causality).
    ``mass``/``damping``: object mass ``m_e`` and damping to ground (admittance causality).
    ``wall``: god-object wall engaged (admittance causality only).
    """

    causality: str = "impedance"
    stiffness: float = 0.0
    damping: float = 0.0
    mass: float = PAPER_OBJECT_MASS
    wall: bool = False

    def __post_init__(self) -> None:
        if self.causality not in _CAUSALITIES:
            raise ValidationError("causality", " or ".join(_CAUSALITIES), self.causality)
        object.__setattr__(self, "stiffness", _nonneg("stiffness", self.stiffness))
        object.__setattr__(self, "damping", _nonneg("damping", self.damping))
        m = _nonneg("mass", self.mass)
        if self.causality == "admittance" and m <= 0:
            raise ValidationError("mass", "> 0 for an admittance environment", self.mass)
        object.__setattr__(self, "mass", m)
        if not isinstance(self.wall, (bool, np.bool_)):
            raise ValidationError("wall", "true or false", self.wall)
        if self.wall and self.causality != "admittance":
            raise ValidationError("wall", "only for an admittance (god-object) environment", self.wall)
        object.__setattr__(self, "wall", bool(self.wall))

    @property
    def rigid(self) -> bool:
        """True for the god-object wall."""
        return self.wall

    @property
    def free(self) -> bool:
        """True when the environment exerts no force at rest (free motion)."""
        return not self.wall and self.stiffness == 0

    def label(self) -> str:
        if self.causality == "impedance":
            return "free (penalty)" if self.stiffness == 0 else f"penalty wall k_obj={self.stiffness:.4g} N/m"
        return "god-object wall" if self.wall else f"free object m_e={self.mass:.4g} kg"

    def to_dict(self) -> dict:
        return {"causality": self.causality, "stiffness": self.stiffness, "damping": self.damping,
                "mass": self.mass, "wall": self.wall}

    @classmethod
    def from_dict(cls, data: dict) -> Environment:
        if not isinstance(data, dict):
            raise ValidationError("environment", "an object", data)
        unknown = set(data) - {"causality", "stiffness", "damping", "mass", "wall"}
        if unknown:
            raise ValidationError("environment", "keys causality, stiffness, damping, mass, wall", sorted(unknown))
        return cls(**data)


def penalty_wall(stiffness: float = PAPER_WALL_STIFFNESS, damping: float = 0.0) -> Environment:
    """The impedance (penalty) wall of eq. (29), engaged."""
    return Environment("impedance", stiffness=stiffness, damping=damping)


def god_object_wall(mass: float = PAPER_OBJECT_MASS) -> Environment:
    """The admittance (constraint) wall, engaged: the object is held on the surface."""
    return Environment("admittance", mass=mass, wall=True)


def free_motion(causality: str = "impedance", mass: float = PAPER_OBJECT_MASS) -> Environment:
    """Free motion: ``F_e = 0`` (penalty) or a free object of mass ``m_e`` (admittance)."""
    return Environment(causality, mass=mass)


@dataclass(frozen=True)
class Termination:
    """One human grasp and one environment."""

    grasp: Grasp
    environment: Environment

    def label(self) -> str:
        g = self.grasp
        who = "hands-off" if g.hands_off else f"grasp m={g.mass:.3g} b={g.damping:.3g} k={g.stiffness:.3g}"
        return f"{who}; {self.environment.label()}"


def default_grasps(top: Grasp = RIGID_GRASP, levels: int = 4) -> list[Grasp]:
    """Hands-off to ``top``: a product grid of mass, damping and stiffness.

    Each parameter takes ``levels`` values: 0 and geometric steps up to the top value
    (factor 10 per step for damping and stiffness, linear for the mass).
    """
    if levels < 2:
        raise ValidationError("levels", ">= 2", levels)

    def steps(top_value: float, geometric: bool) -> np.ndarray:
        if top_value == 0:
            return np.zeros(1)
        if geometric:
            return np.r_[0.0, top_value * np.geomspace(10.0 ** -(levels - 2), 1.0, levels - 1)]
        return np.linspace(0.0, top_value, levels)

    ms, bs, ks = steps(top.mass, False), steps(top.damping, True), steps(top.stiffness, True)
    return [Grasp(float(m), float(b), float(k)) for m in ms for b in bs for k in ks]


def default_environments(causality: str | None = None, top_stiffness: float = PAPER_WALL_STIFFNESS) -> list[Environment]:
    """Free motion to rigid wall, for one causality or both (``None``).

    Penalty: ``k_obj`` = 0 and 8 geometric steps from 1 kN/m to ``top_stiffness``.
    Admittance: free objects of 0.02, 0.2 and 2 kg, and the god-object wall.
    """
    out: list[Environment] = []
    if causality in (None, "impedance"):
        out.append(penalty_wall(0.0))
        out += [penalty_wall(float(k)) for k in np.geomspace(1e3, top_stiffness, 8)]
    if causality in (None, "admittance"):
        out += [free_motion("admittance", m) for m in (PAPER_OBJECT_MASS, 0.2, 2.0)]
        out.append(god_object_wall())
    if not out:
        raise ValidationError("causality", "impedance, admittance or None", causality)
    return out


def default_terminations(causality: str | None = None) -> list[Termination]:
    """Every default grasp with every default environment (64 x 13 = 832 by default)."""
    return [Termination(g, e) for g in default_grasps() for e in default_environments(causality)]
