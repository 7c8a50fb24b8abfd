"""Device profiles: a device, its sample period and band, and the controller settings, as JSON.

A profile file looks like this (schema version 7; the optional sections ``wall``,
``observer`` (schema 2), ``simulation`` (schema 3), ``identification`` (schema 4), ``controller``
(schema 5), ``renderable`` (schema 6) and ``multidof`` (schema 7) are described in
:mod:`analysis.profiles.sections`)::

    {"schema_version": 7, "name": "HBFD", "notes": "...",
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
path of the offending value, e.g. ``hbfd.json: $.device.masses[2] (mass 3): expected a number > 0
and finite, ..., got -1.0``.  Older schema versions are brought up to date by :data:`MIGRATIONS`.

The work is split by what it holds, each module importing only those before it:
:mod:`analysis.profiles.errors` (:class:`ProfileError`), :mod:`analysis.profiles.sections` (the
optional sections and their migrations), :mod:`analysis.profiles.schema` (one declaration of each
field: type, range, unit, and its JSON path by where it sits), :mod:`analysis.profiles.model` (the
:class:`Profile` record), :mod:`analysis.profiles.fields` (reading a current-schema dict by the schema),
:mod:`analysis.profiles.files` (strict JSON reading, atomic writing, bundled presets).  This
module holds the schema version, the migrations and the public entry points, and re-exports the
public names of the others.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import copy
import json
import os
from collections.abc import Callable, Mapping

from analysis.profiles.errors import ProfileError
from analysis.profiles.fields import profile_from_current
from analysis.profiles.files import bundled_profiles, read_json, write_atomically
from analysis.profiles.model import DISPLAYS, Profile
from analysis.profiles.sections import MIGRATION_STEPS, sections_to_dict

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
SCHEMA_VERSION = 7

#: ``MIGRATIONS[v]`` turns a schema-``v`` profile dict into a schema-``v + 1`` one.
MIGRATIONS: dict[int, Callable[[dict], dict]] = dict(MIGRATION_STEPS)


# -- schema versions -----------------------------------------------------------------------------


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
    input is not modified.

    Parameters
    ----------
    data : Mapping
        A parsed profile (a JSON object) with its ``schema_version``.

    Returns
    -------
    dict
        The profile at :data:`SCHEMA_VERSION` (a shallow copy when it already is, a deep copy
        otherwise).

    Raises
    ------
    ProfileError
        For data that is not an object, a missing, invalid or newer schema version, or a
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


# -- dict <-> Profile ----------------------------------------------------------------------------


def _build(data: object) -> Profile:
    if not isinstance(data, Mapping):
        raise ProfileError.at("$", "a JSON object", data)
    return profile_from_current(migrate(data))


def profile_from_dict(data: object, path: str | os.PathLike | None = None) -> Profile:
    """Validate a parsed profile (any schema version) and build the :class:`Profile`.

    Parameters
    ----------
    data : object
        The parsed JSON of a profile.
    path : str or os.PathLike or None, optional
        The file it came from, only used in error messages.

    Returns
    -------
    Profile
        The validated profile.

    Raises
    ------
    ProfileError
        For any problem with ``data`` (and nothing else), naming ``path`` and the JSON path.
    """
    try:
        return _build(data)
    except ProfileError as err:
        raise err.with_path(path) from err.__cause__
    except RecursionError:
        raise ProfileError("the data is nested too deeply", path=path) from None
    except Exception as exc:  # noqa: BLE001 - the promise is: ProfileError and nothing else
        raise ProfileError(f"invalid profile ({type(exc).__name__}: {exc})", path=path) from exc


def profile_to_dict(profile: Profile) -> dict:
    """The JSON-ready dict of a profile (current schema, element dampings in N s/m).

    Parameters
    ----------
    profile : Profile
        The profile.

    Returns
    -------
    dict
        The profile as :func:`save_profile` writes it, at :data:`SCHEMA_VERSION`, with its
        optional sections where the profile has them.
    """
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
        **({} if profile.identification is None else {"identification": profile.identification.to_dict()}),
        **({} if profile.controller is None else {"controller": profile.controller.to_dict()}),
        **({} if profile.renderable is None else {"renderable": profile.renderable.to_dict()}),
        **({} if profile.multidof is None else {"multidof": profile.multidof.to_dict()}),
    }


# -- files ---------------------------------------------------------------------------------------


def load_profile(path: str | os.PathLike) -> Profile:
    """Read and validate a profile file.

    Parameters
    ----------
    path : str or os.PathLike
        The profile's JSON file.

    Returns
    -------
    Profile
        The validated profile (older schema versions migrated).

    Raises
    ------
    ProfileError
        For any problem (and nothing else): an unreadable file, invalid JSON or a bad value,
        naming the file and the JSON path.
    """
    return profile_from_dict(read_json(path), path)


def save_profile(profile: Profile, path: str | os.PathLike) -> None:
    """Write ``profile`` to ``path`` atomically.

    The JSON goes to a temporary file in the same directory, which is flushed, fsynced and then
    renamed over ``path``; on any failure the temporary file is removed and an existing file at
    ``path`` is left untouched.

    Parameters
    ----------
    profile : Profile
        The profile to write.
    path : str or os.PathLike
        The file to write.

    Raises
    ------
    ProfileError
        When the profile cannot be serialised or the file cannot be written (with the
        exception, e.g. the OSError, as its cause).
    """
    try:
        text = json.dumps(profile_to_dict(profile), indent=2, allow_nan=False) + "\n"
    except Exception as exc:  # noqa: BLE001
        raise ProfileError(f"cannot save: {type(exc).__name__}: {exc}", path=path) from exc
    write_atomically(path, text)
