"""The measurement record: one frequency response of the device.

A :class:`Measurement` holds frequencies (rad/s), the complex response, its quantity
(``actuator`` | ``handle`` | ``gauge``, see :mod:`analysis.identify.model`) and boundary
(``free`` | ``clamped``), optional coherence, and how it was taken: continuous (an analyser,
``sample_time=None``) or through the sampled controller (force through a zero-order hold,
sampled sensor, ``delay_samples`` of computation delay), in which case the model is the exact
ZOH-sampled response.

Which bins carry information (issue 23)
---------------------------------------
A measured bin is *informative* when its magnitude-squared coherence is at least
:data:`COHERENCE_THRESHOLD` (0.8: the response's coherent power is at least four times the
noise's, ``gamma^2 / (1 - gamma^2) >= 4``) **and** its input (force) auto-spectrum is at least
:data:`POWER_FRACTION` of the record's peak (1e-4, -40 dB: a logarithmic chirp's spectrum falls
by the ratio of its end frequencies, 300 for 1 to 300 Hz, which stays inside; outside the swept
band a Hann-windowed force falls below it within a few bins).  Coherence says whether the output
is explained by the input; the input power says whether the input was there at all (a record
with almost no output noise shows a coherence near 1 even where nothing was excited).  A
criterion whose data are missing is not applied: an FRF file without coherence or input power
uses every bin, and :class:`BinSelection` says so.  :func:`make_measurement` computes the mask;
:func:`analysis.identify.fit_chain` fits the informative bins only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.identify.errors import MeasurementError
from analysis.identify.model import BOUNDARIES, MEASURED_QUANTITIES

__all__ = ["BinSelection", "COHERENCE_THRESHOLD", "Measurement", "MIN_POINTS", "POWER_FRACTION", "informative_bins",
           "make_measurement"]

#: Fewest frequency points a measurement may have.
MIN_POINTS = 8
#: Least magnitude-squared coherence of an informative bin (module doc).
COHERENCE_THRESHOLD = 0.8
#: Least input auto-spectrum of an informative bin, as a fraction of the record's peak (module doc).
POWER_FRACTION = 1e-4


@dataclass(frozen=True)
class BinSelection:
    """Which bins of one measurement a fit uses, and why the others are left out (module doc).

    Attributes
    ----------
    total : int
        Bins of the measurement.
    used : int
        Informative bins (fitted).
    low_power : int
        Bins left out because the input auto-spectrum is below ``power_fraction`` of its peak.
    low_coherence : int
        Bins with enough input power left out because the coherence is below
        ``coherence_threshold`` (``used + low_power + low_coherence == total``).
    criteria : tuple of str
        The criteria applied: ``"coherence"``, ``"input power"``, both or none (an FRF without
        coherence and input power: every bin is used).
    coherence_threshold, power_fraction : float
        The thresholds (:data:`COHERENCE_THRESHOLD`, :data:`POWER_FRACTION`).
    source : str or None
        The measurement's file, or ``None``.
    """

    total: int
    used: int
    low_power: int
    low_coherence: int
    criteria: tuple[str, ...]
    coherence_threshold: float = COHERENCE_THRESHOLD
    power_fraction: float = POWER_FRACTION
    source: str | None = None

    @property
    def dropped(self) -> int:
        return self.total - self.used

    @property
    def summary(self) -> str:
        """One line: how many bins are used and why the rest are not."""
        name = f"{self.source}: " if self.source else ""
        if not self.criteria:
            return f"{name}all {self.total} bins used (no coherence or input power to judge them by)"
        why = []
        if self.low_power:
            why.append(f"{self.low_power} with input power below {self.power_fraction:g} of its peak")
        if self.low_coherence:
            why.append(f"{self.low_coherence} with coherence below {self.coherence_threshold:g}")
        rest = f"; left out: {', '.join(why)}" if why else ""
        return f"{name}{self.used} of {self.total} bins used (by {' and '.join(self.criteria)}){rest}"


def informative_bins(coherence: np.ndarray | None, input_power: np.ndarray | None,
                     coherence_threshold: float = COHERENCE_THRESHOLD,
                     power_fraction: float = POWER_FRACTION) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The informative-bin mask and the low-power mask (module doc); ``None`` for a criterion
    whose data are missing (both ``None``: every bin is informative).

    Parameters
    ----------
    coherence : numpy.ndarray or None
        Magnitude-squared coherence per bin, shape (F,).
    input_power : numpy.ndarray or None
        Input (force) auto-spectrum per bin [N^2/Hz], shape (F,).
    coherence_threshold : float, optional
        Least coherence of an informative bin.
    power_fraction : float, optional
        Least input power of an informative bin, as a fraction of the peak.

    Returns
    -------
    informative : numpy.ndarray or None
        Bool, shape (F,); ``None`` when neither criterion applies.
    low_power : numpy.ndarray or None
        Bool, shape (F,): below the power fraction; ``None`` without ``input_power``.
    """
    if coherence is None and input_power is None:
        return None, None
    low_power = None
    ok = np.ones((coherence if coherence is not None else input_power).size, bool)
    if input_power is not None:
        peak = float(np.max(input_power))
        low_power = ~(input_power >= power_fraction * peak) if peak > 0 else np.ones(ok.size, bool)
        ok &= ~low_power
    if coherence is not None:
        ok &= coherence >= coherence_threshold
    return ok, low_power


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
    input_power : numpy.ndarray or None
        Input (force) auto-spectrum [N^2/Hz] of a Welch estimate, shape (F,), or ``None``.
    informative : numpy.ndarray or None
        Whether each bin carries information (module doc), bool, shape (F,); ``None``: every bin
        (no coherence or input power to judge by).  :func:`make_measurement` fills it.
    """

    frequency: np.ndarray
    response: np.ndarray
    quantity: str = "actuator"
    boundary: str = "free"
    sample_time: float | None = None
    delay_samples: int = 0
    coherence: np.ndarray | None = None
    source: str | None = None
    input_power: np.ndarray | None = None
    informative: np.ndarray | None = None

    @property
    def size(self) -> int:
        return int(self.frequency.size)

    @property
    def used(self) -> np.ndarray:
        """The bins a fit uses: :attr:`informative`, or every bin when it is ``None`` (bool, (F,))."""
        return np.ones(self.size, bool) if self.informative is None else np.asarray(self.informative, bool)

    @property
    def bins(self) -> BinSelection:
        """How many bins are informative and why the others are not (:class:`BinSelection`)."""
        used = self.used
        criteria = tuple(c for c, a in (("coherence", self.coherence), ("input power", self.input_power))
                         if a is not None)
        _, low = informative_bins(None, self.input_power)
        n_low = 0 if low is None else int(np.count_nonzero(low & ~used))
        return BinSelection(self.size, int(np.count_nonzero(used)), n_low, self.size - int(np.count_nonzero(used))
                            - n_low, criteria, source=self.source)

    def informative_only(self) -> Measurement:
        """This measurement restricted to its informative bins.

        Returns
        -------
        Measurement
            The bins of :attr:`used` with their coherence and input power (``informative``
            ``None``: all of them are used); itself when every bin is informative.
        """
        used = self.used
        if used.all():
            return self
        coh = None if self.coherence is None else self.coherence[used]
        power = None if self.input_power is None else self.input_power[used]
        return Measurement(self.frequency[used], self.response[used], self.quantity, self.boundary, self.sample_time,
                           self.delay_samples, coh, self.source, power, None)

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
                     source: str | None = None, input_power=None) -> Measurement:
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
    input_power : array_like or None, optional
        Input (force) auto-spectrum [N^2/Hz], >= 0 and finite, one value per frequency, or
        ``None``.

    Returns
    -------
    Measurement
        The validated record, with float and complex copies of the arrays and the informative
        bins (:func:`informative_bins`).

    Raises
    ------
    MeasurementError
        For an unknown quantity or boundary, a clamped handle, mismatched lengths, fewer than
        :data:`MIN_POINTS` points, non-finite values, frequencies not > 0 and increasing, a zero
        response, a bad sample time or frequency above Nyquist, a bad delay, or coherence outside
        [0, 1] or of the wrong length, or an input power that is negative, non-finite or of the
        wrong length.
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
    pw = None
    if input_power is not None:
        pw = np.asarray(input_power, dtype=float).reshape(-1)
        if pw.size != w.size or not np.all(np.isfinite(pw) & (pw >= 0)):
            raise MeasurementError("input power must have one finite value >= 0 per frequency", file=source)
    informative, _ = informative_bins(coh, pw)
    return Measurement(frequency=w, response=h, quantity=quantity, boundary=boundary, sample_time=T,
                       delay_samples=d, coherence=coh, source=source, input_power=pw, informative=informative)
