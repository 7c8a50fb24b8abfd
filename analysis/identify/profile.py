"""Profile-likelihood intervals of a chain fit (likelihood-ratio intervals).

Why
---
The Wald interval ``exp(theta +- 1.96 sigma)`` from ``J^T J`` is exact only when the model is
linear in ``theta`` over the interval.  It fails when a parameter is weakly identified: the
HBFD's handle mode, whose pole and zero at the actuator are 0.03 % apart, lets the actuator FRF
fit a family of chains equally well, and the Jacobian at one member of the family knows nothing
of the others.

Method
------
For the free log-parameter ``theta_j`` the profile residual sum of squares is
``RSS_p(t) = min RSS(theta)`` over the other free parameters with ``theta_j = t``.  With
``s^2 = RSS / (R - p)`` (``R`` real residuals, ``p`` free parameters) the profile t statistic is
``tau(t) = sign(t - theta_j) sqrt(RSS_p(t) - RSS) / s`` and the 95 % interval is
``{t : |tau(t)| <= t_{R-p}(0.975)}``, i.e. ``RSS_p(t) - RSS <= F_{1,R-p}(0.95) s^2`` (Seber &
Wild, *Nonlinear Regression*, sec. 5.2.3; Bates & Watts, *Nonlinear Regression Analysis*,
sec. 6.1).  With the error variance estimated from the residual this is the F (small-sample)
form of the likelihood-ratio interval (``chi^2_1(0.95) = 3.84`` as ``R -> inf``).  For a linear
model it equals the Wald interval; otherwise it follows the model.

Each side is walked from the optimum: a step, a Levenberg-Marquardt solve of the other
parameters warm-started from the linear prediction (the covariance's regression of the others
on ``theta_j``, then the secant of the last two profile points), and the step grown by the ratio
of the target to the reached ``tau`` (between 1.3 and 4 times) until ``tau`` passes the target;
the crossing is then located by regula falsi to 0.1 in ``tau`` (2.5 % of the half-width at 95 %).  Steps are capped at 0.5 in
``theta`` (a factor 1.65) and at twice the previous one: in the flat, bent valley of a weakly
visible mode a long extrapolation lands on another branch.  A point past the target is solved
again from the previous profile point, from the optimum and from ``extra_starts`` (the lowest
wins), so that a jump to a worse branch is not taken for the crossing; a fit whose handle mass
shrank to nothing (:mod:`analysis.identify.degenerate`) passes the restarts that give it back
its share, so the walk can leave the plateau.  A side that stays below the
target up to the physical range of the parameter, or a factor 1000 from the estimate, is
unbounded: the interval is reported as ``0`` or ``inf`` on that side (the data do not bound the
parameter).  Once the walk has passed one capped step (0.5) below the target, that end is solved
once from the walk's last point: when it is below the target too, the side is unbounded without
walking the rest (the chain found there lies inside the likelihood region, so the interval's hull
reaches it); otherwise the walk goes on as before.  ``reference`` replaces the optimum's RSS as the level the ratio is taken from
when the optimum's gain over a simpler chain is not evidence (:mod:`analysis.identify.hidden`);
``s^2`` stays the optimum's.  A profile point that fits better than the optimum is recorded: the fit was not the
global optimum, and the caller says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

from analysis.identify.problem import FitProblem, log_bounds, solve_held

__all__ = ["ProfileBound", "Profiler", "curvature_ratios", "profile_critical_value", "profile_intervals"]

_SPAN = math.log(1e3)  # a side not bounded within a factor 1000 of the estimate is unbounded
_MAX_STEPS = 24
_MAX_STEP = 0.5  # largest step of the walk in log units (the valley of a weak mode bends)
_REFINE = 4
_TAU_TOL = 0.1
_NFEV = 30
_TOL = 1e-10


def profile_critical_value(dof: int, level: float = 0.95) -> float:
    """``F_{1,dof}(level) = t_{dof}((1 + level) / 2)^2``: the bound on ``(RSS_p - RSS) / s^2``.

    Parameters
    ----------
    dof : int
        Residual degrees of freedom ``R - p`` (taken as at least 1).
    level : float, optional
        Confidence level in (0, 1), default 0.95.

    Returns
    -------
    float
        The ``level`` quantile of the F distribution with (1, ``dof``) degrees of freedom
        (about 3.84 for a large ``dof`` at 95 %).
    """
    return float(stats.f.ppf(level, 1, max(int(dof), 1)))


@dataclass(frozen=True)
class ProfileBound:
    """One side of a profile interval: ``theta`` (log of the bound; ``-inf``/``inf`` when the
    data do not bound it), ``bounded`` and the number of conditional solves it took."""

    theta: float
    bounded: bool
    solves: int


class Profiler:
    """Profile intervals of the free parameters of ``problem`` around the optimum ``theta``
    (module doc); ``cov`` is the Wald covariance (for the first step and the predictor).

    Parameters
    ----------
    problem : FitProblem
        The least-squares problem; its free keys are profiled.
    theta : numpy.ndarray
        The optimum in log-parameters, shape (p,).
    rss : float
        The weighted residual sum of squares at ``theta``.
    cov : numpy.ndarray
        Wald covariance of ``theta``, shape (p, p) (may be empty, shape (0, 0)).
    extra_starts : tuple of numpy.ndarray, optional
        Further full ``theta`` vectors (shape (p,)) from which a point past the target is solved
        again (e.g. other optima of the multi-start).
    reference : float or None, optional
        RSS the likelihood ratio is referred to when higher than ``rss``
        (:mod:`analysis.identify.hidden`); ``None``: ``rss``.
    """

    def __init__(self, problem: FitProblem, theta: np.ndarray, rss: float, cov: np.ndarray,
                 extra_starts: tuple[np.ndarray, ...] = (), reference: float | None = None) -> None:
        self.problem = problem
        self.theta = np.asarray(theta, float)
        self.rss = float(rss)
        #: RSS the likelihood ratio is referred to: the optimum's, or a higher one when the
        #: optimum's gain over it is not evidence (:mod:`analysis.identify.hidden`).
        self.reference = max(self.rss, float(reference)) if reference is not None else self.rss
        p = self.theta.size
        dof = max(problem.n_residuals - p, 1)
        self.s2 = max(self.rss / dof, 1e-300)
        self.target = math.sqrt(profile_critical_value(dof))
        self.cov = cov
        self.lo, self.hi = log_bounds(problem)
        self.best_rss, self.best_theta = self.rss, self.theta.copy()
        self.solves = 0
        self._done: dict[tuple[int, float, bytes], tuple[float, np.ndarray]] = {}
        self.extra_starts = tuple(np.asarray(x, float) for x in extra_starts)
        #: how far out [log units] a walk still below the target tries its end once (one capped
        #: step; ``math.inf`` walks all the way, as before the probe)
        self.probe_after = _MAX_STEP

    def conditional(self, j: int, tj: float, start: np.ndarray) -> tuple[float, np.ndarray]:
        """``RSS_p(tj)`` and the other parameters at it, from ``start``.

        Records the solve, and the point as :attr:`best_theta` when it fits better than the
        optimum.  A solve from the same (clipped) start at the same ``tj`` is not run again (the
        restarts of a crossing often repeat the walk's own start): its result is returned.

        Parameters
        ----------
        j : int
            Index of the profiled free parameter.
        tj : float
            The value of ``theta_j`` held (log of the parameter).
        start : numpy.ndarray
            Start of the other log-parameters, shape (p - 1,); clipped into the physical range.

        Returns
        -------
        tuple of (float, numpy.ndarray)
            The profile RSS at ``tj`` and the other log-parameters there, shape (p - 1,).
        """
        others = np.arange(self.theta.size) != j
        full = np.empty(self.theta.size)
        full[j] = tj
        full[others] = np.clip(start, self.lo[others] + 1e-9, self.hi[others] - 1e-9)
        key = (j, float(tj), full.tobytes())
        if key in self._done:
            rss, out = self._done[key]
            return rss, out.copy()
        self.solves += 1
        rss, full = solve_held(self.problem, full, (self.problem.keys[j],), _NFEV, _TOL)
        if rss < self.best_rss:
            self.best_rss = rss
            self.best_theta = full
        self._done[key] = (rss, full[others])
        return rss, full[others].copy()

    def tau(self, rss: float) -> float:
        """The profile t statistic's magnitude ``sqrt(max(RSS_p - reference, 0) / s^2)``.

        Parameters
        ----------
        rss : float
            A profile RSS.

        Returns
        -------
        float
            ``|tau|`` (>= 0), compared with :attr:`target`.
        """
        return math.sqrt(max(rss - self.reference, 0.0) / self.s2)

    def _slope(self, j: int) -> np.ndarray:
        c = self.cov
        ok = c.shape[0] == self.theta.size and np.all(np.isfinite(c[:, j])) and c[j, j] > 0
        return np.delete(c[:, j] / c[j, j], j) if ok else np.zeros(self.theta.size - 1)

    def side(self, j: int, sign: int) -> ProfileBound:
        """The bound of parameter ``j`` on the side ``sign`` (+1 upper, -1 lower).

        Parameters
        ----------
        j : int
            Index of the free parameter.
        sign : int
            ``+1`` for the upper bound, ``-1`` for the lower.

        Returns
        -------
        ProfileBound
            ``theta`` of the bound (``sign * inf`` and ``bounded=False`` when the data do not
            bound it) and the number of conditional solves.
        """
        before = self.solves
        limit = (self.hi[j] - self.theta[j]) if sign > 0 else (self.theta[j] - self.lo[j])
        sd = math.sqrt(self.cov[j, j]) if self.cov.shape[0] and np.isfinite(self.cov[j, j]) else 0.0
        delta = min(self.target * sd, _MAX_STEP) if sd > 0 else 0.05
        pts = [(0.0, 0.0, np.delete(self.theta, j))]
        slope = self._slope(j) * sign
        probed = False
        for _ in range(_MAX_STEPS):
            at_limit = delta >= limit
            delta = min(delta, limit)
            d0, _, o0 = pts[-1]
            if len(pts) > 1:
                slope = (pts[-1][2] - pts[-2][2]) / (pts[-1][0] - pts[-2][0])
            tj = self.theta[j] + sign * delta
            rss, oth = self.conditional(j, tj, o0 + slope * (delta - d0))
            if self.tau(rss) >= self.target:  # a crossing, or a jump to another branch: try plain starts
                for start in (o0, pts[0][2], *(np.delete(x, j) for x in self.extra_starts)):
                    r2, o2 = self.conditional(j, tj, start)
                    if r2 < rss:
                        rss, oth = r2, o2
            tau = self.tau(rss)
            if tau >= self.target:
                t = self._refine(j, sign, pts[-1], (delta, tau, oth))
                return ProfileBound(self.theta[j] + sign * t, True, self.solves - before)
            pts.append((delta, tau, oth))
            if at_limit or delta >= _SPAN:
                return ProfileBound(sign * math.inf, False, self.solves - before)
            if not probed and delta >= self.probe_after:
                probed = True
                if self._reaches_end(j, sign, limit, oth):
                    return ProfileBound(sign * math.inf, False, self.solves - before)
            delta = self._next(delta, tau)
        return ProfileBound(sign * math.inf, False, self.solves - before)

    def _next(self, delta: float, tau: float) -> float:
        """The walk's next step from a point at ``delta`` below the target (module doc)."""
        grow = self.target / tau if tau > 0 else 2.0
        return min(delta * min(max(grow, 1.3), 2.0), delta + _MAX_STEP)

    def _reaches_end(self, j: int, sign: int, limit: float, start: np.ndarray) -> bool:
        """Whether the profile at the end of the walk (the physical limit or a factor 1000 from the
        estimate) is below the target, solved once from ``start``: the side is then unbounded
        (that chain lies inside the likelihood region), without walking there."""
        end = min(limit, _SPAN)
        rss, _ = self.conditional(j, self.theta[j] + sign * end, start)
        return self.tau(rss) < self.target

    def _refine(self, j: int, sign: int, a: tuple, b: tuple) -> float:
        """Regula falsi for ``tau = target`` between the profile points ``a`` (below) and ``b``."""
        for _ in range(_REFINE):
            (da, ta, oa), (db, tb, ob) = a, b
            f = (self.target - ta) / (tb - ta) if tb > ta else 0.5
            dc = da + f * (db - da)
            rss, oc = self.conditional(j, self.theta[j] + sign * dc, oa + f * (ob - oa))
            tc = self.tau(rss)
            if abs(tc - self.target) < _TAU_TOL:
                return dc
            if tc < self.target:
                a = (dc, tc, oc)
            else:
                b = (dc, tc, oc)
        (da, ta, _), (db, tb, _) = a, b
        return da + ((self.target - ta) / (tb - ta) if tb > ta else 0.5) * (db - da)

    def interval(self, j: int) -> tuple[ProfileBound, ProfileBound]:
        """Lower and upper bound of free parameter ``j``.

        Parameters
        ----------
        j : int
            Index of the free parameter.

        Returns
        -------
        tuple of (ProfileBound, ProfileBound)
            The lower and the upper bound (:meth:`side`).
        """
        return self.side(j, -1), self.side(j, +1)


def curvature_ratios(problem: FitProblem, theta: np.ndarray, rss: float, cov: np.ndarray) -> np.ndarray:
    """``q_j±``: the rise of RSS at the Wald bounds along the linearized profile path, over the
    rise the linear model predicts (shape (p, 2); 1 for a model linear over the interval).

    Moving ``theta_j`` by ``d`` with the others following the covariance's regression,
    ``Delta = cov[:, j] d / cov[j, j]``, raises RSS by ``d^2 s^2 / cov[j, j]`` in the linear model,
    ``t^2 s^2`` at ``d = +-t sigma_j``.  One batched evaluation of ``2 p`` chains.  Since the
    profile lies below any path, ``q < 1`` proves the profile interval wider than the Wald one.
    """
    p = theta.size
    if p == 0:
        return np.ones((0, 2))
    dof = max(problem.n_residuals - p, 1)
    s2 = max(rss / dof, 1e-300)
    t2 = profile_critical_value(dof)
    sd = np.sqrt(np.diag(cov))
    with np.errstate(divide="ignore", invalid="ignore"):
        steps = (cov / np.where(sd > 0, sd, np.nan)).T * math.sqrt(t2)  # row j: Delta for d = t sigma_j
    ok = np.all(np.isfinite(steps), axis=1) & (sd > 0)
    steps = np.where(ok[:, None], steps, 0.0)
    r = problem.residual_rows(np.concatenate([theta + steps, theta - steps]))
    rise = (np.einsum("ij,ij->i", r, r) - rss) / (t2 * s2)
    q = np.stack([rise[p:], rise[:p]], axis=1)  # (lower, upper)
    return np.where(ok[:, None], q, np.nan)


def profile_intervals(profiler: Profiler, indices: list[int]) -> dict[int, tuple[float, float, bool]]:
    """``{j: (low, high, bounded)}`` in parameter units for the free parameters ``indices``; an
    unbounded side is ``0`` (lower) or ``inf`` (upper)."""
    out = {}
    for j in indices:
        lo, hi = profiler.interval(j)
        out[j] = (math.exp(lo.theta) if lo.bounded else 0.0, math.exp(hi.theta) if hi.bounded else math.inf,
                  lo.bounded and hi.bounded)
    return out
