"""One linear structural model of a multi-DOF haptic device (issue 25).

A device linearized at a configuration is

    ``M q'' + C q' + K q = B_a u``,   handle velocity ``v_h = J_h q'``,   sensed ``y = C_s q``,

over ``n`` generalized coordinates ``q``, with ``M``, ``C``, ``K`` symmetric ``n x n`` (``M``
positive definite, ``C`` and ``K`` positive semidefinite), ``m`` Cartesian axes at the handle,
``u`` the ``m`` actuator commands (a Cartesian force), ``B_a`` (``n x m``) where they act,
``J_h`` (``m x n``) the handle's Cartesian velocity and ``C_s`` (``m x n``) the handle position
the controller measures (its encoders mapped to Cartesian space).  This is the form of Adams,
Moreyra & Hannaford's chain (eq. 25) written for any number of axes.

Special cases:

* :class:`RigidCartesianDevice` -- the handle's Cartesian inertia ``M_x`` and damping ``C_x``
  (``q = x``, ``K = 0``, ``B_a = J_h = C_s = I``), e.g. the ``M_x = J^{-T} M J^{-1}`` of a
  linkage at one configuration (Eom, Suh & Yi, eq. 2);
* :func:`chain_model` -- today's one-axis chain :class:`~analysis.chain.device.Device`
  (``M, C, K`` of :meth:`~analysis.chain.device.Device.matrices`, tridiagonal; the actuator is
  the last mass, the handle the first, the encoder on the actuator).

:func:`structural_model` maps either (or a :class:`StructuralModel`) to the general model, so
every function of :mod:`analysis.multidof` accepts all three.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

import numpy as np

from analysis.chain.device import Device
from analysis.chain.limits import SAMPLE_TIME
from analysis.errors import ValidationError

__all__ = ["StructuralModel", "RigidCartesianDevice", "chain_model", "structural_model", "DeviceLike",
           "SYMMETRY_RTOL"]

#: Relative asymmetry ``max|A - A^T| / max|A|`` above which a matrix is refused as not symmetric,
#: and the relative size of a negative eigenvalue refused as indefinite.
SYMMETRY_RTOL = 1e-12


def _real_matrix(name: str, value: object, shape: tuple[int | None, int | None]) -> np.ndarray:
    """A finite float matrix of ``shape`` (``None`` = any), read-only copy."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValidationError(name, "a matrix of real numbers", value) from None
    if a.ndim != 2 or any(s is not None and s != a.shape[i] for i, s in enumerate(shape)):
        want = " x ".join("any" if s is None else str(s) for s in shape)
        raise ValidationError(name, f"a matrix of shape {want}", f"shape {a.shape}")
    if a.size == 0:
        raise ValidationError(name, "a non-empty matrix", f"shape {a.shape}")
    if not np.all(np.isfinite(a)):
        i, j = np.argwhere(~np.isfinite(a))[0]
        raise ValidationError(name, f"finite entries ({name}[{i}, {j}] is not)", a[i, j])
    a.flags.writeable = False
    return a


def _symmetric(name: str, a: np.ndarray, unit: str, definite: bool) -> None:
    """Refuse a non-symmetric matrix, and an indefinite one (``definite``: not positive definite)."""
    if a.shape[0] != a.shape[1]:
        raise ValidationError(name, "a square matrix", f"shape {a.shape}")
    scale = float(np.max(np.abs(a)))
    asym = np.abs(a - a.T)
    if asym.max() > SYMMETRY_RTOL * scale:
        i, j = np.unravel_index(int(np.argmax(asym)), a.shape)
        raise ValidationError(name, f"a symmetric matrix ({name}[{i}, {j}] = {a[i, j]:.6g} but "
                                    f"{name}[{j}, {i}] = {a[j, i]:.6g})", a.tolist())
    low = float(np.linalg.eigvalsh(a).min())
    if definite and not low > SYMMETRY_RTOL * scale:
        raise ValidationError(name, f"a positive definite matrix (its smallest eigenvalue is {low:.6g} {unit})",
                              a.tolist())
    if not definite and low < -SYMMETRY_RTOL * scale:
        raise ValidationError(name, f"a positive semidefinite matrix (its smallest eigenvalue is {low:.6g} {unit})",
                              a.tolist())


@dataclass(frozen=True, eq=False)
class StructuralModel:
    """``M q'' + C q' + K q = B_a u``, ``v_h = J_h q'``, ``y = C_s q`` (module docstring).

    Equal (and hashed) by value, so that the discretized plants can be cached by value as the
    chain's are (:func:`analysis.sampled.loop.discrete_plants`).

    Parameters
    ----------
    mass : array_like
        ``M`` [kg or kg m^2], shape (n, n), symmetric positive definite.
    damping : array_like
        ``C`` [N s/m], shape (n, n), symmetric positive semidefinite.
    stiffness : array_like
        ``K`` [N/m], shape (n, n), symmetric positive semidefinite.
    actuation : array_like
        ``B_a``, shape (n, m): where the ``m`` actuator commands act.
    handle : array_like
        ``J_h``, shape (m, n): the handle's Cartesian velocity ``J_h q'`` (a grasp acts there).
    sensing : array_like
        ``C_s``, shape (m, n): the Cartesian handle position the controller measures.
    sample_time : float
        Sample period ``T`` [s], within 1 µs .. 1 s.

    Raises
    ------
    ValidationError
        When a matrix has the wrong shape or a non-finite entry, ``M``, ``C`` or ``K`` is not
        symmetric, ``M`` is not positive definite or ``C``, ``K`` are indefinite (the message
        names the matrix, the entries or the eigenvalue), or the sample time is out of range.
    """

    mass: np.ndarray
    damping: np.ndarray
    stiffness: np.ndarray
    actuation: np.ndarray
    handle: np.ndarray
    sensing: np.ndarray
    sample_time: float = 1e-3

    def __post_init__(self) -> None:
        M = _real_matrix("mass", self.mass, (None, None))
        _symmetric("mass", M, "kg", definite=True)
        n = M.shape[0]
        C = _real_matrix("damping", self.damping, (n, n))
        _symmetric("damping", C, "N s/m", definite=False)
        K = _real_matrix("stiffness", self.stiffness, (n, n))
        _symmetric("stiffness", K, "N/m", definite=False)
        Ba = _real_matrix("actuation", self.actuation, (n, None))
        m = Ba.shape[1]
        Jh = _real_matrix("handle", self.handle, (m, n))
        Cs = _real_matrix("sensing", self.sensing, (m, n))
        for name, value in (("mass", M), ("damping", C), ("stiffness", K), ("actuation", Ba), ("handle", Jh),
                            ("sensing", Cs)):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "sample_time", SAMPLE_TIME("sample_time", self.sample_time))

    @property
    def n(self) -> int:
        """Number of generalized coordinates."""
        return int(self.mass.shape[0])

    @property
    def axes(self) -> int:
        """Number ``m`` of Cartesian axes at the handle (actuator commands, sensed positions)."""
        return int(self.actuation.shape[1])

    def _key(self) -> tuple:
        mats = (self.mass, self.damping, self.stiffness, self.actuation, self.handle, self.sensing)
        return tuple((a.shape, a.tobytes()) for a in mats) + (self.sample_time,)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, StructuralModel) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())


@dataclass(frozen=True, eq=False)
class RigidCartesianDevice:
    """A rigid device seen at the handle: Cartesian inertia ``M_x`` and damping ``C_x``.

    ``q = x`` (``m = n`` axes), ``K = 0``, ``B_a = J_h = C_s = I``: the actuators apply the
    commanded Cartesian force at the handle and the controller measures the handle position.

    Parameters
    ----------
    mass : array_like
        ``M_x`` [kg], shape (m, m), symmetric positive definite.
    damping : array_like, optional
        ``C_x`` [N s/m], shape (m, m), symmetric positive semidefinite (default zero).
    sample_time : float, optional
        Sample period ``T`` [s].

    Raises
    ------
    ValidationError
        As :class:`StructuralModel` (a non-symmetric or indefinite mass matrix, a damping
        matrix of another shape, ...).
    """

    mass: np.ndarray
    damping: np.ndarray | None = None
    sample_time: float = 1e-3
    model: StructuralModel = field(init=False, repr=False)

    def __post_init__(self) -> None:
        M = _real_matrix("mass", self.mass, (None, None))
        m = M.shape[0]
        C = np.zeros((m, m)) if self.damping is None else self.damping
        eye = np.eye(m)
        model = StructuralModel(M, C, np.zeros((m, m)), eye, eye, eye, self.sample_time)
        object.__setattr__(self, "mass", model.mass)
        object.__setattr__(self, "damping", model.damping)
        object.__setattr__(self, "sample_time", model.sample_time)
        object.__setattr__(self, "model", model)


def chain_model(device: Device) -> StructuralModel:
    """Today's chain as the general model: ``M, C, K`` of eq. (25), one axis.

    The actuator command acts on the last mass (``B_a = e_{n-1}``; the chain's ``F_d`` enters
    as ``-F_d``, so ``u = -F_d``), the handle is the first mass (``J_h = e_0^T``, where a grasp
    acts) and the encoder reads the actuator mass (``C_s = e_{n-1}^T``).

    Parameters
    ----------
    device : Device
        The chain and its sample time.

    Returns
    -------
    StructuralModel
        The same device, ``n`` coordinates, one axis.
    """
    M, C, K = device.matrices()
    n = device.n
    Ba = np.zeros((n, 1))
    Ba[n - 1, 0] = 1.0
    Jh = np.zeros((1, n))
    Jh[0, 0] = 1.0
    return StructuralModel(M, C, K, Ba, Jh, Ba.T, device.sample_time)


#: What the functions of :mod:`analysis.multidof` accept as a device.
DeviceLike = Union[StructuralModel, RigidCartesianDevice, Device]


def structural_model(device: DeviceLike) -> StructuralModel:
    """The general model of a device (module docstring).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.

    Returns
    -------
    StructuralModel
        ``device`` itself, the rigid device's model, or :func:`chain_model` of a chain.

    Raises
    ------
    ValidationError
        When ``device`` is none of these.
    """
    if isinstance(device, StructuralModel):
        return device
    if isinstance(device, RigidCartesianDevice):
        return device.model
    if isinstance(device, Device):
        return chain_model(device)
    raise ValidationError("device", "a StructuralModel, RigidCartesianDevice or chain Device", type(device).__name__)
