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
from scipy import linalg, optimize

from .device import Device
from .errors import ValidationError
from .hinf import gauss_nodes, local_maxima, panel_breakpoints, refine_peaks
from .hold_models import HOLDS, RATIONAL_HOLDS, hold_response, hold_state_space
from .wall import (
    IndexResult,
    OptimalDamping,
    RobustnessPeak,
    StepResponse,
    TradeoffCurves,
    WallSettings,
    _integer,
    _real,
)

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

# ----------------------------------------------------------------------------------------------
# plant
# ----------------------------------------------------------------------------------------------
class _Plant:
    """``P(s)`` and a minimal realization ``(A, B, Cv)`` (force at the handle -> handle velocity)."""

    def __init__(self, settings: WallSettings, device: Device | None):
        self.device = device
        if device is None:
            m, b = settings.mass, settings.damping
            self.A = np.array([[-b / m]])
            self.B = np.array([[1.0 / m]])
            self.Cv = np.array([[1.0]])
            self.m_w, self.b_w = m, b
            self.handle_mass = m
        else:
            # states: relative displacements d_i = x_i - x_{i+1} (n-1), velocities v (n)
            n = device.n
            mm, k, bb, g = device.masses, device.stiffnesses, device.dampings, device.ground_dampings
            A = np.zeros((2 * n - 1, 2 * n - 1))
            for i in range(n - 1):
                A[i, n - 1 + i] = 1.0
                A[i, n + i] = -1.0
            for i in range(n):
                r = n - 1 + i
                A[r, r] -= g[i] / mm[i]
                if i < n - 1:  # element i pulls mass i back
                    A[r, i] -= k[i] / mm[i]
                    A[r, r] -= bb[i] / mm[i]
                    A[r, r + 1] += bb[i] / mm[i]
                if i > 0:  # element i-1 pushes mass i
                    A[r, i - 1] += k[i - 1] / mm[i]
                    A[r, r - 1] += bb[i - 1] / mm[i]
                    A[r, r] -= bb[i - 1] / mm[i]
            self.A = A
            self.B = np.zeros((2 * n - 1, 1))
            self.B[n - 1, 0] = 1.0 / mm[0]
            self.Cv = np.zeros((1, 2 * n - 1))
            self.Cv[0, n - 1] = 1.0
            self.m_w, self.b_w = device.total_mass, device.total_ground_damping
            self.handle_mass = float(mm[0])

    @property
    def order(self) -> int:
        return self.A.shape[0]

    def impedance(self, s: np.ndarray) -> np.ndarray:
        """``1/P(s)``: ``m s + b``, or the chain's handle impedance by a continued fraction."""
        s = np.asarray(s, dtype=complex)
        if self.device is None:
            return self.m_w * s + self.b_w
        d = self.device
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            R = d.masses[-1] * s + d.ground_dampings[-1]
            for i in range(d.n - 2, -1, -1):
                e = d.dampings[i] + d.stiffnesses[i] / s
                R = d.masses[i] * s + d.ground_dampings[i] + e * R / (e + R)
        return R

    def poles(self) -> np.ndarray:
        return np.linalg.eigvals(self.A) if self.order else np.zeros(0, complex)


def handle_admittance(device: Device, s) -> np.ndarray:
    """``P(s) = y11(s)`` of a chain: handle velocity per unit handle force (O(n) continued fraction)."""
    return 1.0 / _Plant(WallSettings(), device).impedance(np.asarray(s, dtype=complex))


def _ss_freq(A: np.ndarray, B: np.ndarray, C: np.ndarray, D: float, z: np.ndarray) -> np.ndarray:
    """``C (zI - A)^{-1} B + D`` at points ``z`` by batched solves (small systems)."""
    n = A.shape[0]
    M = z[:, None, None] * np.eye(n)[None] - A[None]
    x = np.linalg.solve(M, np.broadcast_to(B, (z.size, n, 1)))
    return (C[None] @ x)[:, 0, 0] + D


# ----------------------------------------------------------------------------------------------
# the design
# ----------------------------------------------------------------------------------------------
class WallDesign:
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

    # -- discrete loop -----------------------------------------------------------------------
    def _zoh(self, A: np.ndarray, B: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
        n, m = A.shape[0], B.shape[1]
        M = np.zeros((n + m, n + m))
        M[:n, :n] = A * dt
        M[:n, n:] = B * dt
        E = linalg.expm(M)
        return E[:n, :n], E[:n, n:]

    def _augmented(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Plant plus handle position ``xi``: ``(A, B, Cv, Cx)``."""
        p = self.plant
        n = p.order
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = p.A
        A[n, :n] = p.Cv[0]
        B = np.vstack([p.B, [[0.0]]])
        Cv = np.hstack([p.Cv, [[0.0]]])
        Cx = np.zeros((1, n + 1))
        Cx[0, n] = 1.0
        return A, B, Cv, Cx

    def _discrete_loop(self, alpha: float = 0.0, beta: float = 0.0):
        """Closed sampled loop ``x+ = (Ad0 + B_c Ad1) x + Bd F``.

        Outputs: velocity ``Cd x`` and the ZOH-sampled ``W P`` of eq. (16),
        ``(CL0 + B_c CL1) x + Dw F``.  State: plant, handle position, previous position.
        """
        key = ("dl",)
        if key not in self._cache:
            A, B, Cv, Cx = self._augmented()
            Phi, Gam = self._zoh(A, B, self.settings.sample_time)
            self._cache[key] = (A, B, Cv, Cx, Phi, Gam)
        A, B, Cv, Cx, Phi, Gam = self._cache[key]
        T, kc = self.settings.sample_time, self.kc
        n = A.shape[0]
        Ad0 = np.zeros((n + 1, n + 1))
        Ad1 = np.zeros((n + 1, n + 1))
        Ad0[:n, :n] = Phi - kc * (Gam @ Cx)
        Ad1[:n, :n] = -(Gam @ Cx) / T
        Ad1[:n, n] = Gam[:, 0] / T
        Ad0[n, :n] = Cx[0]
        Bd = np.vstack([Gam, [[0.0]]])
        Cd = np.hstack([Cv, [[0.0]]])
        # W P sampled: (alpha m Cv A + beta b Cv) x + alpha m Cv B u_p, u_p = F - (kc + bc/T) xi + bc/T xi_prev
        mw, bw = self.plant.m_w, self.plant.b_w
        Cw = alpha * mw * (Cv @ A) + beta * bw * Cv
        Dw = float(alpha * mw * (Cv @ B)[0, 0])
        CL0 = np.hstack([Cw - Dw * kc * Cx, [[0.0]]])
        CL1 = np.hstack([-Dw * Cx / T, [[Dw / T]]])
        return Ad0, Ad1, Bd, Cd, CL0, CL1, Dw

    def _discrete_modal(self, bcs: np.ndarray, alpha: float = 0.0, beta: float = 0.0) -> dict:
        """Poles and residues of ``Y_t(z)`` and ``L(z)`` for every ``B_c`` (batched eigen-solves).

        Rows whose eigenvector matrix is ill-conditioned (cond > 1e8) keep their matrices and
        are evaluated by direct solves instead.
        """
        Ad0, Ad1, Bd, Cd, CL0, CL1, Dw = self._discrete_loop(alpha, beta)
        Ad = Ad0[None] + bcs[:, None, None] * Ad1[None]
        lam, V = np.linalg.eig(Ad)
        good = np.linalg.cond(V) < 1e8
        g = np.linalg.solve(np.where(good[:, None, None], V, np.eye(V.shape[1])[None]),
                            np.broadcast_to(Bd, (bcs.size,) + Bd.shape))[:, :, 0]
        CL = CL0[None] + bcs[:, None, None] * CL1[None]
        rY = (Cd[None] @ V)[:, 0, :] * g
        rL = (CL @ V)[:, 0, :] * g
        return {"lam": lam, "rY": rY, "rL": rL, "Dw": Dw, "good": good, "Ad": Ad, "Bd": Bd, "Cd": Cd, "CL": CL}

    @staticmethod
    def _modal_eval(md: dict, rows: np.ndarray, z: np.ndarray, which: str) -> np.ndarray:
        """``sum_k r_k/(z - lam_k) (+ Dw)`` for ``rows`` (R) at ``z`` (P or R x P)."""
        lam = md["lam"][rows]
        r = md["rY" if which == "Y" else "rL"][rows]
        zz = z if z.ndim == 2 else np.broadcast_to(z, (rows.size, z.size))
        out = np.einsum("rk,rpk->rp", r, 1.0 / (zz[:, :, None] - lam[:, None, :]))
        if which == "L":
            out = out + md["Dw"]
        for q in np.flatnonzero(~md["good"][rows]):
            j = rows[q]
            C = md["Cd"] if which == "Y" else md["CL"][j]
            out[q] = _ss_freq(md["Ad"][j], md["Bd"], C, 0.0 if which == "Y" else md["Dw"], zz[q])
        return out

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

    # -- J ------------------------------------------------------------------------------------
    def _error_parts(self, hold: str):
        """``w1 (Y_v - Y_t)`` for a rational hold as ``(A0, A1, B, C)`` with ``A = A0 + B_c A1``,
        or a reason string when it is not strictly proper."""
        key = ("ep", hold)
        if key in self._cache:
            return self._cache[key]
        st = self.settings
        K, Bw = st.wall_stiffness, st.wall_damping
        r, wc = st.weight_order, st.weight_cutoff
        A0c, A1c, Bcl, Ccl = self._rational_loop(hold)
        Aw = -wc * np.eye(r) + wc * np.eye(r, k=-1)
        Bw_ = np.zeros((r, 1))
        Cw = np.zeros((1, r))
        if r:
            Bw_[0, 0] = wc
            Cw[0, -1] = 1.0
        Dw = 0.0 if r else 1.0
        if Bw > 0 and K > 0:
            Av, Bv, Cv, Dv = np.array([[-K / Bw]]), np.array([[1.0]]), np.array([[-K / Bw**2]]), 1.0 / Bw
        elif Bw > 0:
            Av, Bv, Cv, Dv = np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), 1.0 / Bw
        else:
            Av = Bv = Cv = None
            Dv = 0.0
        nw, nv, nc = r, (0 if Av is None else Av.shape[0]), A0c.shape[0]
        N = nw + nv + nc
        A0 = np.zeros((N, N))
        A1 = np.zeros((N, N))
        B = np.zeros((N, 1))
        C = np.zeros((1, N))
        W, V, L = slice(0, nw), slice(nw, nw + nv), slice(nw + nv, N)
        A0[W, W] = Aw
        B[W] = Bw_
        A0[L, L] = A0c
        A1[L, L] = A1c
        A0[L, W] = Bcl @ Cw
        B[L] = Bcl * Dw
        C[0, L] = -Ccl[0]
        if Av is not None:
            A0[V, V] = Av
            A0[V, W] = Bv @ Cw
            B[V] = Bv * Dw
            C[0, V] = Cv[0]
            C[0, W] += Dv * Cw[0]
            D = Dv * Dw
        elif r == 0:
            D = math.inf
        else:  # B = 0: Y_v = s/K, s w1 = Cw Aw x + Cw Bw F
            C[0, W] += (Cw @ Aw)[0] / K
            D = float((Cw @ Bw_)[0, 0]) / K
        if D != 0.0:
            out = ("Y_v = s/K is improper (wall_damping = 0) and the weight has order 0" if math.isinf(D) else
                   f"w1 (Y_v - Y_t) tends to {D:.6g} at high frequency (not strictly proper): "
                   "raise the weight order")
        else:
            out = (A0, A1, B, C)
        self._cache[key] = out
        return out

    def _unstable_reason(self, ev: np.ndarray) -> str:
        return f"closed loop unstable (pole at {ev[np.argmax(ev.real)]:.6g} rad/s)"

    def _j_lyapunov(self, bc: float, hold: str) -> IndexResult:
        parts = self._error_parts(hold)
        if isinstance(parts, str):
            return IndexResult(bc, math.inf, False, parts, "lyapunov")
        A0, A1, B, C = parts
        A = A0 + bc * A1
        ev = np.linalg.eigvals(A)
        if np.max(ev.real) >= 0:
            return IndexResult(bc, math.inf, False, self._unstable_reason(ev), "lyapunov")
        X = linalg.solve_continuous_lyapunov(A, -B @ B.T)
        return IndexResult(bc, float((C @ X @ C.T)[0, 0]), True, "", "lyapunov")

    def _j_modal_many(self, bcs: np.ndarray, hold: str) -> np.ndarray:
        """H2 norms for many ``B_c`` at once from poles and residues, ``J = -sum_ij r_i r_j^* /
        (p_i + p_j^*)`` (the Lyapunov solution in modal form); rows with an ill-conditioned
        eigenbasis (cond > 1e6) are solved by Lyapunov instead."""
        parts = self._error_parts(hold)
        if isinstance(parts, str):
            return np.full(bcs.size, math.inf)
        A0, A1, B, C = parts
        A = A0[None] + bcs[:, None, None] * A1[None]
        lam, V = np.linalg.eig(A)
        good = np.linalg.cond(V) < 1e6
        Vs = np.where(good[:, None, None], V, np.eye(V.shape[1])[None])
        g = np.linalg.solve(Vs, np.broadcast_to(B, (bcs.size,) + B.shape))[:, :, 0]
        r = (C[None] @ Vs)[:, 0, :] * g
        J = -np.einsum("ri,rj,rij->r", r, r.conj(), 1.0 / (lam[:, :, None] + lam.conj()[:, None, :])).real
        J = np.where(np.max(lam.real, axis=1) < 0, J, math.inf)
        for i in np.flatnonzero(~good):
            J[i] = self._j_lyapunov(float(bcs[i]), hold).index
        return J

    def _static_reason(self) -> str:
        st = self.settings
        if st.hold == "discrete":
            return ""
        if st.wall_damping > 0 and st.weight_order == 0:
            return "w1 (Y_v - Y_t) tends to 1/B at high frequency (weight of order 0): J is infinite"
        if st.wall_damping == 0 and st.weight_order < 2:
            return "Y_v = s/K grows like s (wall_damping = 0): a weight of order >= 2 is needed"
        return ""

    def quadrature_nodes(self, bcs: np.ndarray, per_decade: float = 8.0, order: int = 16,
                         tail_eps: float = 1e-4) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Nodes/weights of the ``J`` quadrature shared by ``bcs``: ``(w, wt, w_tail, wt_tail)``.

        ``w_tail`` are the tail nodes (``e^{-sT}`` of ``zoh`` dropped there); ``J`` is
        ``(1/pi) (sum wt f(w) + sum wt_tail f(w_tail))``.  ``per_decade`` and ``order`` set the
        density (the benchmark varies them); ``tail_eps`` bounds ``|H P C|`` where the ``zoh``
        tail starts.
        """
        st = self.settings
        T = st.sample_time
        c = self._singularities(bcs)
        cmin = float(np.min(np.abs(c)))
        cmax = float(np.max(np.abs(c)))
        lo = 1e-3 * cmin
        if st.hold == "discrete":
            brk = np.concatenate([[0.0], panel_breakpoints(lo, math.pi / T, c, per_decade)])
            w, wt = gauss_nodes(brk, order)
            return w, wt, np.zeros(0), np.zeros(0)
        if st.hold == "zoh":
            bcmax = float(np.max(np.abs(bcs))) + 1e-300
            om = max(20.0 * cmax, 16.0 * math.pi / T,
                     math.sqrt(2.0 * (bcmax + self.kc * T) / (self.plant.handle_mass * T * tail_eps)))
            om = min(om, 4096 * 2 * math.pi / T)
            brk = panel_breakpoints(lo, om, c, per_decade, max_width=math.pi / T)
        else:
            om = 20.0 * cmax
            brk = panel_breakpoints(lo, om, c, per_decade)
        w, wt = gauss_nodes(np.concatenate([[0.0], brk]), order)
        u, ut = gauss_nodes(np.array([0.0, 0.25, 0.5, 1.0]), order)
        return w, wt, om / u, ut * om / (u * u)

    def _yt_rows(self, bcs: np.ndarray, w: np.ndarray, oscillating: bool = True, md: dict | None = None):
        """``Y_t`` (rows = ``bcs``) at ``w``."""
        if self.settings.hold == "discrete":
            md = md if md is not None else self._discrete_modal(bcs)
            return self._modal_eval(md, np.arange(bcs.size), np.exp(1j * w * self.settings.sample_time), "Y")
        a, h = self._continuous_parts(w, oscillating)
        return 1.0 / (a[None, :] + bcs[:, None] * h[None, :])

    def _integrand(self, bcs: np.ndarray, w: np.ndarray, oscillating: bool = True) -> np.ndarray:
        """``|w1 (Y_v - Y_t)|^2`` for each ``B_c`` (rows) at ``w``."""
        s = 1j * w
        e = self.weight(s)[None, :] * (self.wall_admittance(s)[None, :] - self._yt_rows(bcs, w, oscillating))
        return e.real**2 + e.imag**2

    def _stable_many(self, bcs: np.ndarray, nodes=None) -> tuple[np.ndarray, list[str]]:
        """Closed-loop stability per ``B_c`` and the reason when unstable."""
        st = self.settings
        if st.hold == "zoh":
            return self._zoh_stable_many(bcs, nodes)
        if st.hold == "discrete":
            rad = np.max(np.abs(np.exp(self._poles_many(bcs, "discrete") * st.sample_time)), axis=1)
            ok = rad < 1
            return ok, ["" if o else f"sampled loop unstable (|z| = {x:.6g})" for o, x in zip(ok, rad)]
        ev = self._poles_many(bcs, st.hold)
        ok = np.max(ev.real, axis=1) < 0
        return ok, ["" if o else self._unstable_reason(e) for o, e in zip(ok, ev)]

    def _zoh_stable_many(self, bcs: np.ndarray, nodes=None) -> tuple[np.ndarray, list[str]]:
        """Argument principle for ``g(s) = s (1/P + H C)`` (``s`` dropped when ``K_c = 0``).

        ``g`` is analytic in the right half plane (``H`` is entire, ``1/P`` has no RHP poles for
        a passive device) and ``~ m_0 s^d`` on a large arc, ``d = 2`` (1 if ``K_c = 0``), so the
        number of RHP closed-loop poles is ``d/2 - Delta arg g(j w)|_{0+}^{inf} / pi``; the phase
        is tracked on the quadrature nodes (panels resolve every surrogate resonance).
        """
        w0, _, w1, _ = nodes if nodes is not None else self.quadrature_nodes(bcs)
        T = self.settings.sample_time
        w0 = w0[w0 > 0]
        w1 = np.sort(w1)
        w = np.concatenate([w0, w1])
        s = 1j * w
        H = np.concatenate([hold_response("zoh", 1j * w0, T), hold_response("zoh", 1j * w1, T, oscillating=False)])
        Z = self.plant.impedance(s)
        if self.kc != 0:
            g, d = (s * Z)[None, :] + H[None, :] * (bcs[:, None] * s[None, :] + self.kc), 2
        else:
            g, d = Z[None, :] + H[None, :] * bcs[:, None], 1
        ph = np.unwrap(np.angle(g), axis=1)
        step = np.max(np.abs(np.diff(ph, axis=1)), axis=1)
        end = ph[:, -1] + np.angle(np.exp(1j * (d * math.pi / 2 - ph[:, -1])))
        n_rhp = np.rint(d / 2 - (end - ph[:, 0]) / math.pi).astype(int)
        resolved = (step < 0.5 * math.pi) & (np.min(np.abs(g), axis=1) > 0)
        ok = resolved & (n_rhp == 0)
        reasons = []
        for o, rsv, n in zip(ok, resolved, n_rhp):
            reasons.append("" if o else ("stability of the zoh model could not be resolved on the grid" if not rsv
                                         else f"closed loop (zoh model) unstable: {n} poles in the right half plane"))
        return ok, reasons

    def index_result(self, bc: float, method: str = "auto", per_decade: float = 8.0, order: int = 16) -> IndexResult:
        """``J(B_c)`` (eq. 11) with its status; ``method`` ``auto``/``lyapunov``/``quadrature``."""
        bc = float(self._check_bc(bc)[0])
        st = self.settings
        if method == "auto":
            method = "lyapunov" if st.hold in RATIONAL_HOLDS else "quadrature"
        if method == "lyapunov":
            if st.hold not in RATIONAL_HOLDS:
                raise ValidationError("method", "'quadrature' for a non-rational hold", method)
            return self._j_lyapunov(bc, st.hold)
        if method != "quadrature":
            raise ValidationError("method", "'auto', 'lyapunov' or 'quadrature'", method)
        reason = self._static_reason()
        bcs = np.array([bc])
        nodes = self.quadrature_nodes(bcs, per_decade, order)
        if not reason:
            reason = self._stable_many(bcs, nodes)[1][0]
        if reason:
            return IndexResult(bc, math.inf, False, reason, "quadrature")
        w, wt, wtl, wtt = nodes
        total = self._integrand(bcs, w)[0] @ wt
        if wtl.size:
            total += self._integrand(bcs, wtl, oscillating=False)[0] @ wtt
        return IndexResult(bc, float(total / math.pi), True, "", "quadrature", w.size + wtl.size)

    def performance_index(self, bc: float) -> float:
        """``J(B_c)`` of eq. (11); ``inf`` when not finite (see :meth:`index_result` for why)."""
        return self.index_result(bc).index

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

    def _index_many(self, bcs: np.ndarray) -> np.ndarray:
        st = self.settings
        if st.hold in RATIONAL_HOLDS:
            return self._j_modal_many(bcs, st.hold)
        out = np.full(bcs.size, math.inf)
        if self._static_reason():
            return out
        nodes = self.quadrature_nodes(bcs)
        ok = self._stable_many(bcs, nodes)[0]
        if not ok.any():
            return out
        sb = bcs[ok]
        w, wt, wtl, wtt = nodes
        tot = self._integrand(sb, w) @ wt
        if wtl.size:
            tot += self._integrand(sb, wtl, oscillating=False) @ wtt
        out[ok] = tot / math.pi
        return out

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
