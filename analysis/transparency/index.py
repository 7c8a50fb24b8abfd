"""The transparency index ``J`` of the wall controller (Eom, Suh & Yi, eq. 10-11).

Closed-form H2 norm (Lyapunov, or modal for many ``B_c``) for rational holds; Gauss-Legendre
quadrature on pole-adapted panels for ``zoh`` and ``discrete``, with the closed-loop stability
test each needs (:mod:`analysis.transparency.stability`).  See
:mod:`analysis.transparency.design` for the reading of the paper.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from analysis.errors import ValidationError
from analysis.transparency.hinf import gauss_nodes, panel_breakpoints
from analysis.transparency.holds import RATIONAL_HOLDS
from analysis.transparency.loops import LoopRealizations, check_bc
from analysis.transparency.settings import IndexResult, WallSettings
from analysis.transparency.stability import ClosedLoopStability, Nodes, unstable_reason

__all__ = ["ErrorRealization", "TransparencyIndex", "weight", "wall_admittance"]


def weight(settings: WallSettings, s: np.ndarray) -> np.ndarray:
    """``w1(s) = (w_c/(s + w_c))^r`` (eq. 11)."""
    return (settings.weight_cutoff / (np.asarray(s) + settings.weight_cutoff)) ** settings.weight_order


def wall_admittance(settings: WallSettings, s: np.ndarray) -> np.ndarray:
    """``Y_v(s) = s/(K + B s)`` (eq. 8)."""
    s = np.asarray(s, dtype=complex)
    return s / (settings.wall_stiffness + settings.wall_damping * s)


@dataclass(frozen=True)
class ErrorRealization:
    """``w1 (Y_v - Y_t)`` for a rational hold: ``x' = (a0 + B_c a1) x + b F``, ``e = c x``.

    Parameters
    ----------
    a0 : numpy.ndarray
        The part of the state matrix independent of ``B_c``, shape (N, N).
    a1 : numpy.ndarray
        The part of the state matrix per unit ``B_c``, shape (N, N).
    b : numpy.ndarray
        Input column of the human force [N], shape (N, 1).
    c : numpy.ndarray
        Output row of the weighted velocity error [m/s], shape (1, N).
    """

    a0: np.ndarray
    a1: np.ndarray
    b: np.ndarray
    c: np.ndarray


def _weight_ss(r: int, wc: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``w1`` as ``(A, B, C, D)``: a chain of ``r`` first-order low-passes."""
    Aw = -wc * np.eye(r) + wc * np.eye(r, k=-1)
    Bw = np.zeros((r, 1))
    Cw = np.zeros((1, r))
    if r:
        Bw[0, 0] = wc
        Cw[0, -1] = 1.0
    return Aw, Bw, Cw, 0.0 if r else 1.0


def _error_realization(st: WallSettings, loop) -> ErrorRealization | str:
    """Cascade ``w1`` -> (``Y_v`` - closed loop); a reason string when not strictly proper."""
    K, Bw = st.wall_stiffness, st.wall_damping
    Aw, Bw_, Cw, Dw = _weight_ss(st.weight_order, st.weight_cutoff)
    r = st.weight_order
    if Bw > 0 and K > 0:
        Av, Bv, Cv, Dv = np.array([[-K / Bw]]), np.array([[1.0]]), np.array([[-K / Bw**2]]), 1.0 / Bw
    elif Bw > 0:
        Av, Bv, Cv, Dv = np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), 1.0 / Bw
    else:
        Av = Bv = Cv = None
        Dv = 0.0
    nw, nv, nc = r, (0 if Av is None else Av.shape[0]), loop.a0.shape[0]
    N = nw + nv + nc
    A0, A1 = np.zeros((N, N)), np.zeros((N, N))
    B, C = np.zeros((N, 1)), np.zeros((1, N))
    W, V, L = slice(0, nw), slice(nw, nw + nv), slice(nw + nv, N)
    A0[W, W] = Aw
    B[W] = Bw_
    A0[L, L] = loop.a0
    A1[L, L] = loop.a1
    A0[L, W] = loop.b @ Cw
    B[L] = loop.b * Dw
    C[0, L] = -loop.c[0]
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
        return ("Y_v = s/K is improper (wall_damping = 0) and the weight has order 0" if math.isinf(D) else
                f"w1 (Y_v - Y_t) tends to {D:.6g} at high frequency (not strictly proper): "
                "raise the weight order")
    return ErrorRealization(A0, A1, B, C)


class TransparencyIndex:
    """``J(B_c)`` of eq. (11) for one design, one ``B_c`` or many.

    Parameters
    ----------
    loops : LoopRealizations
        The loop realisations of the design.
    """

    def __init__(self, loops: LoopRealizations):
        self.loops = loops
        self.settings = loops.settings
        self.stability = ClosedLoopStability(loops)
        self._errors: dict[str, ErrorRealization | str] = {}

    def error_realization(self, hold: str) -> ErrorRealization | str:
        """``w1 (Y_v - Y_t)`` for a rational hold, or a reason string when it is not strictly
        proper (cached).

        Parameters
        ----------
        hold : str
            A rational hold model: ``"none"``, ``"pade"`` or ``"lowpass2"``.

        Returns
        -------
        ErrorRealization or str
            The realization, or why ``w1 (Y_v - Y_t)`` is not strictly proper.
        """
        out = self._errors.get(hold)
        if out is None:
            out = self._errors[hold] = _error_realization(self.settings, self.loops.rational(hold))
        return out

    def lyapunov(self, bc: float, hold: str) -> IndexResult:
        """``J`` from the Lyapunov equation of :meth:`error_realization`.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m].
        hold : str
            A rational hold model: ``"none"``, ``"pade"`` or ``"lowpass2"``.

        Returns
        -------
        IndexResult
            ``J`` with ``method = "lyapunov"``; not finite when the error is not strictly proper or
            the loop is unstable.
        """
        parts = self.error_realization(hold)
        if isinstance(parts, str):
            return IndexResult(bc, math.inf, False, parts, "lyapunov")
        A = parts.a0 + bc * parts.a1
        ev = np.linalg.eigvals(A)
        if np.max(ev.real) >= 0:
            return IndexResult(bc, math.inf, False, unstable_reason(ev), "lyapunov")
        X = linalg.solve_continuous_lyapunov(A, -parts.b @ parts.b.T)
        return IndexResult(bc, float((parts.c @ X @ parts.c.T)[0, 0]), True, "", "lyapunov")

    def h2_modal_many(self, bcs: np.ndarray, hold: str) -> np.ndarray:
        """H2 norms for many ``B_c`` at once from poles and residues, ``J = -sum_ij r_i r_j^* /
        (p_i + p_j^*)`` (the Lyapunov solution in modal form); rows with an ill-conditioned
        eigenbasis (cond > 1e6) are solved by Lyapunov instead.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        hold : str
            A rational hold model: ``"none"``, ``"pade"`` or ``"lowpass2"``.

        Returns
        -------
        numpy.ndarray
            ``J`` at each ``B_c``, ``inf`` where the loop is unstable or the error not strictly
            proper, shape (R,).
        """
        parts = self.error_realization(hold)
        if isinstance(parts, str):
            return np.full(bcs.size, math.inf)
        A = parts.a0[None] + bcs[:, None, None] * parts.a1[None]
        lam, V = np.linalg.eig(A)
        good = np.linalg.cond(V) < 1e6
        Vs = np.where(good[:, None, None], V, np.eye(V.shape[1])[None])
        g = np.linalg.solve(Vs, np.broadcast_to(parts.b, (bcs.size,) + parts.b.shape))[:, :, 0]
        r = (parts.c[None] @ Vs)[:, 0, :] * g
        J = -np.einsum("ri,rj,rij->r", r, r.conj(), 1.0 / (lam[:, :, None] + lam.conj()[:, None, :])).real
        J = np.where(np.max(lam.real, axis=1) < 0, J, math.inf)
        for i in np.flatnonzero(~good):
            J[i] = self.lyapunov(float(bcs[i]), hold).index
        return J

    def static_reason(self) -> str:
        """Why ``J`` is infinite for every ``B_c`` (the settings alone), or ``""``.

        Returns
        -------
        str
            The reason; ``""`` when the settings alone do not make ``J`` infinite.
        """
        st = self.settings
        if st.hold == "discrete":
            return ""
        if st.wall_damping > 0 and st.weight_order == 0:
            return "w1 (Y_v - Y_t) tends to 1/B at high frequency (weight of order 0): J is infinite"
        if st.wall_damping == 0 and st.weight_order < 2:
            return "Y_v = s/K grows like s (wall_damping = 0): a weight of order >= 2 is needed"
        return ""

    def quadrature_nodes(self, bcs: np.ndarray, per_decade: float = 8.0, order: int = 16,
                         tail_eps: float = 1e-4) -> Nodes:
        """Nodes/weights of the ``J`` quadrature shared by ``bcs``: ``(w, wt, w_tail, wt_tail)``.

        ``w_tail`` are the tail nodes (``e^{-sT}`` of ``zoh`` dropped there); ``J`` is
        ``(1/pi) (sum wt f(w) + sum wt_tail f(w_tail))``.  ``per_decade`` and ``order`` set the
        density (the benchmark varies them); ``tail_eps`` bounds ``|H P C|`` where the ``zoh``
        tail starts.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m] that share the nodes, shape (R,).
        per_decade : float, optional
            Panels per decade between the singularities.
        order : int, optional
            Gauss-Legendre points per panel.
        tail_eps : float, optional
            Bound of ``|H P C|`` at the start of the ``zoh`` tail.

        Returns
        -------
        w : numpy.ndarray
            Nodes of the main part [rad/s], shape (P,).
        wt : numpy.ndarray
            Their weights [rad/s], shape (P,).
        w_tail : numpy.ndarray
            Nodes of the tail [rad/s], shape (Q,) (empty for ``discrete``).
        wt_tail : numpy.ndarray
            Their weights [rad/s], shape (Q,).
        """
        st = self.settings
        T = st.sample_time
        c = self.loops.singularities(bcs)
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
                     math.sqrt(2.0 * (bcmax + st.kc * T) / (self.loops.plant.handle_mass * T * tail_eps)))
            om = min(om, 4096 * 2 * math.pi / T)
            brk = panel_breakpoints(lo, om, c, per_decade, max_width=math.pi / T)
        else:
            om = 20.0 * cmax
            brk = panel_breakpoints(lo, om, c, per_decade)
        w, wt = gauss_nodes(np.concatenate([[0.0], brk]), order)
        u, ut = gauss_nodes(np.array([0.0, 0.25, 0.5, 1.0]), order)
        return w, wt, om / u, ut * om / (u * u)

    def integrand(self, bcs: np.ndarray, w: np.ndarray, oscillating: bool = True) -> np.ndarray:
        """``|w1 (Y_v - Y_t)|^2`` for each ``B_c`` (rows) at ``w``.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        w : numpy.ndarray
            Angular frequencies [rad/s], shape (P,).
        oscillating : bool, optional
            False drops the ``e^{-sT}`` term of the ``zoh`` hold (tail nodes).

        Returns
        -------
        numpy.ndarray
            The integrand [(m/s/N)^2], shape (R, P).
        """
        s = 1j * w
        yt = self.loops.admittance_rows(bcs, w, oscillating)
        e = weight(self.settings, s)[None, :] * (wall_admittance(self.settings, s)[None, :] - yt)
        return e.real**2 + e.imag**2

    def _quadrature(self, bcs: np.ndarray, nodes: Nodes) -> np.ndarray:
        """``J`` for the rows ``bcs`` by the quadrature ``nodes`` (stable loops only)."""
        w, wt, wtl, wtt = nodes
        tot = self.integrand(bcs, w) @ wt
        if wtl.size:
            tot += self.integrand(bcs, wtl, oscillating=False) @ wtt
        return tot / math.pi

    def index_result(self, bc: float, method: str = "auto", per_decade: float = 8.0, order: int = 16) -> IndexResult:
        """``J(B_c)`` (eq. 11) with its status; ``method`` ``auto``/``lyapunov``/``quadrature``.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        method : str, optional
            ``"auto"`` (Lyapunov for a rational hold, else quadrature), ``"lyapunov"`` or
            ``"quadrature"``.
        per_decade : float, optional
            Quadrature panels per decade (see :meth:`quadrature_nodes`).
        order : int, optional
            Gauss-Legendre points per panel.

        Returns
        -------
        IndexResult
            ``J``, whether it is finite and why not, the method and the number of nodes.

        Raises
        ------
        ValidationError
            When ``bc`` is not finite, ``method`` is unknown, or ``"lyapunov"`` is asked for a
            non-rational hold.
        """
        bc = float(check_bc(bc)[0])
        st = self.settings
        if method == "auto":
            method = "lyapunov" if st.hold in RATIONAL_HOLDS else "quadrature"
        if method == "lyapunov":
            if st.hold not in RATIONAL_HOLDS:
                raise ValidationError("method", "'quadrature' for a non-rational hold", method)
            return self.lyapunov(bc, st.hold)
        if method != "quadrature":
            raise ValidationError("method", "'auto', 'lyapunov' or 'quadrature'", method)
        reason = self.static_reason()
        bcs = np.array([bc])
        nodes = self.quadrature_nodes(bcs, per_decade, order)
        if not reason:
            reason = self.stability.stable_many(bcs, nodes)[1][0]
        if reason:
            return IndexResult(bc, math.inf, False, reason, "quadrature")
        w, wt, wtl, wtt = nodes
        total = self.integrand(bcs, w)[0] @ wt
        if wtl.size:
            total += self.integrand(bcs, wtl, oscillating=False)[0] @ wtt
        return IndexResult(bc, float(total / math.pi), True, "", "quadrature", w.size + wtl.size)

    def performance_index(self, bc: float) -> float:
        """``J(B_c)`` of eq. (11); ``inf`` when not finite (see :meth:`index_result` for why).

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.

        Returns
        -------
        float
            ``J`` [(m/s/N)^2 rad/s], or ``inf``.
        """
        return self.index_result(bc).index

    def index_many(self, bcs: np.ndarray) -> np.ndarray:
        """``J`` for every ``B_c`` of ``bcs`` (``inf`` where not finite), batched.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).

        Returns
        -------
        numpy.ndarray
            ``J`` at each ``B_c`` [(m/s/N)^2 rad/s], ``inf`` where not finite, shape (R,).
        """
        st = self.settings
        if st.hold in RATIONAL_HOLDS:
            return self.h2_modal_many(bcs, st.hold)
        out = np.full(bcs.size, math.inf)
        if self.static_reason():
            return out
        nodes = self.quadrature_nodes(bcs)
        ok = self.stability.stable_many(bcs, nodes)[0]
        if not ok.any():
            return out
        out[ok] = self._quadrature(bcs[ok], nodes)
        return out
