"""Transparency and robust stability of a virtual-wall controller (Eom, Suh & Yi, sections 2-3).

Reading of the paper (eq. 7-17) used here
-----------------------------------------
* Device (eq. 7): ``P(s) = 1/(m s + b)``, force at the handle to handle velocity.  A flexible
  device may be given instead as an :class:`analysis.Device` chain; then ``P(s)`` is the chain's
  driving-point admittance at the handle (``y11`` of :func:`analysis.chain.chain_response`, here
  evaluated by its own O(n) continued fraction) and the controller is read as *collocated*: it
  measures the handle position and its force acts at the handle (the paper's ``v_d = v_h``).  The
  robustness weight of a chain uses its rigid-body parameters, ``m = sum m_i``, ``b = sum g_i``.
* Virtual wall (eq. 8): ``V(s) = (K + B s)/s``; its admittance ``Y_v(s) = s/(K + B s)``.
* Controller (eq. 12): ``C(s) = B_c + K_c/s`` acting on the velocity (``K_c x + B_c v``),
  ``K_c = K`` unless ``controller_stiffness`` is given.
* Transmitted admittance (eq. 9): ``Y_t = P/(1 + H P C)`` with ``H`` the hold model
  (:mod:`analysis.hold_models`), i.e. the velocity answer to the human force ``F_h``.
* Index (eq. 10-11): ``J = ||w1 (Y_v - Y_t)||_2^2 = (1/2 pi) int |w1 (Y_v - Y_t)|^2 dw`` over
  the whole axis, with ``w1 = (w_c/(s + w_c))^r`` (default ``r = 1``, ``w_c = 100`` rad/s).
  ``J`` is the H2 norm squared and is finite only if the closed loop is asymptotically stable and
  ``w1 (Y_v - Y_t)`` is strictly proper; otherwise it is ``inf`` and :class:`IndexResult` says
  why.  Ambiguity: the paper says ``J`` is unbounded unless ``K_c = K``; with eq. (11) as printed
  the error vanishes at DC like ``s (1/K - 1/K_c)`` for any ``K_c``, so ``J`` stays finite (the
  statement holds for the *position* error of a force step, ``(Y_v - Y_t)/s``).  We follow
  eq. (11) and allow ``K_c != K``.  ``Y_v - Y_t -> 1/B`` at high frequency, so ``r = 0``
  (no weight) gives ``J = inf``, and ``B = 0`` needs ``r >= 2``.
* Robustness (eq. 13-17): ``P~ = P/(1 + W Delta P)`` with ``W = alpha m s + beta b`` (eq. 15);
  ``L = -W P/(1 + H P C) = -W Y_t`` (eq. 16) and the condition ``||L||_inf <= 1`` (eq. 17).
  ``|L| -> alpha`` as ``w -> inf`` for every continuous hold (and 0 at DC when ``K_c > 0``), so the
  supremum may be the limit at infinity; :class:`RobustnessPeak` reports ``frequency = inf`` then.
* ``discrete`` hold: the exact sampled loop with a ZOH actuator and a position controller
  ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` (backward-difference velocity, no computation
  delay).  ``Y_t(z)`` is the answer of the sampled velocity to a *held* human force (exact for
  forces that are constant between samples), evaluated on the unit circle; ``J`` is then the
  integral over the Nyquist band ``[0, pi/T)`` only (the error has no content beyond it in this
  model) -- not directly comparable with the continuous models, whose ``J`` includes the tail
  ``~ w_c^2/(pi B^2) (T/pi)``.  ``L(z)`` is the ZOH discretization of ``W P`` closed through the
  same loop (the Delta channel read as held too).
* Step response (Figs. 7, 10): always the exact sampled loop above (whatever the hold model),
  ZOH discretization by the matrix exponential; between samples the continuous state is exact as
  well (``substeps`` points per sample).

Numerics
--------
* ``J`` for rational holds: closed-form H2 norm from a Lyapunov equation; for ``zoh`` and
  ``discrete``: composite 16-point Gauss-Legendre on panels adapted to the closed-loop poles (for
  ``zoh``, those of the Pade and low-pass surrogates), half-period panels above Nyquist, and a
  ``w = Omega/u`` tail in which the ``e^{-sT}`` part of the hold is dropped (it integrates to
  < 1e-11 relative there).  Agreement with scipy quad and the Lyapunov value is checked in tests.
* ``||L||_inf``: a grid with points on every closed-loop resonance (``w0 + sigma * {...}``), 48
  per decade elsewhere and 8 per period above Nyquist for ``zoh``, then a zoom refinement of the
  three best local maxima (:func:`analysis.hinf.refine_peaks`).  Above the grid the ``zoh`` ripple
  is bounded analytically; ``certified`` is False if that bound could exceed the peak.
* Curves over ``B_c`` (Fig. 8) reuse everything that does not depend on ``B_c``: with
  ``a = 1/P + H K_c/s`` and ``h = H``, ``Y_t = 1/(a + B_c h)`` on a shared grid.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.transparency.hinf import local_maxima, refine_peaks
from analysis.transparency.holds import HOLDS, hold_response, hold_state_space
from analysis.transparency.settings import (
    IndexResult,
    OptimalDamping,
    RobustnessPeak,
    StepResponse,
    TradeoffCurves,
    WallSettings,
    _integer,
    _real,
)
from analysis.transparency.index import IndexMixin
from analysis.transparency.plant import _Plant, _ss_freq, handle_admittance  # noqa: F401  (_ss_freq re-exported)
from analysis.transparency.loops import SampledLoopMixin

__all__ = [
    "HOLDS",
    "WallSettings",
    "WallDesign",
    "IndexResult",
    "RobustnessPeak",
    "OptimalDamping",
    "TradeoffCurves",
    "StepResponse",
    "handle_admittance",
]


class WallDesign(IndexMixin, SampledLoopMixin):
    """A virtual-wall controller design problem (Eom, Suh & Yi, section 3); see the module doc.

    ``WallDesign(mass=0.01, damping=0.022, wall_stiffness=1000.0, wall_damping=1.0,
    sample_time=1e-3, hold="lowpass2", weight_cutoff=100.0)`` -- any :class:`WallSettings` field
    as a keyword, or ``settings=``; ``device=`` a chain (then ``P = y11``, ``plant = "chain"``;
    the device's own ``sample_time`` is not used, the design's is).
    """

    def __init__(self, settings: WallSettings | None = None, *, device: Device | None = None, **params):
        base = settings if settings is not None else WallSettings()
        if device is not None:
            params.setdefault("plant", "chain")
        self.settings = replace(base, **params) if params else base
        if self.settings.plant == "chain" and device is None:
            raise ValidationError("plant", "'rigid' unless a device chain is given", "chain")
        if self.settings.plant == "rigid":
            device = None
        self.device = device
        self.plant = _Plant(self.settings, device)
        self._cache: dict = {}

    @classmethod
    def from_settings(cls, settings: WallSettings, device: Device | None = None) -> WallDesign:
        return cls(settings, device=device)

    # -- small pieces ------------------------------------------------------------------------
    @property
    def kc(self) -> float:
        return self.settings.kc

    def _check_bc(self, bc) -> np.ndarray:
        arr = np.atleast_1d(np.asarray(bc, dtype=float))
        bad = ~np.isfinite(arr)
        if bad.any():
            raise ValidationError("bc", "finite (N s/m)", float(arr[bad][0]), int(np.flatnonzero(bad)[0]))
        return arr

    def _ab(self, alpha, beta) -> tuple[float, float]:
        a = self.settings.alpha if alpha is None else _real("alpha", alpha, lo=0.0, allowed=">= 0")
        b = self.settings.beta if beta is None else _real("beta", beta, lo=0.0, allowed=">= 0")
        return a, b

    def weight(self, s: np.ndarray) -> np.ndarray:
        """``w1(s) = (w_c/(s + w_c))^r``."""
        st = self.settings
        return (st.weight_cutoff / (np.asarray(s) + st.weight_cutoff)) ** st.weight_order

    def wall_admittance(self, s: np.ndarray) -> np.ndarray:
        """``Y_v(s) = s/(K + B s)`` (eq. 8)."""
        st = self.settings
        s = np.asarray(s, dtype=complex)
        return s / (st.wall_stiffness + st.wall_damping * s)

    def _continuous_parts(self, w: np.ndarray, oscillating: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``a = 1/P + H K_c/s`` and ``h = H`` at ``s = j w``: ``Y_t = 1/(a + B_c h)``."""
        st = self.settings
        s = 1j * np.asarray(w, dtype=float)
        H = hold_response(st.hold, s, st.sample_time, st.lowpass_damping, oscillating)
        return self.plant.impedance(s) + H * (self.kc / s), H

    # -- rational loop (Lyapunov, poles) -----------------------------------------------------
    def _rational_loop(self, hold: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``A_cl(B_c) = A0 + B_c A1``, ``B_cl``, ``C_cl`` (velocity) of eq. (9) with a rational hold.

        States: plant, ``xi = int v`` (only when ``K_c != 0``), hold.
        """
        key = ("rl", hold)
        if key in self._cache:
            return self._cache[key]
        st, p = self.settings, self.plant
        Ah, Bh, Ch, Dh = hold_state_space(hold, st.sample_time, st.lowpass_damping)
        kc = self.kc
        npl, nh = p.order, Ah.shape[0]
        nx = 1 if kc != 0 else 0
        N = npl + nx + nh
        A0 = np.zeros((N, N))
        A1 = np.zeros((N, N))
        P, X, Hs = slice(0, npl), slice(npl, npl + nx), slice(npl + nx, N)
        dh = float(Dh[0, 0])
        A0[P, P] = p.A
        A0[P, Hs] = -p.B @ Ch
        A1[P, P] = -dh * (p.B @ p.Cv)
        A1[Hs, P] = Bh @ p.Cv
        if nx:
            A0[P, X] = -dh * kc * p.B
            A0[X, P] = p.Cv
            A0[Hs, X] = Bh * kc
        A0[Hs, Hs] = Ah
        Bcl = np.zeros((N, 1))
        Bcl[P] = p.B
        Ccl = np.zeros((1, N))
        Ccl[0, P] = p.Cv[0]
        self._cache[key] = (A0, A1, Bcl, Ccl)
        return self._cache[key]

    def closed_loop_poles(self, bc: float, hold: str | None = None) -> np.ndarray:
        """Closed-loop poles (rad/s) for a rational hold, or ``log(z)/T`` for ``discrete``."""
        hold = hold or self.settings.hold
        if hold == "zoh":
            raise ValidationError("hold", "a rational hold or 'discrete' (zoh has infinitely many poles)", hold)
        return self._poles_many(self._check_bc(bc)[:1], hold)[0]

    def _poles_many(self, bcs: np.ndarray, hold: str) -> np.ndarray:
        """Closed-loop poles (rows = ``bcs``), batched; ``log(z)/T`` for ``discrete``."""
        if hold == "discrete":
            Ad0, Ad1 = self._discrete_loop()[:2]
            lam = np.linalg.eigvals(Ad0[None] + bcs[:, None, None] * Ad1[None]).astype(complex)
            with np.errstate(divide="ignore"):
                return np.log(lam) / self.settings.sample_time
        A0, A1, _, _ = self._rational_loop(hold)
        return np.linalg.eigvals(A0[None] + bcs[:, None, None] * A1[None])

    def _singularities(self, bcs: np.ndarray) -> np.ndarray:
        """Complex ``w0 + j sigma`` of the integrand's poles for all ``bcs`` (panel/grid guides)."""
        st = self.settings
        key = ("sing", bcs.tobytes())
        if key in self._cache:
            return self._cache[key]
        sur = ("pade", "lowpass2") if st.hold == "zoh" else (st.hold,)
        poles = [self.plant.poles()] + [self._poles_many(bcs, h).ravel() for h in sur]
        p = np.concatenate(poles)
        c = np.abs(p.imag) + 1j * np.abs(p.real)
        extra = [1j * st.weight_cutoff]
        if st.wall_damping > 0 and st.wall_stiffness > 0:
            extra.append(1j * st.wall_stiffness / st.wall_damping)
        c = np.concatenate([c, extra])
        c = c[np.isfinite(c) & (np.abs(c) > 0)]
        # merge near-duplicates (many B_c give nearby poles): 0.1 % on a log scale
        key2 = np.round(np.log(np.abs(c)) * 1000.0) + 1j * np.round(np.angle(c) * 1000.0)
        _, first = np.unique(key2, return_index=True)
        c = c[np.sort(first)]
        if len(self._cache) > 64:
            self._cache.clear()
        self._cache[key] = c
        return c

    # -- ||L||_inf ----------------------------------------------------------------------------
    def _peak_grid(self, bcs: np.ndarray) -> np.ndarray:
        st = self.settings
        T = st.sample_time
        c = self._singularities(bcs)
        lo = 1e-3 * float(np.min(np.abs(c)))
        hi = math.pi / T if st.hold == "discrete" else 1e3 * float(np.max(np.abs(c)))
        parts = [np.geomspace(lo, hi, int(48 * math.log10(hi / lo)) + 2)]
        light = c[(c.real > 0) & (c.imag < 0.5 * c.real)]
        off = np.array([-3.0, -2.0, -1.0, -0.5, -0.25, 0.0, 0.25, 0.5, 1.0, 2.0, 3.0])
        parts.append((light.real[:, None] + light.imag[:, None] * off[None, :]).ravel())
        if st.hold == "zoh":
            parts.append(np.arange(math.pi / T, self._zoh_grid_end(), 0.25 * math.pi / T))
        g = np.unique(np.concatenate(parts))
        return g[(g >= lo) & (g <= hi)]

    def _zoh_grid_end(self) -> float:
        return 128 * math.pi / self.settings.sample_time

    def _limit(self, alpha: float) -> float:
        """``lim |L|`` as ``w -> inf`` (continuous holds): ``alpha m_W / m_handle``."""
        return alpha * self.plant.m_w / self.plant.handle_mass

    def _peaks(self, bcs: np.ndarray, alpha: float, beta: float) -> list[RobustnessPeak]:
        st = self.settings
        disc = st.hold == "discrete"
        md = self._discrete_modal(bcs, alpha, beta) if disc else None
        mw, bw = self.plant.m_w, self.plant.b_w

        def ev(rows: np.ndarray, w: np.ndarray) -> np.ndarray:
            """``|L|^2`` for ``rows`` at ``w`` (P shared, or R x P)."""
            if disc:
                L = self._modal_eval(md, rows, np.exp(1j * w * st.sample_time), "L")
            else:
                a, h = self._continuous_parts(w.ravel())
                a, h = a.reshape(w.shape), h.reshape(w.shape)
                W = alpha * mw * 1j * w + beta * bw
                bb = bcs[rows][:, None]
                L = W / (a + bb * h) if w.ndim == 2 else W[None, :] / (a[None, :] + bb * h[None, :])
            return L.real**2 + L.imag**2

        grid = self._peak_grid(bcs)
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
        lim = 0.0 if disc else self._limit(alpha)
        for j in range(nb):
            gain, f = math.sqrt(float(vp[j, best[j]])), float(wp[j, best[j]])
            certified = True
            if not disc and lim >= gain:
                gain, f = lim, math.inf
            if st.hold == "zoh":
                certified = bool(self._zoh_tail_bound(float(bcs[j]), alpha, beta) <= gain)
            out.append(RobustnessPeak(float(bcs[j]), gain, f, alpha, beta, lim, certified))
        return out

    def _zoh_tail_bound(self, bc: float, alpha: float, beta: float) -> float:
        """Upper bound of ``|L|`` above the ``zoh`` grid: ``|W P| / (1 - |H P C|)``, ``|H| <= 2/(wT)``.

        Rigid plant: ``|W P|`` lies between ``beta`` and ``alpha``; chain: ``|W P|`` is bounded
        by its value on the grid end times 1.01 (its modes are far below the grid end).
        """
        st = self.settings
        w0 = self._zoh_grid_end()
        s = 1j * w0
        P = 1.0 / self.plant.impedance(np.array([s]))[0]
        hpc = 2.0 / (w0 * st.sample_time) * abs(P) * (abs(bc) + self.kc / w0)
        if hpc >= 1:
            return math.inf
        W = alpha * self.plant.m_w * s + beta * self.plant.b_w
        wp = max(alpha, beta) if self.device is None else 1.01 * max(abs(W * P), self._limit(alpha))
        return wp / (1.0 - hpc)

    def robustness_peak(self, bc: float, alpha: float | None = None, beta: float | None = None) -> RobustnessPeak:
        """``||L||_inf`` (eq. 16-17) and its frequency; ``alpha``, ``beta`` default to the settings."""
        a, b = self._ab(alpha, beta)
        return self._peaks(self._check_bc(bc)[:1], a, b)[0]

    # -- curves and optimum --------------------------------------------------------------------
    def tradeoff(self, bc_values=None, alpha: float | None = None, beta: float | None = None) -> TradeoffCurves:
        """``J(B_c)`` and ``||L||_inf(B_c)`` over ``bc_values`` (default: the settings' range)."""
        st = self.settings
        a, b = self._ab(alpha, beta)
        bcs = (np.linspace(st.bc_min, st.bc_max, st.bc_count) if bc_values is None
               else self._check_bc(bc_values))
        index = self._index_many(bcs)
        pk = self._peaks(bcs, a, b)
        return TradeoffCurves(bcs.copy(), index, np.array([p.gain for p in pk]),
                              np.array([p.frequency for p in pk]), a, b)

    def optimal_damping(self, alpha: float | None = None, beta: float | None = None,
                        bc_range: tuple[float, float] | None = None) -> OptimalDamping:
        """Minimize ``J(B_c)`` subject to ``||L||_inf <= 1`` over the settings' ``B_c`` range.

        A scan of the range (``bc_count`` values) brackets the best feasible point; Brent's
        method polishes it; if the unconstrained minimizer violates eq. (17), the constraint
        boundary is found by Brent's root finder and returned instead.
        """
        st = self.settings
        a, b = self._ab(alpha, beta)
        lo, hi = bc_range if bc_range is not None else (st.bc_min, st.bc_max)
        curves = self.tradeoff(np.linspace(lo, hi, st.bc_count), a, b)
        bc, J, pk = curves.bc, curves.index, curves.peak
        finite = np.isfinite(J)
        if not finite.any():
            return OptimalDamping(math.nan, math.inf, math.nan, math.nan, False, False, math.nan,
                                  "J is not finite anywhere in the range")

        def polish(i: int) -> float:
            left, right = bc[max(i - 1, 0)], bc[min(i + 1, bc.size - 1)]
            res = optimize.minimize_scalar(self.performance_index, bounds=(left, right), method="bounded",
                                           options={"xatol": 1e-9 * max(1.0, abs(bc[i]))})
            return float(res.x) if res.fun <= J[i] else float(bc[i])

        iu = int(np.argmin(np.where(finite, J, np.inf)))
        bu = polish(iu)
        feas = finite & (pk <= 1.0)
        if not feas.any():
            return OptimalDamping(math.nan, math.inf, math.nan, math.nan, False, False, bu,
                                  "no B_c in the range satisfies ||L||_inf <= 1")
        p_u = self.robustness_peak(bu, a, b)
        if p_u.gain <= 1.0:
            return OptimalDamping(bu, self.performance_index(bu), p_u.gain, p_u.frequency, True, False, bu)
        i = int(np.argmin(np.where(feas, J, np.inf)))
        # the optimum sits on the constraint next to the best feasible grid point
        cands = []
        for j in (i - 1, i + 1):
            if 0 <= j < bc.size and not feas[j]:
                g = lambda x: self.robustness_peak(x, a, b).gain - 1.0  # noqa: E731
                cands.append(optimize.brentq(g, min(bc[i], bc[j]), max(bc[i], bc[j]), xtol=1e-10))
        best = min(cands, key=self.performance_index) if cands else float(bc[i])
        p = self.robustness_peak(best, a, b)
        return OptimalDamping(float(best), self.performance_index(best), p.gain, p.frequency, True, True, bu)

    # -- views ----------------------------------------------------------------------------------
    def admittances(self, w, bc: float) -> tuple[np.ndarray, np.ndarray]:
        """``(Y_v, Y_t)`` at ``s = j w`` (Fig. 9); for ``discrete``, ``Y_t(e^{jwT})`` (w < pi/T)."""
        w = np.asarray(w, dtype=float)
        if w.size and (not np.all(np.isfinite(w)) or np.any(w <= 0)):
            raise ValidationError("frequency", "finite and > 0 (rad/s)", w)
        bcs = self._check_bc(bc)[:1]
        flat = w.ravel()
        if self.settings.hold == "discrete":
            if np.any(flat >= math.pi / self.settings.sample_time):
                raise ValidationError("frequency", "< Nyquist for the discrete hold", float(flat.max()))
        yt = self._yt_rows(bcs, flat)[0]
        return self.wall_admittance(1j * w), yt.reshape(w.shape)

    def step_response(self, bc: float, force: float | None = None, duration: float | None = None,
                      substeps: int = 8) -> StepResponse:
        """Human-force step on the exact sampled loop (ZOH discretization via the matrix exponential).

        The device starts at rest at the wall surface ``x = 0``; the controller
        ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` is held over each sample.
        """
        st = self.settings
        bc = float(self._check_bc(bc)[0])
        F = st.step_force if force is None else _real("force", force, allowed="finite (N)")
        dur = st.step_duration if duration is None else _real("duration", duration, lo=0.0, lo_open=True,
                                                               hi=100.0, allowed="in (0, 100] s")
        substeps = _integer("substeps", substeps, 1, 1000)
        T, kc = st.sample_time, self.kc
        A, B, Cv, Cx = self._augmented()
        n = A.shape[0]
        nk = int(math.ceil(dur / T - 1e-9))
        tau = T / substeps
        Phi1, Gam1 = self._zoh(A, B, tau)
        # intersample maps Phi_j, Gam_j for j = 0..substeps
        Phis = [np.eye(n)]
        Gams = [np.zeros((n, 1))]
        for _ in range(substeps):
            Phis.append(Phi1 @ Phis[-1])
            Gams.append(Phi1 @ Gams[-1] + Gam1)
        PhiT, GamT = Phis[-1], Gams[-1]
        x = np.zeros(n)
        prev = 0.0
        xs = np.empty((nk, n))
        us = np.empty(nk)
        cx = Cx[0]
        for k in range(nk):
            pos = float(cx @ x)
            u = kc * pos + bc * (pos - prev) / T
            xs[k], us[k] = x, u
            prev = pos
            x = PhiT @ x + GamT[:, 0] * (F - u)
        P = np.stack(Phis[:-1])  # substeps x n x n
        G = np.stack(Gams[:-1])[:, :, 0]  # substeps x n
        traj = np.einsum("jab,kb->kja", P, xs) + G[None, :, :] * (F - us)[:, None, None]
        traj = np.concatenate([traj.reshape(nk * substeps, n), (PhiT @ xs[-1] + GamT[:, 0] * (F - us[-1]))[None]])
        t = np.arange(nk * substeps + 1) * tau
        force_hist = np.concatenate([np.repeat(us, substeps), us[-1:]])
        K, Bw = st.wall_stiffness, st.wall_damping
        if K > 0 and Bw > 0:
            wall = F / K * (-np.expm1(-K * t / Bw))
        elif K > 0:
            wall = np.full_like(t, F / K)
        else:
            wall = F / Bw * t
        return StepResponse(t, force_hist, traj @ cx, traj @ Cv[0], np.full_like(t, F), wall, bc)
