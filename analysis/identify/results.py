"""Result records of the identification (frozen dataclasses of numpy arrays; nothing draws)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.identify.goodness import Goodness
from analysis.identify.measurement import BinSelection, Measurement

__all__ = ["ChainFit", "OrderSelection", "Parameter"]


@dataclass(frozen=True)
class Parameter:
    """One row of the parameter table.

    Parameters
    ----------
    key : str
        The parameter key, e.g. ``"masses[0]"`` (:mod:`analysis.identify.params`).
    value : float
        The fitted (or fixed) value [kg, N/m or N s/m].
    std_error : float
        Absolute standard error by the delta method, ``value * sigma_log``, in the value's unit;
        0 for a fixed parameter.
    low : float
        Lower end of the 95 % interval (Wald: ``exp(theta - 1.96 sigma)``); 0 when unbounded.
    high : float
        Upper end of the 95 % interval (Wald: ``exp(theta + 1.96 sigma)``); ``inf`` when unbounded.
    fixed : bool
        Whether the value was given rather than fitted.
    identifiable : bool
        Whether the data determine it (not in :attr:`ChainFit.non_identifiable`).
    method : str, optional
        How the interval was found (an entry of :attr:`ChainFit.interval_methods`), default
        ``"wald"``.
    """

    key: str
    value: float
    std_error: float  # absolute, by the delta method value * sigma_log; 0 for a fixed parameter
    low: float  # 95 % interval exp(theta - 1.96 sigma)
    high: float  # exp(theta + 1.96 sigma)
    fixed: bool
    identifiable: bool
    method: str = "wald"  # how the interval was found (ChainFit.interval_methods)


@dataclass(frozen=True, eq=False)
class ChainFit:
    """A fitted chain with its uncertainty (see :mod:`analysis.identify.fit`).

    Attributes
    ----------
    device:
        The fitted :class:`~analysis.Device`: the least-squares optimum, or, when the handle mode
        is not detected, the chain with the handle merged into mass 1 (the BIC's choice,
        :mod:`analysis.identify.hidden`); ``values``, ``responses`` and the RSS are its own.
    keys, values, std_errors, log_std, lower, upper, fixed:
        The parameter table, one entry per key (fixed parameters have zero error and a point
        interval).  ``log_std`` is the standard error of ``log(value)``.
    free_keys, covariance, correlation:
        Covariance ``s^2 (J^T J)^{-1}`` of the free log-parameters and its correlation matrix.
    residual:
        RMS of the weighted real residual vector (log-magnitude and phase in rad).
    cost, rss, aic, bic, n_residuals, dof:
        ``cost = rss / 2``; ``AIC = R ln(RSS/R) + 2p``, ``BIC = R ln(RSS/R) + p ln R``.
    responses:
        Model response at the measured frequencies, one array per measurement.
    non_identifiable, suggestions:
        Keys judged not identifiable from these measurements, and for each what would fix it.
    warnings:
        Human-readable notes (non-convergence, non-identifiable parameters, ...).
    measurements:
        The measurements fitted, in the order of ``responses``.
    converged:
        Whether the least-squares solver reported convergence at the optimum.
    evaluations:
        Number of residual evaluations of the solver runs.
    starts:
        Number of start chains tried by the multi-start.
    interval_methods:
        How each interval was found: ``"wald"`` (``exp(theta +- 1.96 sigma)`` from ``J^T J``),
        ``"profile"`` (profile likelihood, :mod:`analysis.identify.profile`), ``"profile
        (unbounded)"`` (the data do not bound it on one side: ``0`` or ``inf``), ``"fixed"``;
        ``" + other optima"`` when widened to equally good optima of the multi-start,
        ``" + handle family"`` when widened to the handles that fit as well as the merged chain
        (:mod:`analysis.identify.hidden`).
    bins:
        For each measurement, how many bins were fitted and why the others were not
        (:class:`~analysis.identify.measurement.BinSelection`); :attr:`bins_summary` in one line.
        ``residual``, ``rss``, ``n_residuals`` and the criteria count the fitted bins only;
        ``responses`` are at every bin of ``measurements``.
    start_rss:
        Weighted RSS of the optimum reached from the Stieltjes start of the informative band
        (:mod:`analysis.identify.start`), run to convergence on the same bins as every other
        candidate: ``rss`` is at most this, unless the reported chain is the merged one of an
        undetected handle mode (:mod:`analysis.identify.hidden`); ``nan`` without free
        parameters.
    goodness:
        The goodness-of-fit test (:class:`~analysis.identify.goodness.Goodness`: statistic,
        expected, threshold, passed, message) on the fitted bins; when it fails, the intervals
        are not trustworthy (:attr:`intervals_trustworthy`) and its message is the first warning.
    """

    device: Device
    keys: tuple[str, ...]
    values: np.ndarray
    std_errors: np.ndarray
    log_std: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    fixed: np.ndarray
    free_keys: tuple[str, ...]
    covariance: np.ndarray
    correlation: np.ndarray
    residual: float
    cost: float
    rss: float
    aic: float
    bic: float
    n_residuals: int
    dof: int
    responses: tuple[np.ndarray, ...]
    measurements: tuple[Measurement, ...]
    non_identifiable: tuple[str, ...]
    suggestions: dict
    warnings: tuple[str, ...]
    converged: bool
    evaluations: int
    starts: int
    interval_methods: tuple[str, ...] = ()
    bins: tuple[BinSelection, ...] = ()
    start_rss: float = float("nan")
    goodness: Goodness | None = None

    @property
    def intervals_trustworthy(self) -> bool:
        """Whether the intervals may be reported as 95 % intervals: the model explains the data
        (:attr:`goodness` passed).  When not, show them labelled "not trustworthy" with
        ``goodness.message`` (also the first of :attr:`warnings`)."""
        return self.goodness is None or self.goodness.passed

    @property
    def bins_summary(self) -> str:
        """One line: the bins fitted of each measurement and why the others were left out."""
        return "; ".join(b.summary for b in self.bins)

    @property
    def intervals(self) -> dict[str, tuple[float, float]]:
        """``{key: (low, high)}`` at 95 % for every parameter (a fixed one: its value twice; an
        unbounded side ``0`` or ``inf``); :attr:`interval_methods` says how each was found."""
        return {k: (float(lo), float(hi)) for k, lo, hi in zip(self.keys, self.lower, self.upper)}

    @property
    def parameters(self) -> tuple[Parameter, ...]:
        """The parameter table as rows."""
        bad = set(self.non_identifiable)
        methods = self.interval_methods or tuple("fixed" if f else "wald" for f in self.fixed)
        return tuple(Parameter(k, float(v), float(e), float(lo), float(hi), bool(f), k not in bad, m)
                     for k, v, e, lo, hi, f, m in zip(self.keys, self.values, self.std_errors, self.lower,
                                                      self.upper, self.fixed, methods))

    def value(self, key: str) -> float:
        """The fitted (or fixed) value of one parameter.

        Parameters
        ----------
        key : str
            A key of :attr:`keys`, e.g. ``"ground_dampings[3]"``.

        Returns
        -------
        float
            Its value [kg, N/m or N s/m].

        Raises
        ------
        ValueError
            When ``key`` is not one of :attr:`keys` (from ``tuple.index``).
        """
        return float(self.values[self.keys.index(key)])


@dataclass(frozen=True, eq=False)
class OrderSelection:
    """Fits of ``n = 1..N`` masses with their criteria (lower AIC/BIC is better).

    Parameters
    ----------
    n : numpy.ndarray
        The numbers of masses fitted, ascending, int, shape (K,).
    aic : numpy.ndarray
        ``AIC = R ln(RSS/R) + 2p`` of each order, ``nan`` where the fit failed, shape (K,).
    bic : numpy.ndarray
        ``BIC = R ln(RSS/R) + p ln R`` of each order, ``nan`` where the fit failed, shape (K,).
    residual : numpy.ndarray
        RMS weighted residual of each order (:attr:`ChainFit.residual`), ``nan`` where the fit
        failed, shape (K,).
    fits : tuple of (ChainFit or None)
        The fit of each order, ``None`` where it failed.
    errors : tuple of (str or None)
        Why an order could not be fitted, ``None`` where it was.
    best_bic : int or None
        The number of masses with the lowest BIC; ``None`` when no order was fitted.
    """

    n: np.ndarray
    aic: np.ndarray
    bic: np.ndarray
    residual: np.ndarray
    fits: tuple[ChainFit | None, ...]
    errors: tuple[str | None, ...]
    best_bic: int | None
