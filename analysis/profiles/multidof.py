"""The optional ``multidof`` section (schema 7, issue 25): a linkage, its handle, the wall and the map's grid.

A multi-DOF device seen at its handle has an inertia and a damping that change with the
configuration and the direction (:mod:`analysis.multidof`).  The section holds what the
Workspace view, ``zwidth workspace`` and the report need::

    "multidof": {
      "linkage": {"kind": "five_bar", "l1": 0.2, "l2": 0.2, "base": 0.1,
                  "proximal_masses": [0.02, 0.02], "distal_masses": [0.015, 0.015],
                  "handle_mass": 0.0, "rotor_inertia": 0.0, "joint_damping": 0.001},
      "handle": {"x": 0.0, "y": 0.2},
      "wall": {"kind": "isotropic", "normal": [1.0, 0.0], "damping": 0.0},
      "map": {"x": {"min": -0.15, "max": 0.15, "points": 21},
              "y": {"min": 0.1, "max": 0.35, "points": 21}}}

Every key is optional (its default is :class:`MultiDofSection`'s: the five-bar of
:class:`~analysis.transparency.five_bar.FiveBar`'s defaults, the linkage's one home).  Each key is
declared once, with its rule (type, range, unit), in :data:`analysis.profiles.schema.MULTIDOF`;
:func:`parse_multidof` reads by those declarations (:mod:`analysis.profiles.declared`), so an
error names the JSON path (``$.multidof.map.x.points``), and :class:`MultiDofSection` validates
with the same rules, under the API names the schema maps back to those paths.  The handle must
be reachable by the linkage (``$.multidof.handle``); a singular configuration is refused where the
study linearizes it (:func:`analysis.multidof.five_bar_device`), naming the position.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from analysis.errors import ValidationError
from analysis.profiles.declared import declared_tree, declared_value, read_declared
from analysis.profiles.errors import ProfileError
from analysis.profiles.schema import FIELDS_BY_NAME, MULTIDOF
from analysis.transparency.five_bar import FiveBar

__all__ = ["MultiDofSection", "parse_multidof", "MULTIDOF_NAMES"]

#: The API names of the section's values (its record's fields), in the schema's order.
MULTIDOF_NAMES: tuple[str, ...] = tuple(
    name for name, (path, node) in FIELDS_BY_NAME.items() if path.startswith("$.multidof.") and node.kind != "object"
)
_DEFAULT = FiveBar()


@dataclass(frozen=True)
class MultiDofSection:
    """A linkage, the handle's position, the wall and the workspace map's grid.

    Parameters
    ----------
    linkage_kind : str, optional
        The linkage (:data:`analysis.profiles.schema.LINKAGE_KINDS`): ``"five_bar"``.
    l1, l2 : float, optional
        The proximal and distal link lengths [m], > 0.
    base : float, optional
        The distance between the two motors [m], >= 0.
    proximal_masses, distal_masses : tuple of (float, float), optional
        The links' masses (left, right) [kg], >= 0.
    handle_mass : float, optional
        A point mass at the handle [kg].
    rotor_inertia : float, optional
        Each motor's rotor inertia [kg m^2].
    joint_damping : float, optional
        Each motor's viscous friction [N m s/rad].
    handle_x, handle_y : float, optional
        The handle's position [m]: where the per-direction limits and the inertia ellipse are shown.
    wall_kind : str, optional
        ``"isotropic"`` (``K I``) or ``"normal"`` (a plane wall ``K n n^T``).
    wall_normal : tuple of (float, float), optional
        The plane wall's normal (any length but zero; used with ``wall_kind="normal"``).
    wall_damping : float, optional
        The wall's damping ``b`` [N s/m], >= 0.
    x_min, x_max, y_min, y_max : float, optional
        The map's grid [m], ``min < max``.
    x_points, y_points : int, optional
        Grid points per axis, 2 to :data:`~analysis.profiles.schema.MAX_GRID_POINTS`.

    Raises
    ------
    ValidationError
        Naming the field (its JSON path: :func:`analysis.profiles.path_of`) when a value is out of
        range, a mass pair or the normal does not have two values, the normal is zero, a range is
        not increasing, or the handle is outside the linkage's workspace (``handle``).
    """

    linkage_kind: str = "five_bar"
    l1: float = _DEFAULT.l1
    l2: float = _DEFAULT.l2
    base: float = _DEFAULT.base
    proximal_masses: tuple[float, float] = _DEFAULT.proximal_masses
    distal_masses: tuple[float, float] = _DEFAULT.distal_masses
    handle_mass: float = _DEFAULT.handle_mass
    rotor_inertia: float = _DEFAULT.rotor_inertia
    joint_damping: float = _DEFAULT.joint_damping
    handle_x: float = 0.0
    handle_y: float = 0.2
    wall_kind: str = "isotropic"
    wall_normal: tuple[float, float] = (1.0, 0.0)
    wall_damping: float = 0.0
    x_min: float = -0.15
    x_max: float = 0.15
    x_points: int = 21
    y_min: float = 0.1
    y_max: float = 0.35
    y_points: int = 21

    def __post_init__(self) -> None:
        for name in MULTIDOF_NAMES:
            object.__setattr__(self, name, declared_value(name, getattr(self, name)))
        for lo, hi in (("x_min", "x_max"), ("y_min", "y_max")):
            if not getattr(self, lo) < getattr(self, hi):
                raise ValidationError(hi, f"above {lo} = {getattr(self, lo):g} (m)", getattr(self, hi))
        if len(self.wall_normal) != 2 or not math.hypot(*self.wall_normal) > 0:
            raise ValidationError("wall_normal", "two numbers (n_x, n_y), not both zero", list(self.wall_normal))
        linkage = self.linkage  # the pairs' lengths, by FiveBar's own check (its field names are ours)
        try:
            linkage.inverse_kinematics(self.handle)
        except ValidationError as err:
            raise ValidationError("handle", f"a position the linkage reaches ({err.allowed})",
                                  [self.handle_x, self.handle_y]) from err

    @property
    def linkage(self) -> FiveBar:
        """The linkage (:class:`~analysis.transparency.five_bar.FiveBar`)."""
        return FiveBar(l1=self.l1, l2=self.l2, base=self.base, proximal_masses=tuple(self.proximal_masses),
                       distal_masses=tuple(self.distal_masses), handle_mass=self.handle_mass,
                       rotor_inertia=self.rotor_inertia, joint_damping=self.joint_damping)

    @property
    def handle(self) -> np.ndarray:
        """The handle's position ``(x, y)`` [m], shape (2,)."""
        return np.array([self.handle_x, self.handle_y])

    @property
    def normal(self) -> np.ndarray | None:
        """The plane wall's unit normal, shape (2,); ``None`` for the isotropic wall."""
        if self.wall_kind == "isotropic":
            return None
        n = np.asarray(self.wall_normal, dtype=float)
        return n / np.linalg.norm(n)

    def replace(self, **changes: Any) -> MultiDofSection:
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New values of fields, by name (``handle_x``, ``wall_kind``, ...).

        Returns
        -------
        MultiDofSection
            The new section.
        """
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready section, every key written.

        Returns
        -------
        dict of str to Any
            The tree of :data:`analysis.profiles.schema.MULTIDOF`.
        """
        return declared_tree(MULTIDOF, self)


def parse_multidof(data: object) -> MultiDofSection:
    """The ``multidof`` section of a (migrated) profile dict, read by the schema's declarations.

    Parameters
    ----------
    data : object
        The value of the profile's ``multidof`` key (a JSON object).

    Returns
    -------
    MultiDofSection
        The section, every missing key at its default.

    Raises
    ------
    ProfileError
        At the JSON path of the first bad or unknown key, e.g. ``$.multidof.map.x.points``.
    """
    values: dict[str, Any] = {}
    read_declared(MULTIDOF, data, "$.multidof", values)
    try:
        return MultiDofSection(**values)
    except ValidationError as err:
        path = FIELDS_BY_NAME[err.field][0] if err.field in FIELDS_BY_NAME else "$.multidof"
        if err.index is not None:
            path += f"[{err.index}]"
        raise ProfileError.at(path, err.allowed, err.value) from err
