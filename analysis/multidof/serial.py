"""A 3-DOF serial linkage of the PHANToM type: kinematics, joint and Cartesian inertia (issue 25).

Geometry (the PHANToM 1.5's parallelogram arm, gravity not modelled): joint 1 turns the base
about the vertical axis ``z`` by ``theta_1``; in the vertical plane of the arm, ``theta_2`` sets
the upper arm (length ``l1``) from the horizontal and ``theta_3`` the forearm (length ``l2``),
driven through the parallelogram (crank ``l3``) so that both are absolute angles.  With
``rho = l1 cos theta_2 + l2 sin theta_3`` the handle is at

    ``p = (rho cos theta_1, rho sin theta_1, l1 sin theta_2 - l2 cos theta_3)``

(origin where the axes of joints 1 and 2 meet; at ``theta = 0`` the upper arm is horizontal and
the forearm hangs down).  The Jacobian ``J = dp/dtheta`` has ``det J = rho l1 l2 cos(theta_2 -
theta_3)``: it is singular on the base axis (``rho = 0``) and with the arm stretched or folded
(``theta_2 - theta_3 = +-pi/2``).

Joint-space inertia (Çavuşoğlu, Feygin & Tendick 2002, the closed-form mass matrix of the
PHANToM 1.5; bodies ``a`` the forearm, ``c`` the parallelogram link, ``be`` and ``df`` the
drive-side bodies turning with ``theta_2`` and ``theta_3``, and the base)::

    M11 = (4 I_ayy + 4 I_azz + 8 I_base + 4 I_beyy + 4 I_bezz + 4 I_cyy + 4 I_czz + 4 I_dfyy
           + 4 I_dfzz + 4 l1^2 m_a + l2^2 m_a + l1^2 m_c + 4 l3^2 m_c) / 8
          + (4 I_beyy - 4 I_bezz + 4 I_cyy - 4 I_czz + l1^2 (4 m_a + m_c)) cos(2 theta_2) / 8
          + (4 I_ayy - 4 I_azz + 4 I_dfyy - 4 I_dfzz - l2^2 m_a - 4 l3^2 m_c) cos(2 theta_3) / 8
          + l1 (l2 m_a + l3 m_c) cos(theta_2) sin(theta_3)
    M22 = I_bexx + I_cxx + l1^2 m_a + l1^2 m_c / 4
    M23 = -l1 (l2 m_a + l3 m_c) sin(theta_2 - theta_3) / 2
    M33 = I_axx + I_dfxx + l2^2 m_a / 4 + l3^2 m_c,      M12 = M13 = 0.

It is the kinetic energy of the forearm (centre of mass ``l2/2`` from the elbow), the
parallelogram link (``l1/2`` from its pivot, carried by the crank ``l3``) and the bodies turning
with the joints; the tests check it against that kinetic energy along a motion.  The handle's
Cartesian inertia is ``M_x = J^{-T} M J^{-1}`` (links only; the motors enter through the cable
drive of :mod:`analysis.multidof.cable`).

Presets take numbers from published identifications only (:data:`PHANTOM_15_SOURCES` names the
source of each); what is not published is ``None`` and must be entered
(:meth:`~analysis.multidof.cable.CableDrive.require` names it).

References
----------
M. C. Çavuşoğlu, D. Feygin and F. Tendick, "A critical study of the mechanical and electrical
properties of the PHANToM haptic interface and improvements for high-performance control",
Presence 11(6), 555-568, 2002.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from analysis.checks import positive
from analysis.errors import ValidationError
from analysis.multidof.cable import CableDrive, cable_drive_model, rigid_drive_device
from analysis.multidof.model import RigidCartesianDevice, StructuralModel
from analysis.multidof.workspace import SINGULAR_RTOL

__all__ = ["PhantomLinkage", "PHANTOM_15", "PHANTOM_15_SOURCES", "serial_device", "serial_cable_model"]

_PRINCIPAL = ("inertia_a", "inertia_c", "inertia_be", "inertia_df")


@dataclass(frozen=True)
class PhantomLinkage:
    """A PHANToM-type 3-DOF serial linkage: lengths, link masses and inertias, cable drives (SI).

    Parameters
    ----------
    l1 : float
        Upper-arm length [m], > 0.
    l2 : float
        Forearm length [m], > 0.
    l3 : float
        Parallelogram crank length [m], >= 0.
    mass_a : float
        Forearm mass ``m_a`` [kg], >= 0.
    mass_c : float
        Parallelogram link mass ``m_c`` [kg], >= 0.
    inertia_a, inertia_c, inertia_be, inertia_df : tuple of (float, float, float)
        Principal inertias ``(I_xx, I_yy, I_zz)`` [kg m^2] of the forearm, the parallelogram
        link and the two drive-side bodies (``x`` the joint's axis), each >= 0.
    inertia_base : float
        The base's inertia about the vertical axis [kg m^2], >= 0.
    drive : CableDrive, optional
        The cable drive of each joint (fields ``None`` until entered).

    Raises
    ------
    ValidationError
        When a length, mass or inertia is out of range or not finite (named).
    """

    l1: float
    l2: float
    l3: float
    mass_a: float
    mass_c: float
    inertia_a: tuple[float, float, float]
    inertia_c: tuple[float, float, float]
    inertia_be: tuple[float, float, float]
    inertia_df: tuple[float, float, float]
    inertia_base: float
    drive: CableDrive = field(default_factory=CableDrive)

    def __post_init__(self) -> None:
        for name in ("l1", "l2"):
            object.__setattr__(self, name, positive(name, getattr(self, name), "m"))
        for name in ("l3", "mass_a", "mass_c", "inertia_base"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise ValidationError(name, ">= 0 and finite", value)
            object.__setattr__(self, name, float(value))
        for name in _PRINCIPAL:
            v = tuple(getattr(self, name))
            if len(v) != 3 or not all(math.isfinite(float(x)) and float(x) >= 0 for x in v):
                raise ValidationError(name, "three principal inertias (I_xx, I_yy, I_zz) >= 0 in kg m^2", v)
            object.__setattr__(self, name, tuple(float(x) for x in v))
        if not isinstance(self.drive, CableDrive):
            raise ValidationError("drive", "a CableDrive", type(self.drive).__name__)

    # -- kinematics --------------------------------------------------------------------------
    def forward_kinematics(self, q: object) -> np.ndarray:
        """The handle position ``p(theta)`` (module docstring).

        Parameters
        ----------
        q : array_like
            Joint angles ``(theta_1, theta_2, theta_3)`` [rad], shape (3,).

        Returns
        -------
        numpy.ndarray
            ``(x, y, z)`` [m], shape (3,).
        """
        t1, t2, t3 = np.asarray(q, dtype=float)
        rho = self.l1 * math.cos(t2) + self.l2 * math.sin(t3)
        return np.array([rho * math.cos(t1), rho * math.sin(t1), self.l1 * math.sin(t2) - self.l2 * math.cos(t3)])

    def jacobian(self, q: object) -> np.ndarray:
        """``J = dp/dtheta`` [m/rad], shape (3, 3).

        Parameters
        ----------
        q : array_like
            Joint angles [rad], shape (3,).

        Returns
        -------
        numpy.ndarray
            The Jacobian: column ``i`` is the handle's velocity per unit ``theta_i'``.
        """
        t1, t2, t3 = np.asarray(q, dtype=float)
        l1, l2 = self.l1, self.l2
        rho = l1 * math.cos(t2) + l2 * math.sin(t3)
        c1, s1 = math.cos(t1), math.sin(t1)
        return np.array([[-rho * s1, -l1 * math.sin(t2) * c1, l2 * math.cos(t3) * c1],
                         [rho * c1, -l1 * math.sin(t2) * s1, l2 * math.cos(t3) * s1],
                         [0.0, l1 * math.cos(t2), l2 * math.sin(t3)]])

    def inverse_kinematics(self, p: object) -> np.ndarray:
        """The joint angles placing the handle at ``p`` (the branch with the forearm below the elbow).

        ``theta_1 = atan2(y, x)`` (``rho >= 0``); in the arm's plane, the elbow angle
        ``beta = theta_3 - pi/2 - theta_2`` in ``[-pi, 0]`` from the law of cosines.

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y, z)`` [m], shape (3,).

        Returns
        -------
        numpy.ndarray
            ``(theta_1, theta_2, theta_3)`` [rad], shape (3,).

        Raises
        ------
        ValidationError
            When ``p`` is not a finite 3-vector, or is out of reach (its distance from the
            shoulder is not within ``|l1 - l2| .. l1 + l2``); the message names the position.
        """
        pos = _position(p)
        x, y, z = pos
        rho = math.hypot(x, y)
        d2 = rho * rho + z * z
        c = (d2 - self.l1 ** 2 - self.l2 ** 2) / (2.0 * self.l1 * self.l2)
        if not -1.0 <= c <= 1.0:
            raise ValidationError("position", f"inside the reachable workspace (the handle at {_named(pos)} m is "
                                              f"{math.sqrt(d2):.6g} m from the shoulder; the arm reaches "
                                              f"{abs(self.l1 - self.l2):.6g} .. {self.l1 + self.l2:.6g} m)", pos.tolist())
        beta = -math.acos(c)
        t2 = math.atan2(z, rho) - math.atan2(self.l2 * math.sin(beta), self.l1 + self.l2 * math.cos(beta))
        return np.array([math.atan2(y, x), t2, t2 + beta + 0.5 * math.pi])

    def configuration(self, p: object) -> np.ndarray:
        """:meth:`inverse_kinematics`, refusing a singular configuration by its position.

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y, z)`` [m], shape (3,).

        Returns
        -------
        numpy.ndarray
            The joint angles [rad], shape (3,).

        Raises
        ------
        ValidationError
            When the position is out of reach, or the Jacobian's singular values there differ by
            more than ``1/SINGULAR_RTOL`` (on the base axis, or the arm stretched or folded).
        """
        q = self.inverse_kinematics(p)
        s = np.linalg.svd(self.jacobian(q), compute_uv=False)
        if not s[-1] > SINGULAR_RTOL * s[0]:
            raise ValidationError("position", f"a non-singular configuration of the serial linkage (at "
                                              f"{_named(_position(p))} m the Jacobian's singular values are "
                                              f"{s[0]:.3g} .. {s[-1]:.3g} m/rad: on the base axis, or the arm "
                                              "stretched or folded)", _position(p).tolist())
        return q

    # -- inertia -----------------------------------------------------------------------------
    def joint_mass(self, q: object) -> np.ndarray:
        """The links' joint-space inertia ``M(theta)`` [kg m^2] (module docstring), shape (3, 3).

        Parameters
        ----------
        q : array_like
            Joint angles [rad], shape (3,).

        Returns
        -------
        numpy.ndarray
            ``M(theta)``, symmetric positive definite for positive inertias.
        """
        _, t2, t3 = np.asarray(q, dtype=float)
        l1, l2, l3, ma, mc = self.l1, self.l2, self.l3, self.mass_a, self.mass_c
        axx, ayy, azz = self.inertia_a
        cxx, cyy, czz = self.inertia_c
        bexx, beyy, bezz = self.inertia_be
        dfxx, dfyy, dfzz = self.inertia_df
        m11 = ((4 * ayy + 4 * azz + 8 * self.inertia_base + 4 * beyy + 4 * bezz + 4 * cyy + 4 * czz + 4 * dfyy
                + 4 * dfzz + 4 * l1 * l1 * ma + l2 * l2 * ma + l1 * l1 * mc + 4 * l3 * l3 * mc) / 8
               + (4 * beyy - 4 * bezz + 4 * cyy - 4 * czz + l1 * l1 * (4 * ma + mc)) * math.cos(2 * t2) / 8
               + (4 * ayy - 4 * azz + 4 * dfyy - 4 * dfzz - l2 * l2 * ma - 4 * l3 * l3 * mc) * math.cos(2 * t3) / 8
               + l1 * (l2 * ma + l3 * mc) * math.cos(t2) * math.sin(t3))
        m23 = -0.5 * l1 * (l2 * ma + l3 * mc) * math.sin(t2 - t3)
        return np.array([[m11, 0.0, 0.0],
                         [0.0, bexx + cxx + l1 * l1 * ma + 0.25 * l1 * l1 * mc, m23],
                         [0.0, m23, axx + dfxx + 0.25 * l2 * l2 * ma + l3 * l3 * mc]])

    def cartesian_mass(self, p: object) -> np.ndarray:
        """The links' inertia at the handle, ``M_x = J^{-T} M J^{-1}`` [kg], at a handle position.

        Parameters
        ----------
        p : array_like
            Handle position ``(x, y, z)`` [m], shape (3,).

        Returns
        -------
        numpy.ndarray
            ``M_x``, shape (3, 3), symmetric.

        Raises
        ------
        ValidationError
            As :meth:`configuration` (out of reach, singular).
        """
        q = self.configuration(p)
        Jinv = np.linalg.inv(self.jacobian(q))
        Mx = Jinv.T @ self.joint_mass(q) @ Jinv
        return 0.5 * (Mx + Mx.T)


def _position(p: object) -> np.ndarray:
    try:
        a = np.array(p, dtype=float)
    except (TypeError, ValueError):
        raise ValidationError("position", "a handle position (x, y, z) in m", p) from None
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise ValidationError("position", "a finite handle position (x, y, z) in m", p)
    return a


def _named(p: np.ndarray) -> str:
    return "(x, y, z) = (" + ", ".join(f"{v:.6g}" for v in p) + ")"


def serial_device(linkage: PhantomLinkage, position: object, sample_time: float = 1e-3) -> RigidCartesianDevice:
    """The serial linkage with rigid cables at a handle position: ``M_x``, ``C_x`` with the rotors.

    :func:`~analysis.multidof.cable.rigid_drive_device` of the links' ``M(theta)`` and ``J``.

    Parameters
    ----------
    linkage : PhantomLinkage
        The linkage and its drives (``motor_inertia``, ``ratio``, ``motor_damping`` and
        ``joint_damping`` needed).
    position : array_like
        Handle position ``(x, y, z)`` [m].
    sample_time : float, optional
        Sample period ``T`` [s].

    Returns
    -------
    RigidCartesianDevice
        Three Cartesian axes.

    Raises
    ------
    ValidationError
        When the position is out of reach or singular (named), or a drive field is missing
        (named).
    """
    q = linkage.configuration(position)
    return rigid_drive_device(linkage.joint_mass(q), linkage.jacobian(q), linkage.drive, sample_time)


def serial_cable_model(linkage: PhantomLinkage, position: object, sample_time: float = 1e-3) -> StructuralModel:
    """The serial linkage with its cable drives at a handle position: the flexible model, 6 coordinates.

    :func:`~analysis.multidof.cable.cable_drive_model` of the links' ``M(theta)`` and ``J``.

    Parameters
    ----------
    linkage : PhantomLinkage
        The linkage and its drives (every drive field needed).
    position : array_like
        Handle position ``(x, y, z)`` [m].
    sample_time : float, optional
        Sample period ``T`` [s].

    Returns
    -------
    StructuralModel
        ``q = (phi_1..3, theta_1..3)``, three Cartesian axes.

    Raises
    ------
    ValidationError
        When the position is out of reach or singular (named), or a drive field is missing
        (named).
    """
    q = linkage.configuration(position)
    return cable_drive_model(linkage.joint_mass(q), linkage.jacobian(q), linkage.drive, sample_time)


#: Where each number of :data:`PHANTOM_15` comes from.  The numbers are those of the paper's
#: kinematic and mass-parameter tables as transcribed in a public reimplementation of its model;
#: the paper itself could not be consulted when the preset was written, so the table numbers are
#: not given here and the values should be checked against it.  The drive's fields are not
#: entered (``None``): the user enters them.
_CFT = "Çavuşoğlu, Feygin & Tendick 2002, PHANToM 1.5"
PHANTOM_15_SOURCES = {
    "l1": f"{_CFT}: kinematic parameters, l1 = 0.215 m",
    "l2": f"{_CFT}: kinematic parameters, l2 = 0.170 m",
    "l3": f"{_CFT}: mass parameters, l3 = 0.0325 m",
    "mass_a": f"{_CFT}: mass parameters, m_a = 0.0202 kg",
    "mass_c": f"{_CFT}: mass parameters, m_c = 0.0249 kg",
    "inertia_a": f"{_CFT}: mass parameters, I_axx, I_ayy, I_azz",
    "inertia_c": f"{_CFT}: mass parameters, I_cxx, I_cyy, I_czz",
    "inertia_be": f"{_CFT}: mass parameters, I_bexx, I_beyy, I_bezz",
    "inertia_df": f"{_CFT}: mass parameters, I_dfxx, I_dfyy, I_dfzz",
    "inertia_base": f"{_CFT}: mass parameters, I_baseyy",
    "drive": "not entered: motor inertia, transmission ratio, cable stiffness and damping, motor and joint "
             "friction are None until the user enters them",
}

#: The PHANToM 1.5 of Çavuşoğlu, Feygin & Tendick (2002): its links' lengths, masses and inertias
#: (:data:`PHANTOM_15_SOURCES`); the cable drives are left for the user to enter.
PHANTOM_15 = PhantomLinkage(
    l1=0.215, l2=0.170, l3=0.0325,
    mass_a=0.0202, mass_c=0.0249,
    inertia_a=(0.4864e-4, 0.001843e-4, 0.4864e-4),
    inertia_c=(0.959e-4, 0.959e-4, 0.0051e-4),
    inertia_be=(11.09e-4, 10.06e-4, 0.591e-4),
    inertia_df=(7.11e-4, 0.629e-4, 6.246e-4),
    inertia_base=11.87e-4,
)
