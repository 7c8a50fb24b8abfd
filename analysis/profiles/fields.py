"""Checking the fields of a current-schema profile dict and building the :class:`Profile`.

Every check reports a :class:`ProfileError` at the JSON path of the offending value;
:class:`~analysis.errors.ValidationError` from :class:`Device` or :class:`Profile` is translated
to the matching JSON path.  Older schema versions are migrated first, by
:func:`analysis.profiles.io.migrate`.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import json
from collections.abc import Mapping

from analysis.chain.device import Device
from analysis.chain.limits import GROUND_DAMPING, LIMITS, MASS, SAMPLE_TIME, STIFFNESS, Limit
from analysis.checks import Real
from analysis.errors import ValidationError
from analysis.profiles.errors import MISSING, ProfileError
from analysis.profiles.model import DISPLAYS, SCALAR_FIELDS, Profile
from analysis.profiles.controller import parse_controller
from analysis.profiles.identification import parse_identification
from analysis.profiles.sections import SECTION_KEYS, parse_sections

__all__ = ["profile_from_current"]

_TOP_KEYS = {
    "schema_version",
    "name",
    "notes",
    "device",
    "sample_time",
    "band",
    "display",
    "impedance_coupling",
    "admittance_coupling",
    "pd_gains",
    *SECTION_KEYS,
}
_DEVICE_KEYS = {"masses", "stiffnesses", "dampings", "damping_ratios", "ground_dampings", "sensor_element"}

# Device / Profile field -> JSON path (vector fields get "[i]" appended).
_FIELD_PATHS = {
    "masses": "$.device.masses",
    "stiffnesses": "$.device.stiffnesses",
    "dampings": "$.device.dampings",
    "damping_ratios": "$.device.damping_ratios",
    "ground_dampings": "$.device.ground_dampings",
    "sensor_element": "$.device.sensor_element",
    "sample_time": "$.sample_time",
    "band_min": "$.band.min",
    "simulation steps": "$.simulation.scenario.duration",
    "simulation values": "$.simulation.scenario.duration",
    "name": "$.name",
    "notes": "$.notes",
    "display": "$.display",
    "device": "$.device",
    "cutoff": "$.controller.velocity_filter.cutoff",
    **{name: spec.json_path for name, spec in SCALAR_FIELDS.items()},
}


def _translate(err: ValidationError, damping_key: str = "dampings") -> ProfileError:
    """A Device/Profile ValidationError as a ProfileError at the matching JSON path."""
    field_name = damping_key if err.field == "dampings" else err.field
    json_path = _FIELD_PATHS.get(field_name, f"$.{field_name}")
    if err.index is not None:
        json_path += f"[{err.index}]"
    expected = err.allowed
    if err.index is not None or err.field in ("sample_time", "band_min", *SCALAR_FIELDS):
        if not expected.startswith(("a ", "an ", "exactly", "at least")):
            expected = "a number " + expected
    out = ProfileError.at(json_path, expected, err.value)
    out.__cause__ = err
    return out


def _get(obj: Mapping, key: str, jp: str, default: object = MISSING, expected: str = "a value") -> object:
    if key in obj:
        return obj[key]
    if default is MISSING:
        raise ProfileError.at(f"{jp}.{key}", expected, MISSING)
    return default


def _object(value: object, jp: str, allowed_keys: set[str]) -> Mapping:
    if not isinstance(value, Mapping):
        raise ProfileError.at(jp, "a JSON object", value)
    for key in value:
        if key not in allowed_keys:
            name = key if isinstance(key, str) else repr(key)
            raise ProfileError(
                f"unknown key (allowed: {', '.join(sorted(allowed_keys))})",
                json_path=f"{jp}.{name}",
                expected="one of " + ", ".join(sorted(allowed_keys)),
            )
    return value


def _number(value: object, jp: str, limit: Limit | Real) -> float:
    """A real number passing ``limit`` (the field's physical range, :mod:`analysis.chain.limits`)."""
    rule = limit.rule if isinstance(limit, Limit) else limit
    expected = "a number " + rule.text
    try:
        return rule(jp, value)
    except ValidationError as err:
        raise ProfileError.at(jp, expected, err.value) from None


def _numbers(value: object, jp: str, limit: Limit, length: int | None, what: str) -> list[float]:
    if not isinstance(value, list):
        raise ProfileError.at(jp, f"a list of numbers {limit.text}", value)
    if length is not None and len(value) != length:
        n = f"{length} value{'s' if length != 1 else ''}"
        raise ProfileError.at(jp, f"a list of exactly {n} ({what})", value)
    return [_number(v, f"{jp}[{i}]", limit) for i, v in enumerate(value)]


def _string(value: object, jp: str, nonempty: bool = False) -> str:
    if not isinstance(value, str) or (nonempty and not value.strip()):
        raise ProfileError.at(jp, "a non-empty string" if nonempty else "a string", value)
    return value


def _chain(dev: Mapping) -> tuple[list[float], list[float], str, list[float], list[float]]:
    """Masses, stiffnesses, the damping key and its values, and the ground dampings of ``$.device``."""
    masses = _numbers(_get(dev, "masses", "$.device", expected="a list of masses > 0 (kg)"),
                      "$.device.masses", MASS, None, "")
    if not masses:
        raise ProfileError.at("$.device.masses", "a list of at least one mass (kg)", [])
    n = len(masses)
    elements = f"one per element, {n} masses"
    stiffnesses = _numbers(_get(dev, "stiffnesses", "$.device", expected=f"a list of {n - 1} stiffnesses (N/m)"),
                           "$.device.stiffnesses", STIFFNESS, n - 1, elements)
    has_b, has_r = "dampings" in dev, "damping_ratios" in dev
    if has_b == has_r:
        raise ProfileError(
            "give exactly one of 'dampings' and 'damping_ratios'"
            + (" (both are present)" if has_b else " (neither is present)"),
            json_path="$.device",
            expected="exactly one of dampings, damping_ratios",
        )
    damping_key = "dampings" if has_b else "damping_ratios"
    values = _numbers(dev[damping_key], f"$.device.{damping_key}", LIMITS[damping_key], n - 1, elements)
    ground = _numbers(_get(dev, "ground_dampings", "$.device", [0.0] * n), "$.device.ground_dampings",
                      GROUND_DAMPING, n, "one per mass")
    return masses, stiffnesses, damping_key, values, ground


def _device(data: Mapping) -> Device:
    dev = _object(_get(data, "device", "$", expected="a JSON object"), "$.device", _DEVICE_KEYS)
    masses, stiffnesses, damping_key, values, ground = _chain(dev)
    n = len(masses)
    sensor = _get(dev, "sensor_element", "$.device", 0)
    if isinstance(sensor, bool) or not isinstance(sensor, int):
        raise ProfileError.at("$.device.sensor_element", f"an integer in [0, {max(n - 2, 0)}]", sensor)
    sample_time = _number(_get(data, "sample_time", "$", expected="a number (s)"), "$.sample_time", SAMPLE_TIME)
    band = _object(_get(data, "band", "$", {"min": 1.0}), "$.band", {"min"})
    band_min = _number(_get(band, "min", "$.band", expected="a number (rad/s)"), "$.band.min",
                       Real(lo=0.0, lo_open=True, allowed="> 0 and below Nyquist (rad/s)", report_float=True))
    kwargs = {
        "ground_dampings": ground,
        "sensor_element": sensor,
        "sample_time": sample_time,
        "band_min": band_min,
    }
    try:
        if damping_key == "dampings":
            return Device(masses=masses, stiffnesses=stiffnesses, dampings=values, **kwargs)
        return Device.from_damping_ratios(masses, stiffnesses, values, **kwargs)
    except ValidationError as err:
        raise _translate(err, damping_key) from err


def _pair(data: Mapping, key: str, names: tuple[str, str]) -> tuple[object, object]:
    obj = _object(_get(data, key, "$", expected="a JSON object"), f"$.{key}", set(names))
    return tuple(_get(obj, name, f"$.{key}", expected="a number") for name in names)


def profile_from_current(data: Mapping) -> Profile:
    """The :class:`Profile` of a dict already migrated to the current schema version.

    Raises :class:`ProfileError` at the JSON path of the first offending value.
    """
    _object(data, "$", _TOP_KEYS)
    name = _string(_get(data, "name", "$", expected="a non-empty string"), "$.name", nonempty=True)
    notes = _string(_get(data, "notes", "$", ""), "$.notes")
    device = _device(data)
    display = _get(data, "display", "$", expected='"impedance" or "admittance"')
    if not isinstance(display, str) or display not in DISPLAYS:
        raise ProfileError.at("$.display", " or ".join(json.dumps(d) for d in DISPLAYS), display)
    kc, bc = _pair(data, "impedance_coupling", ("stiffness", "damping"))
    mc, bc_adm = _pair(data, "admittance_coupling", ("mass", "damping"))
    kp, kd = _pair(data, "pd_gains", ("stiffness", "damping"))
    scalars = {"kc": kc, "bc": bc, "mc": mc, "bc_adm": bc_adm, "kp": kp, "kd": kd}
    for field_name, value in scalars.items():
        spec = SCALAR_FIELDS[field_name]
        scalars[field_name] = _number(value, spec.json_path, spec.limit)
    sections = parse_sections(data)
    if "identification" in data:
        sections["identification"] = parse_identification(data["identification"])
    if "controller" in data:
        sections["controller"] = parse_controller(data["controller"])
    try:
        return Profile(name=name, notes=notes, device=device, display=display, **scalars, **sections)
    except ValidationError as err:
        raise _translate(err) from err
