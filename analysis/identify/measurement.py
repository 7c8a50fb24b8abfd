"""The measurement record: one frequency response of the device.

A :class:`Measurement` holds frequencies (rad/s), the complex response, its quantity
(``actuator`` | ``handle`` | ``gauge``, see :mod:`analysis.identify.model`) and boundary
(``free`` | ``clamped``), optional coherence, and how it was taken: continuous (an analyser,
``sample_time=None``) or through the sampled controller (force through a zero-order hold,
sampled sensor, ``delay_samples`` of computation delay), in which case the model is the exact
ZOH-sampled response.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.identify.errors import MeasurementError
from analysis.identify.model import BOUNDARIES, MEASURED_QUANTITIES

__all__ = ["Measurement", "make_measurement", "MIN_POINTS"]

#: Fewest frequency points a measurement may have.
MIN_POINTS = 8


@dataclass(frozen=True, eq=False)
class Measurement:
    """One measured frequency response (validated by :func:`make_measurement`).

    Attributes
    ----------
    frequency : numpy.ndarray
        Strictly increasing frequencies [rad/s], shape (F,).
    response : numpy.ndarray
        Complex response at ``frequency`` (m/N for ``actuator``/``handle``, N/N for ``gauge``),
        shape (F,).
    quantity, boundary : str
        What was measured (``"actuator"``, ``"handle"`` or ``"gauge"``) and how the handle was
        held (``"free"`` or ``"clamped"``).
    sample_time : float or None
        Controller sample period in s, or ``None`` for a continuous-time measurement.
    delay_samples : int
        Computation delay in samples (sampled measurements only).
    coherence : numpy.ndarray or None
        Magnitude-squared coherence in [0, 1], shape (F,), or ``None``.
    source : str or None
        File it came from, or ``None``.
    """

    frequency: np.ndarray
    response: np.ndarray
    quantity: str = "actuator"
    boundary: str = "free"
    sample_time: float | None = None
    delay_samples: int = 0
    coherence: np.ndarray | None = None
    source: str | None = None

    @property
    def size(self) -> int:
        return int(self.frequency.size)

    def weights(self, clip: tuple[float, float] = (1e-2, 1e2)) -> np.ndarray:
        """Least-squares weights per point: ``sqrt(gamma^2 / (1 - gamma^2))`` (the inverse standard
        deviation of the log-response of an H1 estimate, up to the number of averages) clipped to
        ``clip`` relative to its median; uniform ``1`` without coherence.

        Parameters
        ----------
        clip : tuple of (float, float), optional
            ``(low, high)`` bounds of the weights as multiples of their median.

        Returns
        -------
        numpy.ndarray
            The weights divided by their median (dimensionless), shape (F,); ones without
            coherence.
        """
        if self.coherence is None:
            return np.ones(self.size)
        g = np.clip(self.coherence, 1e-6, 1 - 1e-9)
        wt = np.sqrt(g / (1.0 - g))
        med = float(np.median(wt))
        return np.clip(wt, clip[0] * med, clip[1] * med) / med


def make_measurement(frequency, response, quantity: str = "actuator", boundary: str = "free",
                     sample_time: float | None = None, delay_samples: int = 0, coherence=None,
                     source: str | None = None) -> Measurement:
    """Validate arrays into a :class:`Measurement` (errors are :class:`MeasurementError`).

    Parameters
    ----------
    frequency : array_like
        Frequencies [rad/s], > 0 and strictly increasing, at least :data:`MIN_POINTS`; flattened
        to shape (F,).
    response : array_like
        Complex response at ``frequency`` [m/N for ``actuator``/``handle``, N/N for ``gauge``],
        finite and nonzero, shape (F,).
    quantity : str, optional
        ``"actuator"``, ``"handle"`` or ``"gauge"`` (:data:`MEASURED_QUANTITIES`).
    boundary : str, optional
        ``"free"`` or ``"clamped"``; a ``"handle"`` measurement needs ``"free"``.
    sample_time : float or None, optional
        Controller sample period [s], > 0 and finite, with every frequency below Nyquist
        ``pi / sample_time``; ``None`` for a continuous-time measurement.
    delay_samples : int, optional
        Computation delay [samples], an integer >= 0; 0 without ``sample_time``.
    coherence : array_like or None, optional
        Magnitude-squared coherence in [0, 1], one value per frequency, or ``None``.
    source : str or None, optional
        File the data came from (named in every error), or ``None``.

    Returns
    -------
    Measurement
        The validated record, with float and complex copies of the arrays.

    Raises
    ------
    MeasurementError
        For an unknown quantity or boundary, a clamped handle, mismatched lengths, fewer than
        :data:`MIN_POINTS` points, non-finite values, frequencies not > 0 and increasing, a zero
        response, a bad sample time or frequency above Nyquist, a bad delay, or coherence outside
        [0, 1] or of the wrong length.
    """
    w = np.asarray(frequency, dtype=float).reshape(-1)
    h = np.asarray(response, dtype=complex).reshape(-1)
    if quantity not in MEASURED_QUANTITIES:
        raise MeasurementError(f"quantity {quantity!r} is not one of {', '.join(MEASURED_QUANTITIES)}", file=source)
    if boundary not in BOUNDARIES:
        raise MeasurementError(f"boundary {boundary!r} is not one of {', '.join(BOUNDARIES)}", file=source)
    if quantity == "handle" and boundary == "clamped":
        raise MeasurementError("a clamped handle does not move: 'handle' needs boundary 'free'", file=source)
    if w.size != h.size:
        raise MeasurementError(f"{w.size} frequencies but {h.size} response values", file=source)
    if w.size < MIN_POINTS:
        raise MeasurementError(f"{w.size} points: at least {MIN_POINTS} are needed", file=source)
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(h))):
        raise MeasurementError("non-finite frequency or response value", file=source)
    if w[0] <= 0 or np.any(np.diff(w) <= 0):
        raise MeasurementError("frequencies must be > 0 and strictly increasing", file=source)
    if np.any(h == 0):
        raise MeasurementError("a response value is exactly zero (its logarithm is needed)", file=source)
    T = None
    if sample_time is not None:
        T = float(sample_time)
        if not (math.isfinite(T) and T > 0):
            raise MeasurementError(f"sample_time = {T!r}: must be > 0 and finite (s)", file=source)
        if w[-1] >= math.pi / T:
            raise MeasurementError(f"frequency {w[-1]:.6g} rad/s is not below Nyquist {math.pi / T:.6g} rad/s",
                                   file=source)
    d = int(delay_samples)
    if d < 0 or d != delay_samples or (T is None and d):
        raise MeasurementError("delay_samples must be an integer >= 0 (and 0 without sample_time)", file=source)
    coh = None
    if coherence is not None:
        coh = np.asarray(coherence, dtype=float).reshape(-1)
        if coh.size != w.size or not np.all((coh >= 0) & (coh <= 1)):
            raise MeasurementError("coherence must have one value in [0, 1] per frequency", file=source)
    return Measurement(frequency=w, response=h, quantity=quantity, boundary=boundary, sample_time=T,
                       delay_samples=d, coherence=coh, source=source)
