"""Cartesian inertia and damping of a planar five-bar parallel linkage (Eom, Suh & Yi, eq. 2).

Geometry: motors at ``A1 = (-d/2, 0)`` and ``A2 = (d/2, 0)`` drive proximal links (length
``l1``, angles ``q1``, ``q2`` from the x axis) to elbows ``B_i = A_i + l1 (cos q_i, sin q_i)``;
distal links (length ``l2``) join ``B1``, ``B2`` to the handle ``P = (x, y)``.  Elbows point
outwards (``B1`` left of ``A1``-``P``, ``B2`` right of ``A2``-``P``).

Derivation (the ``M_x = J^{-T} M J^{-1}`` of eq. 2, written directly in Cartesian velocity):

* Jacobian: ``|P - B_i|^2 = l2^2`` gives ``u_i . (P' - B_i') = 0`` with ``u_i = P - B_i`` and
  ``B_i' = l1 q_i' e_i``, ``e_i = (-sin q_i, cos q_i)``.  Hence ``U P' = D q'`` with rows
  ``U = [u_1; u_2]`` and ``D = diag(l1 u_i . e_i)``: ``J = U^{-1} D`` (``P' = J q'``).
* Kinetic energy: a uniform rod of mass ``m`` whose ends move with ``v_a``, ``v_b`` has
  ``T = m/6 (|v_a|^2 + v_a . v_b + |v_b|^2)`` (integrate ``|(1-s) v_a + s v_b|^2`` over the rod).
  Proximal link ``i`` (pivot fixed) plus motor rotor: ``T = 1/2 (m_p l1^2/3 + I_r) q_i'^2``.
  Distal link ``i``: ends ``B_i' = G_i P'`` with ``G_i = l1 e_i (row i of J^{-1})`` and ``P'``.
  A point mass ``m_h`` (handle) at ``P``.
* Summing, ``T = 1/2 P'^T M_x P'`` with
  ``M_x = J^{-T} diag(m_p l1^2/3 + I_r) J^{-1} + sum_i m_d,i/3 (G_i^T G_i + (G_i + G_i^T)/2 + I)
  + m_h I``, and joint viscous friction ``b_j`` gives ``B_x = J^{-T} diag(b_j) J^{-1}``.

At a point of the symmetry axis with mirror-symmetric masses the kinetic energy is invariant under
``x -> -x``, so ``M_x`` and ``B_x`` are diagonal there: **the centre of a symmetric five-bar with
equal link masses has no cross-axis coupling** (checked in the tests).  The centre preset
therefore states unequal distal-link masses (the handle bracket sits on the right distal link);
the offset preset keeps equal masses and moves the handle off the axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.checks import Real, check_elements, nonnegative, positive
from analysis.errors import ValidationError

__all__ = ["FiveBar", "FIVE_BAR_PRESETS", "five_bar_preset"]


_MASS = Real(lo=0.0, unit="kg")  # ">= 0 and finite (kg)", per link


@dataclass(frozen=True)
class FiveBar:
    """A five-bar linkage with its mass properties (SI units).

    ``proximal_masses``/``distal_masses`` are (left, right); ``rotor_inertia`` is each motor's
    inertia (kg m^2); ``joint_damping`` each motor's viscous friction (N m s/rad).

    Parameters
    ----------
    l1 : float, optional
        Length of the proximal links [m], > 0.
    l2 : float, optional
        Length of the distal links [m], > 0.
    base : float, optional
        Distance ``d`` between the two motors [m], >= 0.
    proximal_masses : tuple of (float, float), optional
        Masses of the proximal links (left, right) [kg], >= 0.
    distal_masses : tuple of (float, float), optional
        Masses of the distal links (left, right) [kg], >= 0.
    handle_mass : float, optional
        Point mass at the handle [kg], >= 0.
    rotor_inertia : float, optional
        Each motor's rotor inertia [kg m^2], >= 0.
    joint_damping : float, optional
        Each motor's viscous friction [N m s/rad], >= 0.

    Raises
    ------
    ValidationError
        When a length, mass, inertia or damping is out of its range, or a mass pair does not
        have two values.
    """

    l1: float = 0.2
    l2: float = 0.2
    base: float = 0.1
    proximal_masses: tuple[float, float] = (0.02, 0.02)
    distal_masses: tuple[float, float] = (0.015, 0.015)
    handle_mass: float = 0.0
    rotor_inertia: float = 0.0
    joint_damping: float = 1e-3

    def __post_init__(self) -> None:
        for name in ("l1", "l2"):
            positive(name, getattr(self, name), "m")
        for name in ("base", "handle_mass", "rotor_inertia", "joint_damping"):
            nonnegative(name, getattr(self, name))
        for name in ("proximal_masses", "distal_masses"):
            v = getattr(self, name)
            if len(v) != 2:
                raise ValidationError(name, "two values (left, right)", v)
            check_elements(name, v, _MASS)

    def centre(self) -> np.ndarray:
        """Centre of the workspace: the midpoint of the reachable part of the symmetry axis,
        ``(0, sqrt((l1 + l2)^2 - (d/2)^2) / 2)``.

        Returns
        -------
        numpy.ndarray
            The handle position ``(x, y)`` [m], shape (2,).
        """
        return np.array([0.0, 0.5 * math.sqrt((self.l1 + self.l2) ** 2 - (0.5 * self.base) ** 2)])

    def bases(self) -> np.ndarray:
        """The motor positions ``A1 = (-d/2, 0)`` and ``A2 = (d/2, 0)``.

        Returns
        -------
        numpy.ndarray
            One row ``(x, y)`` per motor [m], shape (2, 2).
        """
        return np.array([[-0.5 * self.base, 0.0], [0.5 * self.base, 0.0]])

    def inverse_kinematics(self, p) -> np.ndarray:
        """Motor angles ``(q1, q2)`` placing the handle at ``p`` (elbows outwards).

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y)`` [m], shape (2,).

        Returns
        -------
        numpy.ndarray
            The angles ``(q1, q2)`` from the x axis [rad], shape (2,).

        Raises
        ------
        ValidationError
            When ``p`` is outside the reachable workspace.
        """
        p = np.asarray(p, dtype=float)
        q = np.empty(2)
        for i, (a, sign) in enumerate(zip(self.bases(), (1.0, -1.0))):
            r = p - a
            dist = math.hypot(*r)
            c = (self.l1**2 + dist**2 - self.l2**2) / (2 * self.l1 * dist)
            if not -1.0 <= c <= 1.0:
                raise ValidationError("position", "inside the reachable workspace", p.tolist())
            q[i] = math.atan2(r[1], r[0]) + sign * math.acos(c)
        return q

    def elbows(self, q) -> np.ndarray:
        """The elbows ``B_i = A_i + l1 (cos q_i, sin q_i)``.

        Parameters
        ----------
        q : array_like
            Motor angles ``(q1, q2)`` [rad], shape (2,).

        Returns
        -------
        numpy.ndarray
            One row ``(x, y)`` per elbow [m], shape (2, 2).
        """
        return self.bases() + self.l1 * np.stack([np.cos(q), np.sin(q)], axis=1)

    def jacobian(self, p) -> np.ndarray:
        """``J`` with ``P' = J q'`` at handle position ``p``.

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y)`` [m], reachable, shape (2,).

        Returns
        -------
        numpy.ndarray
            The Jacobian [m/rad], shape (2, 2).
        """
        p = np.asarray(p, dtype=float)
        q = self.inverse_kinematics(p)
        u = p[None, :] - self.elbows(q)
        e = np.stack([-np.sin(q), np.cos(q)], axis=1)
        D = np.diag(self.l1 * np.sum(u * e, axis=1))
        return np.linalg.solve(u, D)

    def cartesian_matrices(self, p=None) -> tuple[np.ndarray, np.ndarray]:
        """``(M_x, B_x)`` at handle position ``p`` (default: the workspace centre).

        Parameters
        ----------
        p : array_like or None, optional
            Handle position ``(x, y)`` [m], reachable, shape (2,); ``None`` for :meth:`centre`.

        Returns
        -------
        M_x : numpy.ndarray
            Cartesian inertia [kg], symmetric, shape (2, 2).
        B_x : numpy.ndarray
            Cartesian damping [N s/m], symmetric, shape (2, 2).
        """
        p = self.centre() if p is None else np.asarray(p, dtype=float)
        J = self.jacobian(p)
        Jinv = np.linalg.inv(J)
        q = self.inverse_kinematics(p)
        e = np.stack([-np.sin(q), np.cos(q)], axis=1)
        Iq = np.array([m * self.l1**2 / 3.0 + self.rotor_inertia for m in self.proximal_masses])
        M = Jinv.T @ np.diag(Iq) @ Jinv + self.handle_mass * np.eye(2)
        for i, md in enumerate(self.distal_masses):
            G = self.l1 * np.outer(e[i], Jinv[i])  # B_i' = G P'
            M = M + md / 3.0 * (G.T @ G + 0.5 * (G + G.T) + np.eye(2))
        B = Jinv.T @ (self.joint_damping * np.eye(2)) @ Jinv
        return 0.5 * (M + M.T), 0.5 * (B + B.T)

    def kinetic_energy(self, p, pdot) -> float:
        """Kinetic energy for handle velocity ``pdot`` straight from the link velocities (used to
        check :meth:`cartesian_matrices` independently).

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y)`` [m], reachable, shape (2,).
        pdot : array_like
            Handle velocity [m/s], shape (2,).

        Returns
        -------
        float
            The kinetic energy [J] (distal links as 200 point masses each).
        """
        p = np.asarray(p, dtype=float)
        qd = np.linalg.solve(self.jacobian(p), np.asarray(pdot, dtype=float))
        q = self.inverse_kinematics(p)
        T = 0.0
        for i in range(2):
            T += 0.5 * (self.proximal_masses[i] * self.l1**2 / 3.0 + self.rotor_inertia) * qd[i] ** 2
            vb = self.l1 * qd[i] * np.array([-math.sin(q[i]), math.cos(q[i])])
            # rod as 200 point masses along B_i -> P (independent of the closed form above)
            s = (np.arange(200) + 0.5) / 200
            v = (1 - s)[:, None] * vb[None, :] + s[:, None] * np.asarray(pdot)[None, :]
            T += 0.5 * self.distal_masses[i] / 200 * float(np.sum(v * v))
        return T + 0.5 * self.handle_mass * float(np.dot(pdot, pdot))


#: Presets: the Eom et al. device has 0.2 m links; the base separation and masses are ours.
FIVE_BAR_PRESETS: dict[str, tuple[FiveBar, str]] = {
    "five_bar_centre": (
        FiveBar(l1=0.2, l2=0.2, base=0.1, proximal_masses=(0.02, 0.02), distal_masses=(0.012, 0.024),
                handle_mass=0.0, rotor_inertia=0.0, joint_damping=1e-3),
        "centre",
    ),
    "five_bar_offset": (
        FiveBar(l1=0.2, l2=0.2, base=0.1, proximal_masses=(0.02, 0.02), distal_masses=(0.015, 0.015),
                handle_mass=0.0, rotor_inertia=0.0, joint_damping=1e-3),
        "offset",
    ),
}


def five_bar_preset(name: str) -> tuple[np.ndarray, np.ndarray, FiveBar, np.ndarray]:
    """``(M_x, B_x, linkage, position)`` of a preset.

    ``five_bar_centre``: 0.2 m links, base 0.1 m, proximal links 0.02 kg each, distal links
    0.012 kg (left) and 0.024 kg (right, carrying the handle bracket), joint friction
    1e-3 N m s/rad, at the workspace centre.  ``five_bar_offset``: equal distal links (0.015 kg),
    handle 0.06 m right of the centre.

    Parameters
    ----------
    name : str
        A key of :data:`FIVE_BAR_PRESETS`.

    Returns
    -------
    M_x : numpy.ndarray
        Cartesian inertia at the position [kg], shape (2, 2).
    B_x : numpy.ndarray
        Cartesian damping at the position [N s/m], shape (2, 2).
    linkage : FiveBar
        The linkage.
    position : numpy.ndarray
        The handle position ``(x, y)`` [m], shape (2,).

    Raises
    ------
    ValidationError
        When ``name`` is not a preset.
    """
    if name not in FIVE_BAR_PRESETS:
        raise ValidationError("preset", "one of " + ", ".join(FIVE_BAR_PRESETS), name)
    fb, where = FIVE_BAR_PRESETS[name]
    p = fb.centre() if where == "centre" else fb.centre() + np.array([0.06, 0.0])
    M, B = fb.cartesian_matrices(p)
    return M, B, fb, p
