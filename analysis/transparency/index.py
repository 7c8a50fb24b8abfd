"""The transparency index ``J`` of the wall controller (Eom, Suh & Yi, eq. 10-11).

Closed-form H2 norm (Lyapunov, or modal for many ``B_c``) for rational holds; Gauss-Legendre
quadrature on pole-adapted panels for ``zoh`` and ``discrete``, with the closed-loop stability
test each needs (argument principle for ``zoh``).  See :mod:`analysis.transparency`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from scipy import linalg

from analysis.errors import ValidationError
from analysis.transparency.hinf import gauss_nodes, panel_breakpoints
from analysis.transparency.holds import RATIONAL_HOLDS, hold_response
from analysis.transparency.settings import IndexResult
from analysis.transparency.loops import SampledLoopMixin

__all__ = ["IndexMixin"]


class IndexMixin(SampledLoopMixin):
    """``J`` part of :class:`analysis.transparency.WallDesign`.

    The host provides, besides what :class:`SampledLoopMixin` needs, the methods stubbed below.
    """

    if TYPE_CHECKING:
        def _check_bc(self, bc) -> np.ndarray: ...

        def weight(self, s: np.ndarray) -> np.ndarray: ...

        def wall_admittance(self, s: np.ndarray) -> np.ndarray: ...

        def _continuous_parts(self, w: np.ndarray, oscillating: bool = True) -> tuple[np.ndarray, np.ndarray]: ...

        def _rational_loop(self, hold: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]: ...

        def _poles_many(self, bcs: np.ndarray, hold: str) -> np.ndarray: ...

        def _singularities(self, bcs: np.ndarray) -> np.ndarray: ...

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
