"""A linkage with a cable drive per joint, linearized at a configuration (issue 25).

Each of the ``n`` joints is driven by a motor through a cable (capstan) transmission:

* the motor shaft angle ``phi_i`` (motor side), rotor inertia ``J_m,i`` [kg m^2] and viscous
  friction ``b_m,i`` [N m s/rad] on the motor side;
* the transmission ratio ``r_i = phi_i / theta_i`` of the rigid drive (motor turns per joint
  turn);
* the cable's stiffness ``k_i`` [N m/rad] and damping ``c_i`` [N m s/rad] referred to the joint,
  acting on the twist ``phi_i / r_i - theta_i``;
* the link side: the joint angles ``theta`` with the linkage's joint-space inertia ``M(theta_0)``
  at the configuration and viscous joint friction ``b_j,i`` [N m s/rad].

Linearized at ``theta_0`` (the velocity-product terms of the linkage vanish at rest and gravity
is not modelled), with ``q = (phi, theta)`` (``2n`` coordinates) this is the structural model
:class:`~analysis.multidof.model.StructuralModel`::

    M = [[diag(J_m), 0], [0, M(theta_0)]]
    K = [[diag(k / r^2), -diag(k / r)], [-diag(k / r), diag(k)]]
    C = the same pattern in the cable damping c, plus diag(b_m) and diag(b_j) on the diagonal
    B_a = [[diag(1 / r) J^T], [0]]        (the Cartesian command u as motor torques J^T u / r)
    C_s = [J diag(1 / r), 0]               (encoders on the motors, mapped to the handle)
    J_h = [0, J]                           (the handle moves with the links)

with ``J`` the linkage's Jacobian at ``theta_0`` (square: ``m = n`` Cartesian axes).  This is the
flexible-transmission model of Spong's elastic joint (a spring between each rotor and its link),
with the encoder on the rotor as on the PHANToM (Çavuşoğlu, Feygin & Tendick, 2002).

When the cable is rigid (``k -> inf``) the motor and the link move together (``phi = r theta``)
and the model becomes the rigid linkage of :func:`rigid_drive_device`: the handle's Cartesian
inertia ``M_x = J^{-T} (M(theta_0) + diag(r^2 J_m)) J^{-1}`` and damping
``C_x = J^{-T} diag(b_j + r^2 b_m) J^{-1}`` (Eom, Suh & Yi, eq. 2, with the reflected rotor).

References
----------
M. W. Spong, "Modeling and control of elastic joint robots", ASME J. Dyn. Syst. Meas. Control
109(4), 310-319, 1987.

M. C. Çavuşoğlu, D. Feygin and F. Tendick, "A critical study of the mechanical and electrical
properties of the PHANToM haptic interface and improvements for high-performance control",
Presence 11(6), 555-568, 2002.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from analysis.errors import ValidationError
from analysis.multidof.model import RigidCartesianDevice, StructuralModel

__all__ = ["CableDrive", "cable_drive_model", "rigid_drive_device"]

_UNITS = {"motor_inertia": "kg m^2", "ratio": "", "cable_stiffness": "N m/rad", "cable_damping": "N m s/rad",
          "motor_damping": "N m s/rad", "joint_damping": "N m s/rad"}


@dataclass(frozen=True)
class CableDrive:
    """The cable drive of every joint; a field left ``None`` is not known and must be entered.

    Each field is one value per joint (a scalar is taken for every joint).  A preset leaves a
    field ``None`` where its source does not publish it; a computation that needs the field
    refuses it by name (:meth:`require`).

    Parameters
    ----------
    motor_inertia : float, sequence of float or None
        Rotor inertia ``J_m`` [kg m^2] of each motor, > 0.
    ratio : float, sequence of float or None
        Transmission ratio ``r`` (motor angle per joint angle), > 0.
    cable_stiffness : float, sequence of float or None
        Cable stiffness ``k`` referred to the joint [N m/rad], > 0.
    cable_damping : float, sequence of float or None
        Cable damping ``c`` referred to the joint [N m s/rad], >= 0.
    motor_damping : float, sequence of float or None
        Viscous friction ``b_m`` of each motor [N m s/rad], >= 0.
    joint_damping : float, sequence of float or None
        Viscous friction ``b_j`` of each joint on the link side [N m s/rad], >= 0.

    Raises
    ------
    ValidationError
        When a given value is not finite, or out of its range (``> 0`` for the inertia, the
        ratio and the stiffness, ``>= 0`` for the dampings); the message names the field and
        the joint.
    """

    motor_inertia: object = None
    ratio: object = None
    cable_stiffness: object = None
    cable_damping: object = None
    motor_damping: object = None
    joint_damping: object = None

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            a = np.atleast_1d(np.array(value, dtype=float))
            if a.ndim != 1 or a.size == 0:
                raise ValidationError(f.name, "a value or one value per joint", value)
            strict = f.name in ("motor_inertia", "ratio", "cable_stiffness")
            for i, x in enumerate(a):
                if not np.isfinite(x) or (x <= 0 if strict else x < 0):
                    raise ValidationError(f.name, f"{'> 0' if strict else '>= 0'} and finite {_UNITS[f.name]}".rstrip(),
                                          float(x), index=i)
            a.flags.writeable = False
            object.__setattr__(self, f.name, a)

    def require(self, names: tuple[str, ...], joints: int) -> tuple[np.ndarray, ...]:
        """The fields ``names`` as arrays of one value per joint, refusing a missing one by name.

        Parameters
        ----------
        names : tuple of str
            The fields a computation needs.
        joints : int
            Number of joints ``n``.

        Returns
        -------
        tuple of numpy.ndarray
            One array of shape (n,) per name.

        Raises
        ------
        ValidationError
            When a field is ``None`` (not published for a preset: the user enters it), or has
            neither one value nor ``n`` values.
        """
        out = []
        for name in names:
            value = getattr(self, name)
            if value is None:
                raise ValidationError(name, f"a value in {_UNITS[name] or 'motor turns per joint turn'} "
                                            "(not published for this device: enter it)", None)
            if value.size not in (1, joints):
                raise ValidationError(name, f"one value or {joints} values (one per joint)", value.tolist())
            out.append(np.broadcast_to(value, (joints,)).copy())
        return tuple(out)


def _link_mass(link_mass: object) -> np.ndarray:
    try:
        Ml = np.array(link_mass, dtype=float)
    except (TypeError, ValueError):
        raise ValidationError("link_mass", "a square matrix of real numbers (kg m^2)", link_mass) from None
    if Ml.ndim != 2 or Ml.shape[0] != Ml.shape[1] or Ml.size == 0:
        raise ValidationError("link_mass", "a square joint-space inertia matrix (kg m^2)", f"shape {Ml.shape}")
    return Ml


def _square_jacobian(jacobian: object, joints: int) -> np.ndarray:
    J = np.array(jacobian, dtype=float)
    if J.shape != (joints, joints) or not np.all(np.isfinite(J)):
        raise ValidationError("jacobian", f"a finite {joints} x {joints} matrix (as many axes as joints)",
                              f"shape {J.shape}")
    return J


def cable_drive_model(link_mass: object, jacobian: object, drive: CableDrive,
                      sample_time: float = 1e-3) -> StructuralModel:
    """The linkage with its cable drives at one configuration (module docstring): ``2n`` coordinates.

    Parameters
    ----------
    link_mass : array_like
        The linkage's joint-space inertia ``M(theta_0)`` [kg m^2], shape (n, n), symmetric
        positive definite (links only; the rotors are in ``drive``).
    jacobian : array_like
        The handle Jacobian ``J`` at ``theta_0`` [m/rad], shape (n, n).
    drive : CableDrive
        The drives; ``motor_inertia``, ``ratio``, ``cable_stiffness``, ``cable_damping``,
        ``motor_damping`` and ``joint_damping`` are all needed.
    sample_time : float, optional
        Sample period ``T`` [s].

    Returns
    -------
    StructuralModel
        ``q = (phi, theta)``: motor angles then joint angles; ``m = n`` Cartesian axes.

    Raises
    ------
    ValidationError
        When a drive field is missing (named), the Jacobian is not square and finite, or the
        link inertia is not symmetric positive definite.
    """
    Ml = _link_mass(link_mass)
    n = Ml.shape[0]
    J = _square_jacobian(jacobian, n)
    Jm, r, k, c, bm, bj = drive.require(("motor_inertia", "ratio", "cable_stiffness", "cable_damping",
                                         "motor_damping", "joint_damping"), n)
    M = np.zeros((2 * n, 2 * n))
    M[:n, :n] = np.diag(Jm)
    M[n:, n:] = Ml

    def coupling(g: np.ndarray) -> np.ndarray:
        out = np.zeros((2 * n, 2 * n))
        out[:n, :n] = np.diag(g / (r * r))
        out[:n, n:] = out[n:, :n] = -np.diag(g / r)
        out[n:, n:] = np.diag(g)
        return out

    K = coupling(k)
    C = coupling(c)
    C[:n, :n] += np.diag(bm)
    C[n:, n:] += np.diag(bj)
    Ba = np.zeros((2 * n, n))
    Ba[:n] = J.T / r[:, None]
    Cs = np.zeros((n, 2 * n))
    Cs[:, :n] = J / r[None, :]
    Jh = np.zeros((n, 2 * n))
    Jh[:, n:] = J
    return StructuralModel(M, C, K, Ba, Jh, Cs, sample_time)


def rigid_drive_device(link_mass: object, jacobian: object, drive: CableDrive,
                       sample_time: float = 1e-3) -> RigidCartesianDevice:
    """The rigid-cable limit of :func:`cable_drive_model`: ``M_x`` and ``C_x`` at the handle.

    ``M_x = J^{-T} (M + diag(r^2 J_m)) J^{-1}``, ``C_x = J^{-T} diag(b_j + r^2 b_m) J^{-1}``
    (the rotors and their friction reflected through the ratio; the cable's own stiffness and
    damping drop out).

    Parameters
    ----------
    link_mass : array_like
        The linkage's joint-space inertia ``M(theta_0)`` [kg m^2], shape (n, n).
    jacobian : array_like
        The handle Jacobian ``J`` [m/rad], shape (n, n), invertible.
    drive : CableDrive
        The drives; ``motor_inertia``, ``ratio``, ``motor_damping`` and ``joint_damping`` are
        needed.
    sample_time : float, optional
        Sample period ``T`` [s].

    Returns
    -------
    RigidCartesianDevice
        The handle's Cartesian inertia and damping.

    Raises
    ------
    ValidationError
        When a needed drive field is missing (named), the Jacobian is not square, finite and
        invertible, or ``M_x`` is not symmetric positive definite.
    """
    Ml = _link_mass(link_mass)
    n = Ml.shape[0]
    J = _square_jacobian(jacobian, n)
    Jm, r, bm, bj = drive.require(("motor_inertia", "ratio", "motor_damping", "joint_damping"), n)
    try:
        Jinv = np.linalg.inv(J)
    except np.linalg.LinAlgError:
        raise ValidationError("jacobian", "an invertible Jacobian (a non-singular configuration)", J.tolist()) from None
    Mx = Jinv.T @ (Ml + np.diag(r * r * Jm)) @ Jinv
    Cx = Jinv.T @ np.diag(bj + r * r * bm) @ Jinv
    return RigidCartesianDevice(mass=0.5 * (Mx + Mx.T), damping=0.5 * (Cx + Cx.T), sample_time=sample_time)
