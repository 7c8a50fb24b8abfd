"""Frequency response from time series: Welch's H1 estimator with coherence.

``H1(f) = P_fx(f) / P_ff(f)`` with ``P_ff`` the averaged auto-spectrum of the force and
``P_fx`` the averaged cross-spectrum force -> response (:func:`scipy.signal.welch`,
:func:`scipy.signal.csd`; Bendat & Piersol, *Random Data*, sec. 9.2).  H1 is unbiased by noise
on the output; the magnitude-squared coherence ``|P_fx|^2 / (P_ff P_xx)`` says where the
estimate can be trusted (its random error is about ``sqrt((1 - g^2) / (2 n_d g^2))`` for
``n_d`` averages, which is why :meth:`~analysis.identify.Measurement.weights` uses
``g^2 / (1 - g^2)``).

Each bin is judged informative or not by its coherence and its input power
(:func:`analysis.identify.measurement.informative_bins`): the estimate carries the force's
auto-spectrum ``P_ff`` for that.  By default the segments tile the whole record
(:func:`tiling_overlap`): scipy drops the samples after the last whole segment, which with a
fixed 50 % overlap can be most of a segment -- the last second of a 40 s chirp, where a sweep
spends its top frequencies.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import signal

from analysis.identify.errors import MeasurementError
from analysis.identify.measurement import Measurement, make_measurement

__all__ = ["estimate_frf", "default_segment", "nonuniform_sample", "tiling_overlap"]


def default_segment(n: int) -> int:
    """Default Welch segment: the largest power of two giving at least 8 segments (50 %
    overlap gives about 15 averages), at least 64 samples and at most ``n``."""
    seg = 2 ** max(int(math.floor(math.log2(max(n, 1) / 8))), 6)
    return min(seg, n)


def tiling_overlap(n: int, seg: int) -> int:
    """The overlap (samples, at least half a segment) whose segments of ``seg`` samples cover a
    record of ``n`` samples to within fewer samples than there are segments: the fewest segments
    ``K`` with steps of at most ``seg / 2``, step ``floor((n - seg) / (K - 1))``."""
    if n <= seg:
        return seg // 2
    k = -(-(n - seg) // max(seg // 2, 1)) + 1
    return seg - (n - seg) // (k - 1)


def _check(t: np.ndarray, force: np.ndarray, position: np.ndarray, source: str | None) -> float:
    """Common length, finite values, uniform time step; returns the step."""
    if not (t.size == force.size == position.size):
        raise MeasurementError(f"time, force and position lengths differ ({t.size}, {force.size}, {position.size})",
                               file=source)
    if t.size < 64:
        raise MeasurementError(f"{t.size} samples: at least 64 are needed", file=source)
    for name, v in (("time_s", t), ("force_n", force), ("position_m", position)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise MeasurementError(f"non-finite value at sample {bad[0]}", file=source, column=name)
    j = nonuniform_sample(t)
    if j is not None:
        raise MeasurementError(f"time must increase in uniform steps (sample {j})", file=source, column="time_s")
    return float(np.median(np.diff(t)))


def nonuniform_sample(t: np.ndarray) -> int | None:
    """The 0-based index of the first sample whose time step differs from the median step (by more
    than 1e-6 of it), 1 when the median step is not > 0, or ``None`` when ``t`` is uniformly sampled."""
    dt = np.diff(np.asarray(t, float))
    step = float(np.median(dt))
    bad = np.flatnonzero(np.abs(dt - step) > 1e-6 * abs(step) + 1e-12)
    if step > 0 and not bad.size:
        return None
    return int(bad[0]) + 1 if bad.size else 1


def estimate_frf(t, force, position, quantity: str = "actuator", boundary: str = "free",
                 sample_time: float | None = None, delay_samples: int = 0, *, nperseg: int | None = None,
                 noverlap: int | None = None, window: str = "hann", source: str | None = None) -> Measurement:
    """H1 frequency-response estimate with coherence from a force and a response record.

    ``t`` must be uniformly sampled.  ``sample_time`` marks a measurement taken through the
    sampled controller (force held by a ZOH, response sampled); it must equal the time step.
    ``nperseg`` defaults to :func:`default_segment`, ``noverlap`` to the overlap of at least half
    a segment whose segments cover the whole record (:func:`tiling_overlap`).  The DC bin
    (and, for sampled data, the Nyquist bin) is dropped.  The estimate carries the force's
    auto-spectrum, and each bin is marked informative or not by its coherence and input power
    (:attr:`Measurement.informative`, :attr:`Measurement.bins`).

    Parameters
    ----------
    t : array_like
        Sample times [s], uniformly spaced, at least 64, shape (N,).
    force : array_like
        Actuator force [N], shape (N,).
    position : array_like
        The response: a position [m] (``actuator``, ``handle``) or a gauge force [N]
        (``gauge``), shape (N,).
    quantity : str, optional
        ``"actuator"``, ``"handle"`` or ``"gauge"``.
    boundary : str, optional
        ``"free"`` or ``"clamped"``.
    sample_time : float or None, optional
        Controller sample period [s] of a measurement through the sampled controller (equal to
        the time step); ``None``: continuous.
    delay_samples : int, optional
        Computation delay [samples] (with ``sample_time`` only).
    nperseg : int or None, optional
        Welch segment length [samples], 8 to N; ``None``: :func:`default_segment`.
    noverlap : int or None, optional
        Overlap of the segments [samples], ``0 <= noverlap < nperseg``; ``None``: at least half a
        segment, so that the segments cover the record (:func:`tiling_overlap`).
    window : str, optional
        Window of :func:`scipy.signal.welch`.
    source : str or None, optional
        File the record came from (named in every error), or ``None``.

    Returns
    -------
    Measurement
        The H1 estimate at the positive frequencies [rad/s] below Nyquist where the force has
        content, with coherence, input power and the informative bins.

    Raises
    ------
    MeasurementError
        For records of different lengths, fewer than 64 samples, non-finite values, a time step
        that is not uniform or differs from ``sample_time``, a bad ``nperseg`` or ``noverlap``,
        a force with fewer than 8 usable bins, or an estimate that :func:`make_measurement`
        refuses.
    """
    t = np.asarray(t, float).reshape(-1)
    f = np.asarray(force, float).reshape(-1)
    x = np.asarray(position, float).reshape(-1)
    dt = _check(t, f, x, source)
    if sample_time is not None and abs(dt - float(sample_time)) > 1e-6 * float(sample_time):
        raise MeasurementError(f"time step {dt:.6g} s differs from sample_time {sample_time!r} s",
                               file=source, column="time_s")
    seg = default_segment(t.size) if nperseg is None else int(nperseg)
    if not 8 <= seg <= t.size:
        raise MeasurementError(f"nperseg = {nperseg!r}: must be between 8 and the record length {t.size}",
                               file=source)
    ov = tiling_overlap(t.size, seg) if noverlap is None else int(noverlap)
    if not 0 <= ov < seg:
        raise MeasurementError(f"noverlap = {noverlap!r}: must be >= 0 and < nperseg = {seg}", file=source)
    fs = 1.0 / dt
    kw = dict(fs=fs, window=window, nperseg=seg, noverlap=ov, detrend="constant")
    freq, pff = signal.welch(f, **kw)
    _, pxx = signal.welch(x, **kw)
    _, pfx = signal.csd(f, x, **kw)
    keep = (freq > 0) & (pff > 0) & (freq < 0.5 * fs * (1 - 1e-12))
    if np.count_nonzero(keep) < 8:
        raise MeasurementError("the force has too little content for an FRF (fewer than 8 usable bins)",
                               file=source, column="force_n")
    h = pfx[keep] / pff[keep]
    with np.errstate(divide="ignore", invalid="ignore"):
        coh = np.abs(pfx[keep]) ** 2 / (pff[keep] * pxx[keep])
    coh = np.clip(np.nan_to_num(coh, nan=0.0), 0.0, 1.0)
    nz = h != 0
    return make_measurement(2 * math.pi * freq[keep][nz], h[nz], quantity, boundary, sample_time, delay_samples,
                            coh[nz], source=source, input_power=pff[keep][nz])
