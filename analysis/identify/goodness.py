"""Goodness of fit: does the model explain the data, or only fit them as well as it can? (issue 23)

The statistic compares the fit's residual with the noise of the data, read off the data
themselves.  With ``e_f = log(H_model(w_f) / H_measured(w_f))`` over the fitted (informative)
bins of every measurement, its real part (log-magnitude) and imaginary part (phase, wrapped)
taken as two sequences along frequency:

* the fit's residual variance ``s^2 = sum |e|^2 / (R - p)`` (``R`` real residuals, ``p`` free
  parameters);
* the noise variance ``sigma^2 = sum (e_{f+1} - 2 e_f + e_{f-1})^2 / (6 R_2)`` from the
  second differences along frequency (``R_2`` of them): independent noise of variance ``sigma^2``
  gives second differences of variance ``6 sigma^2``, while a misfit that varies smoothly with
  frequency -- a resonance the model cannot place, a missing mode -- cancels out of them;
* the statistic ``chi2 = s^2 / sigma^2``, expected ``1`` when the model explains the data (the
  residual is noise: a chi-square over its degrees of freedom), ``1 + (misfit / noise)^2``
  when it does not.

The fit passes when ``chi2 <= GOODNESS_THRESHOLD`` (20: the systematic misfit is at most about
``sqrt(19) = 4.4`` times the noise's bin-to-bin scatter).  The threshold is wide because a Welch
estimate is not white: neighbouring bins of a Hann-windowed estimate are correlated, and a chirp
test leaves a smooth estimator bias (leakage near the sweep's start, widened resonances); on the
chirp benchmark (``tests/benchmarks/bench_identify_chirp.py``) the right model order gives 2 to 8
and one mass too few gives 60 to more than 1000.  This uses the noise level rather than the
coherence's prediction ``(1 - gamma^2) / (2 n_d gamma^2)``: a chirp sweeps each frequency in
about one Welch segment, so its coherence is near 1 whatever the noise (one effective average),
and an FRF file may have no coherence at all.  Data matched to round-off (RMS residual below
1e-9) pass.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analysis.identify.measurement import Measurement

__all__ = ["GOODNESS_THRESHOLD", "Goodness", "goodness_of_fit"]

#: Largest ratio of the residual variance to the noise variance of a fit that explains the data.
GOODNESS_THRESHOLD = 20.0
_ROUNDOFF = 1e-9


@dataclass(frozen=True)
class Goodness:
    """The goodness-of-fit test of a chain fit (module doc).

    Attributes
    ----------
    statistic : float
        ``s^2 / sigma^2``: the residual variance over the noise variance read off the data.
    expected : float
        Its value when the model explains the data: 1.
    threshold : float
        The largest value that passes (:data:`GOODNESS_THRESHOLD`).
    passed : bool
        Whether the model explains the data; when not, the intervals are not trustworthy.
    message : str
        One line saying so, with the numbers.
    residual_rms : float
        ``s``, the RMS residual of the log-response (log-magnitude and phase in rad).
    noise_rms : float
        ``sigma``, the noise level of the log-response read off the data.
    """

    statistic: float
    expected: float
    threshold: float
    passed: bool
    message: str
    residual_rms: float
    noise_rms: float


def goodness_of_fit(measurements: Sequence[Measurement], responses: Sequence[np.ndarray], n_params: int,
                    threshold: float = GOODNESS_THRESHOLD) -> Goodness:
    """Test whether the model's ``responses`` explain ``measurements`` (module doc).

    Parameters
    ----------
    measurements : sequence of Measurement
        The bins that were fitted (the informative ones), each in frequency order.
    responses : sequence of numpy.ndarray
        The model response at each measurement's frequencies, shape (F_m,).
    n_params : int
        Number of free parameters of the fit.
    threshold : float, optional
        Largest statistic that passes.

    Returns
    -------
    Goodness
        The statistic, its expected value, the threshold, the verdict and its message.
    """
    parts = []
    with np.errstate(divide="ignore", invalid="ignore"):
        for m, h in zip(measurements, responses):
            e = np.log(np.asarray(h) / m.response)
            parts += [e.real, e.imag]
    n = sum(q.size for q in parts)
    rss = float(sum(q @ q for q in parts))
    d2 = [q[2:] - 2 * q[1:-1] + q[:-2] for q in parts if q.size >= 3]
    n2 = sum(q.size for q in d2)
    s2 = rss / max(n - n_params, 1)
    noise2 = float(sum(q @ q for q in d2)) / (6 * n2) if n2 else math.nan
    s, noise = math.sqrt(s2), math.sqrt(noise2) if noise2 == noise2 else math.nan
    if not math.isfinite(rss):
        return Goodness(math.inf, 1.0, threshold, False, "the model response is not finite at a fitted bin",
                        s, noise)
    if math.sqrt(rss / max(n, 1)) <= _ROUNDOFF:
        return Goodness(1.0, 1.0, threshold, True, "the model matches the data to round-off", s, noise)
    stat = s2 / noise2 if noise2 > 0 else math.inf
    passed = bool(stat <= threshold)
    if passed:
        msg = (f"the model explains the data: residual {s:.3g} against a noise level of {noise:.3g} "
               f"(chi2 = {stat:.3g}, at most {threshold:g})")
    else:
        msg = (f"the model does not explain the data: residual {s:.3g} against a noise level of {noise:.3g} "
               f"(chi2 = {stat:.3g} > {threshold:g}); the intervals are not trustworthy -- try another number "
               f"of masses, or check the measurements")
    return Goodness(stat, 1.0, threshold, passed, msg, s, noise)
