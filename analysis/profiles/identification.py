"""The optional ``identification`` profile section (schema 4, issue 14).

It keeps what a device model was identified from, so that the profile stays self-contained::

    "identification": {
      "intervals": {"masses[0]": [0.19, 0.21], "ground_dampings[3]": [1.2, 5.0]},
      "measurements": [
        {"source": "frf.csv", "quantity": "actuator", "boundary": "free",
         "sample_time": 0.001, "delay_samples": 0,
         "frequency": [...], "real": [...], "imag": [...], "coherence": [...],
         "input_power": [...]}
      ],
      "notes": ["the handle mode is not detected in these measurements: ..."]
    }

* ``intervals`` -- 95 % (or user-typed) intervals on device parameters, keyed by the profile's
  JSON names with 0-based indices (``masses[i]``, ``stiffnesses[i]``, ``dampings[i]``,
  ``ground_dampings[i]``), each ``[low, high]`` with ``0 <= low <= high``; ``low = 0`` and
  ``high = "inf"`` mark a side the data do not bound (a fit's unbounded interval, which the
  robust designs refuse with the parameter named);
* ``measurements`` -- the measured frequency responses, embedded: ``frequency`` in rad/s
  (> 0, strictly increasing), ``real``/``imag`` of the response, optional ``coherence`` in
  [0, 1] and optional ``input_power`` (the input's auto-spectrum of a time series' Welch estimate,
  N^2/Hz, finite and >= 0: with it a reloaded measurement's bins are judged by coherence and input
  power as the fit judged them, issue 23); ``quantity`` (``actuator`` | ``handle`` | ``gauge``), ``boundary`` (``free`` |
  ``clamped``), ``sample_time`` (s, or ``null`` for a continuous-time measurement),
  ``delay_samples`` and an optional ``source`` name;
* ``notes`` (optional) -- the fit's warnings, one string each (e.g. that the handle mode was not
  detected, so the device is the chain with the handle merged into mass 1); the report prints
  them under the parameter table.  Left out of the file when empty.

The section is plain data (this module does not import :mod:`analysis.identify`, which sits in
the same layer); :mod:`analysis.study.identify` turns it into measurements and fits.  Errors are
:class:`~analysis.profiles.errors.ProfileError` at the JSON path, e.g.
``$.identification.measurements[0].frequency[3]``.  Indices are checked against the device by
:func:`check_against_device`.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from analysis.checks import from_json_float, json_float
from analysis.profiles.errors import ProfileError

__all__ = [
    "IDENTIFICATION_QUANTITIES",
    "IDENTIFICATION_BOUNDARIES",
    "PARAMETER_KEY",
    "IdentificationSection",
    "MeasurementData",
    "check_against_device",
    "parse_identification",
]

IDENTIFICATION_QUANTITIES = ("actuator", "handle", "gauge")
IDENTIFICATION_BOUNDARIES = ("free", "clamped")
#: A parameter key: the profile's JSON name of a device vector and a 0-based index.
PARAMETER_KEY = re.compile(r"^(masses|stiffnesses|dampings|ground_dampings)\[(\d+)\]$")
_MEASUREMENT_KEYS = {"source", "quantity", "boundary", "sample_time", "delay_samples", "frequency", "real",
                     "imag", "coherence", "input_power"}
_MIN_POINTS = 8


@dataclass(frozen=True, eq=False)
class MeasurementData:
    """One embedded measured frequency response (plain arrays; see the module doc)."""

    frequency: np.ndarray
    response: np.ndarray
    quantity: str = "actuator"
    boundary: str = "free"
    sample_time: float | None = None
    delay_samples: int = 0
    coherence: np.ndarray | None = None
    source: str | None = None
    input_power: np.ndarray | None = None

    def to_dict(self) -> dict:
        """The JSON-ready measurement (``source`` left out when unknown)."""
        out: dict = {"source": self.source, "quantity": self.quantity, "boundary": self.boundary,
                     "sample_time": self.sample_time, "delay_samples": int(self.delay_samples),
                     "frequency": [float(x) for x in self.frequency],
                     "real": [float(x) for x in self.response.real],
                     "imag": [float(x) for x in self.response.imag]}
        if self.source is None:
            del out["source"]
        if self.coherence is not None:
            out["coherence"] = [float(x) for x in self.coherence]
        if self.input_power is not None:
            out["input_power"] = [float(x) for x in self.input_power]
        return out


@dataclass(frozen=True, eq=False)
class IdentificationSection:
    """Parameter intervals and the embedded measurements they came from."""

    intervals: dict[str, tuple[float, float]]
    measurements: tuple[MeasurementData, ...] = ()
    notes: tuple[str, ...] = ()

    def __eq__(self, other: object) -> bool:
        return isinstance(other, IdentificationSection) and self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        return hash(json.dumps(self.to_dict(), sort_keys=True))

    def to_dict(self) -> dict:
        """The JSON-ready section."""
        out: dict = {"intervals": {k: [float(lo), json_float(float(hi))] for k, (lo, hi) in self.intervals.items()},
                     "measurements": [m.to_dict() for m in self.measurements]}
        if self.notes:
            out["notes"] = list(self.notes)
        return out


def _fail(jp: str, expected: str, value: object) -> ProfileError:
    return ProfileError.at(jp, expected, value)


def _finite(value: object, jp: str, expected: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(jp, expected, value)
    return float(value)


def _vector(value: object, jp: str, expected: str, length: int | None = None) -> np.ndarray:
    if not isinstance(value, list):
        raise _fail(jp, f"a list of numbers ({expected})", value)
    if length is not None and len(value) != length:
        raise _fail(jp, f"a list of exactly {length} values (one per frequency)", value)
    return np.array([_finite(v, f"{jp}[{i}]", f"a finite number ({expected})") for i, v in enumerate(value)])


def _interval(key: object, value: object, jp: str) -> tuple[str, tuple[float, float]]:
    if not isinstance(key, str) or PARAMETER_KEY.match(key) is None:
        raise ProfileError(
            "unknown parameter key (allowed: masses[i], stiffnesses[i], dampings[i], ground_dampings[i])",
            json_path=f"{jp}.{key}", expected="a parameter key such as masses[0]")
    where = f'{jp}["{key}"]'
    if not isinstance(value, list) or len(value) != 2:
        raise _fail(where, "a list [low, high]", value)
    lo = _finite(value[0], f"{where}[0]", "a number >= 0 and finite (0: not bounded below)")
    if lo < 0:
        raise _fail(f"{where}[0]", "a number >= 0 and finite (0: not bounded below)", value[0])
    high = from_json_float(value[1])
    if high != math.inf:
        high = _finite(high, f"{where}[1]", 'a number >= low, or "inf" (not bounded above)')
    if high < lo:
        raise _fail(f"{where}[1]", f'a number >= low ({lo:g}), or "inf" (not bounded above)', value[1])
    return key, (lo, float(high))


def _choice(obj: Mapping, key: str, jp: str, options: Sequence[str], default: str) -> str:
    value = obj.get(key, default)
    if not isinstance(value, str) or value not in options:
        raise _fail(f"{jp}.{key}", " or ".join(f'"{o}"' for o in options), value)
    return value


def _timing(obj: Mapping, jp: str, w: np.ndarray) -> tuple[float | None, int]:
    T = obj.get("sample_time")
    if T is not None:
        T = _finite(T, f"{jp}.sample_time", "null or a number > 0 and finite (s)")
        if T <= 0:
            raise _fail(f"{jp}.sample_time", "null or a number > 0 and finite (s)", T)
        if w[-1] >= math.pi / T:
            raise _fail(f"{jp}.frequency[{w.size - 1}]", f"a frequency below Nyquist {math.pi / T:.6g} rad/s",
                        float(w[-1]))
    d = obj.get("delay_samples", 0)
    if isinstance(d, bool) or not isinstance(d, int) or d < 0 or (T is None and d):
        raise _fail(f"{jp}.delay_samples", "an integer >= 0 (0 without sample_time)", d)
    return T, d


def _measurement(obj: object, jp: str) -> MeasurementData:
    if not isinstance(obj, Mapping):
        raise _fail(jp, "a JSON object", obj)
    unknown = sorted(str(k) for k in obj if k not in _MEASUREMENT_KEYS)
    if unknown:
        raise ProfileError(f"unknown key (allowed: {', '.join(sorted(_MEASUREMENT_KEYS))})",
                           json_path=f"{jp}.{unknown[0]}", expected="one of " + ", ".join(sorted(_MEASUREMENT_KEYS)))
    for key in ("frequency", "real", "imag"):
        if key not in obj:
            raise _fail(f"{jp}.{key}", "a list of numbers", None)
    w = _vector(obj["frequency"], f"{jp}.frequency", "rad/s")
    if w.size < _MIN_POINTS:
        raise _fail(f"{jp}.frequency", f"a list of at least {_MIN_POINTS} frequencies", obj["frequency"])
    for i in range(w.size):
        if w[i] <= 0 or (i and w[i] <= w[i - 1]):
            raise _fail(f"{jp}.frequency[{i}]", "a frequency > 0 above the previous one (rad/s)", float(w[i]))
    h = _vector(obj["real"], f"{jp}.real", "real part", w.size) + 1j * _vector(obj["imag"], f"{jp}.imag",
                                                                                "imaginary part", w.size)
    coh = None
    if obj.get("coherence") is not None:
        coh = _vector(obj["coherence"], f"{jp}.coherence", "in [0, 1]", w.size)
        bad = np.flatnonzero((coh < 0) | (coh > 1))
        if bad.size:
            raise _fail(f"{jp}.coherence[{bad[0]}]", "a number in [0, 1]", float(coh[bad[0]]))
    power = None
    if obj.get("input_power") is not None:
        power = _vector(obj["input_power"], f"{jp}.input_power", "N^2/Hz, >= 0", w.size)
        bad = np.flatnonzero(power < 0)
        if bad.size:
            raise _fail(f"{jp}.input_power[{bad[0]}]", "a number >= 0 and finite (N^2/Hz)", float(power[bad[0]]))
    quantity = _choice(obj, "quantity", jp, IDENTIFICATION_QUANTITIES, "actuator")
    boundary = _choice(obj, "boundary", jp, IDENTIFICATION_BOUNDARIES, "free")
    source = obj.get("source")
    if source is not None and not isinstance(source, str):
        raise _fail(f"{jp}.source", "a string or null", source)
    T, d = _timing(obj, jp, w)
    return MeasurementData(w, h, quantity, boundary, T, d, coh, source, power)


def parse_identification(data: object, jp: str = "$.identification") -> IdentificationSection:
    """The section of a profile dict (strict: unknown keys and bad values raise ProfileError)."""
    if not isinstance(data, Mapping):
        raise _fail(jp, "a JSON object with keys intervals and measurements", data)
    unknown = sorted(str(k) for k in data if k not in ("intervals", "measurements", "notes"))
    if unknown:
        raise ProfileError("unknown key (allowed: intervals, measurements, notes)", json_path=f"{jp}.{unknown[0]}",
                           expected="one of intervals, measurements, notes")
    raw = data.get("intervals", {})
    if not isinstance(raw, Mapping):
        raise _fail(f"{jp}.intervals", "a JSON object {key: [low, high]}", raw)
    intervals = dict(_interval(k, v, f"{jp}.intervals") for k, v in raw.items())
    items = data.get("measurements", [])
    if not isinstance(items, list):
        raise _fail(f"{jp}.measurements", "a list of measurements", items)
    notes = data.get("notes", [])
    if not isinstance(notes, list):
        raise _fail(f"{jp}.notes", "a list of strings", notes)
    for i, text in enumerate(notes):
        if not isinstance(text, str):
            raise _fail(f"{jp}.notes[{i}]", "a string", text)
    return IdentificationSection(intervals, tuple(_measurement(m, f"{jp}.measurements[{i}]")
                                                  for i, m in enumerate(items)), tuple(notes))


def check_against_device(section: IdentificationSection, n_masses: int,
                         jp: str = "$.identification.intervals") -> None:
    """Raise ProfileError when an interval's index lies outside an ``n_masses`` chain."""
    sizes = {"masses": n_masses, "ground_dampings": n_masses, "stiffnesses": n_masses - 1,
             "dampings": n_masses - 1}
    for key in section.intervals:
        match = PARAMETER_KEY.match(key)
        assert match is not None  # checked when parsed
        name, index = match.group(1), int(match.group(2))
        if index >= sizes[name]:
            raise ProfileError(f"index {index} is outside the device ({sizes[name]} {name}, counted from 0)",
                               json_path=f'{jp}["{key}"]', expected=f"an index below {sizes[name]}")
