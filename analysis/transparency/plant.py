"""The device of the wall-controller design: ``P(s)`` and its state-space realization.

A rigid handle ``P(s) = 1/(m s + b)`` or a lumped chain read at the handle (collocated); see
:mod:`analysis.transparency` for the reading of Eom, Suh & Yi.  Used by
:class:`analysis.transparency.WallDesign` and :mod:`analysis.observer`.
"""

from __future__ import annotations

import numpy as np

from analysis.chain.device import Device
from analysis.transparency.settings import WallSettings

__all__ = ["handle_admittance"]


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
