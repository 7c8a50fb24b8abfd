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

Each causality is an object (:class:`EnvironmentCausality`: :data:`PENALTY`, :data:`CONSTRAINT`)
that checks and labels its environments, says when the object touches the wall, and selects the
controller form of a display loop (:mod:`analysis.sampled.controllers`).  :data:`CAUSALITY_KINDS`
is the one mapping from the name a record holds (``"impedance"``/``"admittance"``) to the object.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar, TypeVar

import numpy as np

from analysis.checks import Real, SettingsRecord, boolean, choice
from analysis.errors import ValidationError

__all__ = [
    "CAUSALITIES",
    "CAUSALITY_KINDS",
    "EnvironmentCausality",
    "PenaltyCausality",
    "ConstraintCausality",
    "PENALTY",
    "CONSTRAINT",
    "causality_kind",
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


# ">= 0 and finite", and ">= 0 (a real number)" for a value that is not a number at all.
_NONNEG = Real(lo=0.0, not_real=">= 0 (a real number)")

V = TypeVar("V")


class EnvironmentCausality:
    """One environment causality of section VI (see the module docstring).

    ``name`` is the record's spelling; ``contact(x_e, x_w)`` is true while the object is on the
    wall at ``x_w`` (a penalty wall pushes only while penetrated, a god-object wall holds the
    object on its surface).  :meth:`select` is the double dispatch with a display loop: it
    returns the penalty or the constraint variant of whatever it is given.
    """

    name: ClassVar[str]
    contact: ClassVar[Callable[[float, float], bool]]

    def select(self, penalty: V, constraint: V) -> V:
        raise NotImplementedError

    def check_mass(self, mass: float, given: object) -> None:
        """Refuse an object mass (``given`` as the record holds it) this causality cannot have."""

    def check_wall(self, wall: bool, given: object) -> None:
        """Refuse a wall flag this causality cannot have."""

    def label(self, env: Environment) -> str:
        raise NotImplementedError

    def constrains(self, wall: bool) -> bool:
        """Whether a scenario's wall (``wall`` true) holds the object as a god-object constraint."""
        raise NotImplementedError

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        """Free motion to rigid wall in this causality (see :func:`default_environments`)."""
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<{self.name} environment causality>"


class PenaltyCausality(EnvironmentCausality):
    """``"impedance"``: a massless object and the penalty wall force of eq. (29)."""

    name = "impedance"
    contact = staticmethod(operator.gt)

    def select(self, penalty: V, constraint: V) -> V:
        return penalty

    def check_wall(self, wall: bool, given: object) -> None:
        if wall:
            raise ValidationError("wall", "only for an admittance (god-object) environment", given)

    def label(self, env: Environment) -> str:
        return "free (penalty)" if env.stiffness == 0 else f"penalty wall k_obj={env.stiffness:.4g} N/m"

    def constrains(self, wall: bool) -> bool:
        return False

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        return [penalty_wall(0.0)] + [penalty_wall(float(k)) for k in np.geomspace(1e3, top_stiffness, 8)]


class ConstraintCausality(EnvironmentCausality):
    """``"admittance"``: an object of mass ``m_e`` by backward Euler, held on a god-object wall."""

    name = "admittance"
    contact = staticmethod(operator.ge)

    def select(self, penalty: V, constraint: V) -> V:
        return constraint

    def check_mass(self, mass: float, given: object) -> None:
        if mass <= 0:
            raise ValidationError("mass", "> 0 for an admittance environment", given)

    def label(self, env: Environment) -> str:
        return "god-object wall" if env.wall else f"free object m_e={env.mass:.4g} kg"

    def constrains(self, wall: bool) -> bool:
        return wall

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        return [free_motion("admittance", m) for m in (PAPER_OBJECT_MASS, 0.2, 2.0)] + [god_object_wall()]


PENALTY = PenaltyCausality()
CONSTRAINT = ConstraintCausality()
#: The one mapping from a causality name (environments, scenarios) to its object.
CAUSALITY_KINDS: dict[str, EnvironmentCausality] = {PENALTY.name: PENALTY, CONSTRAINT.name: CONSTRAINT}
#: The environment causalities (section VI): penalty and constraint (god-object).
CAUSALITIES = tuple(CAUSALITY_KINDS)


def causality_kind(causality: str | EnvironmentCausality, field: str = "causality") -> EnvironmentCausality:
    """The object of a causality name (``ValidationError`` on ``field`` for an unknown one)."""
    if isinstance(causality, EnvironmentCausality):
        return causality
    return CAUSALITY_KINDS[choice(field, causality, CAUSALITY_KINDS, allowed=" or ".join(CAUSALITIES))]


@dataclass(frozen=True)
class Grasp(SettingsRecord):
    """A passive human grasp on the handle: mass (kg), damping (N s/m), stiffness (N/m)."""

    record_name = "grasp"

    mass: float = 0.0
    damping: float = 0.0
    stiffness: float = 0.0

    def __post_init__(self) -> None:
        for name in ("mass", "damping", "stiffness"):
            object.__setattr__(self, name, _NONNEG(name, getattr(self, name)))

    @property
    def hands_off(self) -> bool:
        return self.mass == 0 and self.damping == 0 and self.stiffness == 0

HANDS_OFF = Grasp()
#: A firm human grasp (upper range of arm impedance measurements): the top of the default sweep.
FIRM_GRASP = Grasp(mass=2.0, damping=50.0, stiffness=2e3)
#: A rigid grasp: a strong two-handed grip braced against the body (high stiffness, still finite).
RIGID_GRASP = Grasp(mass=3.0, damping=200.0, stiffness=2e4)
#: The handle clamped to ground: the infinite-impedance termination of the two-port theory.
CLAMPED = Grasp(mass=0.0, damping=0.0, stiffness=1e8)


@dataclass(frozen=True)
class Environment(SettingsRecord):
    """A virtual environment seen through the coupling (see module docstring).

    ``causality``: ``"impedance"`` (penalty) or ``"admittance"`` (constraint/god-object).
    ``stiffness``/``damping``: penalty wall ``k_obj``/``b_obj`` (impedance causality).
    ``mass``/``damping``: object mass ``m_e`` and damping to ground (admittance causality).
    ``wall``: god-object wall engaged (admittance causality only).
    """

    record_name = "environment"

    causality: str = "impedance"
    stiffness: float = 0.0
    damping: float = 0.0
    mass: float = PAPER_OBJECT_MASS
    wall: bool = False

    def __post_init__(self) -> None:
        kind = causality_kind(self.causality)
        object.__setattr__(self, "stiffness", _NONNEG("stiffness", self.stiffness))
        object.__setattr__(self, "damping", _NONNEG("damping", self.damping))
        m = _NONNEG("mass", self.mass)
        kind.check_mass(m, self.mass)
        object.__setattr__(self, "mass", m)
        wall = boolean("wall", self.wall)
        kind.check_wall(wall, self.wall)
        object.__setattr__(self, "wall", wall)

    @property
    def kind(self) -> EnvironmentCausality:
        """The causality object (:data:`PENALTY` or :data:`CONSTRAINT`)."""
        return CAUSALITY_KINDS[self.causality]

    @property
    def rigid(self) -> bool:
        """True for the god-object wall."""
        return self.wall

    @property
    def free(self) -> bool:
        """True when the environment exerts no force at rest (free motion)."""
        return not self.wall and self.stiffness == 0

    def label(self) -> str:
        return self.kind.label(self)

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
    if causality is None:
        kinds = tuple(CAUSALITY_KINDS.values())
    elif isinstance(causality, str) and causality in CAUSALITY_KINDS:
        kinds = (CAUSALITY_KINDS[causality],)
    else:
        raise ValidationError("causality", "impedance, admittance or None", causality)
    return [env for kind in kinds for env in kind.default_environments(top_stiffness)]


def default_terminations(causality: str | None = None) -> list[Termination]:
    """Every default grasp with every default environment (64 x 13 = 832 by default)."""
    return [Termination(g, e) for g in default_grasps() for e in default_environments(causality)]
