"""The exact sampled loop of the wall controller (``discrete`` hold and every step response).

ZOH discretization of the plant by the matrix exponential, the closed sampled loop with the
backward-difference controller ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` (see
:mod:`analysis.transparency`), and ``Y_t(z)``, ``L(z)`` in modal form for many ``B_c`` at once.
"""

from __future__ import annotations

import numpy as np
from scipy import linalg

from analysis.transparency.settings import WallSettings
from analysis.transparency.plant import _Plant, _ss_freq

__all__ = ["SampledLoopMixin"]


class SampledLoopMixin:
    """Sampled-loop part of :class:`analysis.transparency.WallDesign`.

    The host provides ``settings``, ``plant``, ``kc`` and the ``_cache`` dict.
    """

    settings: WallSettings
    plant: _Plant
    kc: float
    _cache: dict

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
