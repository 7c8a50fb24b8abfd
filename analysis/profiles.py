"""Device profiles: a device, its sample period and band, and the controller settings, as JSON.

A profile file looks like this (schema version 3; the optional sections ``wall``,
``observer`` (schema 2) and ``simulation`` (schema 3) are described in
:mod:`analysis.profile_sections`)::

    {"schema_version": 3, "name": "HBFD", "notes": "...",
     "device": {"masses": [...], "stiffnesses": [...], "dampings": [...],
                "ground_dampings": [...], "sensor_element": 0},
     "sample_time": 0.001, "band": {"min": 1.0},
     "display": "impedance",
     "impedance_coupling": {"stiffness": 50000.0, "damping": 100.0},
     "admittance_coupling": {"mass": 8.0, "damping": 400.0},
     "pd_gains": {"stiffness": 50000.0, "damping": 100.0}}

``device`` gives either ``dampings`` (N s/m) or ``damping_ratios`` (eq. 28 with the reduced
mass), exactly one of them.  ``notes``, ``ground_dampings`` (default zeros),
``sensor_element`` (default 0) and ``band`` (default ``{"min": 1.0}``) are optional.  Unknown
keys are rejected, so that a misspelt key is not silently ignored.

Every problem with a file is reported as a :class:`ProfileError` naming the file and the JSON
path of the offending value, e.g. ``hbfd.json: $.device.masses[2]: expected a number > 0 and
finite, got -1.0``.  Older schema versions are brought up to date by :data:`MIGRATIONS`.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import os
import stat
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .device import Device
from .observer import ObserverSettings
from .profile_sections import MIGRATION_STEPS, SECTION_KEYS, SimulationSection, parse_sections, sections_to_dict
from .wall import WallSettings
from .errors import ValidationError
from .resources import resource_path

__all__ = [
    "DISPLAYS",
    "MIGRATIONS",
    "SCHEMA_VERSION",
    "Profile",
    "ProfileError",
    "bundled_profiles",
    "load_profile",
    "migrate",
    "profile_from_dict",
    "profile_to_dict",
    "save_profile",
]

#: Schema version written by :func:`save_profile` and the newest one :func:`load_profile` reads.
SCHEMA_VERSION = 3

#: ``MIGRATIONS[v]`` turns a schema-``v`` profile dict into a schema-``v + 1`` one.
MIGRATIONS: dict[int, Callable[[dict], dict]] = dict(MIGRATION_STEPS)

#: The two display types (section III impedance display, section IV admittance display).
DISPLAYS = ("impedance", "admittance")

_MISSING = object()


# -- errors -------------------------------------------------------------------------------------


class ProfileError(ValueError):
    """A profile file or dict cannot be used.

    Attributes
    ----------
    path:
        The file (as given), or ``None`` for a dict that did not come from a file.
    json_path:
        Location of the offending value, e.g. ``"$.device.masses[2]"``; ``None`` when the
        problem is the file as a whole (unreadable, not JSON).
    expected:
        What was expected there, e.g. ``"a number > 0 and finite"``.
    reason:
        The message without the file and JSON path prefixes.
    """

    def __init__(
        self,
        reason: str,
        *,
        path: str | os.PathLike | None = None,
        json_path: str | None = None,
        expected: str | None = None,
    ):
        self.reason = reason
        self.path = None if path is None else os.fspath(path)
        self.json_path = json_path
        self.expected = expected
        prefix = "".join(f"{part}: " for part in (self.path, json_path) if part)
        super().__init__(prefix + reason)

    @classmethod
    def at(cls, json_path: str, expected: str, got: object = _MISSING) -> ProfileError:
        """``$.x: expected <expected>, got <value>`` (``missing`` when the key is absent)."""
        return cls(f"expected {expected}, got {_describe(got)}", json_path=json_path, expected=expected)

    def with_path(self, path: str | os.PathLike | None) -> ProfileError:
        """The same error attributed to file ``path``."""
        if path is None or self.path is not None:
            return self
        err = ProfileError(self.reason, path=path, json_path=self.json_path, expected=self.expected)
        err.__cause__ = self.__cause__
        return err


class _NonFinite:
    """Stands for a NaN / Infinity literal in the JSON text; rejected wherever it appears."""

    __slots__ = ("literal",)

    def __init__(self, literal: str):
        self.literal = literal

    def __repr__(self) -> str:
        return self.literal


class _DuplicateKey(Exception):
    pass


def _describe(value: object) -> str:
    """A short JSON-flavoured description of a rejected value."""
    if value is _MISSING:
        return "nothing (the key is missing)"
    if isinstance(value, _NonFinite):
        return f"{value.literal} (NaN and Infinity are not allowed)"
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, np.integer, np.floating)):
        text = repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))
        return text if len(text) <= 40 else text[:37] + "..."
    if isinstance(value, str):
        shown = value if len(value) <= 40 else value[:37] + "..."
        return f"the string {json.dumps(shown)}"
    if isinstance(value, (list, tuple)):
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}"
    if isinstance(value, Mapping):
        return "an object"
    return type(value).__name__


# -- the profile ---------------------------------------------------------------------------------

# Profile field -> (JSON path, allowed range); used for validation and error translation.
_SCALARS: dict[str, tuple[str, str, bool]] = {
    # name: (json path, allowed text, strictly positive)
    "kc": ("$.impedance_coupling.stiffness", ">= 0 and finite (N/m)", False),
    "bc": ("$.impedance_coupling.damping", ">= 0 and finite (N s/m)", False),
    "mc": ("$.admittance_coupling.mass", "> 0 and finite (kg)", True),
    "bc_adm": ("$.admittance_coupling.damping", "> 0 and finite (N s/m)", True),
    "kp": ("$.pd_gains.stiffness", ">= 0 and finite (N/m)", False),
    "kd": ("$.pd_gains.damping", ">= 0 and finite (N s/m)", False),
}


def _is_real(value: object) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_)
    )


@dataclass(frozen=True)
class Profile:
    """A named device with its virtual coupling and PD wall settings.

    Parameters
    ----------
    name, notes:
        Display name and free text (sources, caveats).
    device:
        The device chain, sample period and analysis band.
    display:
        ``"impedance"`` or ``"admittance"``: which display type the GUI starts with.
    kc, bc:
        Impedance-display virtual coupling stiffness (N/m) and damping (N s/m), >= 0.
    mc, bc_adm:
        Admittance-display virtual coupling mass (kg) and damping (N s/m), > 0.
    kp, kd:
        PD position-loop stiffness (N/m) and damping (N s/m) of the admittance display
        (eq. 30), >= 0.
    wall, observer, simulation:
        Optional sections (schema 2 and 3): the wall-controller design (Eom, Suh & Yi),
        the disturbance observer, and the sampled-data simulator's options and scenario.
    """

    name: str
    notes: str
    device: Device
    display: str
    kc: float
    bc: float
    mc: float
    bc_adm: float
    kp: float
    kd: float
    wall: WallSettings | None = None
    observer: ObserverSettings | None = None
    simulation: SimulationSection | None = None

    def __post_init__(self) -> None:
        for field_name, cls in (("wall", WallSettings), ("observer", ObserverSettings),
                                ("simulation", SimulationSection)):
            value = getattr(self, field_name)
            if value is not None and not isinstance(value, cls):
                raise ValidationError(field_name, f"None or {cls.__name__}", value)
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValidationError("name", "a non-empty string", self.name)
        if not isinstance(self.notes, str):
            raise ValidationError("notes", "a string", self.notes)
        if not isinstance(self.device, Device):
            raise ValidationError("device", "a Device", self.device)
        if not isinstance(self.display, str) or self.display not in DISPLAYS:
            raise ValidationError("display", " or ".join(repr(d) for d in DISPLAYS), self.display)
        for field_name, (_, allowed, positive) in _SCALARS.items():
            value = getattr(self, field_name)
            if not _is_real(value):
                raise ValidationError(field_name, "a real number " + allowed, value)
            try:
                x = float(value)
            except OverflowError:
                raise ValidationError(field_name, allowed, value) from None
            if not math.isfinite(x) or (x <= 0 if positive else x < 0):
                raise ValidationError(field_name, allowed, x)
            object.__setattr__(self, field_name, x)

    def replace(self, **changes) -> Profile:
        """A copy with some fields changed, validated again (raises ValidationError)."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise TypeError(f"Profile has no field(s) {', '.join(sorted(unknown))}")
        return dataclasses.replace(self, **changes)


# -- dict -> Profile -----------------------------------------------------------------------------

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
    "name": "$.name",
    "notes": "$.notes",
    "display": "$.display",
    "device": "$.device",
    **{name: jp for name, (jp, _, _) in _SCALARS.items()},
}


def _translate(err: ValidationError, damping_key: str = "dampings") -> ProfileError:
    """A Device/Profile ValidationError as a ProfileError at the matching JSON path."""
    field_name = damping_key if err.field == "dampings" else err.field
    json_path = _FIELD_PATHS.get(field_name, f"$.{field_name}")
    if err.index is not None:
        json_path += f"[{err.index}]"
    expected = err.allowed
    if err.index is not None or err.field in ("sample_time", "band_min", *_SCALARS):
        if not expected.startswith(("a ", "an ", "exactly", "at least")):
            expected = "a number " + expected
    out = ProfileError.at(json_path, expected, err.value)
    out.__cause__ = err
    return out


def _get(obj: Mapping, key: str, jp: str, default: object = _MISSING, expected: str = "a value") -> object:
    if key in obj:
        return obj[key]
    if default is _MISSING:
        raise ProfileError.at(f"{jp}.{key}", expected, _MISSING)
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


def _number(value: object, jp: str, allowed: str, positive: bool | None) -> float:
    """A finite real number; ``positive`` True: > 0, False: >= 0, None: any sign."""
    expected = f"a number {allowed}"
    if not _is_real(value):
        raise ProfileError.at(jp, expected, value)
    try:
        x = float(value)
    except OverflowError:
        raise ProfileError.at(jp, expected, value) from None
    if not math.isfinite(x) or (positive is True and x <= 0) or (positive is False and x < 0):
        raise ProfileError.at(jp, expected, x)
    return x


def _numbers(
    value: object, jp: str, allowed: str, positive: bool, length: int | None, what: str
) -> list[float]:
    if not isinstance(value, list):
        raise ProfileError.at(jp, f"a list of numbers {allowed}", value)
    if length is not None and len(value) != length:
        n = f"{length} value{'s' if length != 1 else ''}"
        raise ProfileError.at(jp, f"a list of exactly {n} ({what})", value)
    return [_number(v, f"{jp}[{i}]", allowed, positive) for i, v in enumerate(value)]


def _string(value: object, jp: str, nonempty: bool = False) -> str:
    if not isinstance(value, str) or (nonempty and not value.strip()):
        raise ProfileError.at(jp, "a non-empty string" if nonempty else "a string", value)
    return value


def _schema_version(data: Mapping) -> int:
    expected = (
        f"the integer schema version {SCHEMA_VERSION}"
        if SCHEMA_VERSION == 1
        else f"an integer schema version from 1 to {SCHEMA_VERSION}"
    )
    if "schema_version" not in data:
        raise ProfileError.at("$.schema_version", expected)
    v = data["schema_version"]
    if isinstance(v, bool) or not isinstance(v, int) or v < 1:
        raise ProfileError.at("$.schema_version", expected, v)
    if v > SCHEMA_VERSION:
        raise ProfileError.at(
            "$.schema_version",
            f"schema version <= {SCHEMA_VERSION} (the file was written by a newer zwidth)",
            v,
        )
    return v


def migrate(data: Mapping) -> dict:
    """Bring a profile dict of any supported schema version up to :data:`SCHEMA_VERSION`.

    Applies ``MIGRATIONS[v]`` for ``v = data["schema_version"], ..., SCHEMA_VERSION - 1``; the
    input is not modified.  Raises ProfileError for a missing, unknown or newer version or a
    failing migration.
    """
    if not isinstance(data, Mapping):
        raise ProfileError.at("$", "a JSON object", data)
    v = _schema_version(data)
    if v == SCHEMA_VERSION:
        return dict(data)
    out = copy.deepcopy(dict(data))
    while v < SCHEMA_VERSION:
        step = MIGRATIONS.get(v)
        if step is None:
            raise ProfileError(
                f"no migration from schema version {v} to {v + 1}", json_path="$.schema_version"
            )
        try:
            out = step(out)
        except ProfileError:
            raise
        except Exception as exc:  # a malformed old file makes the migration fail
            raise ProfileError(
                f"cannot migrate from schema version {v} to {v + 1}: {type(exc).__name__}: {exc}",
                json_path="$",
            ) from exc
        if not isinstance(out, dict):
            raise ProfileError(f"migration from schema version {v} did not return an object", json_path="$")
        v += 1
        out["schema_version"] = v
    return out


def _device(data: Mapping) -> Device:
    dev = _object(_get(data, "device", "$", expected="a JSON object"), "$.device", _DEVICE_KEYS)
    masses = _numbers(
        _get(dev, "masses", "$.device", expected="a list of masses > 0 (kg)"),
        "$.device.masses",
        "> 0 and finite (kg)",
        True,
        None,
        "",
    )
    if not masses:
        raise ProfileError.at("$.device.masses", "a list of at least one mass (kg)", [])
    n = len(masses)
    elements = f"one per element, {n} masses"
    stiffnesses = _numbers(
        _get(dev, "stiffnesses", "$.device", expected=f"a list of {n - 1} stiffnesses (N/m)"),
        "$.device.stiffnesses",
        "> 0 and finite (N/m)",
        True,
        n - 1,
        elements,
    )
    has_b, has_r = "dampings" in dev, "damping_ratios" in dev
    if has_b == has_r:
        raise ProfileError(
            "give exactly one of 'dampings' and 'damping_ratios'"
            + (" (both are present)" if has_b else " (neither is present)"),
            json_path="$.device",
            expected="exactly one of dampings, damping_ratios",
        )
    damping_key = "dampings" if has_b else "damping_ratios"
    allowed = ">= 0 and finite (N s/m)" if has_b else ">= 0 and finite"
    values = _numbers(dev[damping_key], f"$.device.{damping_key}", allowed, False, n - 1, elements)
    ground = _numbers(
        _get(dev, "ground_dampings", "$.device", [0.0] * n),
        "$.device.ground_dampings",
        ">= 0 and finite (N s/m)",
        False,
        n,
        "one per mass",
    )
    sensor = _get(dev, "sensor_element", "$.device", 0)
    if isinstance(sensor, bool) or not isinstance(sensor, int):
        raise ProfileError.at("$.device.sensor_element", f"an integer in [0, {max(n - 2, 0)}]", sensor)
    sample_time = _number(
        _get(data, "sample_time", "$", expected="a number (s)"), "$.sample_time", "> 0 and finite (s)", True
    )
    band = _object(_get(data, "band", "$", {"min": 1.0}), "$.band", {"min"})
    band_min = _number(
        _get(band, "min", "$.band", expected="a number (rad/s)"),
        "$.band.min",
        "> 0 and below Nyquist (rad/s)",
        True,
    )
    kwargs = {
        "ground_dampings": ground,
        "sensor_element": sensor,
        "sample_time": sample_time,
        "band_min": band_min,
    }
    try:
        if has_b:
            return Device(masses=masses, stiffnesses=stiffnesses, dampings=values, **kwargs)
        return Device.from_damping_ratios(masses, stiffnesses, values, **kwargs)
    except ValidationError as err:
        raise _translate(err, damping_key) from err


def _pair(data: Mapping, key: str, names: tuple[str, str]) -> tuple[object, object]:
    obj = _object(_get(data, key, "$", expected="a JSON object"), f"$.{key}", set(names))
    return tuple(_get(obj, name, f"$.{key}", expected="a number") for name in names)


def _build(data: object) -> Profile:
    if not isinstance(data, Mapping):
        raise ProfileError.at("$", "a JSON object", data)
    data = migrate(data)
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
        jp, allowed, positive = _SCALARS[field_name]
        scalars[field_name] = _number(value, jp, allowed, positive)
    sections = parse_sections(data)
    try:
        return Profile(name=name, notes=notes, device=device, display=display, **scalars, **sections)
    except ValidationError as err:
        raise _translate(err) from err


def profile_from_dict(data: object, path: str | os.PathLike | None = None) -> Profile:
    """Validate a parsed profile (any schema version) and build the :class:`Profile`.

    ``path`` is only used in error messages.  Raises :class:`ProfileError` and nothing else.
    """
    try:
        return _build(data)
    except ProfileError as err:
        raise err.with_path(path) from err.__cause__
    except RecursionError:
        raise ProfileError("the data is nested too deeply", path=path) from None
    except Exception as exc:  # noqa: BLE001 - the promise is: ProfileError and nothing else
        raise ProfileError(f"invalid profile ({type(exc).__name__}: {exc})", path=path) from exc


# -- files ---------------------------------------------------------------------------------------


def _reject_duplicates(pairs: list[tuple[str, object]]) -> dict:
    out: dict = {}
    for key, value in pairs:
        if key in out:
            raise _DuplicateKey(key)
        out[key] = value
    return out


def load_profile(path: str | os.PathLike) -> Profile:
    """Read and validate a profile file.  Raises :class:`ProfileError` and nothing else."""
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise ProfileError(f"cannot read the file: {exc.strerror or exc}", path=path) from exc
    except (TypeError, ValueError) as exc:  # not a path at all, or an embedded NUL
        raise ProfileError(f"not a usable file name: {exc}", path=str(path)) from exc
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ProfileError(f"not UTF-8 text (byte {exc.start}): {exc.reason}", path=path) from exc
    try:
        data = json.loads(text, parse_constant=_NonFinite, object_pairs_hook=_reject_duplicates)
    except json.JSONDecodeError as exc:
        raise ProfileError(
            f"invalid JSON at line {exc.lineno}, column {exc.colno}: {exc.msg}",
            path=path,
            expected="valid JSON",
        ) from exc
    except _DuplicateKey as exc:
        raise ProfileError(
            f"invalid JSON: duplicate key {json.dumps(exc.args[0])} in an object", path=path
        ) from None
    except RecursionError:
        raise ProfileError("invalid JSON: nested too deeply", path=path) from None
    except Exception as exc:  # noqa: BLE001
        raise ProfileError(f"invalid JSON ({type(exc).__name__}: {exc})", path=path) from exc
    return profile_from_dict(data, path)


def profile_to_dict(profile: Profile) -> dict:
    """The JSON-ready dict of a profile (current schema, element dampings in N s/m)."""
    dev = profile.device
    return {
        "schema_version": SCHEMA_VERSION,
        "name": profile.name,
        "notes": profile.notes,
        "device": {
            "masses": [float(x) for x in dev.masses],
            "stiffnesses": [float(x) for x in dev.stiffnesses],
            "dampings": [float(x) for x in dev.dampings],
            "ground_dampings": [float(x) for x in dev.ground_dampings],
            "sensor_element": int(dev.sensor_element),
        },
        "sample_time": float(dev.sample_time),
        "band": {"min": float(dev.band_min)},
        "display": profile.display,
        "impedance_coupling": {"stiffness": profile.kc, "damping": profile.bc},
        "admittance_coupling": {"mass": profile.mc, "damping": profile.bc_adm},
        "pd_gains": {"stiffness": profile.kp, "damping": profile.kd},
        **sections_to_dict(profile.wall, profile.observer, profile.simulation),
    }


def _new_file_mode() -> int:
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def save_profile(profile: Profile, path: str | os.PathLike) -> None:
    """Write ``profile`` to ``path`` atomically.

    The JSON goes to a temporary file in the same directory, which is flushed, fsynced and then
    renamed over ``path``; on any failure the temporary file is removed and an existing file at
    ``path`` is left untouched.  Raises :class:`ProfileError` (with the OSError as its cause).
    """
    try:
        target = Path(os.path.realpath(os.fspath(path)))
    except (TypeError, ValueError) as exc:
        raise ProfileError(f"not a usable file name: {exc}", path=str(path)) from exc
    try:
        text = json.dumps(profile_to_dict(profile), indent=2, allow_nan=False) + "\n"
    except Exception as exc:  # noqa: BLE001
        raise ProfileError(f"cannot save: {type(exc).__name__}: {exc}", path=path) from exc
    tmp_name = None
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        try:
            mode = stat.S_IMODE(os.stat(target).st_mode)
        except FileNotFoundError:
            mode = _new_file_mode()
        os.chmod(tmp_name, mode)
        os.replace(tmp_name, target)
        tmp_name = None
    except Exception as exc:  # noqa: BLE001
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else f"{type(exc).__name__}: {exc}"
        raise ProfileError(f"cannot save: {reason}", path=path) from exc
    finally:
        if tmp_name is not None:
            try:
                os.unlink(tmp_name)
            except OSError:
                pass
    try:  # make the rename itself durable; not possible everywhere
        dir_fd = os.open(target.parent, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    except OSError:
        pass
    finally:
        os.close(dir_fd)


def bundled_profiles() -> dict[str, Path]:
    """The preset profiles shipped in ``resources/profiles``: file stem -> path, sorted by name."""
    try:
        folder = resource_path("profiles")
    except FileNotFoundError:
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.json"))}
