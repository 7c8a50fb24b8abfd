"""The robustness peak ``||L||_inf`` of the wall controller (Eom, Suh & Yi, eq. 13-17).

``L = -W P/(1 + H P C) = -W Y_t`` with ``W = alpha m s + beta b`` (eq. 15-16); robust stability
is ``||L||_inf <= 1`` (eq. 17).  The supremum is found on a grid with points on every closed-loop
resonance, 48 per decade elsewhere and 8 per period above Nyquist for ``zoh``, then a zoom
refinement of the three best local maxima (:func:`analysis.transparency.hinf.refine_peaks`);
above the grid the ``zoh`` ripple is bounded analytically.  See
:mod:`analysis.transparency.design` for the reading of the paper.
"""

from __future__ import annotations

import math

import numpy as np

from analysis.checks import real
from analysis.transparency.hinf import local_maxima, refine_peaks
from analysis.transparency.loops import LoopRealizations, check_bc
from analysis.transparency.settings import RobustnessPeak, WallSettings

__all__ = ["RobustnessAnalysis", "weight_parameters"]


def weight_parameters(settings: WallSettings, alpha: float | None, beta: float | None) -> tuple[float, float]:
    """``(alpha, beta)`` of the weight ``W`` (eq. 15); ``None`` takes the settings' value."""
    a = settings.alpha if alpha is None else real("alpha", alpha, lo=0.0, allowed=">= 0")
    b = settings.beta if beta is None else real("beta", beta, lo=0.0, allowed=">= 0")
    return a, b


class RobustnessAnalysis:
    """``||L||_inf`` (eq. 16-17) of one design, for one ``B_c`` or many.

    Parameters
    ----------
    loops : LoopRealizations
        The loop realisations of the design.
    """

    def __init__(self, loops: LoopRealizations):
        self.loops = loops
        self.settings = loops.settings
        self.plant = loops.plant

    def high_frequency_limit(self, alpha: float) -> float:
        """``lim |L|`` as ``w -> inf`` (continuous holds): ``alpha m_W / m_handle``.

        Parameters
        ----------
        alpha : float
            Mass uncertainty of the weight ``W = alpha m s + beta b`` (eq. 15).

        Returns
        -------
        float
            The limit (dimensionless); ``alpha`` for a rigid handle.
        """
        return alpha * self.plant.m_w / self.plant.handle_mass

    def zoh_grid_end(self) -> float:
        """Upper end of the ``zoh`` grid (128 half-periods above Nyquist).

        Returns
        -------
        float
            ``128 pi / T`` [rad/s].
        """
        return 128 * math.pi / self.settings.sample_time

    def peak_grid(self, bcs: np.ndarray) -> np.ndarray:
        """The search grid shared by ``bcs``: log-spaced, plus points on every light resonance.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).

        Returns
        -------
        numpy.ndarray
            Angular frequencies [rad/s], increasing and distinct, shape (P,); up to ``pi/T`` for
            the ``discrete`` hold.
        """
        st = self.settings
        T = st.sample_time
        c = self.loops.singularities(bcs)
        lo = 1e-3 * float(np.min(np.abs(c)))
        hi = math.pi / T if st.hold == "discrete" else 1e3 * float(np.max(np.abs(c)))
        parts = [np.geomspace(lo, hi, int(48 * math.log10(hi / lo)) + 2)]
        light = c[(c.real > 0) & (c.imag < 0.5 * c.real)]
        off = np.array([-3.0, -2.0, -1.0, -0.5, -0.25, 0.0, 0.25, 0.5, 1.0, 2.0, 3.0])
        parts.append((light.real[:, None] + light.imag[:, None] * off[None, :]).ravel())
        if st.hold == "zoh":
            parts.append(np.arange(math.pi / T, self.zoh_grid_end(), 0.25 * math.pi / T))
        g = np.unique(np.concatenate(parts))
        return g[(g >= lo) & (g <= hi)]

    def _magnitude2(self, bcs: np.ndarray, alpha: float, beta: float):
        """``|L|^2`` as a function ``(rows, w)`` (w shared, or R x P)."""
        st = self.settings
        if st.hold == "discrete":
            md = self.loops.discrete.modal(bcs, alpha, beta)

            def ev_discrete(rows: np.ndarray, w: np.ndarray) -> np.ndarray:
                L = md.robustness(rows, np.exp(1j * w * st.sample_time))
                return L.real**2 + L.imag**2

            return ev_discrete
        mw, bw = self.plant.m_w, self.plant.b_w

        def ev(rows: np.ndarray, w: np.ndarray) -> np.ndarray:
            a, h = self.loops.continuous_parts(w.ravel())
            a, h = a.reshape(w.shape), h.reshape(w.shape)
            W = alpha * mw * 1j * w + beta * bw
            bb = bcs[rows][:, None]
            L = W / (a + bb * h) if w.ndim == 2 else W[None, :] / (a[None, :] + bb * h[None, :])
            return L.real**2 + L.imag**2

        return ev

    def peaks(self, bcs: np.ndarray, alpha: float, beta: float) -> list[RobustnessPeak]:
        """``||L||_inf`` for every ``B_c`` of ``bcs`` (one shared grid, batched refinement).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        alpha : float
            Mass uncertainty of the weight ``W = alpha m s + beta b`` (eq. 15).
        beta : float
            Damping uncertainty of the weight ``W``.

        Returns
        -------
        list of RobustnessPeak
            One peak per ``B_c``, in the order of ``bcs``.
        """
        st = self.settings
        disc = st.hold == "discrete"
        ev = self._magnitude2(bcs, alpha, beta)
        grid = self.peak_grid(bcs)
        allrows = np.arange(bcs.size)
        vals = ev(allrows, grid)
        idx = local_maxima(vals, 3)  # rows x 3
        nb, k = idx.shape
        rows = np.repeat(allrows, k)
        i = idx.ravel()
        lo = grid[np.maximum(i - 1, 0)]
        hi = grid[np.minimum(i + 1, grid.size - 1)]
        wp, vp = refine_peaks(ev, rows, lo, hi)
        wp, vp = wp.reshape(nb, k), vp.reshape(nb, k)
        best = np.argmax(vp, axis=1)
        out = []
        lim = 0.0 if disc else self.high_frequency_limit(alpha)
        for j in range(nb):
            gain, f = math.sqrt(float(vp[j, best[j]])), float(wp[j, best[j]])
            certified = True
            if not disc and lim >= gain:
                gain, f = lim, math.inf
            if st.hold == "zoh":
                certified = bool(self.zoh_tail_bound(float(bcs[j]), alpha, beta) <= gain)
            out.append(RobustnessPeak(float(bcs[j]), gain, f, alpha, beta, lim, certified))
        return out

    def zoh_tail_bound(self, bc: float, alpha: float, beta: float) -> float:
        """Upper bound of ``|L|`` above the ``zoh`` grid: ``|W P| / (1 - |H P C|)``, ``|H| <= 2/(wT)``.

        Rigid plant: ``|W P|`` lies between ``beta`` and ``alpha``; chain: ``|W P|`` is bounded
        by its value on the grid end times 1.01 (its modes are far below the grid end).

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m].
        alpha : float
            Mass uncertainty of the weight ``W`` (eq. 15).
        beta : float
            Damping uncertainty of the weight ``W``.

        Returns
        -------
        float
            The bound (dimensionless); ``inf`` when ``|H P C| >= 1`` at the grid end.
        """
        st = self.settings
        w0 = self.zoh_grid_end()
        s = 1j * w0
        P = 1.0 / self.plant.impedance(np.array([s]))[0]
        hpc = 2.0 / (w0 * st.sample_time) * abs(P) * (abs(bc) + st.kc / w0)
        if hpc >= 1:
            return math.inf
        W = alpha * self.plant.m_w * s + beta * self.plant.b_w
        wp = (max(alpha, beta) if self.plant.device is None
              else 1.01 * max(abs(W * P), self.high_frequency_limit(alpha)))
        return wp / (1.0 - hpc)

    def robustness_peak(self, bc: float, alpha: float | None = None, beta: float | None = None) -> RobustnessPeak:
        """``||L||_inf`` (eq. 16-17) and its frequency; ``alpha``, ``beta`` default to the settings.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.

        Returns
        -------
        RobustnessPeak
            The peak gain, its frequency and whether it is certified.

        Raises
        ------
        ValidationError
            When ``bc`` is not finite or ``alpha``/``beta`` is negative or not finite.
        """
        a, b = weight_parameters(self.settings, alpha, beta)
        return self.peaks(check_bc(bc)[0:1], a, b)[0]
