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
        """The penalty or the constraint variant of what it is given (double dispatch).

        Parameters
        ----------
        penalty : V
            The penalty variant (e.g. a display loop's ``penalty_step``).
        constraint : V
            The constraint variant.

        Returns
        -------
        V
            The variant of this causality.

        Raises
        ------
        NotImplementedError
            Always: each causality overrides it.
        """
        raise NotImplementedError

    def check_mass(self, mass: float, given: object) -> None:
        """Refuse an object mass (``given`` as the record holds it) this causality cannot have.

        The base accepts every mass.

        Parameters
        ----------
        mass : float
            The validated object mass ``m_e`` [kg].
        given : object
            The mass as the record holds it, named in the error.
        """

    def check_wall(self, wall: bool, given: object) -> None:
        """Refuse a wall flag this causality cannot have.

        The base accepts every flag.

        Parameters
        ----------
        wall : bool
            The validated wall flag.
        given : object
            The flag as the record holds it, named in the error.
        """

    def label(self, env: Environment) -> str:
        """A label of an environment of this causality.

        Parameters
        ----------
        env : Environment
            An environment of this causality.

        Returns
        -------
        str
            A short label for plots and reports.

        Raises
        ------
        NotImplementedError
            Always: each causality overrides it.
        """
        raise NotImplementedError

    def constrains(self, wall: bool) -> bool:
        """Whether a scenario's wall (``wall`` true) holds the object as a god-object constraint.

        Parameters
        ----------
        wall : bool
            The scenario's wall flag.

        Returns
        -------
        bool
            True when the object is held on the wall.

        Raises
        ------
        NotImplementedError
            Always: each causality overrides it.
        """
        raise NotImplementedError

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        """Free motion to rigid wall in this causality (see :func:`default_environments`).

        Parameters
        ----------
        top_stiffness : float
            Stiffest penalty wall ``k_obj`` [N/m] (unused by the constraint causality).

        Returns
        -------
        list of Environment
            The environments, free motion first.

        Raises
        ------
        NotImplementedError
            Always: each causality overrides it.
        """
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<{self.name} environment causality>"


class PenaltyCausality(EnvironmentCausality):
    """``"impedance"``: a massless object and the penalty wall force of eq. (29)."""

    name = "impedance"
    contact = staticmethod(operator.gt)

    def select(self, penalty: V, constraint: V) -> V:
        """The penalty variant.

        Parameters
        ----------
        penalty : V
            The penalty variant (e.g. a display loop's ``penalty_step``).
        constraint : V
            The constraint variant.

        Returns
        -------
        V
            The variant of this causality.
        """
        return penalty

    def check_wall(self, wall: bool, given: object) -> None:
        """Refuse a wall flag: a penalty wall is a stiffness, not a constraint.

        Parameters
        ----------
        wall : bool
            The validated wall flag.
        given : object
            The flag as the record holds it, named in the error.

        Raises
        ------
        ValidationError
            When ``wall`` is true.
        """
        if wall:
            raise ValidationError("wall", "only for an admittance (god-object) environment", given)

    def label(self, env: Environment) -> str:
        """``"free (penalty)"`` or the wall stiffness.

        Parameters
        ----------
        env : Environment
            An environment of this causality.

        Returns
        -------
        str
            A short label for plots and reports.
        """
        return "free (penalty)" if env.stiffness == 0 else f"penalty wall k_obj={env.stiffness:.4g} N/m"

    def constrains(self, wall: bool) -> bool:
        """Never: a penalty wall does not hold the object.

        Parameters
        ----------
        wall : bool
            The scenario's wall flag.

        Returns
        -------
        bool
            True when the object is held on the wall.
        """
        return False

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        """Free motion (``k_obj = 0``) and 8 geometric steps from 1 kN/m to ``top_stiffness``.

        Parameters
        ----------
        top_stiffness : float
            Stiffest penalty wall ``k_obj`` [N/m] (unused by the constraint causality).

        Returns
        -------
        list of Environment
            The environments, free motion first.
        """
        return [penalty_wall(0.0)] + [penalty_wall(float(k)) for k in np.geomspace(1e3, top_stiffness, 8)]


class ConstraintCausality(EnvironmentCausality):
    """``"admittance"``: an object of mass ``m_e`` by backward Euler, held on a god-object wall."""

    name = "admittance"
    contact = staticmethod(operator.ge)

    def select(self, penalty: V, constraint: V) -> V:
        """The constraint variant.

        Parameters
        ----------
        penalty : V
            The penalty variant (e.g. a display loop's ``penalty_step``).
        constraint : V
            The constraint variant.

        Returns
        -------
        V
            The variant of this causality.
        """
        return constraint

    def check_mass(self, mass: float, given: object) -> None:
        """Refuse a mass that is not positive: the object is integrated by backward Euler.

        Parameters
        ----------
        mass : float
            The validated object mass ``m_e`` [kg].
        given : object
            The mass as the record holds it, named in the error.

        Raises
        ------
        ValidationError
            When ``mass <= 0``.
        """
        if mass <= 0:
            raise ValidationError("mass", "> 0 for an admittance environment", given)

    def label(self, env: Environment) -> str:
        """``"god-object wall"`` or the free object's mass.

        Parameters
        ----------
        env : Environment
            An environment of this causality.

        Returns
        -------
        str
            A short label for plots and reports.
        """
        return "god-object wall" if env.wall else f"free object m_e={env.mass:.4g} kg"

    def constrains(self, wall: bool) -> bool:
        """Exactly when the scenario has a wall.

        Parameters
        ----------
        wall : bool
            The scenario's wall flag.

        Returns
        -------
        bool
            True when the object is held on the wall.
        """
        return wall

    def default_environments(self, top_stiffness: float) -> list[Environment]:
        """Free objects of 0.02, 0.2 and 2 kg, and the god-object wall.

        Parameters
        ----------
        top_stiffness : float
            Stiffest penalty wall ``k_obj`` [N/m] (unused by the constraint causality).

        Returns
        -------
        list of Environment
            The environments, free motion first.
        """
        return [free_motion("admittance", m) for m in (PAPER_OBJECT_MASS, 0.2, 2.0)] + [god_object_wall()]


PENALTY = PenaltyCausality()
CONSTRAINT = ConstraintCausality()
#: The one mapping from a causality name (environments, scenarios) to its object.
CAUSALITY_KINDS: dict[str, EnvironmentCausality] = {PENALTY.name: PENALTY, CONSTRAINT.name: CONSTRAINT}
#: The environment causalities (section VI): penalty and constraint (god-object).
CAUSALITIES = tuple(CAUSALITY_KINDS)


def causality_kind(causality: str | EnvironmentCausality, field: str = "causality") -> EnvironmentCausality:
    """The object of a causality name (``ValidationError`` on ``field`` for an unknown one).

    Parameters
    ----------
    causality : str or EnvironmentCausality
        ``"impedance"`` or ``"admittance"``, or a causality object (returned as is).
    field : str, optional
        The field named in the error.

    Returns
    -------
    EnvironmentCausality
        :data:`PENALTY` or :data:`CONSTRAINT`.
    """
    if isinstance(causality, EnvironmentCausality):
        return causality
    return CAUSALITY_KINDS[choice(field, causality, CAUSALITY_KINDS, allowed=" or ".join(CAUSALITIES))]


@dataclass(frozen=True)
class Grasp(SettingsRecord):
    """A passive human grasp on the handle: mass (kg), damping (N s/m), stiffness (N/m).

    Parameters
    ----------
    mass : float, optional
        Mass ``m_h`` added to the handle [kg], at least 0.
    damping : float, optional
        Damping ``b_h`` to ground [N s/m], at least 0.
    stiffness : float, optional
        Stiffness ``k_h`` to ground (the shoulder) [N/m], at least 0.

    Raises
    ------
    ValidationError
        When a value is negative or not a real number.
    """

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

    Parameters
    ----------
    causality : str, optional
        ``"impedance"`` (penalty) or ``"admittance"`` (constraint/god-object).
    stiffness : float, optional
        Penalty wall stiffness ``k_obj`` [N/m], at least 0 (impedance causality).
    damping : float, optional
        Penalty wall damping ``b_obj``, or the object's damping ``b_e`` to ground [N s/m], at
        least 0.
    mass : float, optional
        Object mass ``m_e`` [kg]: greater than 0 in the admittance causality.
    wall : bool, optional
        God-object wall engaged (admittance causality only).

    Raises
    ------
    ValidationError
        When a value is out of range or does not fit the causality.
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
        """A short label for plots and reports (from the causality).

        Returns
        -------
        str
            E.g. ``"penalty wall k_obj=5e+05 N/m"`` or ``"god-object wall"``.
        """
        return self.kind.label(self)

def penalty_wall(stiffness: float = PAPER_WALL_STIFFNESS, damping: float = 0.0) -> Environment:
    """The impedance (penalty) wall of eq. (29), engaged.

    Parameters
    ----------
    stiffness : float, optional
        Wall stiffness ``k_obj`` [N/m]; the paper's rigid wall by default.
    damping : float, optional
        Wall damping ``b_obj`` [N s/m].

    Returns
    -------
    Environment
        The penalty environment.
    """
    return Environment("impedance", stiffness=stiffness, damping=damping)


def god_object_wall(mass: float = PAPER_OBJECT_MASS) -> Environment:
    """The admittance (constraint) wall, engaged: the object is held on the surface.

    Parameters
    ----------
    mass : float, optional
        Object mass ``m_e`` [kg]; the paper's 0.02 kg by default.

    Returns
    -------
    Environment
        The god-object environment.
    """
    return Environment("admittance", mass=mass, wall=True)


def free_motion(causality: str = "impedance", mass: float = PAPER_OBJECT_MASS) -> Environment:
    """Free motion: ``F_e = 0`` (penalty) or a free object of mass ``m_e`` (admittance).

    Parameters
    ----------
    causality : str, optional
        ``"impedance"`` or ``"admittance"``.
    mass : float, optional
        Object mass ``m_e`` [kg] (admittance causality).

    Returns
    -------
    Environment
        The free environment.
    """
    return Environment(causality, mass=mass)


@dataclass(frozen=True)
class Termination:
    """One human grasp and one environment.

    Parameters
    ----------
    grasp : Grasp
        The human at the handle.
    environment : Environment
        The virtual environment behind the coupling.
    """

    grasp: Grasp
    environment: Environment

    def label(self) -> str:
        """A short label of the grasp and the environment for plots and reports.

        Returns
        -------
        str
            ``"hands-off; ..."`` or the grasp's values, then the environment's label.
        """
        g = self.grasp
        who = "hands-off" if g.hands_off else f"grasp m={g.mass:.3g} b={g.damping:.3g} k={g.stiffness:.3g}"
        return f"{who}; {self.environment.label()}"


def default_grasps(top: Grasp = RIGID_GRASP, levels: int = 4) -> list[Grasp]:
    """Hands-off to ``top``: a product grid of mass, damping and stiffness.

    Each parameter takes ``levels`` values: 0 and geometric steps up to the top value
    (factor 10 per step for damping and stiffness, linear for the mass).

    Parameters
    ----------
    top : Grasp, optional
        The highest grasp of the grid.
    levels : int, optional
        Values per parameter, at least 2 (a zero top value gives one value, 0).

    Returns
    -------
    list of Grasp
        ``levels**3`` grasps (fewer where a top value is 0), hands-off first.

    Raises
    ------
    ValidationError
        When ``levels < 2``.
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

    Parameters
    ----------
    causality : str or None, optional
        ``"impedance"``, ``"admittance"`` or ``None`` for both.
    top_stiffness : float, optional
        Stiffest penalty wall [N/m].

    Returns
    -------
    list of Environment
        9 penalty environments, 4 admittance environments, or both (13).

    Raises
    ------
    ValidationError
        When ``causality`` is none of these.
    """
    if causality is None:
        kinds = tuple(CAUSALITY_KINDS.values())
    elif isinstance(causality, str) and causality in CAUSALITY_KINDS:
        kinds = (CAUSALITY_KINDS[causality],)
    else:
        raise ValidationError("causality", "impedance, admittance or None", causality)
    return [env for kind in kinds for env in kind.default_environments(top_stiffness)]


def default_terminations(causality: str | None = None) -> list[Termination]:
    """Every default grasp with every default environment (64 x 13 = 832 by default).

    Parameters
    ----------
    causality : str or None, optional
        ``"impedance"``, ``"admittance"`` or ``None`` for both (:func:`default_environments`).

    Returns
    -------
    list of Termination
        Grasp-major: every environment for the first grasp, then the next.
    """
    return [Termination(g, e) for g in default_grasps() for e in default_environments(causality)]
