"""The workspace map of a planar five-bar: the critical wall stiffness over handle positions.

The five-bar's kinematics and mass properties have one home,
:class:`analysis.transparency.five_bar.FiveBar` (the Jacobian, ``M_x = J^{-T} M J^{-1}`` plus
the distal links, and ``B_x``, Eom, Suh & Yi eq. 2), used by the two-axis disturbance observer
and here.  :func:`five_bar_device` linearizes it at a handle position into a
:class:`~analysis.multidof.model.RigidCartesianDevice`, refusing a position outside the
workspace or at (or within :data:`SINGULAR_RTOL` of) a singular configuration by name.

:func:`workspace_map` evaluates, at every reachable point of a grid, the critical stiffness of
the isotropic wall and the worst plane-wall normal of a dense check of directions, all points
and directions in one batch: by default from each point's wall-free loop, its frequency response
computed once and every wall a projection of it, certified on the exact loop
(:func:`analysis.multidof.loci.frequency_first_crossings`), or by the scan of every wall
(:func:`analysis.multidof.limits.first_crossings`, ``method="scan"``); the design
bound, :attr:`WorkspaceMap.minimum`, is the smallest plane-wall stiffness over the workspace,
with its position and normal, refined there by :func:`analysis.multidof.limits.worst_normal`
(and never above the map's own smallest value: the conservative minimum).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import integer, nonnegative
from analysis.errors import ValidationError
from analysis.multidof.limits import check_directions, first_crossings, worst_normal
from analysis.multidof.loci import frequency_first_crossings
from analysis.multidof.loop import loop_parts
from analysis.multidof.model import RigidCartesianDevice
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled.terminations import HANDS_OFF, Grasp, Termination, god_object_wall
from analysis.sampled.zwidth import zwidth_region
from analysis.transparency.five_bar import FiveBar

__all__ = ["SINGULAR_RTOL", "METHODS", "five_bar_device", "normal_device", "workspace_map", "WorkspaceMap",
           "WorkspaceMinimum"]

#: A configuration is refused as singular when the Jacobian's smallest singular value is below
#: this fraction of its largest (the handle loses, or gains an infinitely light, direction).
SINGULAR_RTOL = 1e-6
#: The routes of :func:`workspace_map` to the critical stiffnesses: the certified loci, or the scan.
METHODS = ("loci", "scan")


def five_bar_device(linkage: FiveBar, position: object, sample_time: float = 1e-3) -> RigidCartesianDevice:
    """The five-bar linearized at a handle position: its Cartesian ``M_x`` and ``B_x``.

    Parameters
    ----------
    linkage : FiveBar
        The linkage and its mass properties.
    position : array_like
        Handle position ``(x, y)`` [m], shape (2,).
    sample_time : float, optional
        Sample period ``T`` [s].

    Returns
    -------
    RigidCartesianDevice
        ``M_x``, ``B_x`` at the position (:meth:`FiveBar.cartesian_matrices`).

    Raises
    ------
    ValidationError
        When the position is outside the workspace, or at a singular configuration (the
        Jacobian's singular values differ by more than ``1/SINGULAR_RTOL``); the message
        names the position.
    """
    p = np.asarray(position, dtype=float)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValidationError("position", "a finite handle position (x, y) in m", position)
    linkage.inverse_kinematics(p)  # refuses a position outside the workspace, naming it
    try:
        s = np.linalg.svd(linkage.jacobian(p), compute_uv=False)
    except np.linalg.LinAlgError:
        s = np.array([1.0, 0.0])
    if not s[-1] > SINGULAR_RTOL * s[0]:
        raise ValidationError("position", f"a non-singular configuration of the five-bar (at (x, y) = "
                                          f"({p[0]:.6g}, {p[1]:.6g}) m the Jacobian's singular values are "
                                          f"{s[0]:.3g} and {s[-1]:.3g} m/rad)", p.tolist())
    M, B = linkage.cartesian_matrices(p)
    return RigidCartesianDevice(mass=M, damping=B, sample_time=sample_time)


def normal_device(device: RigidCartesianDevice, normal: object) -> Device:
    """The rigid device seen along a wall normal, as a one-axis chain :class:`~analysis.chain.device.Device`.

    A plane wall leaves the handle free across its normal ``n``, so the mass it pushes is
    ``m_n = 1 / (n^T M^{-1} n)`` and the damping ``b_n = m_n^2 n^T M^{-1} C M^{-1} n``: the
    one-axis ``1/(m_n s + b_n)`` that matches the first two terms of the handle's mobility
    ``n^T (M s + C)^{-1} n`` at high frequency, where the sampled loop's limits are set.  Exact
    (the plane wall's loop) when ``n`` is a principal direction of both ``M`` and ``C``; an
    approximation with cross-coupling.

    Parameters
    ----------
    device : RigidCartesianDevice
        The device at the handle.
    normal : array_like
        The wall's normal, shape (m,), nonzero.

    Returns
    -------
    Device
        One mass ``m_n`` [kg] with the ground damping ``b_n`` [N s/m], the device's sample time.

    Raises
    ------
    ValidationError
        When the normal is zero, not finite or of the wrong length.
    """
    u = np.asarray(normal, dtype=float)
    if u.shape != (device.mass.shape[0],) or not np.all(np.isfinite(u)) or not np.linalg.norm(u) > 0:
        raise ValidationError("normal", f"a finite nonzero vector of {device.mass.shape[0]} components", normal)
    u = u / np.linalg.norm(u)
    mu = np.linalg.solve(device.mass, u)
    m_n = 1.0 / float(u @ mu)
    b_n = max(m_n * m_n * float(mu @ device.damping @ mu), 0.0)
    return Device(masses=[m_n], ground_dampings=[b_n], sample_time=device.sample_time)


@dataclass(frozen=True)
class WorkspaceMinimum:
    """The design bound: the smallest plane-wall critical stiffness over the workspace.

    Parameters
    ----------
    stiffness : float
        The critical stiffness [N/m].
    position : numpy.ndarray
        Where, ``(x, y)`` [m], shape (2,).
    normal : numpy.ndarray
        The wall's unit normal there, shape (2,).
    """

    stiffness: float
    position: np.ndarray
    normal: np.ndarray


@dataclass(frozen=True)
class WorkspaceMap:
    """Critical wall stiffnesses over a grid of handle positions (NaN where unreachable).

    Parameters
    ----------
    x : numpy.ndarray
        Grid abscissae [m], shape (nx,).
    y : numpy.ndarray
        Grid ordinates [m], shape (ny,).
    reachable : numpy.ndarray
        Whether each point is reachable and not singular, shape (ny, nx).
    k_max : numpy.ndarray
        Critical stiffness of the isotropic wall [N/m], shape (ny, nx).
    worst_stiffness : numpy.ndarray
        Critical stiffness of the worst plane wall of the dense check [N/m], shape (ny, nx).
    worst_normal : numpy.ndarray
        Its unit normal, shape (ny, nx, 2).
    minimum : WorkspaceMinimum
        The design bound over the workspace, refined at its point.
    directions : int
        Directions of the dense check at each point.
    zwidth_area : numpy.ndarray or None
        The 1-DOF Z-width area ``int K_max dB`` [N^2 s/m^2] of the device seen along each
        point's worst normal (:func:`normal_device`, :func:`analysis.sampled.zwidth_region`
        over :attr:`zwidth_b`), shape (ny, nx); ``None`` when not asked for.
    zwidth_b : numpy.ndarray or None
        The wall dampings [N s/m] of that area, or ``None``.
    """

    x: np.ndarray
    y: np.ndarray
    reachable: np.ndarray
    k_max: np.ndarray
    worst_stiffness: np.ndarray
    worst_normal: np.ndarray
    minimum: WorkspaceMinimum
    directions: int
    zwidth_area: np.ndarray | None = None
    zwidth_b: np.ndarray | None = None


def _pencils(devices: list[RigidCartesianDevice], shapes: np.ndarray, damping: float, delay_samples: int,
             grasp: Grasp, velocity_filter: VelocityFilter | None) -> tuple[np.ndarray, np.ndarray]:
    """Pencils ``P0 + k P1`` of every device with every wall shape, shape (P * S, N, N)."""
    P0s, P1s = [], []
    for dev in devices:
        Phi0, G, Y, V = loop_parts(dev, delay_samples, grasp, velocity_filter)
        P0s.append(Phi0 + G @ -(damping * shapes @ V))
        P1s.append(G @ -(shapes @ Y))
    return np.concatenate(P0s), np.concatenate(P1s)


def _zwidth_layer(devices: list, points: list, normal: np.ndarray, zwidth_b: object, delay_samples: int,
                  grasp: Grasp, velocity_filter: VelocityFilter | None, k_range: tuple[float, float],
                  step: object, cancelled: Cancelled | None) -> tuple[np.ndarray, np.ndarray]:
    """The 1-DOF Z-width area along each reachable point's worst normal (``step(n)`` after the n-th
    point, ``cancelled`` polled before each) and the B grid of the regions."""
    term = None if grasp.hands_off else Termination(grasp, god_object_wall())
    area, bz = np.full(normal.shape[:2], math.nan), None
    for n, (dev, (j, i)) in enumerate(zip(devices, points), start=1):
        check_cancelled(cancelled)
        region = zwidth_region(normal_device(dev, normal[j, i]), zwidth_b, delay_samples, velocity_filter,
                               termination=term, k_range=k_range, passive=False)
        area[j, i], bz = region.area_linear, region.b
        step(n)
    return area, bz


@none_if_cancelled
def workspace_map(linkage: FiveBar, x: object, y: object, damping: float = 0.0, delay_samples: int = 1, *,
                  sample_time: float = 1e-3, grasp: Grasp = HANDS_OFF, velocity_filter: VelocityFilter | None = None,
                  directions: int = 12, k_range: tuple[float, float] = (1.0, 1e9), method: str = "loci",
                  zwidth_b: object = None, progress: Progress | None = None,
                  cancelled: Cancelled | None = None) -> WorkspaceMap | None:
    """The isotropic and the worst plane-wall critical stiffness over a grid of handle positions.

    Parameters
    ----------
    linkage : FiveBar
        The linkage.
    x, y : array_like
        Grid abscissae and ordinates [m], shapes (nx,) and (ny,).
    damping : float, optional
        Wall damping ``b`` [N s/m], at least 0.
    delay_samples : int, optional
        Computation delay in samples.
    sample_time : float, optional
        Sample period ``T`` [s].
    grasp : Grasp, optional
        The human grasp at the handle (hands-off by default).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate; ``None`` for the backward difference.
    directions : int, optional
        Directions of the dense check at each point (over the half circle), 2 to 3600.
    k_range : tuple of (float, float), optional
        The scanned ``k`` [N/m], ``(low, high)``.
    method : str, optional
        ``"loci"`` (default): the crossings from the wall-free loop's frequency response, certified
        on the exact loop (:func:`analysis.multidof.loci.frequency_first_crossings`); ``"scan"``:
        the geometric scan and bisection of every wall
        (:func:`analysis.multidof.limits.first_crossings`).  Both give the stable end of a
        bracket of relative width 1e-12 of the exact loop.
    zwidth_b : array_like or None, optional
        Wall dampings [N s/m] (at least two, increasing) of the third layer: the 1-DOF Z-width
        area along each point's worst normal (:attr:`WorkspaceMap.zwidth_area`); ``None``
        (default) leaves it out.  It costs one :func:`analysis.sampled.zwidth_region` a point.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` after each grid row's devices, after the crossings of
        every wall, after the refinement of the worst point and after each point's Z-width area
        (the one protocol of :mod:`analysis.progress`).
    cancelled : Cancelled or None, optional
        Polled between those steps; true stops the map.

    Returns
    -------
    WorkspaceMap or None
        The maps and the design bound; ``None`` once cancelled.

    Raises
    ------
    ValidationError
        When no grid point is reachable, the grid has more than 160000 points, the method is
        unknown, or an argument is out of range.
    """
    xs = np.asarray(x, dtype=float).reshape(-1)
    ys = np.asarray(y, dtype=float).reshape(-1)
    if xs.size * ys.size > 160_000:
        raise ValidationError("x, y", "at most 160000 grid points", xs.size * ys.size)
    b = nonnegative("damping", damping, "N s/m")
    D = integer("directions", directions, 2, 3600)
    if method not in METHODS:
        raise ValidationError("method", " or ".join(repr(m) for m in METHODS), method)
    dirs = check_directions(2, D)
    shapes = np.concatenate([np.eye(2)[None], dirs[:, :, None] * dirs[:, None, :]])
    total = ys.size + 2 + (xs.size * ys.size if zwidth_b is not None else 0)
    devices, points = [], []
    for j, yv in enumerate(ys):
        check_cancelled(cancelled)
        for i, xv in enumerate(xs):
            try:
                devices.append(five_bar_device(linkage, (xv, yv), sample_time))
            except ValidationError:
                continue
            points.append((j, i))
        report_progress(progress, j + 1, total)
    check_cancelled(cancelled)
    if not devices:
        raise ValidationError("x, y", "a grid with at least one reachable, non-singular position", "none")
    if method == "loci":
        ks, _ = frequency_first_crossings(devices, shapes, b, delay_samples, grasp, velocity_filter, k_range)
    else:
        ks = first_crossings(*_pencils(devices, shapes, b, delay_samples, grasp, velocity_filter), k_range)
    ks = ks.reshape(len(devices), D + 1)
    report_progress(progress, ys.size + 1, total)
    check_cancelled(cancelled)
    shape = (ys.size, xs.size)
    reachable = np.zeros(shape, dtype=bool)
    k_iso, k_worst = np.full(shape, math.nan), np.full(shape, math.nan)
    normal = np.full(shape + (2,), math.nan)
    for (j, i), row in zip(points, ks):
        reachable[j, i] = True
        k_iso[j, i] = row[0]
        w = int(np.argmin(row[1:]))
        k_worst[j, i], normal[j, i] = row[1 + w], dirs[w]
    j, i = np.unravel_index(int(np.nanargmin(k_worst)), shape)
    refined = worst_normal(five_bar_device(linkage, (xs[i], ys[j]), sample_time), b, delay_samples, grasp=grasp,
                           velocity_filter=velocity_filter, k_range=k_range, directions=max(D, 4))
    best_k, best_n = (refined.stiffness, refined.normal) if refined.stiffness < k_worst[j, i] else \
        (float(k_worst[j, i]), normal[j, i])
    minimum = WorkspaceMinimum(stiffness=float(best_k), position=np.array([xs[i], ys[j]]), normal=np.asarray(best_n))
    report_progress(progress, ys.size + 2, total)
    area, bz = None, None
    if zwidth_b is not None:
        area, bz = _zwidth_layer(devices, points, normal, zwidth_b, delay_samples, grasp, velocity_filter, k_range,
                                 lambda n: report_progress(progress, ys.size + 2 + n, total), cancelled)
        report_progress(progress, total, total)  # the unreachable points have no area to compute
    return WorkspaceMap(x=xs, y=ys, reachable=reachable, k_max=k_iso, worst_stiffness=k_worst, worst_normal=normal,
                        minimum=minimum, directions=D, zwidth_area=area, zwidth_b=bz)
