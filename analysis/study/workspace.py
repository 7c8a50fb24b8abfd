"""The workspace of a multi-DOF linkage (issue 25): the map, and the limits at the handle.

A profile's ``multidof`` section (:class:`~analysis.profiles.MultiDofSection`, its defaults without
one) gives a planar five-bar, a handle position, a wall (isotropic, or a plane wall along a
normal, with its damping) and a grid.  Two requests, two results; the GUI's graph nodes, the
command line (``zwidth workspace``) and the report build from them:

* :class:`WorkspaceRequest` -> :func:`workspace_study`: the :class:`~analysis.multidof.WorkspaceMap`
  of :func:`analysis.multidof.workspace_map` over the grid (the isotropic and the worst plane-wall
  critical stiffness at every point, the design bound with its position and normal).  It is
  computed in bands of grid rows, one :func:`~analysis.multidof.workspace_map` call each, for
  progress and cancel; the bands are joined exactly as one call over the grid would give them
  (:func:`join_bands`).  The handle is not part of the request: moving it recomputes no map.
* :class:`HandleRequest` -> :func:`workspace_point`: at the handle, the linearized device
  (:func:`analysis.multidof.five_bar_device`), its inertia ellipse (the eigen-decomposition of
  ``M_x``), the critical stiffness of a plane wall along every direction (the dense check of
  :func:`analysis.multidof.worst_normal`, whose worst normal it also gives), of the isotropic wall
  and of the profile's wall, and the linkage's joints for drawing.

The loop is the profile's: its sample period, velocity filter (controller section) and delay (the
simulation section's, plus one for its implementation delay, as :mod:`analysis.study.renderable`
counts it), hands-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.velocity_filter import VelocityFilter
from analysis.errors import ValidationError
from analysis.multidof import (
    DEFAULT_DIRECTIONS,
    WorkspaceMap,
    WorstNormal,
    critical_wall_stiffness,
    five_bar_device,
    workspace_map,
    worst_normal,
)
from analysis.profiles.model import Profile
from analysis.profiles.multidof import MultiDofSection
from analysis.progress import Cancelled, OperationCancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.study.displays import profile_filter
from analysis.study.requests import delays
from analysis.transparency.five_bar import FiveBar

__all__ = ["MAP_BANDS", "K_RANGE", "HandleRequest", "WorkspacePoint", "WorkspaceRequest", "handle_edits", "inertia_ellipse",
           "join_bands", "multidof_section", "polar_curve", "workspace_point", "workspace_study"]

#: The map is computed in at most this many bands of grid rows (one progress step each).
MAP_BANDS = 8
#: The wall stiffnesses the workspace scans [N/m], from 1 µN/m: a five-bar with little joint damping
#: renders only walls of a few mN/m near the edge of its workspace (the Colgate & Brown limit 2b/T of
#: its weakest direction), which the analysis's default range (1 N/m and up) reported as 0 N/m.
K_RANGE = (1e-6, 1e9)


def multidof_section(profile: Profile) -> MultiDofSection:
    """The profile's ``multidof`` section, or the default one (the default five-bar, isotropic wall).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    MultiDofSection
        The section.
    """
    return MultiDofSection() if profile.multidof is None else profile.multidof


def handle_edits(x: float, y: float) -> dict[str, float]:
    """The section's changes that move the handle to ``(x, y)`` [m] (one edit of the section).

    Parameters
    ----------
    x, y : float
        The handle's new position [m].

    Returns
    -------
    dict of str to float
        ``{"handle_x": x, "handle_y": y}``.
    """
    return {"handle_x": float(x), "handle_y": float(y)}


def _loop(profile: Profile) -> tuple[float, int, VelocityFilter | None]:
    d, implementation = delays(profile)
    return float(profile.device.sample_time), int(d) + int(implementation), profile_filter(profile)


@dataclass(frozen=True)
class WorkspaceRequest:
    """What the workspace map depends on (hashable: the graph's cache key).

    Attributes
    ----------
    linkage : FiveBar
        The linkage.
    x, y : tuple of float
        The grid [m].
    damping : float
        The wall's damping [N s/m].
    sample_time : float
        The sample period [s].
    delay_samples : int
        The loop's delay in samples.
    velocity_filter : VelocityFilter or None
        The velocity estimate; ``None`` for the backward difference.
    """

    linkage: FiveBar
    x: tuple[float, ...]
    y: tuple[float, ...]
    damping: float
    sample_time: float
    delay_samples: int
    velocity_filter: VelocityFilter | None

    @classmethod
    def of(cls, profile: Profile) -> WorkspaceRequest:
        """The request of ``profile``'s multidof section and loop.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        WorkspaceRequest
            The request.
        """
        s = multidof_section(profile)
        T, d, vf = _loop(profile)
        x = tuple(float(v) for v in np.linspace(s.x_min, s.x_max, s.x_points))
        y = tuple(float(v) for v in np.linspace(s.y_min, s.y_max, s.y_points))
        return cls(s.linkage, x, y, s.wall_damping, T, d, vf)


@dataclass(frozen=True)
class HandleRequest:
    """What the limits at the handle depend on (hashable).

    Attributes
    ----------
    linkage : FiveBar
        The linkage.
    position : tuple of (float, float)
        The handle [m].
    normal : tuple of (float, float) or None
        The profile's plane wall's unit normal; ``None`` for the isotropic wall.
    damping : float
        The wall's damping [N s/m].
    sample_time : float
        The sample period [s].
    delay_samples : int
        The loop's delay in samples.
    velocity_filter : VelocityFilter or None
        The velocity estimate.
    """

    linkage: FiveBar
    position: tuple[float, float]
    normal: tuple[float, float] | None
    damping: float
    sample_time: float
    delay_samples: int
    velocity_filter: VelocityFilter | None

    @classmethod
    def of(cls, profile: Profile) -> HandleRequest:
        """The request of ``profile``'s handle, wall and loop.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        HandleRequest
            The request.
        """
        s = multidof_section(profile)
        T, d, vf = _loop(profile)
        n = s.normal
        return cls(s.linkage, (s.handle_x, s.handle_y), None if n is None else (float(n[0]), float(n[1])),
                   s.wall_damping, T, d, vf)


def join_bands(bands: list[WorkspaceMap | None], x: np.ndarray, rows: list[np.ndarray]) -> WorkspaceMap:
    """One map from maps of consecutive bands of grid rows, as one call over the whole grid gives it.

    :func:`~analysis.multidof.workspace_map` takes its design bound at the first grid point (row
    major) of the smallest worst-normal stiffness and refines it there; that point lies in the first
    band whose smallest value is the grid's smallest, so that band's refined bound is the grid's.

    Parameters
    ----------
    bands : list of WorkspaceMap or None
        The maps of the bands, in row order; ``None`` for a band with no reachable point.
    x : numpy.ndarray
        The grid's abscissae [m].
    rows : list of numpy.ndarray
        The ordinates of each band [m].

    Returns
    -------
    WorkspaceMap
        The map of the whole grid.

    Raises
    ------
    ValidationError
        When no band has a reachable point.
    """
    found = [b for b in bands if b is not None]
    if not found:
        raise ValidationError("x, y", "a grid with at least one reachable, non-singular position", "none")
    best = found[0]
    for b in found[1:]:
        if np.nanmin(b.worst_stiffness) < np.nanmin(best.worst_stiffness):
            best = b

    def stack(name: str, fill: tuple[int, ...] = ()) -> np.ndarray:
        parts = []
        for b, ys in zip(bands, rows):
            if b is not None:
                parts.append(getattr(b, name))
            elif name == "reachable":
                parts.append(np.zeros((ys.size, x.size), dtype=bool))
            else:
                parts.append(np.full((ys.size, x.size) + fill, math.nan))
        return np.concatenate(parts, axis=0)

    return WorkspaceMap(x=np.asarray(x, float), y=np.concatenate(rows), reachable=stack("reachable"),
                        k_max=stack("k_max"), worst_stiffness=stack("worst_stiffness"),
                        worst_normal=stack("worst_normal", (2,)), minimum=best.minimum, directions=best.directions)


def _reaches(linkage: FiveBar, x: np.ndarray, ys: np.ndarray, sample_time: float) -> bool:
    for yv in ys:
        for xv in x:
            try:
                five_bar_device(linkage, (xv, yv), sample_time)
                return True
            except ValidationError:
                continue
    return False


@none_if_cancelled
def workspace_study(request: WorkspaceRequest | Profile, *, progress: Progress | None = None,
                    cancelled: Cancelled | None = None) -> WorkspaceMap | None:
    """The workspace map of a profile's linkage (module docstring), in bands of grid rows.

    Parameters
    ----------
    request : WorkspaceRequest or Profile
        The request, or a profile.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` after each band.
    cancelled : Cancelled or None, optional
        Polled between bands.

    Returns
    -------
    WorkspaceMap or None
        The map (as :func:`analysis.multidof.workspace_map` over the whole grid); ``None`` once
        cancelled.

    Raises
    ------
    ValidationError
        When no grid point is reachable.
    """
    req = request if isinstance(request, WorkspaceRequest) else WorkspaceRequest.of(request)
    x, y = np.asarray(req.x, float), np.asarray(req.y, float)
    rows = [r for r in np.array_split(y, min(MAP_BANDS, y.size)) if r.size]
    bands: list[WorkspaceMap | None] = []
    for i, ys in enumerate(rows):
        check_cancelled(cancelled)
        if _reaches(req.linkage, x, ys, req.sample_time):
            band = workspace_map(req.linkage, x, ys, req.damping, req.delay_samples, sample_time=req.sample_time,
                                 velocity_filter=req.velocity_filter, k_range=K_RANGE, cancelled=cancelled)
            if band is None:  # cancelled inside the band
                raise OperationCancelled("the workspace map was cancelled")
            bands.append(band)
        else:
            bands.append(None)
        report_progress(progress, i + 1, len(rows))
    return join_bands(bands, x, rows)


@dataclass(frozen=True)
class WorkspacePoint:
    """The device at the handle and its wall limits per direction.

    Attributes
    ----------
    position : numpy.ndarray
        The handle ``(x, y)`` [m].
    mass, damping : numpy.ndarray
        ``M_x`` [kg] and ``B_x`` [N s/m] at the handle, shape (2, 2).
    principal_masses : numpy.ndarray
        The eigenvalues of ``M_x`` [kg], ascending, shape (2,).
    principal_axes : numpy.ndarray
        Their unit eigenvectors as columns, shape (2, 2).
    angles : numpy.ndarray
        The plane wall normals' angles [rad] over the whole circle, shape (2D,).
    stiffness : numpy.ndarray
        The critical stiffness of the plane wall along each angle [N/m], shape (2D,) (``n`` and
        ``-n`` are one wall: the second half repeats the first).
    isotropic : float
        The critical stiffness of the isotropic wall [N/m].
    wall : float
        The critical stiffness of the profile's wall [N/m] (isotropic, or along its normal).
    normal : numpy.ndarray or None
        The profile's wall normal (unit), ``None`` for the isotropic wall.
    worst : WorstNormal
        The worst normal at the handle (:func:`analysis.multidof.worst_normal`).
    joints : numpy.ndarray
        The linkage's joints for drawing: left motor, left elbow, handle, right elbow, right
        motor [m], shape (5, 2).
    """

    position: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    principal_masses: np.ndarray
    principal_axes: np.ndarray
    angles: np.ndarray
    stiffness: np.ndarray
    isotropic: float
    wall: float
    normal: np.ndarray | None
    worst: WorstNormal
    joints: np.ndarray


def workspace_point(request: HandleRequest | Profile) -> WorkspacePoint:
    """The device at the handle, its inertia ellipse and its wall limits per direction.

    Parameters
    ----------
    request : HandleRequest or Profile
        The request, or a profile.

    Returns
    -------
    WorkspacePoint
        The limits at the handle.

    Raises
    ------
    ValidationError
        When the handle is outside the workspace or at a singular configuration (naming it).
    """
    req = request if isinstance(request, HandleRequest) else HandleRequest.of(request)
    p = np.asarray(req.position, float)
    dev = five_bar_device(req.linkage, p, req.sample_time)
    loop = dict(velocity_filter=req.velocity_filter, k_range=K_RANGE)
    worst = worst_normal(dev, req.damping, req.delay_samples, directions=DEFAULT_DIRECTIONS[2], **loop)
    theta = np.arctan2(worst.directions[:, 1], worst.directions[:, 0])
    iso = critical_wall_stiffness(dev, req.damping, req.delay_samples, None, **loop)
    wall = iso if req.normal is None else critical_wall_stiffness(dev, req.damping, req.delay_samples,
                                                                  np.asarray(req.normal), **loop)
    values, vectors = np.linalg.eigh(dev.mass)
    elbows = req.linkage.elbows(req.linkage.inverse_kinematics(p))
    bases = req.linkage.bases()
    joints = np.array([bases[0], elbows[0], p, elbows[1], bases[1]])
    return WorkspacePoint(position=p, mass=np.asarray(dev.mass), damping=np.asarray(dev.damping),
                          principal_masses=values, principal_axes=vectors,
                          angles=np.concatenate([theta, theta + math.pi]),
                          stiffness=np.concatenate([worst.stiffnesses, worst.stiffnesses]), isotropic=float(iso),
                          wall=float(wall), normal=None if req.normal is None else np.asarray(req.normal, float),
                          worst=worst, joints=joints)


def inertia_ellipse(point: WorkspacePoint, scale: float, count: int = 121) -> tuple[np.ndarray, np.ndarray]:
    """The inertia ellipse at the handle: semi-axes along ``M_x``'s eigenvectors, ``scale`` times its eigenvalues.

    Parameters
    ----------
    point : WorkspacePoint
        The limits at the handle.
    scale : float
        Metres drawn per kilogram of effective mass.
    count : int, optional
        Points of the closed curve.

    Returns
    -------
    x, y : numpy.ndarray
        The curve [m], centred on the handle, shape (count,) each.
    """
    t = np.linspace(0.0, 2.0 * math.pi, count)
    axes = point.principal_axes * (scale * point.principal_masses)[None, :]
    xy = point.position[:, None] + axes @ np.vstack([np.cos(t), np.sin(t)])
    return xy[0], xy[1]


def polar_curve(point: WorkspacePoint) -> tuple[np.ndarray, np.ndarray]:
    """The per-direction limits in polar form: ``x = k cos(theta)``, ``y = k sin(theta)`` [N/m], closed.

    Parameters
    ----------
    point : WorkspacePoint
        The limits at the handle.

    Returns
    -------
    x, y : numpy.ndarray
        The curve [N/m], shape (2D + 1,) each (inf drawn as NaN).
    """
    k = np.where(np.isfinite(point.stiffness), point.stiffness, math.nan)
    th = np.append(point.angles, point.angles[0] + 2.0 * math.pi)
    k = np.append(k, k[0])
    return k * np.cos(th), k * np.sin(th)
