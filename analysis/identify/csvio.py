"""Measurement files: FRF and time-series CSV.

Both are read by the one CSV reader, :func:`analysis.csvtable.read_table`: UTF-8, comma-separated
with one header row; blank lines and lines starting with ``#`` are skipped (but counted, so that
reported line numbers match an editor's).

FRF files
    Frequency: exactly one of ``frequency_hz`` or ``frequency_rad_s``.  Response: exactly one of
    the sets ``real`` + ``imag``, ``magnitude`` + ``phase_deg``, ``magnitude_db`` + ``phase_deg``
    (magnitude in the quantity's unit, m/N or N/N; ``magnitude_db = 20 log10 magnitude``).
    Optional ``coherence`` in [0, 1].
Time-series files
    ``time_s``, ``force_n``, ``position_m`` (or a gauge reading in N in the third column when
    the quantity is ``gauge``), uniformly sampled; turned into an FRF by
    :func:`analysis.identify.estimate_frf`.

Every problem raises :class:`~analysis.identify.MeasurementError` naming the file, the line
(1-based, header = line 1; the message adds the 1-based data row) and the column: a missing
file, a folder, an empty file, UTF-16 or other non-UTF-8 text, rows with too few or too many
values, unreadable numbers, non-finite values, non-increasing frequency or time, non-positive magnitude,
coherence outside [0, 1], unknown, missing, duplicate or mixed columns (both frequency units,
or two response forms), and too few points.
"""

from __future__ import annotations

import math
import os

import numpy as np

from analysis import csvtable
from analysis.csvtable import Table
from analysis.identify.errors import MeasurementError
from analysis.identify.measurement import MIN_POINTS, Measurement, make_measurement

__all__ = ["read_table", "read_frf", "read_timeseries", "load_measurement", "FRF_COLUMNS", "TIME_COLUMNS"]

_FREQ = ("frequency_hz", "frequency_rad_s")
_FORMS = (("real", "imag"), ("magnitude", "phase_deg"), ("magnitude_db", "phase_deg"))
FRF_COLUMNS = (*_FREQ, "real", "imag", "magnitude", "magnitude_db", "phase_deg", "coherence")
TIME_COLUMNS = ("time_s", "force_n", "position_m")


def read_table(path: str | os.PathLike, allowed: tuple[str, ...]) -> Table:
    """Read a numeric CSV with a header naming only ``allowed`` columns (:func:`analysis.csvtable.read_table`,
    raising :class:`~analysis.identify.MeasurementError`)."""
    return csvtable.read_table(path, allowed, error=MeasurementError)


def _increasing(t: Table, column: str, positive: bool) -> None:
    v = t.columns[column]
    if positive and v.size and not v[0] > 0:
        raise MeasurementError("must be > 0", file=t.path, line=int(t.lines[0]), column=column)
    bad = np.flatnonzero(np.diff(v) <= 0)
    if bad.size:
        raise MeasurementError(f"must increase strictly ({float(v[bad[0] + 1])!r} after {float(v[bad[0]])!r})",
                               file=t.path,
                               line=int(t.lines[bad[0] + 1]), column=column)


def _one_of(t: Table, options: tuple[str, ...], what: str, hline: int) -> str:
    have = [c for c in options if c in t.columns]
    if len(have) != 1:
        if have:
            raise MeasurementError(f"mixed units: both {' and '.join(have)} given for the {what}; keep one",
                                   file=t.path, line=hline, column=have[1])
        raise MeasurementError(f"no {what} column: one of {', '.join(options)} is needed", file=t.path, line=hline)
    return have[0]


def _response(t: Table, hline: int) -> np.ndarray:
    """The complex response from exactly one of the response forms."""
    present = [f for f in _FORMS if any(c in t.columns for c in f if c != "phase_deg")]
    if len(present) != 1:
        if present:
            cols = [c for f in present for c in f if c != "phase_deg" and c in t.columns]
            raise MeasurementError(f"mixed response forms: {' and '.join(cols)}; use one of real+imag, "
                                   "magnitude+phase_deg, magnitude_db+phase_deg", file=t.path, line=hline,
                                   column=cols[-1])
        raise MeasurementError("no response columns: real+imag, magnitude+phase_deg or magnitude_db+phase_deg",
                               file=t.path, line=hline)
    a, b = present[0]
    if b not in t.columns:
        raise MeasurementError(f"column {b!r} is missing (it goes with {a!r})", file=t.path, line=hline, column=b)
    x, y = t.columns[a], t.columns[b]
    if a == "real":
        h = x + 1j * y
        zero = np.flatnonzero(h == 0)
        if zero.size:
            raise MeasurementError("response is exactly zero", file=t.path, line=int(t.lines[zero[0]]), column=a)
        return h
    if a == "magnitude":
        bad = np.flatnonzero(x <= 0)
        if bad.size:
            raise MeasurementError(f"magnitude must be > 0, got {float(x[bad[0]])!r}", file=t.path,
                                   line=int(t.lines[bad[0]]), column=a)
    else:
        x = 10.0 ** (x / 20.0)
    return x * np.exp(1j * np.deg2rad(y))


def read_frf(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, str]:
    """Frequencies (rad/s), complex response, coherence (or ``None``) and the file name.

    Parameters
    ----------
    path : str or os.PathLike
        The FRF file (module doc: columns :data:`FRF_COLUMNS`).

    Returns
    -------
    frequency : numpy.ndarray
        Frequencies [rad/s] (converted from Hz when the file has ``frequency_hz``), > 0 and
        strictly increasing, shape (F,).
    response : numpy.ndarray
        Complex response in the quantity's unit (m/N or N/N), shape (F,).
    coherence : numpy.ndarray or None
        Magnitude-squared coherence in [0, 1], shape (F,); ``None`` without the column.
    path : str
        The file as given.

    Raises
    ------
    MeasurementError
        For every fault of the file (module doc), with the file, line and column.
    """
    t = read_table(path, FRF_COLUMNS)
    hline = t.header_line
    fcol = _one_of(t, _FREQ, "frequency", hline)
    h = _response(t, hline)
    if t.lines.size < MIN_POINTS:
        raise MeasurementError(f"{t.lines.size} data rows: at least {MIN_POINTS} are needed", file=t.path)
    _increasing(t, fcol, positive=True)
    w = t.columns[fcol] * (2 * math.pi if fcol == "frequency_hz" else 1.0)
    coh = t.columns.get("coherence")
    if coh is not None:
        bad = np.flatnonzero((coh < 0) | (coh > 1))
        if bad.size:
            raise MeasurementError(f"coherence must be in [0, 1], got {float(coh[bad[0]])!r}", file=t.path,
                                   line=int(t.lines[bad[0]]), column="coherence")
    return w, h, coh, t.path


def read_timeseries(path: str | os.PathLike, min_points: int = 64) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``time_s``, ``force_n``, ``position_m`` arrays of a time-series file (checked).

    Parameters
    ----------
    path : str or os.PathLike
        The time-series file (module doc: columns :data:`TIME_COLUMNS`).
    min_points : int, optional
        Fewest data rows accepted.

    Returns
    -------
    t : numpy.ndarray
        Sample times [s], increasing in uniform steps, shape (N,).
    force : numpy.ndarray
        Actuator force [N], shape (N,).
    position : numpy.ndarray
        Position [m] (or a gauge force [N]), shape (N,).

    Raises
    ------
    MeasurementError
        For every fault of the file (module doc), a missing column, fewer than ``min_points``
        rows or times that do not increase in uniform steps, with the file, line and column.
    """
    t = read_table(path, TIME_COLUMNS)
    hline = t.header_line
    for c in TIME_COLUMNS:
        if c not in t.columns:
            raise MeasurementError("column is missing", file=t.path, line=hline, column=c)
    if t.lines.size < min_points:
        raise MeasurementError(f"{t.lines.size} samples: at least {min_points} are needed", file=t.path)
    _increasing(t, "time_s", positive=False)
    from analysis.identify.welch import nonuniform_sample

    j = nonuniform_sample(t.columns["time_s"])
    if j is not None:  # the file's line, not the 0-based sample index estimate_frf would name
        step = float(np.median(np.diff(t.columns["time_s"])))
        raise MeasurementError(f"time must increase in uniform steps of {step:.6g} s (the median step); "
                               f"{float(t.columns['time_s'][j])!r} after {float(t.columns['time_s'][j - 1])!r}",
                               file=t.path, line=int(t.lines[j]), column="time_s")
    return t.columns["time_s"], t.columns["force_n"], t.columns["position_m"]


def load_measurement(path: str | os.PathLike, quantity: str = "actuator", boundary: str = "free",
                     sample_time: float | None = None, delay_samples: int = 0, **welch) -> Measurement:
    """A :class:`~analysis.identify.Measurement` from an FRF file, or from a time-series file
    (recognised by its ``time_s`` column) through :func:`analysis.identify.estimate_frf`
    (``welch`` keyword arguments: ``nperseg``, ``noverlap``, ``window``).

    Parameters
    ----------
    path : str or os.PathLike
        An FRF or a time-series CSV file (module doc).
    quantity : str, optional
        ``"actuator"``, ``"handle"`` or ``"gauge"``.
    boundary : str, optional
        ``"free"`` or ``"clamped"``.
    sample_time : float or None, optional
        Controller sample period [s] of a measurement through the sampled controller; ``None``:
        continuous.
    delay_samples : int, optional
        Computation delay [samples] (with ``sample_time`` only).
    **welch
        ``nperseg``, ``noverlap``, ``window`` of :func:`analysis.identify.estimate_frf` (time
        series only).

    Returns
    -------
    Measurement
        The validated measurement, its ``source`` the file name.

    Raises
    ------
    MeasurementError
        For every fault of the file or of the measurement it makes (:func:`read_frf`,
        :func:`read_timeseries`, :func:`~analysis.identify.make_measurement`), naming the file.
    """
    name = os.fspath(path)
    if "time_s" in csvtable.read_header(name, error=MeasurementError)[1]:
        from analysis.identify.welch import estimate_frf

        t, f, x = read_timeseries(name)
        return estimate_frf(t, f, x, quantity=quantity, boundary=boundary, sample_time=sample_time,
                            delay_samples=delay_samples, source=name, **welch)
    w, h, coh, _ = read_frf(name)
    try:
        return make_measurement(w, h, quantity, boundary, sample_time, delay_samples, coh, source=name)
    except MeasurementError as exc:
        raise MeasurementError(exc.reason, file=name) from None
