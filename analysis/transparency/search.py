"""The design search of the wall controller: ``J`` and ``||L||_inf`` over ``B_c`` (Eom, Suh & Yi,
Fig. 8) and the optimal ``B_c`` -- minimal ``J`` (eq. 11) subject to ``||L||_inf <= 1`` (eq. 17).

Curves over ``B_c`` reuse everything that does not depend on ``B_c`` (see
:mod:`analysis.transparency.loops`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from analysis.transparency.index import TransparencyIndex
from analysis.transparency.loops import check_bc
from analysis.transparency.robustness import RobustnessAnalysis, weight_parameters
from analysis.transparency.settings import OptimalDamping, TradeoffCurves

__all__ = ["DampingSearch"]


class DampingSearch:
    """Fig. 8 curves and the optimal ``B_c`` of one design.

    Parameters
    ----------
    index : TransparencyIndex
        ``J`` of the design.
    robustness : RobustnessAnalysis
        ``||L||_inf`` of the same design.
    """

    def __init__(self, index: TransparencyIndex, robustness: RobustnessAnalysis):
        self.index = index
        self.robustness = robustness
        self.settings = index.settings

    def tradeoff(self, bc_values=None, alpha: float | None = None, beta: float | None = None) -> TradeoffCurves:
        """``J(B_c)`` and ``||L||_inf(B_c)`` over ``bc_values`` (default: the settings' range).

        Parameters
        ----------
        bc_values : array_like or None, optional
            Controller dampings ``B_c`` [N s/m], finite, shape (N,); ``None`` for the settings'
            ``bc_count`` values from ``bc_min`` to ``bc_max``.
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.

        Returns
        -------
        TradeoffCurves
            ``J``, ``||L||_inf`` and the peak frequencies at each ``B_c``.

        Raises
        ------
        ValidationError
            When a ``B_c`` is not finite or ``alpha``/``beta`` is negative.
        """
        st = self.settings
        a, b = weight_parameters(st, alpha, beta)
        bcs = (np.linspace(st.bc_min, st.bc_max, st.bc_count) if bc_values is None
               else check_bc(bc_values))
        index = self.index.index_many(bcs)
        pk = self.robustness.peaks(bcs, a, b)
        return TradeoffCurves(bcs.copy(), index, np.array([p.gain for p in pk]),
                              np.array([p.frequency for p in pk]), a, b)

    def optimal_damping(self, alpha: float | None = None, beta: float | None = None,
                        bc_range: tuple[float, float] | None = None) -> OptimalDamping:
        """Minimize ``J(B_c)`` subject to ``||L||_inf <= 1`` over the settings' ``B_c`` range.

        A scan of the range (``bc_count`` values) brackets the best feasible point; Brent's
        method polishes it; if the unconstrained minimizer violates eq. (17), the constraint
        boundary is found by Brent's root finder and returned instead.

        Parameters
        ----------
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.
        bc_range : tuple of (float, float) or None, optional
            The searched ``(low, high)`` range of ``B_c`` [N s/m]; ``None`` for the settings'
            ``(bc_min, bc_max)``.

        Returns
        -------
        OptimalDamping
            The optimum, or ``feasible = False`` with the reason.

        Raises
        ------
        ValidationError
            When ``alpha``/``beta`` is negative or the range is not finite.
        """
        st = self.settings
        a, b = weight_parameters(st, alpha, beta)
        lo, hi = bc_range if bc_range is not None else (st.bc_min, st.bc_max)
        curves = self.tradeoff(np.linspace(lo, hi, st.bc_count), a, b)
        bc, J, pk = curves.bc, curves.index, curves.peak
        finite = np.isfinite(J)
        if not finite.any():
            return OptimalDamping(math.nan, math.inf, math.nan, math.nan, False, False, math.nan,
                                  "J is not finite anywhere in the range")
        bu = self._polish(bc, J, int(np.argmin(np.where(finite, J, np.inf))))
        feas = finite & (pk <= 1.0)
        if not feas.any():
            return OptimalDamping(math.nan, math.inf, math.nan, math.nan, False, False, bu,
                                  "no B_c in the range satisfies ||L||_inf <= 1")
        J_of = self.index.performance_index
        p_u = self.robustness.robustness_peak(bu, a, b)
        if p_u.gain <= 1.0:
            return OptimalDamping(bu, J_of(bu), p_u.gain, p_u.frequency, True, False, bu)
        best = self._on_constraint(bc, J, feas, a, b)
        p = self.robustness.robustness_peak(best, a, b)
        return OptimalDamping(float(best), J_of(best), p.gain, p.frequency, True, True, bu)

    def _polish(self, bc: np.ndarray, J: np.ndarray, i: int) -> float:
        """Brent's minimum of ``J`` between the neighbours of grid point ``i`` (if it improves)."""
        left, right = bc[max(i - 1, 0)], bc[min(i + 1, bc.size - 1)]
        res = optimize.minimize_scalar(self.index.performance_index, bounds=(left, right), method="bounded",
                                       options={"xatol": 1e-9 * max(1.0, abs(bc[i]))})
        return float(res.x) if res.fun <= J[i] else float(bc[i])

    def _on_constraint(self, bc: np.ndarray, J: np.ndarray, feas: np.ndarray, a: float, b: float) -> float:
        """The optimum on ``||L||_inf = 1`` next to the best feasible grid point."""
        i = int(np.argmin(np.where(feas, J, np.inf)))
        cands = []
        for j in (i - 1, i + 1):
            if 0 <= j < bc.size and not feas[j]:
                g = lambda x: self.robustness.robustness_peak(x, a, b).gain - 1.0  # noqa: E731
                cands.append(optimize.brentq(g, min(bc[i], bc[j]), max(bc[i], bc[j]), xtol=1e-10))
        return min(cands, key=self.index.performance_index) if cands else float(bc[i])
