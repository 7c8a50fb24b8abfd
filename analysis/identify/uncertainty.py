"""Uncertainty of a chain fit from the Jacobian at the optimum.

With ``J`` the (central-difference) Jacobian of the weighted real residual vector in the free
log-parameters ``theta``, ``R`` residuals, ``p`` free parameters and ``RSS`` the weighted sum
of squares, the residual variance is ``s^2 = RSS / (R - p)`` and the asymptotic covariance of
``theta`` is ``s^2 (J^T J)^{-1}`` (Gauss-Newton / Fisher information of Gaussian errors;
e.g. Seber & Wild, *Nonlinear Regression*, sec. 2.1).  It is formed from the SVD
``J = U S V^T`` as ``s^2 V S^{-2} V^T``.  The 95 % interval of a parameter is
``exp(theta +- 1.96 sigma)`` (symmetric in log, so always positive), its standard error by the
delta method ``value * sigma``.

Identifiability: singular values below ``1e-8`` of the largest span directions the data do not
constrain; parameters with a component above 0.1 in such a direction, and parameters whose
interval spans more than a factor 10 (``sigma > ln(10)/3.92``), are reported as not identifiable,
with the measurement that would constrain them (:func:`suggestion`).  A handle mode that the
data do not show changes the reference of the likelihood-ratio intervals
(:mod:`analysis.identify.hidden`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.identify.degenerate import SHARES, degenerate_masses, restart
from analysis.identify.goodness import goodness_of_fit
from analysis.identify.hidden import HANDLE_KEYS, MERGED_SHARE, HiddenHandle, adopt_best, hidden_handle
from analysis.identify.measurement import Measurement
from analysis.identify.params import ChainParameters, parse_key
from analysis.identify.problem import FitProblem
from analysis.identify.profile import Profiler, curvature_ratios, profile_intervals
from analysis.identify.results import ChainFit

__all__ = ["CURVATURE_TOLERANCE", "INTERVAL_MODES", "build_fit", "covariance", "profile_selection", "suggestion"]

Z95 = 1.959963984540054
_SINGULAR = 1e-8
_WIDE = math.log(10.0) / (2 * Z95)
_CHI2_1 = 3.841458820694124  # 95 % quantile of chi-square with 1 degree of freedom


def suggestion(key: str, n: int, measured: set[tuple[str, str]], handle_hidden: bool = False) -> str:
    """What measurement would constrain ``key`` better, given the (quantity, boundary) pairs used;
    ``handle_hidden``: the data do not show the handle mode (:mod:`analysis.identify.hidden`), so
    whatever it leaves loose is fixed by showing it."""
    name, i = parse_key(key, n)
    handle_side = (name == "masses" and i < n - 1) or (name in ("stiffnesses", "dampings") and i == 0)
    handle_side = handle_side or (handle_hidden and name != "ground_dampings")
    if handle_side and ("actuator", "clamped") not in measured:
        return "add a clamped-handle test (actuator quantity, boundary 'clamped')"
    if handle_side and not ({("handle", "free"), ("gauge", "free")} & measured):
        return "add a 'handle' or 'gauge' measurement with the handle free"
    if name == "ground_dampings":
        return "extend the band to lower frequencies, where the damper to ground dominates, or fix it"
    if name == "dampings":
        return "add frequency points (and coherence) around the resonances, or fix it"
    return "extend the band above the highest resonance, or fix this parameter to a known value"


def covariance(J: np.ndarray, rss: float) -> tuple[np.ndarray, np.ndarray]:
    """``s^2 (J^T J)^{-1}`` by the SVD, and a boolean mask of parameters in near-null directions."""
    R, p = J.shape
    if p == 0:
        return np.zeros((0, 0)), np.zeros(0, bool)
    U, S, Vt = np.linalg.svd(J, full_matrices=False)
    keep = S > _SINGULAR * S[0] if S[0] > 0 else np.zeros(p, bool)
    s2 = rss / max(R - p, 1)
    V = Vt.T
    cov = (V[:, keep] / S[keep] ** 2) @ V[:, keep].T * s2
    null = np.any(np.abs(V[:, ~keep]) > 0.1, axis=1) if np.any(~keep) else np.zeros(p, bool)
    return cov, null


def _table(keys: Sequence[str], problem: FitProblem, theta: np.ndarray, cov: np.ndarray, null: np.ndarray,
           fixed: Mapping[str, float]) -> tuple[np.ndarray, ...]:
    """Values, log sigmas, lower/upper and fixed flags in the order of ``keys``."""
    chain = problem.chains(theta)
    vals, lsd, fx = [], [], []
    free = list(problem.keys)
    for key in keys:
        name, i = parse_key(key, chain.n)
        vals.append(float(getattr(chain, name)[0, i]))
        if key in fixed:
            lsd.append(0.0)
            fx.append(True)
        else:
            j = free.index(key)
            lsd.append(math.inf if null[j] else math.sqrt(max(cov[j, j], 0.0)))
            fx.append(False)
    v, s = np.array(vals), np.array(lsd)
    with np.errstate(over="ignore", invalid="ignore"):
        lo = np.where(np.isfinite(s), v * np.exp(-Z95 * s), 0.0)
        hi = np.where(np.isfinite(s), v * np.exp(Z95 * s), np.inf)
        se = v * s
    return v, s, se, lo, hi, np.array(fx)


def likelihood_level(problem: FitProblem, rss: float, p: int, reference: float | None = None) -> float:
    """The largest RSS of a chain inside every 95 % likelihood-ratio interval: ``max(RSS,
    reference) + chi2_1(0.95) s^2`` with ``s^2 = RSS / (R - p)``."""
    s2 = rss / max(problem.n_residuals - p, 1)
    return max(rss, reference if reference is not None else rss) + _CHI2_1 * s2


def widen_to_equivalent_optima(keys: Sequence[str], problem: FitProblem, lo: np.ndarray, hi: np.ndarray,
                               rss: float, p: int, alternatives: Sequence[np.ndarray],
                               reference: float | None = None) -> tuple[np.ndarray, np.ndarray, set[str]]:
    """Widen the intervals to every alternative chain that the data cannot tell from the best.

    A chain ``theta_i`` with ``RSS_i - RSS <= chi2_1(0.95) s^2`` (3.84 s^2) lies inside every
    parameter's 95 % profile-likelihood interval (the profile at ``theta_i``'s value is at most
    ``RSS_i``), so including it is a justified lower bound on that interval; it need not be an
    optimum.  This catches what the local (Jacobian) intervals cannot: several basins fitting
    equally well, as when a mode is nearly invisible in the measured quantity.  ``reference``
    (default ``rss``) is the RSS the ratio is taken from (:mod:`analysis.identify.hidden`).
    Returns (lo, hi, keys whose interval moved).
    """
    level = likelihood_level(problem, rss, p, reference)
    lo, hi = lo.copy(), hi.copy()
    moved: set[str] = set()
    for alt in alternatives:
        r = problem.residual(alt)
        if float(r @ r) > level:
            continue
        chain = problem.chains(alt)
        for j, key in enumerate(keys):
            name, i = parse_key(key, chain.n)
            v = float(getattr(chain, name)[0, i])
            if key in problem.keys and not lo[j] <= v <= hi[j]:
                lo[j], hi[j] = min(lo[j], v), max(hi[j], v)
                moved.add(key)
    return lo, hi, moved


INTERVAL_MODES = ("auto", "wald", "profile")
#: Largest accepted departure of the curvature ratio from 1 (:func:`curvature_ratios`) before the
#: Wald interval is replaced by the profile: at ``q = 0.85`` the profile bound is at least 8 %
#: further out than the Wald bound, and the nominal 95 % falls to about 93 %.
CURVATURE_TOLERANCE = 0.15
#: RMS residual below which the data are taken as exact (noise-free) and the check is skipped.
_ROUNDOFF = 1e-9


def profile_selection(mode: str, keys: Sequence[str], wide: np.ndarray, q: np.ndarray,
                      corr: np.ndarray) -> tuple[list[int], list[int]]:
    """Free parameters whose interval comes from the profile likelihood, and those reported as
    unbounded.

    ``"wald"``: none; ``"profile"``: all profiled; ``"auto"``: the parameters that are not
    identifiable (``wide``: a near-null direction of ``J^T J`` or a Wald interval wider than a
    factor 10) are reported unbounded, ``(0, inf)``, without a profile -- the data leave several
    disconnected families of chains within the likelihood bound (on the HBFD's actuator FRF
    the handle side can even swap places with the next mass), which a local profile walk cannot
    follow; then every other free parameter is profiled (its Wald interval holds at one point of a
    flat valley, and at a degenerate point of it -- a handle mass shrunk to nothing -- the
    correlations do not show the link).  Otherwise the parameters that fail the curvature check
    (``|q - 1| > CURVATURE_TOLERANCE`` on a side) are profiled.

    Parameters
    ----------
    mode : str
        ``"auto"``, ``"wald"`` or ``"profile"`` (:data:`INTERVAL_MODES`).
    keys : sequence of str
        The free parameter keys (``p`` of them).
    wide : numpy.ndarray
        Whether each free parameter is not identifiable, bool, shape (p,).
    q : numpy.ndarray
        Curvature ratios (lower, upper) of each free parameter
        (:func:`~analysis.identify.profile.curvature_ratios`), shape (p, 2).
    corr : numpy.ndarray
        Correlation matrix of the free log-parameters, shape (p, p); the rule above does not
        read it.

    Returns
    -------
    profiled : list of int
        Indices of the free parameters whose interval is profiled.
    unbounded : list of int
        Indices of those reported unbounded, ``(0, inf)``.

    Raises
    ------
    ValidationError
        When ``mode`` is not one of :data:`INTERVAL_MODES`.
    """
    if mode not in INTERVAL_MODES:
        from analysis.errors import ValidationError

        raise ValidationError("intervals", " | ".join(INTERVAL_MODES), mode)
    p = len(keys)
    if mode == "wald" or p == 0:
        return [], []
    if mode == "profile":
        return list(range(p)), []
    bent = ~np.all(np.abs(q - 1.0) <= CURVATURE_TOLERANCE, axis=1)
    if np.any(wide):  # the others' Wald intervals hold at one point of a flat valley
        return [j for j in range(p) if not wide[j]], [j for j in range(p) if wide[j]]
    return [j for j in range(p) if bent[j]], []


def _with_profiles(problem: FitProblem, theta: np.ndarray, rss: float, cov: np.ndarray, keys: Sequence[str],
                   lo: np.ndarray, hi: np.ndarray, methods: list[str], chosen: list[int],
                   reference: float | None) -> Profiler:
    """Replace the intervals of the free parameters ``chosen`` by their profile intervals."""
    extra = tuple(restart(problem, theta, i, f) for i in degenerate_masses(problem, theta) for f in SHARES)
    prof = Profiler(problem, theta, rss, cov, extra, reference)
    for j, (low, high, bounded) in profile_intervals(prof, chosen).items():
        at = list(keys).index(problem.keys[j])
        lo[at], hi[at] = low, high
        methods[at] = "profile" if bounded else "profile (unbounded)"
    return prof


def _choose_intervals(problem: FitProblem, theta: np.ndarray, rss: float, cov: np.ndarray, corr: np.ndarray,
                      keys: Sequence[str], s: np.ndarray, fx: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                      intervals: str, notes: Sequence[str],
                      hidden: HiddenHandle | None) -> tuple[list[str], list[str]]:
    """Apply :func:`profile_selection` to ``lo``/``hi`` in place; the method of each interval
    and the notes (plus one when the profile met a better fit than the optimum).  An undetected
    handle mode (``hidden``, :mod:`analysis.identify.hidden`) makes the handle's unknowns
    unbounded and refers every other (profiled) interval to the merged chain's RSS."""
    p = theta.size
    methods = ["fixed" if f else "wald" for f in fx]
    free_at = [list(keys).index(k) for k in problem.keys]
    wide = np.array([not (s[a] <= _WIDE) for a in free_at], bool)
    q = curvature_ratios(problem, theta, rss, cov) if intervals == "auto" and not _exact(problem, rss) else np.ones((p, 2))
    chosen, loose = profile_selection(intervals, problem.keys, wide, q, corr)
    reference = None
    if hidden is not None and not hidden.detected:
        reference = hidden.rss_merged
        loose = sorted(set(loose) | {j for j, k in enumerate(problem.keys) if k in HANDLE_KEYS})
        chosen = [j for j in range(p) if j not in loose]
    for j in loose:
        at = free_at[j]
        lo[at], hi[at], methods[at] = 0.0, math.inf, "unbounded (not identifiable)"
    notes = list(notes)
    if chosen:
        prof = _with_profiles(problem, theta, rss, cov, keys, lo, hi, methods, chosen, reference)
        if prof.best_rss < rss - 0.01 * prof.s2:
            notes.append(f"a chain that fits better than the optimum was met on the profile "
                         f"(RSS lower by {(rss - prof.best_rss) / prof.s2:.3g} s^2): the data leave the fit ambiguous")
    return methods, notes


def _exact(problem: FitProblem, rss: float) -> bool:
    """Noise-free data: the RMS residual is round-off, and RSS differences mean nothing."""
    return rss <= _ROUNDOFF**2 * max(problem.n_residuals, 1)


def _hidden_note(hidden: HiddenHandle, accepted: int) -> str:
    return (f"the handle mode is not detected in these measurements: the chain with mass 0 merged into "
            f"mass 1 fits within the BIC margin (RSS higher by {hidden.statistic:.3g} s^2, at most "
            f"3 ln R = {hidden.critical:.3g}); the fitted device is that chain (its handle a "
            f"{MERGED_SHARE:.0e} share of the pair's mass on a stiff element), the intervals are referred "
            f"to it, and contain the {accepted} of {len(hidden.family)} scanned handle configurations that "
            f"fit as well")


def _grouped(bad: Sequence[str], sugg: Mapping[str, str], unbounded: set[str]) -> list[str]:
    """One warning per suggestion, naming every key it fixes (and which have unbounded intervals)."""
    out = []
    for text in dict.fromkeys(sugg[k] for k in bad):
        ks = [k for k in bad if sugg[k] == text]
        loose = [k for k in ks if k in unbounded]
        verb = "is" if len(ks) == 1 else "are"
        side = ""
        if loose:
            side = (" (its 95 % interval is unbounded)" if ks == loose and len(ks) == 1 else
                    " (95 % interval unbounded: " + ", ".join(loose) + ")")
        out.append(f"{', '.join(ks)} {verb} not identifiable from these measurements{side}: {text}")
    return out


def _widen(problem: FitProblem, keys: Sequence[str], lo: np.ndarray, hi: np.ndarray, rss: float,
           alternatives: Sequence[np.ndarray], hidden: HiddenHandle | None, methods: list[str],
           notes: list[str]) -> tuple[np.ndarray, np.ndarray, set[str], list[str]]:
    """Widen to the multi-start's other optima, and to the handle family of an undetected handle
    mode (methods updated in place); the keys moved by the optima and the notes."""
    p = len(problem.keys)
    lo, hi, moved = widen_to_equivalent_optima(keys, problem, lo, hi, rss, p, alternatives)
    for k in moved:
        methods[list(keys).index(k)] += " + other optima"
    if hidden is not None and not hidden.detected:
        lo, hi, family = widen_to_equivalent_optima(keys, problem, lo, hi, rss, p,
                                                    [*hidden.family, hidden.merged], reference=hidden.rss_merged)
        for k in family:
            methods[list(keys).index(k)] += " + handle family"
        level = likelihood_level(problem, rss, p, hidden.rss_merged)
        accepted = int(np.count_nonzero(hidden.family_rss <= level))
        notes = [*notes, _hidden_note(hidden, accepted)]
    return lo, hi, moved, list(notes)


def _at(problem: FitProblem, theta: np.ndarray, rss: float, keys: Sequence[str],
        fixed: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, ...]]:
    """Covariance, correlation and the Wald table (:func:`_table`) at ``theta``."""
    p = theta.size
    J = problem.jacobian(theta, central=True) if p else np.zeros((problem.n_residuals, 0))
    cov, null = covariance(J, rss)
    table = _table(keys, problem, theta, cov, null, fixed)
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = cov / np.outer(sd, sd)
    return cov, corr, table


def build_fit(problem: FitProblem, sol: optimize.OptimizeResult | None, keys: Sequence[str],
              fixed: Mapping[str, float], template: Device, n_starts: int,
              notes: Sequence[str] = (), alternatives: Sequence[np.ndarray] = (),
              intervals: str = "auto", originals: Sequence[Measurement] | None = None) -> ChainFit:
    """Assemble the :class:`ChainFit` (module doc) from the solver's optimum; ``alternatives`` are
    other local optima of the multi-start (see :func:`widen_to_equivalent_optima`); ``intervals``
    chooses Wald or profile-likelihood intervals (:func:`profile_selection`).  ``originals`` are
    the measurements with every bin (``problem`` holds their informative bins): the fit reports
    them, with the model's response at all their bins (default: ``problem.measurements``)."""
    theta = np.zeros(0) if sol is None else np.asarray(sol.x, float)
    r = problem.residual(theta)
    rss = float(r @ r)
    R, p = r.size, theta.size
    hidden = hidden_handle(problem, theta, rss) if intervals != "wald" and p and not _exact(problem, rss) else None
    theta, rss, hidden = adopt_best(problem, theta, rss, hidden)
    cov, corr, (v, s, se, lo, hi, fx) = _at(problem, theta, rss, keys, fixed)
    methods, notes = _choose_intervals(problem, theta, rss, cov, corr, keys, s, fx, lo, hi, intervals, notes,
                                       hidden)
    lo, hi, moved, notes = _widen(problem, keys, lo, hi, rss, alternatives, hidden, methods, notes)
    undetected = hidden is not None and not hidden.detected
    if undetected:  # the reported chain is the merged one (analysis.identify.hidden)
        theta = np.asarray(hidden.merged, float)
        r = problem.residual(theta)
        rss = float(r @ r)
        cov, corr, (v, s, se, _, _, fx) = _at(problem, theta, rss, keys, fixed)
    chain: ChainParameters = problem.chains(theta)
    n = chain.n
    device = chain.device(0, template)
    bad = tuple(k for k, sk, f, m, a, b in zip(keys, s, fx, methods, lo, hi) if not f and (
        (not (sk <= _WIDE) and not m.startswith("profile")) or k in moved or "unbounded" in m
        or not b <= 10.0 * a))
    measured = {(m.quantity, m.boundary) for m in problem.measurements}
    sugg = {k: suggestion(k, n, measured, undetected) for k in bad}
    if moved:
        notes = [*notes, f"other local optima fit the data as well (within the 95 % likelihood-ratio bound); "
                 f"the intervals of {', '.join(sorted(moved))} are widened to include them"]
    unbounded = {k for k, m in zip(keys, methods) if "unbounded" in m}
    warnings = list(notes) + _grouped(bad, sugg, unbounded)
    converged = sol is None or sol.status > 0
    if not converged:
        warnings.append(f"the optimizer stopped before convergence: {sol.message}")
    floor = max(rss / R, 1e-300)
    aic = R * math.log(floor) + 2 * p
    bic = R * math.log(floor) + p * math.log(R)
    goodness = goodness_of_fit(problem.measurements, [h[0] for h in problem.responses(theta)], p)
    if not goodness.passed:
        warnings.insert(0, goodness.message)
    shown = tuple(problem.measurements if originals is None else originals)
    responses = tuple(h[0] for h in FitProblem(shown, problem.keys, problem.base,
                                                problem.sensor_element).responses(theta))
    return ChainFit(device=device, keys=tuple(keys), values=v, std_errors=se, log_std=s, lower=lo, upper=hi,
                    fixed=fx, free_keys=problem.keys, covariance=cov, correlation=corr,
                    residual=math.sqrt(rss / R), cost=rss / 2, rss=rss, aic=aic, bic=bic, n_residuals=R,
                    dof=R - p, responses=responses, measurements=shown, non_identifiable=bad,
                    suggestions=sugg, warnings=tuple(warnings), converged=converged,
                    evaluations=0 if sol is None else int(sol.nfev), starts=n_starts,
                    interval_methods=tuple(methods), bins=tuple(m.bins for m in shown), goodness=goodness)
