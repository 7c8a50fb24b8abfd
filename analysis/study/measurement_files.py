"""Measurement files as the command line names them: ``FILE[:QUANTITY[:BOUNDARY]]`` (issue 23).

* :func:`parse_measurement_spec` -- one argument to a :class:`MeasurementSpec`: the file and,
  when given, its own quantity and boundary (the command's ``--quantity``/``--boundary`` are the
  default for a file without them);
* :func:`read_measurement_files` -- each file read by :func:`analysis.identify.load_measurement`,
  with what it was (FRF or time series) and where its sample time came from: a time series is
  sampled, so without a sample time it takes its own time step (``step_as_sample_time``).

Numpy and scipy only; never imports Qt.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from analysis import csvtable
from analysis.identify import BOUNDARIES, MEASURED_QUANTITIES, Measurement, MeasurementError, load_measurement
from analysis.identify.csvio import read_timeseries

__all__ = ["MeasurementSpec", "LoadedMeasurement", "parse_measurement_spec", "read_measurement_files",
           "SAMPLE_TIME_GIVEN", "SAMPLE_TIME_STEP", "SAMPLE_TIME_CONTINUOUS"]

#: where a measurement's sample time came from: the caller's value (``--sample-time``)
SAMPLE_TIME_GIVEN = "given"
#: ... the time series' own time step (a time series is sampled)
SAMPLE_TIME_STEP = "time step"
#: ... none: a continuous-time measurement (an analyser's FRF, or ``--continuous``)
SAMPLE_TIME_CONTINUOUS = "continuous"

_WORD = re.compile(r"[A-Za-z_-]*")


@dataclass(frozen=True)
class MeasurementSpec:
    """One measurement file and, when the argument named them, its own quantity and boundary.

    Attributes
    ----------
    path : str
        The file.
    quantity : str or None
        ``"actuator"``, ``"handle"`` or ``"gauge"``; ``None``: the command's default.
    boundary : str or None
        ``"free"`` or ``"clamped"``; ``None``: the command's default.
    """

    path: str
    quantity: str | None = None
    boundary: str | None = None

    def kind(self, quantity: str, boundary: str) -> tuple[str, str]:
        """``(quantity, boundary)`` of this file, the defaults filling what it does not name."""
        return self.quantity or quantity, self.boundary or boundary


@dataclass(frozen=True, eq=False)
class LoadedMeasurement:
    """A measurement file as read: its spec, the measurement, whether it was a time series and
    where its sample time came from (:data:`SAMPLE_TIME_GIVEN`, :data:`SAMPLE_TIME_STEP` or
    :data:`SAMPLE_TIME_CONTINUOUS`).

    Attributes
    ----------
    spec : MeasurementSpec
        The file as named.
    measurement : Measurement
        The measurement (a time series already turned into an FRF by Welch's estimator).
    time_series : bool
        Whether the file was a time series (``time_s`` column).
    sample_time_source : str
        Where ``measurement.sample_time`` came from.
    """

    spec: MeasurementSpec
    measurement: Measurement
    time_series: bool
    sample_time_source: str


def _unknown(word: str, what: str, allowed: Sequence[str], text: str, hint: str = "") -> ValueError:
    return ValueError(f"{text!r}: unknown {what} {word!r}; allowed: {', '.join(allowed)}{hint} "
                      "(FILE[:QUANTITY[:BOUNDARY]])")


def parse_measurement_spec(text: str | os.PathLike, *,
                           is_file: Callable[[str], bool] = os.path.isfile) -> MeasurementSpec:
    """``"c.csv:actuator:clamped"`` -> ``MeasurementSpec("c.csv", "actuator", "clamped")``.

    The whole argument is the file when such a file exists (a path that contains ``:``, a Windows
    drive ``C:\\x.csv``).  Otherwise up to two trailing ``:WORD`` parts (letters only) are the
    quantity and the boundary (case-insensitive; an empty part keeps the default,
    ``c.csv::clamped``).  A part with a path separator, a dot or a digit belongs to the path:
    ``C:\\data\\x.csv`` that does not exist is reported as a missing file where it is read.

    Parameters
    ----------
    text : str or os.PathLike
        The argument.
    is_file : callable, optional
        Whether a path names an existing file (:func:`os.path.isfile`).

    Returns
    -------
    MeasurementSpec
        The file and its own quantity and boundary (``None`` where not given).

    Raises
    ------
    ValueError
        When a trailing part is a word but not a quantity (then boundary) the model knows; the
        message names the allowed ones.
    """
    text = os.fspath(text)
    if is_file(text):
        return MeasurementSpec(text)
    parts = text.split(":")
    words = 0  # trailing word parts (at most two), leaving a non-empty path
    while words < min(2, len(parts) - 1) and _WORD.fullmatch(parts[-1 - words]) and ":".join(parts[:-1 - words]):
        words += 1
    if not words:
        return MeasurementSpec(text)  # "x.csv", "C:\\x.csv", "dir:v2/x.csv": a path, not a kind
    last = parts[-1].lower()
    if last in MEASURED_QUANTITIES or (not last and words == 1):
        return MeasurementSpec(":".join(parts[:-1]), last or None)
    if words == 2 and (last in BOUNDARIES or not last):
        q = parts[-2].lower()
        if q and q not in MEASURED_QUANTITIES:
            raise _unknown(parts[-2], "quantity", MEASURED_QUANTITIES, text)
        return MeasurementSpec(":".join(parts[:-2]), q or None, last or None)
    if last in BOUNDARIES:
        raise _unknown(parts[-1], "quantity", MEASURED_QUANTITIES, text,
                       f"; a boundary follows the quantity, e.g. {':'.join(parts[:-1])}:actuator:{last}")
    if words == 2 and parts[-2].lower() in MEASURED_QUANTITIES:
        raise _unknown(parts[-1], "boundary", BOUNDARIES, text)
    raise _unknown(parts[-1], "quantity", MEASURED_QUANTITIES, text)


def _is_time_series(path: str) -> bool:
    return "time_s" in csvtable.read_header(path, error=MeasurementError)[1]


def read_measurement_files(specs: Sequence[MeasurementSpec | str | os.PathLike], quantity: str = "actuator",
                           boundary: str = "free", sample_time: float | None = None, delay_samples: int = 0, *,
                           step_as_sample_time: bool = False) -> list[LoadedMeasurement]:
    """Read every file (:func:`analysis.identify.load_measurement`), each with its own kind.

    Parameters
    ----------
    specs : sequence of MeasurementSpec, str or os.PathLike
        The files; a plain path takes the defaults ``quantity`` and ``boundary``.
    quantity, boundary : str, optional
        The defaults for files that do not name their own.
    sample_time : float or None, optional
        Controller sample period [s] of every measurement, or ``None``.
    delay_samples : int, optional
        Computation delay in samples (sampled measurements only).
    step_as_sample_time : bool, optional
        With ``sample_time`` ``None``: a time series is sampled through the controller at its own
        time step (the command line's default; ``False`` reads it as continuous-time, as an
        analyser's record).  FRF files are continuous-time without ``sample_time`` either way.

    Returns
    -------
    list of LoadedMeasurement
        One per file, in order.

    Raises
    ------
    MeasurementError
        When a file cannot be read or its data are unusable (it names the file, row and column).
    """
    out = []
    for item in specs:
        spec = item if isinstance(item, MeasurementSpec) else MeasurementSpec(os.fspath(item))
        q, b = spec.kind(quantity, boundary)
        series = _is_time_series(spec.path)
        T, source = sample_time, SAMPLE_TIME_GIVEN
        if T is None:
            source = SAMPLE_TIME_CONTINUOUS
            if series and step_as_sample_time:
                # the uniform step, checked by the reader; estimate_frf checks it again against T
                T, source = float(np.median(np.diff(read_timeseries(spec.path)[0]))), SAMPLE_TIME_STEP
        if delay_samples and T is None:
            raise MeasurementError(f"a computation delay of {delay_samples} samples needs a sampled measurement; "
                                   "this one is continuous-time (give --sample-time)", file=spec.path)
        m = load_measurement(spec.path, quantity=q, boundary=b, sample_time=T, delay_samples=delay_samples)
        out.append(LoadedMeasurement(spec, m, series, source))
    return out
