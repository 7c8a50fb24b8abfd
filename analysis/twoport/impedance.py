"""Impedance display: Adams, Moreyra & Hannaford, eq. (2), (4), (7)-(12).

The discrete device admittance (eq. 2) is the continuous chain admittance at the Tustin
image ``s = j (2/T) tan(theta)``, ``theta = w T / 2``, with the actuator column multiplied
by the hold factor ``h = cos(theta) e^{-j theta}``.  The coupling is
``Z_c = b_c + k_c T z/(z-1)`` (eq. 4), and unconditional stability of the interface (eq. 7)
requires ``Re(1/Z_c) >= bound`` with the bound of eq. (9)::

    bound = (|Y12 Y21| + Re(Y12 Y21)) / (2 Re Y11) - Re Y22.

Cancellation-free form
----------------------
With ``y = y12 = y21`` (reciprocal chain) and ``a = Re(y e^{-j theta/2})``,
``|p| + Re p = 2 cos(theta) a^2``, and the bound is ``-cos(theta) det H / Re y11`` where
``H`` is the Hermitian part of ``diag(1, e^{-j theta/2}) y diag(1, e^{-j theta/2})``.
Expanding with ``c2 = cos(theta/2)``, ``s2 = sin(theta/2)``::

    det H = c2^2 Re X + 2 s2 c2 Im X - s2^2 (Re y11 Re y22 + (Im y)^2)
          = s2^2 |y|^2 - cos(theta) Re X - sin(theta) Im X,
    X = Re y11 y22 - Re y * y       (so Re X = Re y11 Re y22 - (Re y)^2),

with ``X`` computed from minors of the chain responses (see chain.py).  At low frequency
``X -> 0`` (the chain moves as a rigid body) and the bound tends to
``cos(theta) sin^2(theta/2) |y|^2 / Re y11``: tiny, but every digit is kept.  Only the
responses to a force on the handle are needed (plus ``y22`` for Y itself).
"""

from __future__ import annotations

import math

import numpy as np

from analysis.chain import grids
from analysis.chain.continued_fraction import (
    frozen_impedances,
    handle_impedance,
    handle_impedance_at,
    terminated_handle_impedance,
)
from analysis.chain.response import chain_response
from analysis.chain.velocity_filter import VelocityFilter, display_filter
from analysis.chain.discretize import check_frequencies, spring_damper, theta_of
from analysis.twoport.display_base import APPARENT_FREQUENCY, DisplayBase, FrequencyGrid, safe_ratio
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.twoport.results import BoundResult, StabilityResult, StiffnessChart, StiffnessDesign, TwoPort

__all__ = ["ImpedanceDisplay", "coupling_impedance", "re_inv_coupling", "kc_upper", "kc_upper_filtered"]

_SAFETY = 1e-9  # relative back-off that keeps reported designs on the safe side


def coupling_impedance(w, sample_time: float, kc: float, bc: float,
                       velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """``Z_c = b_c H_f(z) + k_c T z/(z-1)`` on the unit circle (eq. 4; ``H_f = 1`` by default).

    ``H_f`` is the low-pass of the controller's velocity estimate ``V(z) = H_f(z)(z-1)/(Tz)``
    (:class:`~analysis.chain.velocity_filter.VelocityFilter`): the damping the controller applies.

    Parameters
    ----------
    w : array_like
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    kc : float
        Coupling stiffness k_c [N/m].
    bc : float
        Coupling damping b_c [N s/m].
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter; ``None`` (or ``"backward"``) for ``H_f = 1``.

    Returns
    -------
    numpy.ndarray
        ``Z_c`` [N s/m], complex, shape (N,).
    """
    w = np.asarray(w, float)
    if velocity_filter is None or velocity_filter.is_backward:
        return spring_damper(w, sample_time, kc, bc)
    th = 0.5 * w * sample_time
    return bc * velocity_filter.filter_response(w, sample_time) + (0.5 * kc * sample_time) * (1.0 - 1j / np.tan(th))


def re_inv_coupling(w, sample_time: float, kc: float, bc: float,
                    velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """``Re(1/Z_c) = (b_c + k_c T/2) / |Z_c|^2`` (eq. 9, left side), cancellation-free.

    With a filter, ``Re Z_c / |Z_c|^2`` from the direct complex ``Z_c`` (``Re Z_c = b_c Re H_f +
    k_c T/2`` has no cancellation while ``Re H_f > 0``; the tests compare it with 50-digit values).
    """
    th = 0.5 * np.asarray(w, float) * sample_time
    if velocity_filter is None or velocity_filter.is_backward:
        return _re_inv_coupling(np.tan(th), sample_time, kc, bc)
    z = coupling_impedance(w, sample_time, kc, bc, velocity_filter)
    with np.errstate(divide="ignore", invalid="ignore"):
        return z.real / (z.real * z.real + z.imag * z.imag)


def _re_inv_coupling(tan_th: np.ndarray, sample_time: float, kc: float, bc: float) -> np.ndarray:
    """:func:`re_inv_coupling` from ``tan(theta)``."""
    beta = bc + 0.5 * kc * sample_time
    gam = 0.5 * kc * sample_time / tan_th
    with np.errstate(divide="ignore", invalid="ignore"):
        out = beta / (beta * beta + gam * gam)
    if beta == 0:
        out = np.where(gam == 0, np.inf, out)
    return out


def kc_upper(bound: np.ndarray, w: np.ndarray, sample_time: float, bc: float) -> np.ndarray:
    """Largest k_c with ``Re(1/Z_c) >= bound`` at each frequency (closed form).

    ``B[(b_c + k T/2)^2 + (k T cot(theta)/2)^2] <= b_c + k T/2`` is quadratic in ``k``:
    ``a2 k^2 + a1 k + a0 <= 0`` with ``a2 = B T^2 / (4 sin^2 theta)``,
    ``a1 = T (B b_c - 1/2)``, ``a0 = b_c (B b_c - 1)``.  Returns ``+inf`` where the bound
    is not positive and ``-inf`` where no ``k >= 0`` works (``B b_c > 1``).

    Parameters
    ----------
    bound : numpy.ndarray
        The bound ``B`` of eq. (9) [m/(N s)], shape (N,).
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    bc : float
        Coupling damping b_c [N s/m].

    Returns
    -------
    numpy.ndarray
        The largest k_c [N/m] at each frequency, shape (N,); ``+inf`` where the bound is not
        positive, ``-inf`` where no ``k >= 0`` works or the bound is singular.
    """
    T = sample_time
    B = np.asarray(bound, float)
    th = 0.5 * np.asarray(w, float) * T
    sn = np.sin(th)
    with np.errstate(invalid="ignore", over="ignore"):
        a2 = B * T * T / (4.0 * sn * sn)
        a1 = T * (B * bc - 0.5)
        a0 = bc * (B * bc - 1.0)
    out = np.full(B.shape, np.inf)
    out[(B == np.inf) | np.isnan(B)] = -np.inf  # singular (lossless) points: nothing is safe
    pos = (B > 0) & np.isfinite(B)
    if np.any(pos):
        a2p, a1p, a0p = a2[pos], a1[pos], a0[pos]
        disc = np.sqrt(np.maximum(a1p * a1p - 4.0 * a2p * a0p, 0.0))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            r_neg = (-a1p + disc) / (2.0 * a2p)
            r_pos = -2.0 * a0p / (a1p + disc)
        root = np.where(a1p <= 0, r_neg, r_pos)
        out[pos] = np.where(a0p > 0, -np.inf, root)
    return out


def kc_upper_filtered(bound: np.ndarray, w: np.ndarray, sample_time: float, bc: float,
                      velocity_filter: VelocityFilter) -> np.ndarray:
    """:func:`kc_upper` for ``Z_c = P + k Q`` with ``P = b_c H_f``, ``Q = T z/(z-1)``.

    ``Re Z >= B |Z|^2`` is ``a2 k^2 + a1 k + a0 <= 0`` with ``a2 = B |Q|^2``,
    ``a1 = 2 B Re(P conj Q) - T/2``, ``a0 = B |P|^2 - Re P``; for ``B > 0`` the largest root,
    ``-inf`` where there is none or it is negative; ``+inf`` where ``B <= 0``.
    """
    T = sample_time
    B = np.asarray(bound, float)
    th = 0.5 * np.asarray(w, float) * T
    P = bc * velocity_filter.filter_response(w, T)
    Q = (0.5 * T) * (1.0 - 1j / np.tan(th))
    out = np.full(B.shape, np.inf)
    out[(B == np.inf) | np.isnan(B)] = -np.inf
    pos = (B > 0) & np.isfinite(B)
    if np.any(pos):
        Bp, Pp, Qp = B[pos], P[pos], Q[pos]
        a2 = Bp * (Qp.real ** 2 + Qp.imag ** 2)
        a1 = 2.0 * Bp * (Pp * np.conj(Qp)).real - 0.5 * T
        a0 = Bp * (Pp.real ** 2 + Pp.imag ** 2) - Pp.real
        disc = a1 * a1 - 4.0 * a2 * a0
        sq = np.sqrt(np.maximum(disc, 0.0))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            root = np.where(a1 <= 0, (-a1 + sq) / (2.0 * a2), 2.0 * a0 / (-a1 - sq))
        out[pos] = np.where((disc < 0) | (root < 0), -np.inf, root)
    return out


class ImpedanceDisplay(DisplayBase):
    """Impedance display of a device chain with a spring-damper virtual coupling.

    ``velocity_filter`` (default ``None``: the backward difference of eq. 4) filters the
    coupling's damping term: ``Z_c = b_c H_f(z) + k_c T z/(z-1)``, so eq. (9), Z_max and the
    design use the damping the controller really applies.

    Parameters
    ----------
    device : Device
        The device chain and its sample period.
    velocity_filter : VelocityFilter or None, optional
        The controller's velocity filter; ``None`` for the backward difference.

    Raises
    ------
    TypeError
        When ``device`` is not a :class:`~analysis.chain.Device`.
    ValidationError
        When ``velocity_filter`` is not a VelocityFilter or None, or its cut-off is not below
        Nyquist.
    """

    display = "impedance"

    def __init__(self, device, velocity_filter: VelocityFilter | None = None):
        super().__init__(device)
        self._apparent: tuple[complex, float] | None = None
        self.velocity_filter = display_filter(velocity_filter, device.sample_time)

    def modes(self) -> np.ndarray:
        """The undamped modes that shape the bound of eq. (9) (:func:`~analysis.chain.grids.device_modes`).

        Returns
        -------
        numpy.ndarray
            Continuous-time modes [rad/s], sorted, shape (M,).
        """
        return grids.device_modes(self.device)

    # -- eq. (2), (9) -------------------------------------------------------------------
    def _compute(self, w: np.ndarray) -> tuple[BoundResult, TwoPort]:
        """Y(z) of eq. (2) and the bound of eq. (9) from one chain sweep."""
        fg = self._freq_grid(w)
        c, sn = fg.cos, fg.sin
        r = chain_response(self.device, fg.s, want_left=False, impedances=self._impedances(fg))
        y = r.y12
        abs_y2 = y.real * y.real + y.imag * y.imag
        # det H = c2^2 Re X + 2 s2 c2 Im X - s2^2 (Re y11 Re y22 + (Im y)^2), and
        # Re y11 Re y22 = Re X + (Re y)^2, so det H = s2^2 |y|^2 - cos(th) Re X - sin(th) Im X;
        # s2^2 = sin^2(th/2) = sin^2(th) / (2 (1 + cos th))  (no subtraction: 0 < th < pi/2)
        s2sq = sn * sn / (2.0 + 2.0 * c)
        num = s2sq * abs_y2
        num -= c * r.x.real
        num -= sn * r.x.imag
        num *= c
        bound, singular = safe_ratio(num, r.re_y11)
        h = np.empty(w.shape, dtype=complex)  # hold factor cos(th) e^{-j th}
        np.multiply(c, c, out=h.real)
        np.multiply(c, -sn, out=h.imag)
        abs_p = abs_y2 * c
        re_p = (y * y * h).real
        br = BoundResult(w=w, bound=bound, p11=r.y11, re_p11=r.re_y11, abs_p=abs_p, re_p=re_p, singular=singular)
        return br, TwoPort(w=w, p11=r.y11, p12=r.y12 * h, p21=r.y12, p22=r.y22 * h)

    # -- coupling (eq. 4, 9) -------------------------------------------------------------
    def coupling(self, w, kc: float, bc: float) -> np.ndarray:
        """The coupling impedance ``Z_c`` of eq. (4) with this display's velocity filter.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        kc : float
            Coupling stiffness k_c [N/m].
        bc : float
            Coupling damping b_c [N s/m].

        Returns
        -------
        numpy.ndarray
            ``Z_c`` [N s/m], complex, shape (N,) (:func:`coupling_impedance`).
        """
        return coupling_impedance(w, self.device.sample_time, kc, bc, self.velocity_filter)

    def coupling_term(self, w, kc: float, bc: float) -> np.ndarray:
        """``Re(1/Z_c)``, the left side of eq. (9).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        kc : float
            Coupling stiffness k_c [N/m].
        bc : float
            Coupling damping b_c [N s/m].

        Returns
        -------
        numpy.ndarray
            ``Re(1/Z_c)`` [m/(N s)], shape (N,).
        """
        return re_inv_coupling(w, self.device.sample_time, kc, bc, self.velocity_filter)

    # -- eq. (11), (12) -----------------------------------------------------------------
    def impedance_range(self, w, kc: float, bc: float) -> tuple[np.ndarray, np.ndarray]:
        """``(Z_min, Z_max)`` of eq. (11) and (12), complex arrays (N s/m).

        ``Z_max`` is the handle impedance of the chain with ``h Z_c`` from the actuator to
        ground, which is eq. (12) rewritten without its subtraction.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        kc : float
            Coupling stiffness k_c [N/m].
        bc : float
            Coupling damping b_c [N s/m].

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
        return 1.0 / self.two_port(w).p11, self._zmax(w, kc, bc)

    def _impedances(self, fg: FrequencyGrid) -> tuple[np.ndarray, np.ndarray]:
        """The chain's (node, element) impedances at the Tustin image of ``fg`` (kept on it)."""
        if fg.imp is None:
            fg.imp = frozen_impedances(self.device, fg.W)
        return fg.imp

    def _zmax(self, w: np.ndarray, kc: float, bc: float) -> np.ndarray:
        fg = self._freq_grid(w)
        # held spring-damper h Z_c = b c^2 - j c (b s + k T / (2 s)) (discretize.held_spring_damper)
        c, sn = fg.cos, fg.sin
        term = np.empty(w.shape, dtype=complex)
        if self.velocity_filter is None:
            np.multiply(bc * c, c, out=term.real)
            np.multiply(-c, bc * sn + 0.5 * kc * self.device.sample_time / sn, out=term.imag)
        else:  # h b_c H_f + h k_c T z/(z-1), the latter -j (k_c T/2) cot(theta)
            hold = c * (c - 1j * sn)
            term[:] = bc * hold * self.velocity_filter.filter_response(w, self.device.sample_time)
            term.imag -= 0.5 * kc * self.device.sample_time * c / sn
        return terminated_handle_impedance(self.device, self._impedances(fg), term)

    def apparent_impedance(self) -> complex:
        """Z_min at :data:`APPARENT_FREQUENCY`: the free-motion impedance (device only, cached).

        Returns
        -------
        complex
            The handle impedance [N s/m] at the Tustin image of :data:`APPARENT_FREQUENCY`;
            its real part is the apparent damping, its imaginary part over ``W`` the apparent
            mass.
        """
        if self._apparent is None:
            T = self.device.sample_time
            W = float((2.0 / T) * np.tan(theta_of(np.array([APPARENT_FREQUENCY]), T))[0])
            za = handle_impedance_at(self.device, W)
            if za is None:  # exact pole of a lossless chain: numpy's inf/nan semantics
                za = complex(handle_impedance(self.device, np.array([1j * W]))[0])
            self._apparent = (za, W)
        return self._apparent[0]

    def k_max(self, kc: float) -> float:
        """Low-frequency stiffness of Z_max: coupling spring in series with the chain springs.

        Parameters
        ----------
        kc : float
            Coupling stiffness k_c [N/m].

        Returns
        -------
        float
            ``1 / (1/k_c + sum 1/k_i)`` [N/m]; 0 when ``k_c <= 0``.
        """
        if kc <= 0:
            return 0.0
        return 1.0 / (1.0 / kc + self.device.static_compliance)

    def b_min(self) -> float:
        """Low-frequency damping of Z_min: the device's damping to ground (eq. 11).

        Returns
        -------
        float
            The sum of the dampings to ground [N s/m].
        """
        return self.device.total_ground_damping

    def evaluate(self, kc: float, bc: float, w=None, refine: bool = True) -> StabilityResult:
        """Bound, Re(1/Z_c), margin, eta, Z_min, Z_max and headline numbers.

        Parameters
        ----------
        kc : float
            Coupling stiffness k_c [N/m].
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
        if w is None:
            w = self.frequencies()
            br = self.bound_result(w)
        else:
            w = check_frequencies(w, self.device.sample_time)
            br = self._cached(w, checked=True)[0]
        if self.velocity_filter is None:
            term = _re_inv_coupling(self._freq_grid(w).tan, self.device.sample_time, kc, bc)
        else:
            term = self.coupling_term(w, kc, bc)
        margin = term - br.bound
        with np.errstate(divide="ignore", invalid="ignore"):  # exact poles of a lossless chain
            zmin = 1.0 / br.p11
        zmax = self._zmax(w, kc, bc)
        za = self.apparent_impedance()
        return self._result(w, kc, bc, br, term, margin, zmin, zmax, self.k_max(kc), self.b_min(),
                            za.imag / self._apparent[1], za.real, refine)

    # -- design ------------------------------------------------------------------------
    def max_stiffness(self, bc: float, w=None) -> StiffnessDesign:
        """Largest k_c satisfying eq. (9) over the band, for damping ``b_c``.

        The bound is sampled on the resonance-aware grid, the per-frequency closed-form
        limit :func:`kc_upper` is minimized, and every local minimum is refined; the
        result is backed off by 1e-9 relative so that it is conservative.  With a velocity
        filter the per-frequency limit is :func:`kc_upper_filtered`, and the design is
        refused (``kc=None``) when the result fails eq. (9) somewhere (the filter's phase lag
        can make ``Re Z_c < 0``, which bounds k_c from below).

        Parameters
        ----------
        bc : float
            Coupling damping b_c [N s/m], finite and >= 0.
        w : array_like or None, optional
            Angular frequencies [rad/s], shape (N,); ``None`` for :meth:`frequencies`.

        Returns
        -------
        StiffnessDesign
            The largest k_c (``None`` when none works, ``inf`` when every one does), where it
            binds, the margin there and the number of bound evaluations.

        Raises
        ------
        ValidationError
            When ``bc`` is negative or not finite, or a frequency of ``w`` is invalid.
        """
        if not (math.isfinite(bc) and bc >= 0):
            from analysis.errors import ValidationError

            raise ValidationError("bc", ">= 0 and finite (N s/m)", bc)
        w = self.frequencies() if w is None else check_frequencies(w, self.device.sample_time)
        T = self.device.sample_time
        before = self.bound_evaluations
        B = self.bound(w)
        vf = self.velocity_filter

        def upper(b: np.ndarray, x: np.ndarray) -> np.ndarray:
            return kc_upper(b, x, T, bc) if vf is None else kc_upper_filtered(b, x, T, bc, vf)

        vals = upper(B, w)
        lo, hi = grids.band_edges(self.device)

        def f(x: np.ndarray) -> np.ndarray:
            return upper(self._uncached_bound(x), x)

        rw, rv = grids.refine_minima(f, w, vals, lo, hi, candidates=8)
        j = int(np.argmin(vals))
        kmin, wmin = float(vals[j]), float(w[j])
        if rv.size and rv[0] < kmin:
            kmin, wmin = float(rv[0]), float(rw[0])
        evals = self.bound_evaluations - before
        if kmin == -math.inf:
            return StiffnessDesign(bc=bc, kc=None, frequency=wmin, margin=-math.inf, evaluations=evals)
        if kmin == math.inf:
            return StiffnessDesign(bc=bc, kc=math.inf, frequency=math.nan, margin=math.inf, evaluations=evals)
        kc = kmin * (1.0 - _SAFETY)
        pts = np.concatenate([w, rw])
        m = self.coupling_term(pts, kc, bc) - np.concatenate([B, self._compute_checked(rw)[0].bound])
        if vf is not None and float(np.min(m)) < 0:  # a filter's lag can also bound k_c from below
            return StiffnessDesign(bc=bc, kc=None, frequency=wmin, margin=float(np.min(m)), evaluations=evals)
        return StiffnessDesign(bc=bc, kc=kc, frequency=wmin, margin=float(np.min(m)), evaluations=evals)

    @none_if_cancelled
    def stiffness_chart(self, bc_values, w=None, *, progress: Progress | None = None,
                        cancelled: Cancelled | None = None) -> StiffnessChart | None:
        """Largest k_c satisfying eq. (9) as a function of b_c (the design chart).

        ``progress(done, total)`` is called after each b_c; when ``cancelled()`` turns true
        the chart stops and ``None`` is returned.

        Parameters
        ----------
        bc_values : array_like
            Coupling dampings b_c [N s/m], shape (M,).
        w : array_like or None, optional
            Angular frequencies [rad/s]; ``None`` for :meth:`frequencies`.
        progress : callable or None, optional
            ``progress(done, total)``, called after each b_c.
        cancelled : callable or None, optional
            ``cancelled() -> bool``, polled before each b_c; true stops the chart.

        Returns
        -------
        StiffnessChart or None
            The chart, shape (M,) per field; ``None`` when cancelled.
        """
        bcs = np.asarray(bc_values, float)
        kcs = np.full(bcs.size, np.nan)
        fr = np.full(bcs.size, np.nan)
        for i, bc in enumerate(bcs):
            check_cancelled(cancelled)
            d = self.max_stiffness(float(bc), w)
            kcs[i] = np.nan if d.kc is None else d.kc
            fr[i] = d.frequency
            report_progress(progress, i + 1, bcs.size)
        return StiffnessChart(bc=bcs, kc=kcs, frequency=fr)
