"""The exact sampled loop of the wall controller (``discrete`` hold and every step response).

ZOH discretization of the plant (:func:`analysis.chain.discretize.discretize_zoh`), the closed
sampled loop with the backward-difference controller ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T``
(Eom, Suh & Yi, eq. 12, sampled; see :mod:`analysis.transparency.design`), and ``Y_t(z)``
(eq. 9) and ``L(z)`` (eq. 16) in modal form for many ``B_c`` at once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.chain.discretize import discretize_zoh
from analysis.transparency.plant import AugmentedPlant, WallPlant
from analysis.transparency.settings import WallSettings

__all__ = ["SampledPlant", "DiscreteLoopMatrices", "DiscreteModal", "DiscreteLoop", "transfer_at"]


def transfer_at(A: np.ndarray, B: np.ndarray, C: np.ndarray, D: float, z: np.ndarray) -> np.ndarray:
    """``C (zI - A)^{-1} B + D`` at points ``z`` by batched solves (small systems)."""
    n = A.shape[0]
    M = z[:, None, None] * np.eye(n)[None] - A[None]
    x = np.linalg.solve(M, np.broadcast_to(B, (z.size, n, 1)))
    return (C[None] @ x)[:, 0, 0] + D


@dataclass(frozen=True)
class SampledPlant:
    """The augmented plant (:class:`AugmentedPlant`) and its ZOH discretization over one sample.

    Parameters
    ----------
    plant : AugmentedPlant
        The plant plus the handle position, ``n`` states.
    phi : numpy.ndarray
        ``e^{A T}``, shape (n, n).
    gamma : numpy.ndarray
        ``int_0^T e^{A t} dt B``, shape (n, 1).
    """

    plant: AugmentedPlant
    phi: np.ndarray
    gamma: np.ndarray


@dataclass(frozen=True)
class DiscreteLoopMatrices:
    """Closed sampled loop ``x+ = (ad0 + B_c ad1) x + bd F``; velocity ``cd x``; the ZOH-sampled
    ``W P`` of eq. (16), ``(cl0 + B_c cl1) x + dw F``.  State: plant, handle position, previous
    position.

    Parameters
    ----------
    ad0 : numpy.ndarray
        The part of the transition matrix independent of ``B_c``, shape (N, N).
    ad1 : numpy.ndarray
        The part of the transition matrix per unit ``B_c``, shape (N, N).
    bd : numpy.ndarray
        Input column of the held human force [N], shape (N, 1).
    cd : numpy.ndarray
        Output row of the handle velocity [m/s], shape (1, N).
    cl0 : numpy.ndarray
        The part of the ``W P`` output row independent of ``B_c``, shape (1, N).
    cl1 : numpy.ndarray
        The part of the ``W P`` output row per unit ``B_c``, shape (1, N).
    dw : float
        Feedthrough of the ``W P`` output.
    """

    ad0: np.ndarray
    ad1: np.ndarray
    bd: np.ndarray
    cd: np.ndarray
    cl0: np.ndarray
    cl1: np.ndarray
    dw: float


@dataclass(frozen=True)
class DiscreteModal:
    """Poles ``lam`` and residues of ``Y_t(z)`` (``r_y``) and ``L(z)`` (``r_l``) for rows of ``B_c``.

    Rows whose eigenvector matrix is ill-conditioned (``good`` False) keep their matrices
    (``ad``, ``bd``, ``cd``, ``cl``) and are evaluated by direct solves instead.

    Parameters
    ----------
    lam : numpy.ndarray
        Closed-loop poles ``z``, complex, shape (R, N).
    r_y : numpy.ndarray
        Residues of ``Y_t(z)``, complex, shape (R, N).
    r_l : numpy.ndarray
        Residues of ``L(z)``, complex, shape (R, N).
    dw : float
        Feedthrough of ``L(z)``.
    good : numpy.ndarray
        Whether each row's eigenvector matrix is well conditioned, bool, shape (R,).
    ad : numpy.ndarray
        Transition matrix of each row, shape (R, N, N).
    bd : numpy.ndarray
        Input column of the held human force, shape (N, 1).
    cd : numpy.ndarray
        Output row of the handle velocity, shape (1, N).
    cl : numpy.ndarray
        Output row of ``W P`` of each row, shape (R, 1, N).
    """

    lam: np.ndarray
    r_y: np.ndarray
    r_l: np.ndarray
    dw: float
    good: np.ndarray
    ad: np.ndarray
    bd: np.ndarray
    cd: np.ndarray
    cl: np.ndarray

    def admittance(self, rows: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``Y_t(z)`` (eq. 9, sampled) for ``rows`` (R) at ``z`` (P or R x P).

        Parameters
        ----------
        rows : numpy.ndarray
            Indices of the ``B_c`` rows, int, shape (R,).
        z : numpy.ndarray
            Points of the z-plane (usually ``e^{j w T}``), complex, shape (P,) shared by the rows
            or (R, P).

        Returns
        -------
        numpy.ndarray
            ``Y_t(z)`` [m/(N s)], complex, shape (R, P).
        """
        return self._evaluate(rows, z, robustness=False)

    def robustness(self, rows: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``L(z)`` (eq. 16, sampled) for ``rows`` (R) at ``z`` (P or R x P).

        Parameters
        ----------
        rows : numpy.ndarray
            Indices of the ``B_c`` rows, int, shape (R,).
        z : numpy.ndarray
            Points of the z-plane (usually ``e^{j w T}``), complex, shape (P,) shared by the rows
            or (R, P).

        Returns
        -------
        numpy.ndarray
            ``L(z)`` (dimensionless), complex, shape (R, P).
        """
        return self._evaluate(rows, z, robustness=True)

    def _evaluate(self, rows: np.ndarray, z: np.ndarray, robustness: bool) -> np.ndarray:
        """``sum_k r_k/(z - lam_k) (+ dw)``."""
        lam = self.lam[rows]
        r = (self.r_l if robustness else self.r_y)[rows]
        zz = z if z.ndim == 2 else np.broadcast_to(z, (rows.size, z.size))
        out = np.einsum("rk,rpk->rp", r, 1.0 / (zz[:, :, None] - lam[:, None, :]))
        if robustness:
            out = out + self.dw
        for q in np.flatnonzero(~self.good[rows]):
            j = rows[q]
            C = self.cl[j] if robustness else self.cd
            out[q] = transfer_at(self.ad[j], self.bd, C, self.dw if robustness else 0.0, zz[q])
        return out


class DiscreteLoop:
    """The sampled loop of a design (its ZOH plant is computed once).

    Parameters
    ----------
    settings : WallSettings
        The design (sample time ``T``, ``K_c``).
    plant : WallPlant
        Its plant ``P(s)``.
    """

    def __init__(self, settings: WallSettings, plant: WallPlant):
        self.settings = settings
        self.plant = plant
        self._sampled: SampledPlant | None = None

    def sampled_plant(self) -> SampledPlant:
        """The augmented plant and its ZOH discretization over ``T`` (cached).

        Returns
        -------
        SampledPlant
            The augmented plant with ``phi`` and ``gamma``.
        """
        if self._sampled is None:
            aug = self.plant.augmented()
            phi, gam = discretize_zoh(aug.A, aug.B, self.settings.sample_time)
            self._sampled = SampledPlant(aug, phi, gam)
        return self._sampled

    def matrices(self, alpha: float = 0.0, beta: float = 0.0) -> DiscreteLoopMatrices:
        """The closed sampled loop; ``alpha``, ``beta`` weight the ``W P`` output (eq. 15-16).

        Parameters
        ----------
        alpha : float, optional
            Mass uncertainty of the weight ``W = alpha m s + beta b``.
        beta : float, optional
            Damping uncertainty of the weight ``W``.

        Returns
        -------
        DiscreteLoopMatrices
            The loop, affine in ``B_c``.
        """
        sp = self.sampled_plant()
        A, B, Cv, Cx = sp.plant.A, sp.plant.B, sp.plant.Cv, sp.plant.Cx
        Phi, Gam = sp.phi, sp.gamma
        T, kc = self.settings.sample_time, self.settings.kc
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
        return DiscreteLoopMatrices(Ad0, Ad1, Bd, Cd, CL0, CL1, Dw)

    def modal(self, bcs: np.ndarray, alpha: float = 0.0, beta: float = 0.0) -> DiscreteModal:
        """Poles and residues of ``Y_t(z)`` and ``L(z)`` for every ``B_c`` (batched eigen-solves).

        Rows whose eigenvector matrix is ill-conditioned (cond > 1e8) are evaluated by direct
        solves instead (see :class:`DiscreteModal`).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        alpha : float, optional
            Mass uncertainty of the weight ``W`` of ``L(z)``.
        beta : float, optional
            Damping uncertainty of the weight ``W`` of ``L(z)``.

        Returns
        -------
        DiscreteModal
            Poles and residues, one row per ``B_c``.
        """
        m = self.matrices(alpha, beta)
        Ad = m.ad0[None] + bcs[:, None, None] * m.ad1[None]
        lam, V = np.linalg.eig(Ad)
        good = np.linalg.cond(V) < 1e8
        g = np.linalg.solve(np.where(good[:, None, None], V, np.eye(V.shape[1])[None]),
                            np.broadcast_to(m.bd, (bcs.size,) + m.bd.shape))[:, :, 0]
        CL = m.cl0[None] + bcs[:, None, None] * m.cl1[None]
        rY = (m.cd[None] @ V)[:, 0, :] * g
        rL = (CL @ V)[:, 0, :] * g
        return DiscreteModal(lam, rY, rL, m.dw, good, Ad, m.bd, m.cd, CL)

    def poles(self, bcs: np.ndarray) -> np.ndarray:
        """Closed-loop poles ``log(z)/T`` (rows = ``bcs``).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).

        Returns
        -------
        numpy.ndarray
            Equivalent continuous poles [rad/s], complex, shape (R, N); ``-inf`` real part for a
            pole at ``z = 0``.
        """
        m = self.matrices()
        lam = np.linalg.eigvals(m.ad0[None] + bcs[:, None, None] * m.ad1[None]).astype(complex)
        with np.errstate(divide="ignore"):
            return np.log(lam) / self.settings.sample_time
