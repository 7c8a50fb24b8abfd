"""The device of the wall-controller design: ``P(s)`` and its state-space realization.

A rigid handle ``P(s) = 1/(m s + b)`` (Eom, Suh & Yi, eq. 7) or a lumped chain read at the
handle (collocated): then ``1/P`` is the chain's one continued fraction
(:func:`analysis.chain.continued_fraction.handle_impedance`) and the realization its minimal
handle state space (:func:`analysis.chain.state_space.handle_state_space`).  See
:mod:`analysis.transparency.design` for the reading of the paper.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.chain.continued_fraction import handle_impedance
from analysis.chain.device import Device
from analysis.chain.state_space import handle_state_space
from analysis.transparency.settings import WallSettings

__all__ = ["WallPlant", "AugmentedPlant"]


@dataclass(frozen=True)
class AugmentedPlant:
    """The plant plus the handle position ``xi = int v``: ``x' = A x + B F``, ``v = Cv x``,
    ``xi = Cx x`` (the state of the sampled loop and of the step response).

    Parameters
    ----------
    A : numpy.ndarray
        State matrix, the plant's plus the position row, shape (n + 1, n + 1).
    B : numpy.ndarray
        Input matrix (force at the handle [N]), shape (n + 1, 1).
    Cv : numpy.ndarray
        Output row of the handle velocity [m/s], shape (1, n + 1).
    Cx : numpy.ndarray
        Output row of the handle position [m] (the last state), shape (1, n + 1).
    """

    A: np.ndarray
    B: np.ndarray
    Cv: np.ndarray
    Cx: np.ndarray


class WallPlant:
    """``P(s)`` and a minimal realization ``(A, B, Cv)`` (force at the handle -> handle velocity).

    ``m_w``, ``b_w`` are the rigid-body parameters of the robustness weight ``W`` (eq. 15):
    ``m``, ``b`` of a rigid handle, ``sum m_i``, ``sum g_i`` of a chain.

    Parameters
    ----------
    settings : WallSettings
        The design; its ``mass`` and ``damping`` make the rigid plant when ``device`` is None.
    device : Device or None
        The device chain read at the handle, or ``None`` for the rigid plant of eq. (7).
    """

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
            self.A, self.B, self.Cv = handle_state_space(device)
            self.m_w, self.b_w = device.total_mass, device.total_ground_damping
            self.handle_mass = float(device.masses[0])

    @property
    def order(self) -> int:
        return self.A.shape[0]

    def impedance(self, s: np.ndarray) -> np.ndarray:
        """``1/P(s)``: ``m s + b``, or the chain's handle impedance (continued fraction).

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.

        Returns
        -------
        numpy.ndarray
            The handle impedance [N s/m], complex, the shape of ``s``.
        """
        s = np.asarray(s, dtype=complex)
        if self.device is None:
            return self.m_w * s + self.b_w
        return handle_impedance(self.device, s)

    def poles(self) -> np.ndarray:
        """The open-loop poles of ``P(s)``, the eigenvalues of ``A``.

        Returns
        -------
        numpy.ndarray
            Poles [rad/s], complex, shape (n,) (empty for a zero-order plant).
        """
        return np.linalg.eigvals(self.A) if self.order else np.zeros(0, complex)

    def augmented(self) -> AugmentedPlant:
        """The plant plus the handle position (last state).

        Returns
        -------
        AugmentedPlant
            The realization with ``n + 1`` states.
        """
        n = self.order
        A = np.zeros((n + 1, n + 1))
        A[:n, :n] = self.A
        A[n, :n] = self.Cv[0]
        B = np.vstack([self.B, [[0.0]]])
        Cv = np.hstack([self.Cv, [[0.0]]])
        Cx = np.zeros((1, n + 1))
        Cx[0, n] = 1.0
        return AugmentedPlant(A, B, Cv, Cx)
