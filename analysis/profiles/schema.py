"""The profile schema: one declaration of each field, its JSON path derived from where it sits.

:data:`SCHEMA` is the tree of a current-schema profile file.  Each :class:`Field` gives a JSON
key, what kind of value it holds, its rule (a :class:`~analysis.chain.limits.Limit` of
:mod:`analysis.chain.limits`: type, physical range and unit, or a :class:`~analysis.checks.Real`)
and the name the API gives the value (``Device(masses=...)``, ``Profile(kc=...)``: the ``field``
of a :class:`~analysis.errors.ValidationError`).  The JSON path of a field is the chain of keys
above it, so nothing maps names to paths by hand:

* the loader (:mod:`analysis.profiles.fields`) reads the top level and the device by these
  declarations, and reports an error of :class:`~analysis.chain.Device` or
  :class:`~analysis.profiles.Profile` at :func:`path_of` the name it carries;
* :data:`analysis.profiles.SCALAR_FIELDS` (the couplings and gains) is derived from it;
* a list declared :data:`PER_MASS` (``ground_dampings``, the simulator's ``friction``) is checked
  against the device's number of masses wherever it sits (:data:`PER_MASS_LISTS`), and those of
  the sections are dropped by :func:`drop_per_mass` when a profile takes a chain of another order
  (the device ``zwidth identify`` fits: :func:`analysis.study.identify.profile_with_fit`).

The optional ``renderable`` section (schema 6, issue 24: the rendered environment and the
qualities' settings) and the optional ``multidof`` section (schema 7, issue 25: the linkage, the
handle, the wall and the workspace map's grid) are declared key by key here, each number with its
rule, and read by these declarations (:mod:`analysis.profiles.declared`, used by
:mod:`analysis.profiles.renderable` and :mod:`analysis.profiles.multidof`); their records validate
with the same rules.

The other optional sections (``wall``, ``observer``, ``simulation``, ``identification``,
``controller``) are validated by their own records (:mod:`analysis.profiles.sections`,
:mod:`~analysis.profiles.identification`, :mod:`~analysis.profiles.controller`), whose field
names are their JSON keys; the tree declares only what the profile checks across them (the
per-mass friction, the scenario's duration against the simulation's size, the velocity
filter's cut-off against Nyquist).

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from analysis.chain.limits import (
    BAND_MIN,
    DAMPING,
    DAMPING_RATIO,
    GROUND_DAMPING,
    LIMITS,
    MASS,
    SAMPLE_TIME,
    STIFFNESS,
    Limit,
)
from analysis.checks import Real
from analysis.sampled.qualities import QUALITIES
from analysis.sampled.rendered import ACCELERATION_KINDS, LOWPASS_KINDS
from analysis.sampled.velocity_noise import ENCODER_RESOLUTION, FORCE_NOISE

__all__ = [
    "PER_ELEMENT",
    "PER_MASS",
    "Field",
    "SCHEMA",
    "FIELDS_BY_NAME",
    "PER_MASS_LISTS",
    "per_mass_values",
    "drop_per_mass",
    "edit_per_mass",
    "GAIN_NAMES",
    "DISPLAYS",
    "walk",
    "path_of",
    "GRASP_SETS",
    "RENDERABLE",
    "MAX_GRID_POINTS",
    "MULTIDOF",
    "LINKAGE_KINDS",
    "WALL_KINDS",
]

#: ``Field.length``: one value per mass (``n``) or per element (``n - 1``).
PER_MASS = "one per mass"
PER_ELEMENT = "one per element"

#: The two display types (section III impedance display, section IV admittance display).
DISPLAYS = ("impedance", "admittance")
#: The API names of the couplings' and PD loop's gains (:class:`Profile` fields), in file order.
GAIN_NAMES = ("kc", "bc", "mc", "bc_adm", "kp", "kd")

_KINDS = ("object", "section", "number", "numbers", "integer", "string", "choice", "choices")


@dataclass(frozen=True)
class Field:
    """One key of a profile file; its JSON path is the keys above it in :data:`SCHEMA`.

    Parameters
    ----------
    key : str
        The JSON key in the enclosing object.
    kind : str
        ``object`` (its ``children`` are the only keys allowed), ``section`` (validated by its
        settings record; ``children`` declare only the keys the profile checks across sections),
        ``number``, ``numbers`` (a list), ``integer``, ``string``, ``choice`` (one of ``options``) or
        ``choices`` (a non-empty list of ``options``, each once).
    name : str or None
        The API's name of the value (the ``field`` of a ValidationError raised for it).
    rule : Limit or Real or None
        The number rule: type, range and unit.
    required : bool
        The key must be present.
    nonempty : bool
        A string with a non-blank character.
    length : str or None
        :data:`PER_MASS` or :data:`PER_ELEMENT` for a list whose length follows the device.
    empty_ok : bool
        Such a list may also be empty (no friction).
    options : tuple of str
        The values a ``choice`` allows.
    children : tuple of Field
        The keys inside an ``object`` or ``section``.
    blamed_for : tuple of str
        Other API names reported at this key (a work limit that follows from it).
    """

    key: str
    kind: str
    name: str | None = None
    rule: Limit | Real | None = None
    required: bool = True
    nonempty: bool = False
    length: str | None = None
    empty_ok: bool = False
    options: tuple[str, ...] = ()
    children: tuple[Field, ...] = ()
    blamed_for: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in _KINDS:
            raise ValueError(f"unknown kind {self.kind!r}")

    @property
    def keys(self) -> tuple[str, ...]:
        """The keys of the children (the keys an ``object`` allows)."""
        return tuple(c.key for c in self.children)

    def child(self, key: str) -> Field:
        """The child declared under ``key``.

        Parameters
        ----------
        key : str
            A JSON key inside this object.

        Returns
        -------
        Field
            Its declaration.

        Raises
        ------
        KeyError
            When no child has that key.
        """
        for c in self.children:
            if c.key == key:
                return c
        raise KeyError(key)

    @property
    def range_text(self) -> str:
        """The allowed range and unit of the rule (``""`` without a rule)."""
        return "" if self.rule is None else self.rule.text

    def count(self, n: int | None) -> int | None:
        """The length a list must have on a device of ``n`` masses.

        Parameters
        ----------
        n : int or None
            The device's number of masses (``None``: not known yet).

        Returns
        -------
        int or None
            ``n`` or ``n - 1``; ``None`` for a list of any length.
        """
        if n is None or self.length is None:
            return None
        return n if self.length == PER_MASS else n - 1

    def expected(self, n: int | None = None) -> str:
        """What belongs at this key, as an error says it (kind, length, range and unit).

        Parameters
        ----------
        n : int or None
            The device's number of masses, for a list whose length follows it.

        Returns
        -------
        str
            E.g. ``"a number > 0 and finite, within the physical range [1e-06, 1] (s)"``.
        """
        if self.kind == "number":
            return f"a number {self.range_text}".rstrip()
        if self.kind == "numbers":
            count = self.count(n)
            if count is None:
                text = "a list of numbers"
            else:
                per = f"{self.length}, {n} mass{'es' if n != 1 else ''}"
                text = f"a list of exactly {count} value{'s' if count != 1 else ''} ({per})"
            text += f", each {self.range_text}" if self.range_text else ""
            return text + (", or an empty list" if self.empty_ok else "")
        if self.kind == "integer":
            return "an integer"
        if self.kind == "string":
            return "a non-empty string" if self.nonempty else "a string"
        if self.kind == "choice":
            return " or ".join(f'"{o}"' for o in self.options)
        if self.kind == "choices":
            return "a non-empty list of " + ", ".join(f'"{o}"' for o in self.options) + ", each at most once"
        return "a JSON object"


def _number(key: str, name: str, rule: Limit | Real, required: bool = True) -> Field:
    return Field(key, "number", name=name, rule=rule, required=required)


def _numbers(key: str, name: str, rule: Limit, length: str | None, required: bool = True) -> Field:
    return Field(key, "numbers", name=name, rule=rule, length=length, required=required)


#: The loader's rule for ``band.min`` (the device's own check adds the Nyquist frequency of its T).
BAND_RULE = Real(lo=BAND_MIN.lo, report_float=True,
                 allowed=f"> 0 and below Nyquist pi/T, within the physical range [{BAND_MIN.lo:g}, pi/T) "
                         f"({BAND_MIN.unit})",
                 not_real=f"a real number > 0 and below Nyquist pi/T ({BAND_MIN.unit})")

def _pair(key: str, prefix: str, rule: Real, required: bool = False) -> Field:
    """``{"min": ..., "max": ..., "points": ...}`` of a grid axis, each declared under ``prefix_*``."""
    return Field(key, "object", required=required, children=(
        _number("min", f"{prefix}_min", rule, required=False),
        _number("max", f"{prefix}_max", rule, required=False),
        Field("points", "integer", name=f"{prefix}_points", rule=_POINTS, required=False)))


#: The largest number of values of each axis of the renderable space's grid.
MAX_GRID_POINTS = 201
_POINTS = Real(lo=2, hi=MAX_GRID_POINTS, unit="")
#: The grasp sets of the ``stable`` quality (``$.renderable.qualities.grasps``), by name; the records
#: themselves are :mod:`analysis.sampled.terminations`' (hands-off, firm, rigid grasp).
GRASP_SETS = {"hands_off": "hands-off only", "firm": "hands-off and a firm grasp",
              "all": "hands-off, a firm and a rigid grasp"}
#: A virtual mass or damping: either sign, within the physical range of masses and dampings.
_VIRTUAL_MASS = Real(lo=-MASS.hi, hi=MASS.hi, unit="kg", not_real="a real number")
_VIRTUAL_DAMPING = Real(lo=-DAMPING.hi, hi=DAMPING.hi, unit="N s/m", not_real="a real number")

#: The optional ``renderable`` section (schema 6, issue 24): the rendered environment
#: ``F = M a^ + B v^ + K x``, its acceleration estimate, the qualities and their settings, and the
#: (M, B) grid of the renderable space.  Each number's API name is the field of
#: :class:`analysis.profiles.renderable.RenderableSection` that holds it.
RENDERABLE = Field("renderable", "section", name="renderable", required=False, children=(
    Field("environment", "object", required=False, children=(
        _number("mass", "virtual_mass", _VIRTUAL_MASS, required=False),
        _number("damping", "virtual_damping", _VIRTUAL_DAMPING, required=False),
        _number("stiffness", "virtual_stiffness", Real(lo=0.0, hi=STIFFNESS.hi, unit="N/m"), required=False),
    )),
    Field("acceleration", "object", required=False, children=(
        Field("kind", "choice", name="acceleration_kind", options=tuple(ACCELERATION_KINDS), required=False),
        Field("lowpass", "choice", name="acceleration_lowpass", options=tuple(LOWPASS_KINDS), required=False),
        _number("cutoff", "acceleration_cutoff", Real(lo=0.0, lo_open=True, allow_inf=True, unit="rad/s"),
                required=False),
    )),
    Field("qualities", "object", required=False, children=(
        Field("names", "choices", name="qualities", options=tuple(QUALITIES), required=False),
        Field("grasps", "choice", name="grasps", options=tuple(GRASP_SETS), required=False),
        Field("band", "object", required=False, children=(
            _number("min", "band_low", Real(lo=0.0, lo_open=True, unit="rad/s"), required=False),
            _number("max", "band_high", Real(lo=0.0, lo_open=True, unit="rad/s"), required=False))),
        _number("tolerance", "tolerance", Real(lo=0.0, lo_open=True, hi=10.0, unit=""), required=False),
        _number("encoder_resolution", "quiet_resolution", ENCODER_RESOLUTION, required=False),
        _number("force_noise", "quiet_force_noise", FORCE_NOISE, required=False),
    )),
    Field("grid", "object", required=False, children=(
        _pair("mass", "mass", _VIRTUAL_MASS), _pair("damping", "damping", _VIRTUAL_DAMPING))),
))

#: The linkages of the ``multidof`` section (``$.multidof.linkage.kind``): the planar five-bar
#: (:class:`analysis.transparency.five_bar.FiveBar`) for now.
LINKAGE_KINDS = {"five_bar": "planar five-bar"}
#: The walls of the ``multidof`` section (``$.multidof.wall.kind``): isotropic ``K I``, or a plane wall
#: ``K n n^T`` with the normal ``$.multidof.wall.normal``.
WALL_KINDS = {"isotropic": "isotropic wall (K I)", "normal": "plane wall along a normal (K n nᵀ)"}
_LENGTH = Real(lo=0.0, lo_open=True, hi=10.0, unit="m")
_COORDINATE = Real(lo=-10.0, hi=10.0, unit="m")
_LINK_MASS = Real(lo=0.0, hi=MASS.hi, unit="kg")

#: The optional ``multidof`` section (schema 7, issue 25): the linkage (a planar five-bar: link lengths,
#: base, masses, rotor inertia, joint friction), the handle's position, the wall (isotropic or along a
#: normal, with its damping) and the workspace map's grid.  Each number's API name is the field of
#: :class:`analysis.profiles.multidof.MultiDofSection` that holds it.
MULTIDOF = Field("multidof", "section", name="multidof", required=False, children=(
    Field("linkage", "object", required=False, children=(
        Field("kind", "choice", name="linkage_kind", options=tuple(LINKAGE_KINDS), required=False),
        _number("l1", "l1", _LENGTH, required=False),
        _number("l2", "l2", _LENGTH, required=False),
        _number("base", "base", Real(lo=0.0, hi=10.0, unit="m"), required=False),
        Field("proximal_masses", "numbers", name="proximal_masses", rule=_LINK_MASS, required=False),
        Field("distal_masses", "numbers", name="distal_masses", rule=_LINK_MASS, required=False),
        _number("handle_mass", "handle_mass", _LINK_MASS, required=False),
        _number("rotor_inertia", "rotor_inertia", Real(lo=0.0, hi=1e3, unit="kg m^2"), required=False),
        _number("joint_damping", "joint_damping", Real(lo=0.0, hi=1e6, unit="N m s/rad"), required=False),
    )),
    Field("handle", "object", name="handle", required=False, children=(
        _number("x", "handle_x", _COORDINATE, required=False),
        _number("y", "handle_y", _COORDINATE, required=False),
    )),
    Field("wall", "object", required=False, children=(
        Field("kind", "choice", name="wall_kind", options=tuple(WALL_KINDS), required=False),
        Field("normal", "numbers", name="wall_normal", rule=Real(lo=-1e6, hi=1e6, unit=""), required=False),
        _number("damping", "wall_damping", Real(lo=0.0, hi=DAMPING.hi, unit="N s/m"), required=False),
    )),
    Field("map", "object", required=False, children=(_pair("x", "x", _COORDINATE), _pair("y", "y", _COORDINATE))),
))

#: The profile file (schema :data:`analysis.profiles.SCHEMA_VERSION`).
SCHEMA = Field("$", "object", children=(
    Field("schema_version", "integer"),
    Field("name", "string", name="name", nonempty=True),
    Field("notes", "string", name="notes", required=False),
    Field("device", "object", name="device", children=(
        _numbers("masses", "masses", MASS, None),
        _numbers("stiffnesses", "stiffnesses", STIFFNESS, PER_ELEMENT),
        _numbers("dampings", "dampings", LIMITS["dampings"], PER_ELEMENT, required=False),
        _numbers("damping_ratios", "damping_ratios", DAMPING_RATIO, PER_ELEMENT, required=False),
        _numbers("ground_dampings", "ground_dampings", GROUND_DAMPING, PER_MASS, required=False),
        Field("sensor_element", "integer", name="sensor_element", required=False),
    )),
    _number("sample_time", "sample_time", SAMPLE_TIME),
    Field("band", "object", required=False, children=(_number("min", "band_min", BAND_RULE),)),
    Field("display", "choice", name="display", options=DISPLAYS),
    Field("impedance_coupling", "object", children=(
        _number("stiffness", "kc", LIMITS["kc"]), _number("damping", "bc", LIMITS["bc"]))),
    Field("admittance_coupling", "object", children=(
        _number("mass", "mc", LIMITS["mc"]), _number("damping", "bc_adm", LIMITS["bc_adm"]))),
    Field("pd_gains", "object", children=(
        _number("stiffness", "kp", LIMITS["kp"]), _number("damping", "kd", LIMITS["kd"]))),
    Field("wall", "section", name="wall", required=False),
    Field("observer", "section", name="observer", required=False),
    Field("simulation", "section", name="simulation", required=False, children=(
        Field("options", "section", required=False, children=(
            Field("friction", "numbers", name="friction", length=PER_MASS, empty_ok=True,
                  rule=Real(lo=0.0, unit="N")),
        )),
        Field("scenario", "section", required=False, children=(
            Field("duration", "number", name="duration", blamed_for=("simulation steps", "simulation values")),
        )),
    )),
    Field("identification", "section", name="identification", required=False),
    Field("controller", "section", name="controller", required=False, children=(
        Field("velocity_filter", "section", required=False, children=(Field("cutoff", "number", name="cutoff"),)),
    )),
    RENDERABLE,
    MULTIDOF,
))


def walk(node: Field = SCHEMA, path: str = "$") -> Iterator[tuple[str, Field]]:
    """Every field below ``node`` with its JSON path (``$.device.masses``), depth first."""
    for c in node.children:
        where = f"{path}.{c.key}"
        yield where, c
        yield from walk(c, where)


def _by_name() -> dict[str, tuple[str, Field]]:
    out: dict[str, tuple[str, Field]] = {}
    for path, node in walk():
        for name in (node.name, *node.blamed_for):
            if name is not None:
                if name in out:
                    raise ValueError(f"the API name {name!r} is declared twice in the profile schema")
                out[name] = (path, node)
    return out


#: API name (a ValidationError's ``field``) -> (JSON path, field), derived from :data:`SCHEMA`.
FIELDS_BY_NAME: dict[str, tuple[str, Field]] = _by_name()

def _per_mass_lists() -> tuple[tuple[str, Field], ...]:
    out = tuple((path, node) for path, node in walk() if node.length == PER_MASS and not path.startswith("$.device."))
    for path, node in out:
        if not node.empty_ok:  # a profile whose chain changes order must be able to drop it
            raise ValueError(f"the per-mass list {path} inside a section must allow an empty list")
        if node.name is None:  # a Profile's refusal names it, and error_at maps the name to the path
            raise ValueError(f"the per-mass list {path} inside a section must declare its API name")
    return out


#: The per-mass lists inside the optional sections, by JSON path (the device's own are read with it).
#: This is the one list of them: the loader checks each against the device's masses
#: (:mod:`analysis.profiles.fields`), and a profile given a chain of another order drops each that
#: no longer fits (:func:`drop_per_mass`).  A path without its ``$`` is
#: also the chain of attributes that holds the list on a :class:`~analysis.profiles.Profile`
#: (``$.simulation.options.friction``: ``profile.simulation.options.friction``), and each allows an
#: empty list (none: no friction), so that it can always be dropped.
PER_MASS_LISTS: tuple[tuple[str, Field], ...] = _per_mass_lists()


def path_of(name: str) -> str | None:
    """The JSON path of the value the API calls ``name``.

    Parameters
    ----------
    name : str
        A Device or Profile field (``"kc"``) or another name declared in :data:`SCHEMA`.

    Returns
    -------
    str or None
        E.g. ``"$.impedance_coupling.stiffness"``; ``None`` for a name the schema does not declare.
    """
    found = FIELDS_BY_NAME.get(name)
    return None if found is None else found[0]


def per_mass_values(record: object) -> dict[str, tuple[float, ...]]:
    """The per-mass lists a profile holds (:data:`~analysis.profiles.schema.PER_MASS_LISTS`), by JSON path.

    Parameters
    ----------
    record : object
        A :class:`~analysis.profiles.Profile` (any record whose attributes follow the schema's keys).

    Returns
    -------
    dict of str to tuple of float
        JSON path (``"$.simulation.options.friction"``) -> the list's values, for each list whose
        section is present (an empty tuple: the list is empty).
    """
    out: dict[str, tuple[float, ...]] = {}
    for path, _ in PER_MASS_LISTS:
        value: Any = record
        for key in path.split(".")[1:]:
            value = getattr(value, key, None)
            if value is None:
                break
        if value is not None:
            out[path] = tuple(float(v) for v in value)
    return out


def _replaced(obj: Any, keys: list[str], value: object) -> Any:
    """``obj`` with the attribute at the chain ``keys`` set to ``value`` (each record validated again)."""
    if not keys:
        return value
    return dataclasses.replace(obj, **{keys[0]: _replaced(getattr(obj, keys[0]), keys[1:], value)})


def drop_per_mass(record: object, n: int) -> tuple[dict[str, Any], dict[str, tuple[float, ...]]]:
    """The changes that empty every per-mass list of ``record`` that does not hold ``n`` values.

    A list indexed by mass belongs to the chain it was set for: on a chain of another order its
    values would sit on other masses, so it is dropped (an empty list: none, e.g. no friction)
    rather than stretched.  Apply the changes with the new device,
    ``profile.replace(device=new, **changes)``: the loader refuses a per-mass list of another
    length than the device's masses.

    Parameters
    ----------
    record : object
        A :class:`~analysis.profiles.Profile` before its device changes.
    n : int
        The number of masses of the new device.

    Returns
    -------
    changes : dict of str to object
        Profile field -> its new value (e.g. ``{"simulation": SimulationSection}``); empty when
        every list already fits.
    dropped : dict of str to tuple of float
        JSON path -> the values dropped there.
    """
    return edit_per_mass(record, lambda values: () if values and len(values) != n else values)


def edit_per_mass(record: object, edit: Callable[[tuple[float, ...]], tuple[float, ...]]
                  ) -> tuple[dict[str, Any], dict[str, tuple[float, ...]]]:
    """The changes that replace each per-mass list of ``record`` (:data:`PER_MASS_LISTS`) by ``edit``
    of its values; :func:`drop_per_mass` and :func:`analysis.profiles.per_mass_changes` are two such
    edits.

    Parameters
    ----------
    record : object
        A :class:`~analysis.profiles.Profile` (its lists read by :func:`per_mass_values`).
    edit : callable
        The list's values -> its new values (the same values: unchanged).

    Returns
    -------
    changes : dict of str to object
        Profile field -> its new value (each section rebuilt, so validated again); empty when no
        list changes.
    old : dict of str to tuple of float
        JSON path -> the values replaced there.
    """
    changes: dict[str, Any] = {}
    old: dict[str, tuple[float, ...]] = {}
    for path, values in per_mass_values(record).items():
        new = tuple(float(v) for v in edit(values))
        if new == values:
            continue
        top, *rest = path.split(".")[1:]
        changes[top] = _replaced(changes.get(top, getattr(record, top)), rest, new)
        old[path] = values
    return changes, old
