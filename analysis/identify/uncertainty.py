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
with the measurement that would constrain them (:func:`suggestion`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.identify.params import ChainParameters, parse_key
from analysis.identify.problem import FitProblem
from analysis.identify.results import ChainFit

__all__ = ["build_fit", "suggestion", "covariance"]

Z95 = 1.959963984540054
_SINGULAR = 1e-8
_WIDE = math.log(10.0) / (2 * Z95)
_CHI2_1 = 3.841458820694124  # 95 % quantile of chi-square with 1 degree of freedom


def suggestion(key: str, n: int, measured: set[tuple[str, str]]) -> str:
    """What measurement would constrain ``key`` better, given the (quantity, boundary) pairs used."""
    name, i = parse_key(key, n)
    handle_side = (name == "masses" and i < n - 1) or (name in ("stiffnesses", "dampings") and i == 0)
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


def widen_to_equivalent_optima(keys: Sequence[str], problem: FitProblem, lo: np.ndarray, hi: np.ndarray,
                               rss: float, p: int,
                               alternatives: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray, set[str]]:
    """Widen the intervals to every alternative optimum that the data cannot tell from the best.

    An optimum ``theta_i`` with ``RSS_i - RSS <= chi2_1(0.95) s^2`` (3.84 s^2) lies inside every
    parameter's 95 % profile-likelihood interval (the profile at ``theta_i``'s value is at most
    ``RSS_i``), so including it is a justified lower bound on that interval.  This catches what
    the local (Jacobian) intervals cannot: several basins fitting equally well, as when a mode
    is nearly invisible in the measured quantity.  Returns (lo, hi, keys whose interval moved).
    """
    R = problem.n_residuals
    s2 = rss / max(R - p, 1)
    lo, hi = lo.copy(), hi.copy()
    moved: set[str] = set()
    for alt in alternatives:
        r = problem.residual(alt)
        if float(r @ r) - rss > _CHI2_1 * s2:
            continue
        chain = problem.chains(alt)
        for j, key in enumerate(keys):
            name, i = parse_key(key, chain.n)
            v = float(getattr(chain, name)[0, i])
            if key in problem.keys and not lo[j] <= v <= hi[j]:
                lo[j], hi[j] = min(lo[j], v), max(hi[j], v)
                moved.add(key)
    return lo, hi, moved


def build_fit(problem: FitProblem, sol: optimize.OptimizeResult | None, keys: Sequence[str],
              fixed: Mapping[str, float], template: Device, n_starts: int,
              notes: Sequence[str] = (), alternatives: Sequence[np.ndarray] = ()) -> ChainFit:
    """Assemble the :class:`ChainFit` (module doc) from the solver's optimum; ``alternatives`` are
    other local optima of the multi-start (see :func:`widen_to_equivalent_optima`)."""
    theta = np.zeros(0) if sol is None else np.asarray(sol.x, float)
    r = problem.residual(theta)
    rss = float(r @ r)
    R, p = r.size, theta.size
    J = problem.jacobian(theta, central=True) if p else np.zeros((R, 0))
    cov, null = covariance(J, rss)
    v, s, se, lo, hi, fx = _table(keys, problem, theta, cov, null, fixed)
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = cov / np.outer(sd, sd)
    chain: ChainParameters = problem.chains(theta)
    n = chain.n
    device = chain.device(0, template)
    lo, hi, moved = widen_to_equivalent_optima(keys, problem, lo, hi, rss, p, alternatives)
    bad = tuple(k for k, sk, f in zip(keys, s, fx) if not f and (not (sk <= _WIDE) or k in moved))
    measured = {(m.quantity, m.boundary) for m in problem.measurements}
    sugg = {k: suggestion(k, n, measured) for k in bad}
    if moved:
        notes = [*notes, f"other local optima fit the data as well (within the 95 % likelihood-ratio bound); "
                 f"the intervals of {', '.join(sorted(moved))} are widened to include them"]
    warnings = list(notes) + [f"{k} is not identifiable from these measurements: {sugg[k]}" for k in bad]
    converged = sol is None or sol.status > 0
    if not converged:
        warnings.append(f"the optimizer stopped before convergence: {sol.message}")
    floor = max(rss / R, 1e-300)
    aic = R * math.log(floor) + 2 * p
    bic = R * math.log(floor) + p * math.log(R)
    responses = tuple(h[0] for h in problem.responses(theta))
    return ChainFit(device=device, keys=tuple(keys), values=v, std_errors=se, log_std=s, lower=lo, upper=hi,
                    fixed=fx, free_keys=problem.keys, covariance=cov, correlation=corr,
                    residual=math.sqrt(rss / R), cost=rss / 2, rss=rss, aic=aic, bic=bic, n_residuals=R,
                    dof=R - p, responses=responses, measurements=problem.measurements, non_identifiable=bad,
                    suggestions=sugg, warnings=tuple(warnings), converged=converged,
                    evaluations=0 if sol is None else int(sol.nfev), starts=n_starts)
