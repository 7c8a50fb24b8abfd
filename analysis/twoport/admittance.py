"""Admittance display: Adams, Moreyra & Hannaford, eq. (13)-(24), (27), (30).

A PD position loop ``K_d(z) = k_p Tz/(z-1) + k_d`` (eq. 30) closes around the actuator, and
the force gauge (eq. 27, read as in the design notes) gives ``F_meas``.  The resulting
alternate hybrid array ``G(z)`` (eq. 14) maps ``(F_h, -v_com)`` to ``(v_h, F_meas)``.

Closing the loop is the same as hanging the impedance ``K' = h K_d`` from the actuator mass
to ground, where ``h`` is the hold factor of eq. (2).  ``Re K' = k_d cos^2(theta)`` exactly,
so ``G11`` is the handle admittance of a passive terminated chain and ``Re G11`` is a sum of
dissipated powers.  With ``w'`` the response of that chain to a unit force on the actuator::

    G11 = y11',  G12 = K' y12',  G21 = z_s nu'_s,  G22 = -K' z_s w'_s-relative.

The bound of eq. (21) is ``(|p| + Re p) / (2 Re G11) - Re G22`` with ``p = G12 G21``;
near DC ``p -> -1`` and ``|p| + Re p`` is evaluated as ``(Im p)^2 / (|p| - Re p)``.
"""

from __future__ import annotations

import math

import numpy as np

from analysis.chain import grids
from analysis.chain.response import chain_response
from analysis.chain.velocity_filter import VelocityFilter, display_filter
from analysis.chain.discretize import check_frequencies, held_spring_damper, mass_damper_admittance
from analysis.twoport.display_base import APPARENT_FREQUENCY, DisplayBase, safe_ratio
from analysis.chain.limits import LIMITS
from analysis.errors import ValidationError
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.twoport.results import (
    BoundResult,
    DampingInterval,
    MassChart,
    MassDesign,
    StabilityResult,
    TwoPort,
)

__all__ = ["AdmittanceDisplay", "re_coupling_impedance", "coupling_admittance"]

_SAFETY = 1e-9


def coupling_admittance(w, sample_time: float, mc: float, bc: float) -> np.ndarray:
    """``Y_cA = 1/b_c + 1/(m_c s)``, ``s = (z-1)/(Tz)`` (eq. 16).

    Parameters
    ----------
    w : array_like
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    mc : float
        Coupling mass m_c [kg].
    bc : float
        Coupling damping b_c [N s/m]; ``inf`` for a pure mass.

    Returns
    -------
    numpy.ndarray
        ``Y_cA`` [m/(N s)], complex, shape (N,).
    """
    return mass_damper_admittance(np.asarray(w, float), sample_time, mc, bc)


def re_coupling_impedance(w, sample_time: float, mc: float, bc: float) -> np.ndarray:
    """``Re(Z_cA) = Re(Y_cA) / |Y_cA|^2`` (left side of eq. 21).

    Parameters
    ----------
    w : array_like
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    mc : float
        Coupling mass m_c [kg].
    bc : float
        Coupling damping b_c [N s/m]; ``inf`` for a pure mass.

    Returns
    -------
    numpy.ndarray
        ``Re(Z_cA)`` [N s/m], shape (N,).
    """
    y = coupling_admittance(w, sample_time, mc, bc)
    return y.real / (y.real ** 2 + y.imag ** 2)


class AdmittanceDisplay(DisplayBase):
    """Admittance display: device chain + PD position loop + mass-damper coupling.

    ``velocity_filter`` (default ``None``: the backward difference) filters the PD loop's
    derivative term, ``K_d(z) = k_p T z/(z-1) + k_d H_f(z)`` (eq. 30), so ``G(z)`` and the bound
    of eq. (21) use the damping the controller really applies.  The coupling ``Y_cA`` (eq. 16)
    has no velocity estimate and is unchanged.

    Parameters
    ----------
    device : Device
        The device chain and its sample period.
    kp : float
        Proportional gain k_p of the PD position loop [N/m] (eq. 30).
    kd : float
        Derivative gain k_d of the PD position loop [N s/m] (eq. 30).
    velocity_filter : VelocityFilter or None, optional
        The controller's velocity filter; ``None`` for the backward difference.

    Raises
    ------
    TypeError
        When ``device`` is not a :class:`~analysis.chain.Device`.
    ValidationError
        When ``kp`` or ``kd`` is outside its physical range, or ``velocity_filter`` is not a
        VelocityFilter or None, or its cut-off is not below Nyquist.
    """

    display = "admittance"

    def __init__(self, device, kp: float, kd: float, velocity_filter: VelocityFilter | None = None):
        super().__init__(device)
        self.kp = LIMITS["kp"]("kp", kp)  # the physical ranges of analysis.chain.limits
        self.kd = LIMITS["kd"]("kd", kd)
        self.velocity_filter = display_filter(velocity_filter, device.sample_time)

    def modes(self) -> np.ndarray:
        """The undamped modes that shape the bound of eq. (21), with ``k_p`` at the actuator.

        Returns
        -------
        numpy.ndarray
            Continuous-time modes [rad/s], sorted, shape (M,)
            (:func:`~analysis.chain.grids.device_modes`).
        """
        return grids.device_modes(self.device, actuator_stiffness=self.kp)

    def _loop(self, w: np.ndarray):
        th = self._theta(w)
        if self.velocity_filter is None:
            kprime = held_spring_damper(w, self.device.sample_time, self.kp, self.kd)
            re_k = self.kd * np.cos(th) ** 2
        else:  # h k_d H_f + h k_p T z/(z-1); the second term is -j (k_p T/2) cot(theta)
            c, sn = np.cos(th), np.sin(th)
            kprime = self.kd * c * (c - 1j * sn) * self.velocity_filter.filter_response(w, self.device.sample_time)
            re_k = kprime.real.copy()
            kprime = kprime - 0.5j * self.kp * self.device.sample_time * c / sn
        r = chain_response(self.device, self._s(w), termination=kprime, re_termination=re_k, want_x=False)
        return r, kprime

    def _compute(self, w: np.ndarray) -> tuple[BoundResult, TwoPort]:
        """G(z) of eq. (14) and the bound of eq. (21) from one sweep of the looped chain."""
        r, kprime = self._loop(w)
        g12 = kprime * r.y12
        g21 = r.sensor_from_handle
        g22 = -kprime * r.sensor_from_actuator
        p = g12 * g21
        ap = np.abs(p)
        with np.errstate(divide="ignore", invalid="ignore"):
            folded = p.imag ** 2 / (ap - p.real)
        num = np.where(p.real < 0, np.where(ap - p.real > 0, folded, 0.0), ap + p.real)
        first, singular = safe_ratio(num, 2.0 * r.re_y11)
        br = BoundResult(w=w, bound=first - g22.real, p11=r.y11, re_p11=r.re_y11, abs_p=ap, re_p=p.real,
                         singular=singular)
        return br, TwoPort(w=w, p11=r.y11, p12=g12, p21=g21, p22=g22)

    # -- coupling (eq. 16) -------------------------------------------------------------
    def coupling(self, w, mc: float, bc: float) -> np.ndarray:
        """``Z_cA = 1/Y_cA`` (eq. 16).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        mc : float
            Coupling mass m_c [kg].
        bc : float
            Coupling damping b_c [N s/m]; ``inf`` for a pure mass.

        Returns
        -------
        numpy.ndarray
            ``Z_cA`` [N s/m], complex, shape (N,).
        """
        return 1.0 / coupling_admittance(w, self.device.sample_time, mc, bc)

    def coupling_term(self, w, mc: float, bc: float) -> np.ndarray:
        """``Re(Z_cA)``, the left side of eq. (21).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        mc : float
            Coupling mass m_c [kg].
        bc : float
            Coupling damping b_c [N s/m]; ``inf`` for a pure mass.

        Returns
        -------
        numpy.ndarray
            ``Re(Z_cA)`` [N s/m], shape (N,).
        """
        return re_coupling_impedance(w, self.device.sample_time, mc, bc)

    # -- eq. (23), (24) -----------------------------------------------------------------
    def impedance_range(self, w, mc: float, bc: float) -> tuple[np.ndarray, np.ndarray]:
        """``(Z_min, Z_max)`` of eq. (23) and (24), complex arrays (N s/m).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        mc : float
            Coupling mass m_c [kg].
        bc : float
            Coupling damping b_c [N s/m]; ``inf`` for a pure mass.

        Returns
        -------
        Z_min, Z_max : numpy.ndarray
            The impedance range [N s/m], complex, each of shape (N,).

        Raises
        ------
        ValidationError
            When a frequency is not finite, > 0 and below Nyquist.
        """
        w = check_frequencies(w, self.device.sample_time)
        return self._range(self.two_port(w), w, mc, bc)

    def _range(self, g: TwoPort, w: np.ndarray, mc: float, bc: float) -> tuple[np.ndarray, np.ndarray]:
        d = g.p22 + self.coupling(w, mc, bc)
        with np.errstate(divide="ignore", invalid="ignore"):
            return d / (g.p11 * d - g.p12 * g.p21), 1.0 / g.p11

    def k_max(self) -> float:
        """Low-frequency stiffness of Z_max: the PD spring in series with the chain springs.

        Returns
        -------
        float
            ``1 / (1/k_p + sum 1/k_i)`` [N/m]; 0 when ``k_p <= 0``.
        """
        if self.kp <= 0:
            return 0.0
        return 1.0 / (1.0 / self.kp + self.device.static_compliance)

    def evaluate(self, mc: float, bc: float, w=None, refine: bool = True) -> StabilityResult:
        """Bound, Re(Z_cA), margin, eta, Z_min, Z_max and headline numbers.

        Parameters
        ----------
        mc : float
            Coupling mass m_c [kg].
        bc : float
            Coupling damping b_c [N s/m].
        w : array_like or None, optional
            Angular frequencies [rad/s], shape (N,); ``None`` for :meth:`frequencies`.
        refine : bool, optional
            Whether the worst margin and relative margin are refined between grid points
            (else they are the grid's minima).

        Returns
        -------
        StabilityResult
            The arrays at ``w`` and the headline numbers.

        Raises
        ------
        ValidationError
            When a frequency of ``w`` is not finite, > 0 and below Nyquist.
        """
        w = self.frequencies() if w is None else check_frequencies(w, self.device.sample_time)
        br = self.bound_result(w)
        term = self.coupling_term(w, mc, bc)
        margin = term - br.bound
        zmin, zmax = self._range(self.two_port(w), w, mc, bc)
        wa = np.array([APPARENT_FREQUENCY])
        za = self._range(self._compute(wa)[1], wa, mc, bc)[0][0]
        omega = abs(self._s(wa)[0])
        # b_min: the low-frequency (DC) damping of Z_min, read where Z_min is the apparent
        # free-motion impedance
        return self._result(w, mc, bc, br, term, margin, zmin, zmax, self.k_max(), za.real,
                            za.imag / omega, za.real, refine)

    # -- design ------------------------------------------------------------------------
    def inverse_damping_limits(self, B: np.ndarray, w: np.ndarray, mc: float) -> tuple[np.ndarray, np.ndarray]:
        """Per-frequency interval ``[L, U]`` for ``u = 1/b_c`` from eq. (21).

        With ``t = u + T/(2 m_c)`` and ``g = T cot(theta)/(2 m_c)`` the condition is
        ``B t^2 - t + B g^2 <= 0``.  Where it has no solution, ``U = -inf``.

        Parameters
        ----------
        B : numpy.ndarray
            The bound of eq. (21) [N s/m], shape (N,).
        w : numpy.ndarray
            Angular frequencies [rad/s], shape (N,).
        mc : float
            Coupling mass m_c [kg].

        Returns
        -------
        L, U : numpy.ndarray
            Lower and upper limits of ``1/b_c`` [m/(N s)] at each frequency, shape (N,);
            ``L = -inf``, ``U = inf`` where the bound is not positive, and ``L = inf``,
            ``U = -inf`` where nothing works (no solution or a NaN bound).
        """
        T = self.device.sample_time
        th = 0.5 * w * T
        a = 0.5 * T / mc
        g = a / np.tan(th)
        L = np.full(w.shape, -np.inf)
        U = np.full(w.shape, np.inf)
        pos = B > 0
        if np.any(pos):
            Bp, gp = B[pos], g[pos]
            disc = 1.0 - 4.0 * Bp * Bp * gp * gp
            sq = np.sqrt(np.maximum(disc, 0.0))
            tm = 2.0 * Bp * gp * gp / (1.0 + sq)
            tp = (1.0 + sq) / (2.0 * Bp)
            L[pos] = np.where(disc < 0, np.inf, tm - a)
            U[pos] = np.where(disc < 0, -np.inf, tp - a)
        bad = np.isnan(B)
        return np.where(bad, np.inf, L), np.where(bad, -np.inf, U)

    def feasible_damping(self, mc: float, w=None) -> DampingInterval:
        """Interval of b_c for which the coupling (m_c, b_c) satisfies eq. (21) on the band.

        Conservative: both edges are refined between grid points and pulled inwards by
        1e-9 relative.

        Parameters
        ----------
        mc : float
            Coupling mass m_c [kg], finite and > 0.
        w : array_like or None, optional
            Angular frequencies [rad/s], shape (N,); ``None`` for :meth:`frequencies`.

        Returns
        -------
        DampingInterval
            The feasible ``[low, high]`` of b_c [N s/m] and where each edge binds; ``low``
            and ``high`` are ``None`` when no b_c works.

        Raises
        ------
        ValidationError
            When ``mc`` is not finite and > 0, or a frequency of ``w`` is invalid.
        """
        if isinstance(mc, bool) or not math.isfinite(mc) or mc <= 0:
            raise ValidationError("mc", "> 0 and finite (kg)", mc)
        w = self.frequencies() if w is None else check_frequencies(w, self.device.sample_time)
        B = self.bound(w)
        L, U = self.inverse_damping_limits(B, w, mc)
        lo, hi = grids.band_edges(self.device)

        def fu(x):
            return self.inverse_damping_limits(self._uncached_bound(x), x, mc)[1]

        def fl(x):
            return -self.inverse_damping_limits(self._uncached_bound(x), x, mc)[0]

        uw, uv = grids.refine_minima(fu, w, U, lo, hi, candidates=8)
        lw, lv = grids.refine_minima(fl, w, -L, lo, hi, candidates=8)
        ju, jl = int(np.argmin(U)), int(np.argmax(L))
        u_hi, f_hi = float(U[ju]), float(w[ju])
        if uv.size and uv[0] < u_hi:
            u_hi, f_hi = float(uv[0]), float(uw[0])
        u_lo, f_lo = float(L[jl]), float(w[jl])
        if lv.size and -lv[0] > u_lo:
            u_lo, f_lo = float(-lv[0]), float(lw[0])
        u_hi *= 1.0 - _SAFETY
        u_lo = max(u_lo, 0.0) * (1.0 + _SAFETY)
        if not (u_hi > u_lo) or not math.isfinite(u_lo):
            return DampingInterval(mc=mc, low=None, high=None, low_frequency=f_hi, high_frequency=f_lo)
        low = 1.0 / u_hi if math.isfinite(u_hi) else 0.0
        high = math.inf if u_lo == 0.0 else 1.0 / u_lo
        return DampingInterval(mc=mc, low=low, high=high, low_frequency=f_hi,
                               high_frequency=f_lo if u_lo > 0 else math.nan)

    def _feasible_on(self, B: np.ndarray, w: np.ndarray, mc: float) -> bool:
        L, U = self.inverse_damping_limits(B, w, mc)
        return float(np.max(np.maximum(L, 0.0))) < float(np.min(U))

    def min_mass(self, w=None, rtol: float = 1e-10) -> MassDesign:
        """Smallest m_c for which a feasible b_c exists (feasibility grows with m_c).

        Bisection in log m_c on the grid; then the grid is densified around the binding
        frequencies and the bisection repeated, so the pinch point is resolved to about
        1e-7 relative.  The final mass is accepted only by the refined, backed-off check
        of :meth:`feasible_damping`, so the result is conservative.

        Parameters
        ----------
        w : array_like or None, optional
            Angular frequencies [rad/s], shape (N,); ``None`` for :meth:`frequencies`.
        rtol : float, optional
            Relative tolerance of the bisection in m_c.

        Returns
        -------
        MassDesign
            The smallest m_c [kg], a b_c [N s/m] inside its feasible interval (the geometric
            mean of its edges, or the lower edge when the upper is infinite), the binding
            frequency and the interval.

        Raises
        ------
        ValueError
            When no feasible coupling mass is found, or the search does not converge.
        """
        w = self.frequencies() if w is None else check_frequencies(w, self.device.sample_time)
        pts, vals = w, self.bound(w)
        T = self.device.sample_time
        mc_hi = max(1e-6, float(np.max(np.where(vals > 0, vals, 0.0) * T / np.tan(0.5 * w * T))) * 2.0)
        for _ in range(200):
            if self._feasible_on(vals, pts, mc_hi):
                break
            mc_hi *= 2.0
        else:
            raise ValueError("no feasible coupling mass found")
        lo_b, hi_b = grids.band_edges(self.device)
        interval: DampingInterval | None = None
        for attempt in range(3):
            lo_m, hi_m = mc_hi * 1e-12, mc_hi
            if self._feasible_on(vals, pts, lo_m):
                hi_m = lo_m
            while hi_m / lo_m - 1.0 > rtol:
                mid = math.sqrt(lo_m * hi_m)
                if self._feasible_on(vals, pts, mid):
                    hi_m = mid
                else:
                    lo_m = mid
            # at the pinch the interval has zero width: step up until the refined,
            # backed-off check accepts it (the result stays on the safe side)
            for step in (1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2):
                mc = hi_m * (1.0 + step)
                interval = self.feasible_damping(mc, w)
                if interval.feasible:
                    break
            assert interval is not None
            if attempt == 2 or (interval.feasible and step <= 1e-7):
                break
            # densify around the binding frequencies and bisect again
            extra = [pts]
            for f in (interval.low_frequency, interval.high_frequency):
                if math.isfinite(f):
                    extra.append(np.geomspace(max(f / 1.3, lo_b), min(f * 1.3, hi_b), 4000))
            pts = np.unique(np.concatenate(extra))
            vals = self._uncached_bound(pts)
            mc_hi = mc
        assert interval is not None
        if not interval.feasible:
            raise ValueError("minimum coupling mass search did not converge")
        bc = math.sqrt(interval.low * interval.high) if math.isfinite(interval.high) else interval.low
        return MassDesign(mc=mc, bc=bc, frequency=interval.low_frequency, interval=interval)

    @none_if_cancelled
    def mass_chart(self, mc_values, w=None, *, progress: Progress | None = None,
                   cancelled: Cancelled | None = None) -> MassChart | None:
        """Feasible b_c interval of eq. (21) as a function of m_c (the design chart).

        ``progress(done, total)`` is called after each m_c; when ``cancelled()`` turns true
        the chart stops and ``None`` is returned.

        Parameters
        ----------
        mc_values : array_like
            Coupling masses m_c [kg], shape (M,).
        w : array_like or None, optional
            Angular frequencies [rad/s]; ``None`` for :meth:`frequencies`.
        progress : callable or None, optional
            ``progress(done, total)``, called after each m_c.
        cancelled : callable or None, optional
            ``cancelled() -> bool``, polled before each m_c; true stops the chart.

        Returns
        -------
        MassChart or None
            The chart, shape (M,) per field; ``None`` when cancelled.
        """
        mcs = np.asarray(mc_values, float)
        low = np.full(mcs.size, np.nan)
        high = np.full(mcs.size, np.nan)
        for i, mc in enumerate(mcs):
            check_cancelled(cancelled)
            d = self.feasible_damping(float(mc), w)
            if d.feasible:
                low[i], high[i] = d.low, d.high
            report_progress(progress, i + 1, mcs.size)
        return MassChart(mc=mcs, low=low, high=high)
