"""Checking the fields of a current-schema profile dict and building the :class:`Profile`.

The top level and the device are read by their declarations in :data:`~analysis.profiles.schema.SCHEMA`
(type, range, unit; the JSON path is where the declaration sits).  Every check reports a
:class:`ProfileError` at the JSON path of the offending value; a
:class:`~analysis.errors.ValidationError` from :class:`Device` or :class:`Profile` is reported at
the path of the field that declares its name (:func:`error_at`).  Lists indexed by mass inside the
sections (the simulator's friction) are checked against the device's masses.  Older schema
versions are migrated first, by :func:`analysis.profiles.io.migrate`.

Nothing is built before every value has been read, so a failed load leaves nothing half-applied.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

from collections.abc import Mapping

from analysis.chain.device import Device
from analysis.chain.limits import Limit
from analysis.errors import ValidationError
from analysis.profiles.controller import parse_controller
from analysis.profiles.errors import MISSING, ProfileError
from analysis.profiles.identification import parse_identification
from analysis.profiles.model import Profile
from analysis.profiles.multidof import parse_multidof
from analysis.profiles.renderable import parse_renderable
from analysis.profiles.schema import GAIN_NAMES, PER_MASS_LISTS, SCHEMA, FIELDS_BY_NAME, Field
from analysis.profiles.sections import parse_sections

__all__ = ["error_at", "profile_from_current"]

_DEVICE = SCHEMA.child("device")
_PAIRS = tuple(node for node in SCHEMA.children if node.children and {c.name for c in node.children} <= set(GAIN_NAMES))


def error_at(err: ValidationError, rename: Mapping[str, str] | None = None) -> ProfileError:
    """A ValidationError of :class:`Device` or :class:`Profile` as a :class:`ProfileError` at the
    JSON path of the field that declares its name in :data:`~analysis.profiles.schema.SCHEMA`.

    Parameters
    ----------
    err : ValidationError
        The refusal (its ``field`` and ``index`` locate the value, ``allowed`` is its range).
    rename : Mapping or None
        API name -> declared name, e.g. ``{"dampings": "damping_ratios"}`` when the device's
        element dampings came from the file's damping ratios.

    Returns
    -------
    ProfileError
        At the declared path (``[index]`` appended), or at ``$`` naming the field when the schema
        does not declare it; ``err`` is its cause.
    """
    name = (rename or {}).get(err.field, err.field)
    path, node = FIELDS_BY_NAME.get(name, ("$", None))
    expected = err.allowed
    if node is None:  # a name the schema does not declare: the profile as a whole, named
        expected = f"{err.field} {expected}"
    elif err.index is not None:
        path += f"[{err.index}]"
    if node is not None and name == node.name and node.kind in ("number", "numbers") and not expected.startswith(
            ("a ", "an ", "exactly", "at least", "at most")):
        expected = "a number " + expected
    out = ProfileError.at(path, expected, err.value)
    out.__cause__ = err
    return out


def _get(obj: Mapping, node: Field, jp: str, n: int | None = None, default: object = MISSING) -> object:
    """The value of ``node`` in ``obj`` (at ``jp``), ``default`` if absent, else a missing-key error."""
    if node.key in obj:
        return obj[node.key]
    if default is MISSING or node.required:
        raise ProfileError.at(f"{jp}.{node.key}", node.expected(n), MISSING)
    return default


def _object(value: object, jp: str, node: Field) -> Mapping:
    if not isinstance(value, Mapping):
        raise ProfileError.at(jp, node.expected(), value)
    allowed = sorted(node.keys)
    for key in value:
        if key not in allowed:
            name = key if isinstance(key, str) else repr(key)
            raise ProfileError(f"unknown key (allowed: {', '.join(allowed)})", json_path=f"{jp}.{name}",
                               expected="one of " + ", ".join(allowed))
    return value


def _number(value: object, jp: str, node: Field) -> float:
    """A real number passing the field's rule (its physical range, :mod:`analysis.chain.limits`)."""
    rule = node.rule.rule if isinstance(node.rule, Limit) else node.rule
    try:
        return rule(jp, value)
    except ValidationError as err:
        raise ProfileError.at(jp, node.expected(), err.value) from None


def _numbers(value: object, jp: str, node: Field, n: int | None) -> list[float]:
    if not isinstance(value, list):
        raise ProfileError.at(jp, node.expected(n), value)
    count = node.count(n)
    if count is not None and len(value) != count:
        raise ProfileError.at(jp, node.expected(n), value)
    item = Field(node.key, "number", rule=node.rule)
    return [_number(v, f"{jp}[{i}]", item) for i, v in enumerate(value)]


def _string(value: object, jp: str, node: Field) -> str:
    if not isinstance(value, str) or (node.nonempty and not value.strip()):
        raise ProfileError.at(jp, node.expected(), value)
    return value


def _chain(dev: Mapping) -> tuple[list[float], list[float], str, list[float], list[float]]:
    """Masses, stiffnesses, the damping key and its values, and the ground dampings of ``$.device``."""
    jp = "$.device"
    masses_node = _DEVICE.child("masses")
    masses = _numbers(_get(dev, masses_node, jp), f"{jp}.masses", masses_node, None)
    if not masses:
        raise ProfileError.at(f"{jp}.masses", f"a list of at least one mass {masses_node.range_text}", [])
    n = len(masses)
    node = _DEVICE.child("stiffnesses")
    stiffnesses = _numbers(_get(dev, node, jp, n), f"{jp}.stiffnesses", node, n)
    has_b, has_r = "dampings" in dev, "damping_ratios" in dev
    if has_b == has_r:
        raise ProfileError(
            "give exactly one of 'dampings' and 'damping_ratios'"
            + (" (both are present)" if has_b else " (neither is present)"),
            json_path=jp,
            expected="exactly one of dampings, damping_ratios",
        )
    damping_key = "dampings" if has_b else "damping_ratios"
    node = _DEVICE.child(damping_key)
    values = _numbers(dev[damping_key], f"{jp}.{damping_key}", node, n)
    node = _DEVICE.child("ground_dampings")
    ground = _numbers(_get(dev, node, jp, n, [0.0] * n), f"{jp}.ground_dampings", node, n)
    return masses, stiffnesses, damping_key, values, ground


def _device(data: Mapping) -> Device:
    dev = _object(_get(data, _DEVICE, "$"), "$.device", _DEVICE)
    masses, stiffnesses, damping_key, values, ground = _chain(dev)
    n = len(masses)
    sensor = _get(dev, _DEVICE.child("sensor_element"), "$.device", n, 0)
    if isinstance(sensor, bool) or not isinstance(sensor, int):
        raise ProfileError.at("$.device.sensor_element", f"an integer in [0, {max(n - 2, 0)}]", sensor)
    sample_time = _number(_get(data, SCHEMA.child("sample_time"), "$"), "$.sample_time", SCHEMA.child("sample_time"))
    band_node = SCHEMA.child("band")
    band = _object(_get(data, band_node, "$", default={"min": 1.0}), "$.band", band_node)
    min_node = band_node.child("min")
    band_min = _number(_get(band, min_node, "$.band"), "$.band.min", min_node)
    kwargs = {"ground_dampings": ground, "sensor_element": sensor, "sample_time": sample_time,
              "band_min": band_min}
    try:
        if damping_key == "dampings":
            return Device(masses=masses, stiffnesses=stiffnesses, dampings=values, **kwargs)
        return Device.from_damping_ratios(masses, stiffnesses, values, **kwargs)
    except ValidationError as err:
        raise error_at(err, {"dampings": damping_key}) from err


def _gains(data: Mapping) -> dict[str, float]:
    """The couplings' and the PD loop's gains by their :class:`Profile` names."""
    out: dict[str, float] = {}
    for pair in _PAIRS:
        jp = f"$.{pair.key}"
        obj = _object(_get(data, pair, "$"), jp, pair)
        for node in pair.children:
            out[node.name] = _number(_get(obj, node, jp), f"{jp}.{node.key}", node)
    return {name: out[name] for name in GAIN_NAMES}


def _check_per_mass(data: Mapping, n: int) -> None:
    """Every list indexed by mass inside the sections (:data:`~analysis.profiles.schema.PER_MASS_LISTS`)
    has one value per mass of the device (or none, where the schema allows an empty list)."""
    for path, node in PER_MASS_LISTS:
        value: object = data
        for key in path.split(".")[1:]:
            value = value.get(key, MISSING) if isinstance(value, Mapping) else MISSING
        if isinstance(value, list) and len(value) != n and not (node.empty_ok and not value):
            raise ProfileError.at(path, node.expected(n), value)


def profile_from_current(data: Mapping) -> Profile:
    """The :class:`Profile` of a dict already migrated to the current schema version.

    Parameters
    ----------
    data : Mapping
        The parsed profile (schema :data:`~analysis.profiles.SCHEMA_VERSION`); not modified.

    Returns
    -------
    Profile
        Built only after every value has been read and checked.

    Raises
    ------
    ProfileError
        At the JSON path of the first offending value, naming the allowed range and unit.
    """
    _object(data, "$", SCHEMA)
    name = _string(_get(data, SCHEMA.child("name"), "$"), "$.name", SCHEMA.child("name"))
    notes = _string(_get(data, SCHEMA.child("notes"), "$", default=""), "$.notes", SCHEMA.child("notes"))
    device = _device(data)
    display_node = SCHEMA.child("display")
    display = _get(data, display_node, "$")
    if not isinstance(display, str) or display not in display_node.options:
        raise ProfileError.at("$.display", display_node.expected(), display)
    gains = _gains(data)
    sections = parse_sections(data)
    if "identification" in data:
        sections["identification"] = parse_identification(data["identification"])
    if "controller" in data:
        sections["controller"] = parse_controller(data["controller"])
    if "renderable" in data:
        sections["renderable"] = parse_renderable(data["renderable"])
    if "multidof" in data:
        sections["multidof"] = parse_multidof(data["multidof"])
    _check_per_mass(data, device.n)
    try:
        return Profile(name=name, notes=notes, device=device, display=display, **gains, **sections)
    except ValidationError as err:
        raise error_at(err) from err
