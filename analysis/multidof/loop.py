"""The exact sampled MIMO loop of a multi-DOF device against a wall rendered in Cartesian space.

Plant
-----
The model of :mod:`analysis.multidof.model` in ``X = (q, q')`` with a human grasp at the handle
(mass ``m_h``, damper ``b_h`` and spring ``k_h`` to ground, the same in every direction:
``m_h J_h^T J_h`` added to ``M``, and likewise to ``C`` and ``K``), inputs ``(u, F_ext)``:
the ``m`` actuator commands through ``B_a`` and an external Cartesian force at the handle
through ``J_h^T``.  The commands are held by a zero-order hold and the plant is discretized
exactly by :func:`analysis.chain.discretize.discretize_zoh` (one batched ``expm``, Van Loan),
the same function and the same realization as the chain's
(:func:`analysis.chain.state_space.chain_state_space`; a diagonal ``M`` is inverted by the same
reciprocal, so a chain's plant is bit for bit the chain's, with the sign of the command column
flipped).  :func:`discrete_plant` caches it by value like
:func:`analysis.sampled.loop.discrete_plants` (same size limits).

Controller
----------
The impedance display of Adams et al. (eq. 4) with the god-object wall (the wall holds the
coupling's far end at the origin) in ``m`` Cartesian axes: the controller reads ``y = C_s q``
at ``kT``, estimates the velocity of each axis with the controller's
:class:`~analysis.chain.velocity_filter.VelocityFilter` (backward difference, optionally
low-pass; the same filter on every axis, so it commutes with the wall's matrices) and commands
``u = -(K_w y + B_w v)``, held on ``[(k+d)T, (k+d+1)T)`` after a computation delay of ``d``
samples.  The wall is rendered in Cartesian space (:func:`wall_shape`): isotropic
(``K_w = k I``, ``B_w = b I``), a plane wall with unit normal ``n`` (``k n n^T``, ``b n n^T``)
or any symmetric positive semidefinite shape ``S`` (``k S``, ``b S``); :func:`wall_radii` takes
full stiffness and damping matrices.

Closed loop: state ``X`` (2n) | last sensed ``y`` (m) | filter states (``p m``) | ``d`` queued
commands (``d m``).  Stability is the one rule of :func:`analysis.sampled.loop.is_stable`, the
spectral radius by :func:`analysis.sampled.loop.spectral_radius` (rigid-body modes of the free
directions of a plane wall sit at ``z = 1`` and count as 1).  With one axis this is the chain's
hands-off loop against the god-object wall (:func:`analysis.sampled.critical_stiffness`).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache

import numpy as np

from analysis.chain.discretize import discretize_zoh
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import integer
from analysis.errors import ValidationError
from analysis.multidof.model import DeviceLike, StructuralModel, structural_model
from analysis.sampled.loop import PLANT_CACHE_BYTES, PLANT_CACHE_SIZE, spectral_radius
from analysis.sampled.terminations import HANDS_OFF, Grasp

__all__ = ["plant_matrices", "discrete_plant", "wall_shape", "loop_parts", "closed_loop_matrices", "wall_pencil",
           "wall_radii"]


def plant_matrices(model: StructuralModel, grasps: Sequence[Grasp] = (HANDS_OFF,)) -> tuple[np.ndarray, np.ndarray]:
    """Continuous ``A`` (G, 2n, 2n) and ``B`` (G, 2n, 2m) for each grasp; inputs ``(u, F_ext)``.

    Parameters
    ----------
    model : StructuralModel
        The device.
    grasps : sequence of Grasp, optional
        The grasps at the handle, ``G`` of them (default hands-off).

    Returns
    -------
    tuple of numpy.ndarray
        ``(A, B)`` in ``X = (q, q')``: shapes (G, 2n, 2n) and (G, 2n, 2m), the columns of
        ``B`` the ``m`` commands then the ``m`` components of the external handle force.
    """
    n, m = model.n, model.axes
    Jh = model.handle
    JtJ = Jh.T @ Jh
    G = len(grasps)
    Ms = np.broadcast_to(model.mass, (G, n, n)).copy()
    Cs = np.broadcast_to(model.damping, (G, n, n)).copy()
    Ks = np.broadcast_to(model.stiffness, (G, n, n)).copy()
    for i, g in enumerate(grasps):
        if not g.hands_off:
            Ms[i] += g.mass * JtJ
            Cs[i] += g.damping * JtJ
            Ks[i] += g.stiffness * JtJ
    inputs = np.concatenate([model.actuation, Jh.T], axis=1)
    A = np.zeros((G, 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    Bu = np.zeros((G, 2 * n, 2 * m))
    off = Ms - Ms * np.eye(n)
    if not off.any():  # a diagonal mass matrix: the chain's reciprocal (chain_state_space), bit for bit
        inv = 1.0 / np.diagonal(Ms, axis1=1, axis2=2)[:, :, None]
        A[:, n:, :n] = -Ks * inv
        A[:, n:, n:] = -Cs * inv
        Bu[:, n:, :] = inputs * inv
    else:
        A[:, n:, :n] = -np.linalg.solve(Ms, Ks)
        A[:, n:, n:] = -np.linalg.solve(Ms, Cs)
        Bu[:, n:, :] = np.linalg.solve(Ms, np.broadcast_to(inputs, (G, n, 2 * m)))
    return A, Bu


def _zoh(model: StructuralModel, grasps: tuple[Grasp, ...]) -> tuple[np.ndarray, np.ndarray]:
    Ad, Bd = discretize_zoh(*plant_matrices(model, grasps), model.sample_time)
    Ad.flags.writeable = False
    Bd.flags.writeable = False
    return Ad, Bd


_cached_zoh = lru_cache(maxsize=PLANT_CACHE_SIZE)(_zoh)


def discrete_plant(device: DeviceLike, grasps: Sequence[Grasp] = (HANDS_OFF,)) -> tuple[np.ndarray, np.ndarray]:
    """The exact ZOH plants of :func:`plant_matrices`, one per grasp, read-only, cached by value.

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device (:func:`~analysis.multidof.model.structural_model`).
    grasps : sequence of Grasp, optional
        The grasps at the handle (default hands-off).

    Returns
    -------
    tuple of numpy.ndarray
        ``(Ad, Bd)``, shapes (G, 2n, 2n) and (G, 2n, 2m); not writeable.
    """
    model = structural_model(device)
    gs = tuple(grasps)
    N, m = 2 * model.n, model.axes
    if len(gs) * N * (N + 2 * m) * 8 > PLANT_CACHE_BYTES:
        return _zoh(model, gs)
    return _cached_zoh(model, gs)


def wall_shape(axes: int, normal: object = None) -> np.ndarray:
    """The shape ``S`` of a wall in ``axes`` Cartesian axes: ``K_w = k S``, ``B_w = b S``.

    Parameters
    ----------
    axes : int
        Number of Cartesian axes ``m``.
    normal : None, array_like of shape (m,) or (m, m), optional
        ``None`` for the isotropic wall (``S = I``); a nonzero vector for a plane wall with that
        normal (``S = n n^T``, ``n`` normalized); a symmetric positive semidefinite matrix for
        a full stiffness shape (taken as is).

    Returns
    -------
    numpy.ndarray
        ``S``, shape (m, m).

    Raises
    ------
    ValidationError
        When the normal is zero, not finite or of the wrong length, or the matrix is not
        symmetric positive semidefinite.
    """
    if normal is None:
        return np.eye(axes)
    a = np.asarray(normal, dtype=float)
    if a.shape == (axes,):
        norm = float(np.linalg.norm(a))
        if not (np.all(np.isfinite(a)) and norm > 0):
            raise ValidationError("normal", "a finite nonzero vector", a.tolist())
        u = a / norm
        return np.outer(u, u)
    if a.shape == (axes, axes):
        if not np.all(np.isfinite(a)) or np.abs(a - a.T).max() > 1e-12 * np.abs(a).max() or \
                np.linalg.eigvalsh(a).min() < -1e-12 * np.abs(a).max():
            raise ValidationError("normal", "a symmetric positive semidefinite wall shape", a.tolist())
        return a
    raise ValidationError("normal", f"None, a vector of {axes} components or a {axes} x {axes} matrix",
                          f"shape {a.shape}")


def _check_walls(m: int, stiffness: object, damping: object) -> tuple[np.ndarray, np.ndarray]:
    """Wall matrices ``K_w``, ``B_w`` as arrays of shape (W, m, m)."""
    Kw, Bw = np.broadcast_arrays(np.asarray(stiffness, dtype=float), np.asarray(damping, dtype=float))
    if Kw.ndim == 2:
        Kw, Bw = Kw[None], Bw[None]
    if Kw.ndim != 3 or Kw.shape[1:] != (m, m):
        raise ValidationError("stiffness", f"wall matrices of shape (W, {m}, {m})", f"shape {Kw.shape}")
    return Kw, Bw


def loop_parts(device: DeviceLike, delay_samples: int = 0, grasp: Grasp = HANDS_OFF,
               velocity_filter: VelocityFilter | None = None, *,
               plant: tuple[np.ndarray, np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The closed loop without the wall: ``Phi = Phi_0 + G (-(K_w Y + B_w V))`` (module docstring).

    The wall's command ``u = -(K_w y + B_w v)`` is the only part of the loop that depends on the
    wall; ``y = Y s`` and ``v = V s`` on the closed-loop state ``s``, and ``G`` is where the
    command enters (through the held plant, or the delay queue).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    delay_samples : int, optional
        Computation delay ``d`` in samples, 0 to 1000.
    grasp : Grasp, optional
        The human grasp at the handle (hands-off by default).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate of every axis; ``None`` for the backward difference.
    plant : tuple of numpy.ndarray, optional
        ``(Ad, Bd)`` of :func:`discrete_plant` for this device and grasp, shapes (2n, 2n) and
        (2n, 2m), when the caller discretized many devices in one batch; ``None`` to take
        them from :func:`discrete_plant`.

    Returns
    -------
    Phi0 : numpy.ndarray
        The loop with no wall, shape (N, N), ``N = 2n + m (1 + p + d)``.
    G : numpy.ndarray
        Where the command enters, shape (N, m).
    Y : numpy.ndarray
        The sensed position, shape (m, N).
    V : numpy.ndarray
        The velocity estimate, shape (m, N).

    Raises
    ------
    ValidationError
        When the delay is out of range, or the filter is not a VelocityFilter or its cut-off
        is not below Nyquist.
    """
    model = structural_model(device)
    n2, m = 2 * model.n, model.axes
    d = integer("delay_samples", delay_samples, 0, 1000)
    vf = VelocityFilter() if velocity_filter is None else velocity_filter
    if not isinstance(vf, VelocityFilter):
        raise ValidationError("velocity_filter", "a VelocityFilter or None", vf)
    r = vf.realization(model.sample_time)
    p, T = r.order, model.sample_time
    Ad, Bd = discrete_plant(model, (grasp,)) if plant is None else (plant[0][None], plant[1][None])
    N = n2 + m * (1 + p + d)
    iy, isf, iq = n2, n2 + m, n2 + m + p * m  # offsets: last y, filter states, queued commands
    eye_m = np.eye(m)
    Y = np.zeros((m, N))
    Y[:, :model.n] = model.sensing
    dif = Y.copy()
    dif[:, iy:iy + m] -= eye_m
    dif /= T  # the backward difference (y - y[k-1]) / T
    V = r.D * dif
    for i in range(p):
        V[:, isf + i * m:isf + (i + 1) * m] += r.C[i] * eye_m
    Phi = np.zeros((N, N))
    Phi[:n2, :n2] = Ad[0]
    G = np.zeros((N, m))
    if d:
        Phi[:n2, iq:iq + m] = Bd[0, :, :m]
        for j in range(d - 1):
            Phi[iq + j * m:iq + (j + 1) * m, iq + (j + 1) * m:iq + (j + 2) * m] = eye_m
        G[iq + (d - 1) * m:, :] = eye_m
    else:
        G[:n2, :] = Bd[0, :, :m]
    Phi[iy:iy + m, :] = Y
    for i in range(p):
        row = r.B[i] * dif
        for j in range(p):
            row[:, isf + j * m:isf + (j + 1) * m] += r.A[i, j] * eye_m
        Phi[isf + i * m:isf + (i + 1) * m, :] = row
    return Phi, G, Y, V


def closed_loop_matrices(device: DeviceLike, stiffness: np.ndarray, damping: np.ndarray, delay_samples: int = 0,
                         grasp: Grasp = HANDS_OFF, velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """Closed-loop state matrices ``Phi`` (W, N, N) for ``W`` walls (module docstring).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    stiffness : array_like
        Wall stiffness matrices ``K_w`` [N/m], shape (W, m, m) (or (m, m) for one wall).
    damping : array_like
        Wall damping matrices ``B_w`` [N s/m], broadcast with ``stiffness``.
    delay_samples : int, optional
        Computation delay ``d`` in samples, 0 to 1000.
    grasp : Grasp, optional
        The human grasp at the handle (hands-off by default).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate of every axis; ``None`` for the backward difference.

    Returns
    -------
    numpy.ndarray
        ``Phi``, shape (W, N, N), ``N = 2n + m (1 + p + d)`` with ``p`` the filter order.

    Raises
    ------
    ValidationError
        When the delay is out of range, the filter is not a VelocityFilter or its cut-off is
        not below Nyquist, or the wall matrices do not match the axes.
    """
    model = structural_model(device)
    Kw, Bw = _check_walls(model.axes, stiffness, damping)
    Phi0, G, Y, V = loop_parts(model, delay_samples, grasp, velocity_filter)
    return Phi0 + G @ -(Kw @ Y + Bw @ V)


def wall_pencil(device: DeviceLike, shape: np.ndarray, damping: float, delay_samples: int = 0,
                grasp: Grasp = HANDS_OFF, velocity_filter: VelocityFilter | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The loop as a pencil in the wall stiffness: ``Phi(k) = P0 + k P1`` for ``K_w = k S``, ``B_w = b S``.

    A sweep over ``k`` then costs one eigenvalue computation per ``k`` and no rebuilding.

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    shape : array_like
        Wall shapes ``S`` (:func:`wall_shape`), shape (W, m, m) or (m, m).
    damping : float
        Wall damping ``b`` [N s/m].
    delay_samples : int, optional
        Computation delay in samples.
    grasp : Grasp, optional
        The human grasp at the handle.
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    P0, P1 : numpy.ndarray
        Shapes (W, N, N) each.

    Raises
    ------
    ValidationError
        As :func:`closed_loop_matrices`.
    """
    model = structural_model(device)
    S, _ = _check_walls(model.axes, shape, 0.0)
    Phi0, G, Y, V = loop_parts(model, delay_samples, grasp, velocity_filter)
    return Phi0 + G @ -(float(damping) * S @ V), G @ -(S @ Y)


def wall_radii(device: DeviceLike, stiffness: np.ndarray, damping: np.ndarray, delay_samples: int = 0,
               grasp: Grasp = HANDS_OFF, velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """Spectral radius of the closed loop for each wall (batched; stable when ``is_stable``).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    stiffness : array_like
        Wall stiffness matrices ``K_w`` [N/m], shape (W, m, m) or (m, m).
    damping : array_like
        Wall damping matrices ``B_w`` [N s/m], broadcast with ``stiffness``.
    delay_samples : int, optional
        Computation delay in samples.
    grasp : Grasp, optional
        The human grasp at the handle.
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    numpy.ndarray
        Spectral radii, shape (W,).

    Raises
    ------
    ValidationError
        As :func:`closed_loop_matrices`.
    """
    return spectral_radius(closed_loop_matrices(device, stiffness, damping, delay_samples, grasp, velocity_filter))
