"""The step response of the wall controller (Eom, Suh & Yi, Figs. 7 and 10).

Always the exact sampled loop, whatever the hold model of the frequency-domain analysis: the
plant is discretized by the ZOH (:func:`analysis.chain.discretize.discretize_zoh`) over a
sub-step ``T / substeps``, the controller ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` (eq. 12,
backward-difference velocity) is held over each sample, and between samples the continuous
state is exact as well.
"""

from __future__ import annotations

import math

import numpy as np

from analysis.chain.discretize import discretize_zoh
from analysis.checks import integer, real
from analysis.transparency.loops import check_bc
from analysis.transparency.plant import WallPlant
from analysis.transparency.settings import StepResponse, WallSettings

__all__ = ["StepSimulation", "wall_step"]


def wall_step(settings: WallSettings, force: float, t: np.ndarray) -> np.ndarray:
    """Position of the virtual wall ``V(s) = (K + B s)/s`` (eq. 8) under the force step."""
    K, Bw = settings.wall_stiffness, settings.wall_damping
    if K > 0 and Bw > 0:
        return force / K * (-np.expm1(-K * t / Bw))
    if K > 0:
        return np.full_like(t, force / K)
    return force / Bw * t


def _intersample_maps(A: np.ndarray, B: np.ndarray, tau: float, substeps: int) -> tuple[list, list]:
    """``Phi_j, Gam_j`` over ``j`` sub-steps, ``j = 0 .. substeps``."""
    n = A.shape[0]
    Phi1, Gam1 = discretize_zoh(A, B, tau)
    Phis = [np.eye(n)]
    Gams = [np.zeros((n, 1))]
    for _ in range(substeps):
        Phis.append(Phi1 @ Phis[-1])
        Gams.append(Phi1 @ Gams[-1] + Gam1)
    return Phis, Gams


class StepSimulation:
    """Human-force steps on the exact sampled loop of one design.

    Parameters
    ----------
    settings : WallSettings
        The design (sample time, ``K_c``, default step force and duration).
    plant : WallPlant
        Its plant ``P(s)``.
    """

    def __init__(self, settings: WallSettings, plant: WallPlant):
        self.settings = settings
        self.plant = plant

    def step_response(self, bc: float, force: float | None = None, duration: float | None = None,
                      substeps: int = 8) -> StepResponse:
        """Human-force step on the exact sampled loop (ZOH discretization via the matrix exponential).

        The device starts at rest at the wall surface ``x = 0``; the controller
        ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` is held over each sample.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        force : float or None, optional
            The human-force step [N], finite; ``None`` for the settings' ``step_force``.
        duration : float or None, optional
            Duration [s], in (0, 100]; ``None`` for the settings' ``step_duration``.
        substeps : int, optional
            Points per sample between the samples, 1 .. 1000.

        Returns
        -------
        StepResponse
            ``ceil(duration/T) * substeps + 1`` points from ``t = 0``.

        Raises
        ------
        ValidationError
            When an argument is out of its range.
        """
        st = self.settings
        bc = float(check_bc(bc)[0])
        F = st.step_force if force is None else real("force", force, allowed="finite (N)")
        dur = st.step_duration if duration is None else real("duration", duration, lo=0.0, lo_open=True,
                                                              hi=100.0, allowed="in (0, 100] s")
        substeps = integer("substeps", substeps, 1, 1000)
        T, kc = st.sample_time, st.kc
        aug = self.plant.augmented()
        n = aug.A.shape[0]
        nk = int(math.ceil(dur / T - 1e-9))
        tau = T / substeps
        Phis, Gams = _intersample_maps(aug.A, aug.B, tau, substeps)
        PhiT, GamT = Phis[-1], Gams[-1]
        x = np.zeros(n)
        prev = 0.0
        xs = np.empty((nk, n))
        us = np.empty(nk)
        cx = aug.Cx[0]
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
        return StepResponse(t, force_hist, traj @ cx, traj @ aug.Cv[0], np.full_like(t, F), wall_step(st, F, t), bc)
