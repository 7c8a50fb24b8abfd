"""The weighted least-squares problem of the chain fit, in log-parameters.

Residual
--------
For each measurement ``m`` and frequency ``w_f`` the complex residual is
``r = sqrt(W_f) log(H_model / H_measured)``: its real part is the log-magnitude error and its
imaginary part the phase error wrapped to ``(-pi, pi]`` (``np.angle`` of the ratio), so no phase
unwrapping of noisy data is ever needed.  ``W_f`` is the coherence weight of
:meth:`analysis.identify.Measurement.weights` (or 1).  The real vector handed to
:func:`scipy.optimize.least_squares` is ``[Re r, Im r]`` over all measurements together.
The unknowns are ``theta = log(parameter)`` of the free parameters, so every value stays
positive; fixed parameters keep their given value.

Jacobian
--------
Forward differences in ``theta`` with every perturbed model evaluated in one batched call of
the model kernels (:mod:`analysis.identify.model`), so a Jacobian costs one vectorized evaluation
of ``p + 1`` chains rather than ``p + 1`` Python-level ones.  :meth:`FitProblem.jacobian` with
``central=True`` (used for the covariance) is second-order accurate.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import optimize

from analysis.identify.measurement import Measurement
from analysis.identify.model import response
from analysis.identify.params import ChainParameters, physical_range
from analysis.progress import Cancelled, check_cancelled

__all__ = ["FitProblem", "log_bounds", "solve", "solve_held"]

_FD_STEP = 1e-7
_CENTRAL_STEP = 1e-5
_THETA_MAX = 80.0  # |log(parameter)| beyond this is treated as divergence
_PENALTY = 1e6  # residual of a parameter row that cannot be evaluated


@dataclass(frozen=True, eq=False)
class FitProblem:
    """Measurements, the free keys and the fixed remainder of the chain.

    ``base`` holds every parameter (free ones at any value, fixed ones at theirs);
    ``keys`` are the free parameters, ``theta = log(values of keys)``.  ``cancelled`` (optional)
    is asked before every model evaluation; when it returns True the evaluation raises
    :class:`~analysis.progress.OperationCancelled` (``FitCancelled``).

    Parameters
    ----------
    measurements : tuple of Measurement
        The measurements fitted together.
    keys : tuple of str
        The free parameter keys (:mod:`analysis.identify.params`), in the order of ``theta``.
    base : ChainParameters
        One chain (its first row is used) holding every parameter: the fixed ones at their
        values, the free ones at any value.
    sensor_element : int, optional
        The element of the force gauge (``gauge`` measurements), 0-based.
    cancelled : callable or None, optional
        ``cancelled() -> bool``, asked before every model evaluation; ``None``: never cancelled.
    """

    measurements: tuple[Measurement, ...]
    keys: tuple[str, ...]
    base: ChainParameters
    sensor_element: int = 0
    cancelled: Cancelled | None = None

    def sub(self, keys: tuple[str, ...], base: ChainParameters) -> FitProblem:
        """The same measurements, sensor and cancel hook with other free ``keys`` and ``base``.

        Parameters
        ----------
        keys : tuple of str
            The free parameter keys of the new problem.
        base : ChainParameters
            The chain holding every other parameter.

        Returns
        -------
        FitProblem
            A new problem; this one is unchanged.
        """
        return FitProblem(self.measurements, tuple(keys), base, self.sensor_element, self.cancelled)

    @cached_property
    def _targets(self) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """Per measurement, ``sqrt(W_f)`` and ``1 / H_measured`` (rows of shape (1, F_m)): read once,
        not at each of the thousands of model evaluations of a fit."""
        return tuple((np.sqrt(m.weights())[None, :], 1.0 / m.response[None, :]) for m in self.measurements)

    @property
    def n_residuals(self) -> int:
        return 2 * sum(m.size for m in self.measurements)

    def chains(self, thetas: np.ndarray) -> ChainParameters:
        """The chains of ``P`` log-parameter rows: ``base`` with :attr:`keys` set to ``exp(thetas)``.

        Parameters
        ----------
        thetas : numpy.ndarray
            Logs of the free parameters (values in kg, N/m, N s/m), shape (P, p) or (p,).

        Returns
        -------
        ChainParameters
            ``P`` chains.
        """
        return ChainParameters.from_rows(list(self.keys), np.exp(np.atleast_2d(thetas)), self.base)

    def responses(self, thetas: np.ndarray) -> list[np.ndarray]:
        """Model responses (P, F_m) per measurement.

        Parameters
        ----------
        thetas : numpy.ndarray
            Logs of the free parameters, shape (P, p) or (p,).

        Returns
        -------
        list of numpy.ndarray
            One complex array per measurement, shape (P, F_m), at its frequencies and in its
            quantity's unit (m/N or N/N).
        """
        p = self.chains(thetas)
        return [response(p, m.frequency, m.quantity, m.boundary, self.sensor_element, m.sample_time,
                         m.delay_samples) for m in self.measurements]

    def residual_rows(self, thetas: np.ndarray) -> np.ndarray:
        """Real residual vectors (P, R) of ``P`` parameter rows (module doc).

        A row that is not finite, has ``|theta| >= 80`` or whose model cannot be evaluated gets
        the penalty ``1e6`` in every entry (so does every non-finite entry).

        Parameters
        ----------
        thetas : numpy.ndarray
            Logs of the free parameters, shape (P, p) or (p,).

        Returns
        -------
        numpy.ndarray
            ``[Re r, Im r]`` of each measurement in turn, concatenated, shape (P, R) with
            ``R = 2 sum F_m`` (:attr:`n_residuals`).

        Raises
        ------
        OperationCancelled
            When ``cancelled()`` returns True (``FitCancelled`` is its deprecated alias).
        """
        check_cancelled(self.cancelled, "the fit was cancelled")
        thetas = np.atleast_2d(np.asarray(thetas, float))
        bad = ~np.all(np.isfinite(thetas) & (np.abs(thetas) < _THETA_MAX), axis=1)
        thetas = np.where(bad[:, None], 0.0, thetas)  # evaluated harmlessly, then penalized
        parts = []
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            try:
                hs = self.responses(thetas)
            except np.linalg.LinAlgError:
                return np.full((thetas.shape[0], self.n_residuals), _PENALTY)
            for (sw, inverse), h in zip(self._targets, hs):
                ratio = h * inverse
                parts.append(sw * np.log(np.abs(ratio)))
                parts.append(sw * np.angle(ratio))
        out = np.concatenate(parts, axis=1)
        out[bad] = _PENALTY
        return np.where(np.isfinite(out), out, _PENALTY)

    def residual(self, theta: np.ndarray) -> np.ndarray:
        """The real residual vector of one parameter row (the function least squares minimizes).

        Parameters
        ----------
        theta : numpy.ndarray
            Logs of the free parameters, shape (p,).

        Returns
        -------
        numpy.ndarray
            The residual, shape (R,) (:meth:`residual_rows`).

        Raises
        ------
        OperationCancelled
            When ``cancelled()`` returns True (``FitCancelled`` is its deprecated alias).
        """
        return self.residual_rows(np.asarray(theta, float)[None, :])[0]

    def jacobian(self, theta: np.ndarray, central: bool = False, at: np.ndarray | None = None) -> np.ndarray:
        """Finite-difference Jacobian (R, p) in log-parameters, all perturbations in one batch.

        Parameters
        ----------
        theta : numpy.ndarray
            Logs of the free parameters, shape (p,).
        central : bool, optional
            ``True``: central differences with step ``1e-5`` (second-order, used for the
            covariance); ``False``: forward differences with step ``1e-7`` (the solver's).
        at : numpy.ndarray or None, optional
            The residual at ``theta`` when already evaluated (forward differences only): then only
            the ``p`` perturbed chains are evaluated.

        Returns
        -------
        numpy.ndarray
            ``d residual / d theta``, shape (R, p).

        Raises
        ------
        OperationCancelled
            When ``cancelled()`` returns True (raised by :meth:`residual_rows`).
        """
        theta = np.asarray(theta, float)
        p = theta.size
        if central:
            h = _CENTRAL_STEP
            rows = np.concatenate([theta + h * np.eye(p), theta - h * np.eye(p)])
            r = self.residual_rows(rows)
            return ((r[:p] - r[p:]) / (2 * h)).T
        h = _FD_STEP
        if at is not None:
            return ((self.residual_rows(theta + h * np.eye(p)) - at) / h).T
        rows = np.concatenate([theta[None, :], theta + h * np.eye(p)])
        r = self.residual_rows(rows)
        return ((r[1:] - r[0]) / h).T


class _Memo:
    """The residual and forward Jacobian of one solver run, remembering the last residual: the
    solver asks for the Jacobian at the point whose residual it has just evaluated, so that chain
    is not evaluated twice (p of the p + 1 chains per Jacobian)."""

    def __init__(self, problem: FitProblem) -> None:
        self.problem = problem
        self.x: np.ndarray | None = None
        self.r: np.ndarray | None = None

    def residual(self, theta: np.ndarray) -> np.ndarray:
        r = self.problem.residual(theta)
        self.x, self.r = np.array(theta, float), r
        return r

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        same = self.x is not None and np.array_equal(self.x, theta)
        return self.problem.jacobian(theta, at=self.r if same else None)


def solve(problem: FitProblem, theta0: np.ndarray, max_nfev: int, tol: float = 1e-15) -> optimize.OptimizeResult:
    """Levenberg-Marquardt on the residual with the batched Jacobian; when it leaves the physical
    range of a parameter (:func:`analysis.identify.params.physical_range`, enforced by
    :class:`~analysis.Device`), the bounded trust-region method from the clipped point instead."""
    lo, hi = log_bounds(problem)
    memo = _Memo(problem)
    kw = dict(jac=memo.jacobian, x_scale="jac", xtol=tol, ftol=tol, gtol=tol, max_nfev=max_nfev)
    inside = np.all((theta0 > lo) & (theta0 < hi))
    if inside:
        r = optimize.least_squares(memo.residual, theta0, method="lm", **kw)
        if np.all((r.x >= lo) & (r.x <= hi)):
            return r
        theta0 = r.x
    pad = 1e-9 * (hi - lo)
    start = np.clip(theta0, lo + pad, hi - pad)
    return optimize.least_squares(memo.residual, start, method="trf", bounds=(lo, hi), **kw)


def log_bounds(problem: FitProblem) -> tuple[np.ndarray, np.ndarray]:
    """Physical range of the free parameters in ``theta = log(value)`` (lower, upper)."""
    n = problem.base.n
    b = np.log(np.array([physical_range(k, n) for k in problem.keys]).reshape(-1, 2))
    return b[:, 0], b[:, 1]


def solve_held(problem: FitProblem, theta: np.ndarray, held: tuple[str, ...], max_nfev: int,
               tol: float = 1e-10) -> tuple[float, np.ndarray]:
    """RSS and the full ``theta`` after refitting every free key of ``problem`` except ``held``
    (kept at their values in ``theta``), started from ``theta``: the conditional fit of a
    profile point (:mod:`analysis.identify.profile`) and of a handle-family member
    (:mod:`analysis.identify.hidden`)."""
    keys = list(problem.keys)
    rest = [k for k in keys if k not in held]
    theta = np.asarray(theta, float)
    base = ChainParameters.from_rows(keys, np.exp(theta)[None, :], problem.base)
    sub = problem.sub(tuple(rest), base)
    if not rest:
        r = sub.residual(np.zeros(0))
        return float(r @ r), theta.copy()
    idx = [keys.index(k) for k in rest]
    sol = solve(sub, theta[idx], max_nfev, tol=tol)
    out = theta.copy()
    out[idx] = sol.x
    return 2.0 * float(sol.cost), out

