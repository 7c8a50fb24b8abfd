"""Fitting a chain to measurements: :func:`fit_chain` and :func:`order_selection`.

Method
------
0. Bins: only the informative bins of each measurement are fitted (coherence and input power,
   :func:`analysis.identify.measurement.informative_bins`; an FRF without either: every bin);
   everything below -- the start, every candidate's RSS, the intervals -- sees those bins only.
   :attr:`ChainFit.bins` says how many were used and why the others were not.
1. Unknowns: ``n`` masses, ``n - 1`` stiffnesses, ``n - 1`` element dampings and the selected
   ground dampings (default: the actuator mass, ``n - 1``), minus the ``fixed`` ones; they are
   fitted as ``theta = log(value)`` (:mod:`analysis.identify.problem`).
2. Start: :func:`analysis.identify.start.start_chains` (undamped chain from the resonances and
   antiresonances of the first ``actuator``/``free`` measurement by the Stieltjes / Lanczos
   inverse; pairs it does not show are placed at peaks of the other measurements or where a fit
   without them misses most, plus seeded candidates).  Every candidate gets a short
   Levenberg-Marquardt run (:func:`scipy.optimize.least_squares`, ``method="lm"``), the best two
   are run to convergence and the lower cost wins.  The Stieltjes start of the informative band
   (the first data-derived candidate) is always among those run to convergence, whatever its
   short run gave: every candidate's weighted RSS is compared on the same bins, and the result
   is never worse than the optimum reached from the data's own spectrum
   (:attr:`ChainFit.start_rss`).  Without an ``actuator``/``free``
   measurement the start is generic and the fit says so in its warnings.  With ``fixed``
   unknowns, the candidates also include the optimum of the fit with them released, the fixed
   values put back as they are and with the handle side rescaled to keep its modes
   (:func:`_released_starts`): the data-derived start knows nothing of the fixed values.
   When the optimum has a handle-side mass shrunk to nothing (a degenerate plateau of a weakly
   visible mode), restarts give it back a share of its neighbour's mass
   (:func:`analysis.identify.degenerate.reinflate`).
3. Uncertainty at the optimum (:mod:`analysis.identify.uncertainty`): covariance
   ``s^2 (J^T J)^{-1}`` in log-parameters, 95 % intervals ``exp(theta +- 1.96 sigma)`` where they
   are reliable, profile-likelihood intervals (:mod:`analysis.identify.profile`) where not,
   unbounded ``(0, inf)`` for parameters that are not identifiable (``intervals="auto"``);
   widened to other optima that fit equally well (likelihood-ratio bound), identifiability
   with suggestions.  A handle mode the data do not show (BIC against the chain with mass 0
   merged into mass 1) refers the intervals to that chain, makes the handle's unknowns
   unbounded and widens the rest to the family of handles that fit as well (the fit restarts
   from the family's best member when it fits better), and the reported device is that merged
   chain, the BIC's choice (:mod:`analysis.identify.hidden`).

Identifiability of the HBFD
---------------------------
At the actuator the HBFD's handle mode has its pole (842.45 rad/s) and zero (842.72 rad/s) 0.03 %
apart: noise-free data determine the handle side (every parameter to 1e-6 from the automatic
start), but at 1 % noise the actuator FRF alone cannot place it -- several basins fit equally
well and the handle-side parameters are reported as not identifiable, the others with
intervals that contain every handle the data allow.  A ``gauge`` (or ``handle``) measurement
with the handle free shows the mode and fixes it.
4. Model order: :func:`order_selection` fits ``n = 1..N`` and reports AIC and BIC.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.identify.degenerate import reinflate
from analysis.identify.errors import MeasurementError
from analysis.identify.measurement import MIN_POINTS, Measurement
from analysis.identify.params import ChainParameters, parameter_keys, parse_key
from analysis.identify.problem import FitProblem, solve
from analysis.identify.results import ChainFit, OrderSelection
from analysis.identify.start import other_peaks, start_chains, visible_spectrum
from analysis.identify.uncertainty import build_fit
from analysis.progress import Cancelled

__all__ = ["fit_chain", "order_selection"]

_SHORT_RUN = 15
_FULL_RUNS = 2


def _check(measurements: Sequence[Measurement], n_masses: int, ground: Sequence[int],
           fixed: Mapping[str, float]) -> None:
    from analysis.errors import ValidationError

    if not measurements:
        raise ValidationError("measurements", "at least one measurement", [])
    if isinstance(n_masses, bool) or int(n_masses) != n_masses or n_masses < 1:
        raise ValidationError("n_masses", "an integer >= 1", n_masses)
    for g in ground:
        if not 0 <= int(g) < n_masses:
            raise ValidationError("ground_dampings", f"mass indices 0..{n_masses - 1}", g)
    for key, v in fixed.items():
        name, _ = parse_key(key, n_masses)
        positive = name in ("masses", "stiffnesses")
        if not (np.isfinite(v) and (v > 0 if positive else v >= 0)):
            raise ValidationError(key, "> 0 and finite" if positive else ">= 0 and finite", v)
    for m in measurements:
        b = m.bins
        if b.used < MIN_POINTS:
            raise MeasurementError(f"{b.used} of {b.total} bins carry information ({b.summary.split(': ', 1)[-1]}): "
                                   f"at least {MIN_POINTS} are needed; excite the band to be fitted", file=m.source)


def fit_chain(measurements: Sequence[Measurement], n_masses: int, ground_dampings: Sequence[int] | None = None,
              fixed: Mapping[str, float] | None = None, *, sensor_element: int = 0,
              sample_time: float | None = None, band_min: float = 1.0, starts: int = 4, seed: int = 0,
              max_nfev: int = 200, intervals: str = "auto",
              cancelled: Cancelled | None = None) -> ChainFit:
    """Fit an ``n_masses`` chain to ``measurements`` together (module doc).

    ``ground_dampings`` selects the masses with a damper to ground (default ``(n - 1,)``, the
    actuator); ``fixed`` maps keys such as ``"masses[0]"`` to known values.  The fitted
    :class:`~analysis.Device` carries ``sensor_element``, the sample time (``sample_time``, else
    the measurements' common one, else 1 ms) and ``band_min``.  ``starts`` seeded candidates are
    tried when the data do not show every resonance.  ``intervals``: ``"auto"`` (Wald intervals,
    replaced by profile-likelihood ones where the Wald interval is unreliable), ``"wald"`` (the
    Jacobian only, fastest) or ``"profile"`` (every free parameter profiled); see
    :func:`analysis.identify.uncertainty.profile_selection`.  ``cancelled()`` is asked before
    every model evaluation; once it returns True the fit raises
    :class:`~analysis.progress.OperationCancelled` (``FitCancelled``).

    Parameters
    ----------
    measurements : sequence of Measurement
        The measurements fitted together (at least one).
    n_masses : int
        Number of masses of the chain, >= 1.
    ground_dampings : sequence of int or None, optional
        Indices (0-based, handle 0) of the masses with a damper to ground; ``None``: the
        actuator, ``(n_masses - 1,)``.
    fixed : mapping of str to float or None, optional
        Known values by key, e.g. ``{"masses[0]": 0.02}`` [kg, N/m or N s/m]; masses and
        stiffnesses > 0, dampings >= 0.
    sensor_element : int, optional
        The element of the force gauge (``gauge`` measurements), 0-based.
    sample_time : float or None, optional
        Sample time [s] of the fitted device; ``None``: the measurements' common one, else 1 ms.
    band_min : float, optional
        Lowest frequency [rad/s] of the fitted device's analysis band.
    starts : int, optional
        Number of seeded start candidates when the data do not show every resonance.
    seed : int, optional
        Seed of the start candidates.
    max_nfev : int, optional
        Largest number of residual evaluations of each full solver run.
    intervals : str, optional
        ``"auto"``, ``"wald"`` or ``"profile"`` (:data:`INTERVAL_MODES`).
    cancelled : callable or None, optional
        ``cancelled() -> bool``, asked before every model evaluation.

    Returns
    -------
    ChainFit
        The fitted device with its parameter table, intervals, covariance, criteria, responses
        and warnings.

    Raises
    ------
    ValidationError
        For no measurements, ``n_masses`` not an integer >= 1, a ground-damping index outside
        the chain, a fixed value out of range, or an unknown ``intervals`` mode.
    MeasurementError
        When a measurement has fewer than :data:`~analysis.identify.measurement.MIN_POINTS`
        informative bins.
    ParameterKeyError
        When a key of ``fixed`` does not name a parameter of an ``n_masses`` chain.
    OperationCancelled
        When ``cancelled()`` returns True (``FitCancelled`` is its deprecated alias).
    """
    fixed = dict(fixed or {})
    ground = tuple(sorted(set((n_masses - 1,) if ground_dampings is None else (int(g) for g in ground_dampings))))
    _check(measurements, n_masses, ground, fixed)
    originals = tuple(measurements)
    measurements = tuple(m.informative_only() for m in originals)
    keys = parameter_keys(n_masses, ground)
    for key in fixed:
        if key not in keys:
            keys.append(key)  # a fixed ground damping not selected for fitting
    free = [k for k in keys if k not in fixed]
    hints = _hidden_hints(measurements, n_masses, seed, cancelled)
    rows = start_chains(measurements, n_masses, ground, fixed, count=starts, seed=seed, hints=hints)
    all_keys = parameter_keys(n_masses, None)
    base = ChainParameters.from_rows(all_keys, _values(rows, all_keys)[:1], rows)
    problem = FitProblem(tuple(measurements), tuple(free), base, int(sensor_element), cancelled)
    thetas = np.log(np.maximum(_values(rows, free), 1e-300))
    if free and set(fixed) & set(parameter_keys(n_masses, ground)):
        released = _released_starts(problem, ground, fixed, rows.count, seed, hints, max_nfev)
        thetas = np.vstack([released, thetas])
    stieltjes = thetas.shape[0] - rows.count  # the first data-derived row, after any released starts
    sol, others, anchor = _multistart(problem, thetas, max_nfev, always=stieltjes) if free else (None, [], None)
    if sol is not None:
        sol = reinflate(problem, sol, max_nfev)
    T = sample_time if sample_time is not None else _common_sample_time(measurements)
    template = Device(masses=np.ones(n_masses), stiffnesses=np.ones(n_masses - 1),
                      dampings=np.zeros(n_masses - 1), sensor_element=sensor_element, sample_time=T,
                      band_min=band_min)
    notes = () if any(m.quantity == "actuator" and m.boundary == "free" for m in measurements) else (
        "no actuator/free measurement: the start is generic (modes spread over the band), not read off the "
        "data; check the fit, or add the collocated actuator test with the handle free",)
    fit = build_fit(problem, sol, keys, fixed, template, n_starts=thetas.shape[0], notes=notes,
                    alternatives=[o.x for o in others], intervals=intervals, originals=originals)
    return replace(fit, start_rss=float("nan") if anchor is None else 2.0 * float(anchor.cost))


def _multistart(problem: FitProblem, thetas: np.ndarray, max_nfev: int, always: int | None = None
                ) -> tuple[optimize.OptimizeResult, list[optimize.OptimizeResult], optimize.OptimizeResult | None]:
    """Short runs from every start, full runs from the best :data:`_FULL_RUNS` and from the start
    ``always`` (the Stieltjes start, whatever its short run gave); returns the lowest-cost optimum,
    the other full-run optima (for :func:`analysis.identify.uncertainty.widen_to_equivalent_optima`)
    and the full run from ``always`` (``None`` without it)."""
    if thetas.shape[0] == 1:
        only = solve(problem, thetas[0], max_nfev)
        return only, [], only if always is not None else None
    short = [solve(problem, th, _SHORT_RUN) for th in thetas]
    order = sorted(range(len(short)), key=lambda i: short[i].cost)
    chosen = order[:_FULL_RUNS] + ([always] if always is not None and always not in order[:_FULL_RUNS] else [])
    runs = {i: solve(problem, short[i].x, max_nfev) for i in chosen}
    full = sorted(runs.values(), key=lambda r: r.cost)
    return full[0], full[1:], runs.get(always) if always is not None else None


def _released_starts(problem: FitProblem, ground: tuple[int, ...], fixed: Mapping[str, float], count: int,
                     seed: int, hints: np.ndarray | None, max_nfev: int) -> np.ndarray:
    """Starts consistent with the fixed values: the fit with the chain's own fixed unknowns
    released (fitted too), then the fixed values put back, as they are and with the handle side
    rescaled (:func:`_rescaled`); rows of ``theta`` of ``problem.keys``.

    The data-derived start (:func:`start_chains`) knows nothing of the fixed values: pasting a
    fixed handle mass into a start whose hidden handle mode came from a guessed pair width moves
    that mode far away, and the constrained search lands in another basin.  The released fit
    starts from the same data-derived candidates as the unconstrained :func:`fit_chain` and
    lands near the data's optimum; with the fixed values put back it starts the constrained
    search in the right basin (on noise-free data with true fixed values, at the truth).
    """
    n = problem.base.n
    own = parameter_keys(n, ground)
    held = {k: v for k, v in fixed.items() if k not in own}  # fixed ground dampings not selected
    rows = start_chains(problem.measurements, n, ground, held, count=count, seed=seed, hints=hints)
    all_keys = parameter_keys(n, None)
    base = ChainParameters.from_rows(all_keys, _values(rows, all_keys)[:1], rows)
    released = problem.sub(tuple(own), base)
    sol, _, _ = _multistart(released, np.log(np.maximum(_values(rows, own), 1e-300)), max_nfev)
    chain = released.chains(sol.x)
    chain = ChainParameters(*(np.concatenate([a, a]) for a in
                              (chain.masses, chain.stiffnesses, chain.dampings, chain.ground_dampings)))
    _rescaled(chain, 1, fixed)
    for key, v in fixed.items():
        name, i = parse_key(key, n)
        getattr(chain, name)[:, i] = float(v)
    thetas = np.log(np.maximum(_values(chain, problem.keys), 1e-300))
    return thetas[:1] if np.allclose(thetas[0], thetas[1], rtol=0.0, atol=1e-9) else thetas


def _rescaled(chain: ChainParameters, row: int, fixed: Mapping[str, float]) -> None:
    """Rescale the handle side of ``chain[row]`` in place so that a fixed mass or stiffness keeps
    the modes of that side.

    For a fixed ``masses[i]`` or ``stiffnesses[i]`` with ratio ``r = fixed / fitted``, the masses
    ``0..i`` and the elements ``0..i`` (stiffness and damping) are multiplied by ``r``: the
    sub-chain's ``K - w^2 M`` scales by ``r``, so its modes against the rest (e.g. the handle
    mode ``sqrt(k_0 / m_0)``) and their damping ratios stay where the data put them.  A poorly
    determined handle mass from the released fit (1 % noise) otherwise moves the handle mode by
    orders of magnitude when the known value is put in.
    """
    n = chain.n
    for key, v in fixed.items():
        name, i = parse_key(key, n)
        if name not in ("masses", "stiffnesses"):
            continue
        old = float(getattr(chain, name)[row, i])
        if not (old > 0 and v > 0):
            continue
        r = float(v) / old
        top = min(i, n - 2)
        chain.masses[row, : i + 1] *= r
        chain.stiffnesses[row, : top + 1] *= r
        chain.dampings[row, : top + 1] *= r


def _hidden_hints(measurements: Sequence[Measurement], n: int, seed: int,
                  cancelled: Cancelled | None = None) -> np.ndarray | None:
    """Frequencies of resonance pairs an ``n``-mass chain needs but the driving point does not show.

    First the peaks of the other measurements away from the visible resonances
    (:func:`analysis.identify.start.other_peaks`).  Then a chain with only the visible pairs is
    fitted (briefly) to the driving-point measurement; its misfit ``|log(model/measured)|``,
    smoothed over 5 points, peaks where the hidden pairs sit (a mode that the actuator barely
    sees still leaves a small local signature).  The largest local maxima, at least 20 % apart
    in frequency, fill the remaining hints.
    """
    z, p = visible_spectrum(measurements, n)
    k = z.size
    missing = n - 1 - k
    dp = [m for m in measurements if m.quantity == "actuator" and m.boundary == "free"]
    if missing <= 0 or not dp:
        return None
    picked = list(other_peaks(measurements, p)[:missing])
    if len(picked) == missing:
        return np.array(picked)
    rows = start_chains(dp[:1], k + 1, (k,), {}, count=1, seed=seed)
    keys = parameter_keys(k + 1, (k,))
    problem = FitProblem((dp[0],), tuple(keys), rows, 0, cancelled)
    th = solve(problem, np.log(_values(rows, keys)[0]), _SHORT_RUN).x
    r = problem.residual(th)
    F = dp[0].size
    mis = np.convolve(np.hypot(r[:F], r[F:]), np.ones(5) / 5, mode="same")
    w = dp[0].frequency
    for j in np.argsort(mis)[::-1]:
        if len(picked) == missing:
            break
        if 0 < j < F - 1 and mis[j] >= mis[j - 1] and mis[j] >= mis[j + 1]:
            if all(abs(np.log(w[j] / f)) > np.log(1.2) for f in picked):
                picked.append(float(w[j]))
    return np.array(picked) if picked else None


def _values(params: ChainParameters, keys: Sequence[str]) -> np.ndarray:
    out = np.empty((params.count, len(keys)))
    for j, key in enumerate(keys):
        name, i = parse_key(key, params.n)
        out[:, j] = getattr(params, name)[:, i]
    return out


def _common_sample_time(measurements: Sequence[Measurement]) -> float:
    ts = {m.sample_time for m in measurements if m.sample_time is not None}
    return ts.pop() if len(ts) == 1 else 1e-3


@dataclass(frozen=True)
class _Order:
    n: int
    fit: ChainFit | None
    error: str | None


def order_selection(measurements: Sequence[Measurement], max_masses: int, *, min_masses: int = 1,
                    **kwargs) -> OrderSelection:
    """Fit ``n = min_masses .. max_masses`` and report AIC, BIC and the residual of each.

    ``AIC = R ln(RSS/R) + 2 p`` and ``BIC = R ln(RSS/R) + p ln R`` with ``R`` real residuals and
    ``p`` free parameters (Gaussian errors of unknown variance).  ``kwargs`` go to
    :func:`fit_chain` (``intervals`` defaults to ``"wald"`` here: the table needs no profiles);
    ``ground_dampings`` defaults to the actuator of each order.  An order that
    cannot be fitted (e.g. a fixed key outside the chain) is reported with ``nan``.

    Parameters
    ----------
    measurements : sequence of Measurement
        The measurements fitted together.
    max_masses : int
        Largest number of masses fitted.
    min_masses : int, optional
        Smallest number of masses fitted.
    **kwargs
        Keyword arguments of :func:`fit_chain`.

    Returns
    -------
    OrderSelection
        The criteria and fit of each order (``nan`` and the error message where the fit raised
        a ``ValueError``), and the order with the lowest BIC.

    Raises
    ------
    OperationCancelled
        When ``cancelled()`` (passed in ``kwargs``) returns True.
    """
    out = []
    kwargs.setdefault("intervals", "wald")
    for n in range(int(min_masses), int(max_masses) + 1):
        try:
            out.append(_Order(n, fit_chain(measurements, n, **kwargs), None))
        except ValueError as exc:
            out.append(_Order(n, None, str(exc)))
    nan = float("nan")
    aic = np.array([o.fit.aic if o.fit else nan for o in out])
    bic = np.array([o.fit.bic if o.fit else nan for o in out])
    res = np.array([o.fit.residual if o.fit else nan for o in out])
    best = int(np.array([o.n for o in out])[np.nanargmin(bic)]) if np.any(np.isfinite(bic)) else None
    return OrderSelection(n=np.array([o.n for o in out]), aic=aic, bic=bic, residual=res,
                          fits=tuple(o.fit for o in out), errors=tuple(o.error for o in out), best_bic=best)
