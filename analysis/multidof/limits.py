"""The critical wall stiffness of a multi-DOF device, for a direction and for the worst one.

:func:`critical_wall_stiffness` is the largest stable ``k`` of the wall ``K_w = k S``,
``B_w = b S`` (:func:`analysis.multidof.loop.wall_shape`: isotropic, a plane wall of a given
normal, or a shape matrix) found as the 1-DOF :func:`analysis.sampled.critical_stiffness` is:
the first crossing of spectral radius 1 from small ``k`` (a geometric scan of 24 points per
decade, then Brent's method to a relative bracket of 1e-12, keeping the stable end;
:func:`analysis.sampled.sweeps.first_crossing`), on the exact MIMO loop of
:mod:`analysis.multidof.loop`.  Brent follows :func:`moving_radius`, which is stable exactly
where the spectral radius is but, unlike it, is not flat at 1 on the stable side (a plane wall
leaves the tangent directions free, their rigid-body modes at z = 1): about 10 evaluations a
crossing instead of 50.

:func:`worst_normal` is the plane wall whose normal gives the smallest critical stiffness:
a dense check of directions (the half circle in 2-D, a Fibonacci lattice of the half sphere in
3-D; ``n`` and ``-n`` are one wall), then a local optimization (bounded Brent in the angle in
2-D, Nelder-Mead in the two sphere angles in 3-D) from the best local minima of the check.
The result is the smallest stiffness of *every* direction evaluated, check and optimizer
together, so no direction that was evaluated is stiffer-limited than the one reported (the
conservative minimum), and :attr:`WorstNormal.stiffnesses` keeps the check.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import integer, nonnegative
from analysis.errors import ValidationError
from analysis.multidof.loop import wall_pencil, wall_shape
from analysis.multidof.model import DeviceLike, structural_model
from analysis.sampled.loop import RIGID_TOL, is_stable, spectral_radius
from analysis.sampled.sweeps import CROSSING_RTOL, first_crossing
from analysis.sampled.terminations import HANDS_OFF, Grasp

__all__ = ["critical_wall_stiffness", "worst_normal", "WorstNormal", "check_directions", "first_crossings",
           "narrow_brackets", "DEFAULT_DIRECTIONS", "PER_DECADE"]

#: Directions of the dense check of :func:`worst_normal` by number of axes (2-D: every 2.5 degrees).
DEFAULT_DIRECTIONS = {1: 1, 2: 72, 3: 256}
#: Points a decade of the scan of :func:`first_crossings` (the scan of :func:`analysis.sampled.critical_stiffness`).
PER_DECADE = 24
_REFINED = 3  # local minima of the check refined by the optimizer


@dataclass(frozen=True)
class WorstNormal:
    """The plane wall with the smallest critical stiffness, and the dense check behind it.

    Parameters
    ----------
    normal : numpy.ndarray
        The worst unit normal, shape (m,) (its sign is arbitrary: ``n`` and ``-n`` are one wall).
    stiffness : float
        Its critical stiffness [N/m]: the smallest of every direction evaluated.
    directions : numpy.ndarray
        The unit normals of the dense check, shape (D, m).
    stiffnesses : numpy.ndarray
        Their critical stiffnesses [N/m], shape (D,).
    evaluations : int
        Directions evaluated in all (check and optimizer).
    """

    normal: np.ndarray
    stiffness: float
    directions: np.ndarray
    stiffnesses: np.ndarray
    evaluations: int


def check_directions(axes: int, count: int) -> np.ndarray:
    """The unit normals of the dense check: ``count`` of them over the half circle or half sphere.

    Parameters
    ----------
    axes : int
        Number of Cartesian axes, 1 to 3.
    count : int
        Number of directions (1 for one axis).

    Returns
    -------
    numpy.ndarray
        Unit normals, shape (count, axes): equally spaced angles in ``[0, pi)`` in 2-D, a
        Fibonacci lattice of the upper half sphere in 3-D.

    Raises
    ------
    ValidationError
        When ``axes`` is not 1, 2 or 3.
    """
    if axes == 1:
        return np.ones((1, 1))
    if axes == 2:
        th = np.pi * np.arange(count) / count
        return np.column_stack([np.cos(th), np.sin(th)])
    if axes == 3:
        i = np.arange(count) + 0.5
        z = 1.0 - i / count  # uniform in z on (0, 1]: equal areas of the half sphere
        phi = math.pi * (3.0 - math.sqrt(5.0)) * i
        r = np.sqrt(1.0 - z * z)
        return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])
    raise ValidationError("axes", "1, 2 or 3 Cartesian axes for a worst normal", axes)


def check_k_range(k_range: tuple[float, float]) -> tuple[float, float]:
    """The searched wall-stiffness range ``(low, high)`` [N/m], checked: 0 < low < high < inf."""
    lo, hi = float(k_range[0]), float(k_range[1])
    if not 0 < lo < hi < math.inf:
        raise ValidationError("k_range", "0 < low < high < inf (N/m)", k_range)
    return lo, hi


def moving_radius(Phi: np.ndarray) -> np.ndarray:
    """Largest eigenvalue magnitude of each matrix's modes other than its rigid-body ones.

    The modes within ``RIGID_TOL`` of z = 1, which :func:`~analysis.sampled.loop.spectral_radius`
    counts as magnitude at most 1, are left out (0 where every mode is one).  So
    ``is_stable(moving_radius(Phi)) == is_stable(spectral_radius(Phi))`` for every matrix (a
    rigid-body mode is never unstable), while the spectral radius of a loop with free directions
    is 1 all over the stable side: a root finder on it sees a flat function there and halves its
    bracket, one on this one converges as on a smooth function.

    Parameters
    ----------
    Phi : numpy.ndarray
        Closed-loop state matrices, shape (..., N, N).

    Returns
    -------
    numpy.ndarray
        The radii, shape (...,).
    """
    ev = np.linalg.eigvals(Phi)
    return np.where(np.abs(ev - 1.0) < RIGID_TOL, 0.0, np.abs(ev)).max(axis=-1)


def _stiffness_function(device: DeviceLike, damping: float, delay_samples: int, grasp: Grasp,
                        velocity_filter: VelocityFilter | None,
                        k_range: tuple[float, float]) -> Callable[[object], float]:
    """``k_crit(normal)`` of one device and loop (normal as :func:`wall_shape` takes it)."""
    model = structural_model(device)
    b = nonnegative("damping", damping, "N s/m")
    lo, hi = check_k_range(k_range)

    def k_crit(normal: object) -> float:
        P0, P1 = wall_pencil(model, wall_shape(model.axes, normal), b, delay_samples, grasp, velocity_filter)

        def f(ks: np.ndarray) -> np.ndarray:  # the stability of spectral_radius, smooth for Brent
            return moving_radius(P0 + ks[:, None, None] * P1)

        return float(first_crossing(f, lo, hi, increasing=True))

    return k_crit


def first_crossings(P0: np.ndarray, P1: np.ndarray, k_range: tuple[float, float] = (1.0, 1e9),
                    rtol: float = CROSSING_RTOL) -> np.ndarray:
    """The first unstable ``k`` of many pencils ``P0 + k P1`` at once, keeping the stable end.

    The batched form of :func:`analysis.sampled.sweeps.first_crossing` for many walls or
    devices: the same geometric scan from ``k_range[0]`` (:data:`PER_DECADE` points a decade,
    a decade per batch, each pencil leaving the scan at its first unstable point), then the
    bracket of each pencil halved (geometrically) in one batch per step until its relative
    width is at most ``rtol``.  Bisection rather than Brent's method, because one batched
    eigenvalue computation per step serves every pencil; the result is, as there, a ``k``
    found stable, below every ``k`` of its pencil found unstable.

    Parameters
    ----------
    P0, P1 : numpy.ndarray
        Pencils, shapes (W, N, N) (:func:`~analysis.multidof.loop.wall_pencil`).
    k_range : tuple of (float, float), optional
        The scanned ``k`` [N/m], ``(low, high)``.
    rtol : float, optional
        Relative width of the final brackets.

    Returns
    -------
    numpy.ndarray
        The largest stable ``k`` of each pencil [N/m], shape (W,): ``inf`` when nothing below
        ``k_range[1]`` is unstable, ``0.0`` when ``k_range[0]`` already is.

    Raises
    ------
    ValidationError
        When the range is not ``0 < low < high < inf``.
    """
    lo, hi = check_k_range(k_range)
    W = P0.shape[0]
    n = max(int(math.ceil(PER_DECADE * math.log10(hi / lo))), 2) + 1
    grid = np.geomspace(lo, hi, n)
    out = np.full(W, math.inf)
    below = np.zeros(W)
    active = np.arange(W)
    bracket = np.zeros(W, dtype=bool)
    for start in range(0, n, PER_DECADE):
        if active.size == 0:
            break
        ks = grid[start:start + PER_DECADE]
        rho = spectral_radius(P0[active, None] + ks[None, :, None, None] * P1[active, None])
        bad = ~np.asarray(is_stable(rho))
        hit = bad.any(axis=1)
        j = start + np.argmax(bad, axis=1)
        done = active[hit]
        out[done] = grid[j[hit]]
        below[done] = np.where(j[hit] > 0, grid[np.maximum(j[hit] - 1, 0)], 0.0)
        bracket[done] = j[hit] > 0
        active = active[~hit]
    sel = np.flatnonzero(bracket)
    out[sel] = narrow_brackets(P0[sel], P1[sel], below[sel], out[sel], rtol)
    out[~bracket & np.isfinite(out)] = 0.0
    return out


def narrow_brackets(P0: np.ndarray, P1: np.ndarray, stable: np.ndarray, unstable: np.ndarray,
                    rtol: float = CROSSING_RTOL) -> np.ndarray:
    """Shrink brackets ``[stable, unstable]`` of pencils ``P0 + k P1`` by geometric bisection.

    One batched eigenvalue computation per step serves every pencil whose bracket is still
    wider than ``rtol`` (relative).

    Parameters
    ----------
    P0, P1 : numpy.ndarray
        Pencils, shapes (W, N, N).
    stable, unstable : numpy.ndarray
        A stable and an unstable ``k`` of each pencil [N/m], shapes (W,), ``0 < stable < unstable``.
    rtol : float, optional
        Relative width of the final brackets.

    Returns
    -------
    numpy.ndarray
        The stable end of each final bracket [N/m], shape (W,): found stable, within ``rtol``
        (relative) of a ``k`` found unstable.
    """
    a, u = np.array(stable, dtype=float), np.array(unstable, dtype=float)
    while a.size:
        idx = np.flatnonzero(u > a * (1.0 + rtol))
        if idx.size == 0:
            break
        mid = np.sqrt(a[idx] * u[idx])
        ok = np.asarray(is_stable(spectral_radius(P0[idx] + mid[:, None, None] * P1[idx])))
        a[idx] = np.where(ok, mid, a[idx])
        u[idx] = np.where(ok, u[idx], mid)
    return a


def critical_wall_stiffness(device: DeviceLike, damping: float = 0.0, delay_samples: int = 0, normal: object = None,
                            *, grasp: Grasp = HANDS_OFF, velocity_filter: VelocityFilter | None = None,
                            k_range: tuple[float, float] = (1.0, 1e9)) -> float:
    """Largest stable stiffness ``k`` [N/m] of a wall rendered in Cartesian space, exactly.

    The wall is ``K_w = k S``, ``B_w = damping S`` against the god-object (module docstring of
    :mod:`analysis.multidof.loop`).  With a chain :class:`~analysis.chain.device.Device` this is
    :func:`analysis.sampled.critical_stiffness` (hands-off, god-object wall).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    damping : float, optional
        Wall damping ``b`` [N s/m], at least 0.
    delay_samples : int, optional
        Computation delay in samples.
    normal : None, array_like of shape (m,) or (m, m), optional
        ``None`` for the isotropic wall, a normal vector for a plane wall, or a wall shape
        matrix (:func:`~analysis.multidof.loop.wall_shape`).
    grasp : Grasp, optional
        The human grasp at the handle (hands-off by default).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate of every axis; ``None`` for the backward difference.
    k_range : tuple of (float, float), optional
        The scanned ``k`` [N/m], ``(low, high)``.

    Returns
    -------
    float
        The largest stable ``k`` [N/m]; ``inf`` if none below ``k_range[1]`` is unstable,
        ``0.0`` if ``k_range[0]`` already is.

    Raises
    ------
    ValidationError
        When the damping is negative, the normal is zero or of the wrong size, the range is
        empty, or a setting of the loop is out of range.
    """
    return _stiffness_function(device, damping, delay_samples, grasp, velocity_filter, k_range)(normal)


def _angles(u: np.ndarray) -> np.ndarray:
    """Sphere angles (polar from +z, azimuth) of a unit normal."""
    return np.array([math.acos(max(-1.0, min(1.0, float(u[2])))), math.atan2(float(u[1]), float(u[0]))])


def _unit(axes: int, a: np.ndarray) -> np.ndarray:
    """The unit normal of an angle (2-D) or of sphere angles (3-D)."""
    if axes == 2:
        return np.array([math.cos(a[0]), math.sin(a[0])])
    s = math.sin(a[0])
    return np.array([s * math.cos(a[1]), s * math.sin(a[1]), math.cos(a[0])])


def _local_minima(values: np.ndarray, axes: int, dirs: np.ndarray) -> list[int]:
    """Indices of the check's best local minima (2-D: on the circle of normals; 3-D: the best values)."""
    finite = np.isfinite(values)
    if axes == 2:
        prev, nxt = np.roll(values, 1), np.roll(values, -1)
        idx = [int(i) for i in np.flatnonzero(finite & (values <= prev) & (values <= nxt))]
    else:
        idx = [int(i) for i in np.flatnonzero(finite)]
    return sorted(idx, key=lambda i: values[i])[:_REFINED]


def worst_normal(device: DeviceLike, damping: float = 0.0, delay_samples: int = 0, *, grasp: Grasp = HANDS_OFF,
                 velocity_filter: VelocityFilter | None = None, k_range: tuple[float, float] = (1.0, 1e9),
                 directions: int | None = None) -> WorstNormal:
    """The plane-wall normal with the smallest critical stiffness (module docstring).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device, 1 to 3 Cartesian axes.
    damping : float, optional
        Wall damping ``b`` [N s/m] along the normal, at least 0.
    delay_samples : int, optional
        Computation delay in samples.
    grasp : Grasp, optional
        The human grasp at the handle (hands-off by default).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate of every axis; ``None`` for the backward difference.
    k_range : tuple of (float, float), optional
        The scanned ``k`` [N/m], ``(low, high)``.
    directions : int or None, optional
        Directions of the dense check, 4 to 100000; ``None`` for :data:`DEFAULT_DIRECTIONS`.

    Returns
    -------
    WorstNormal
        The worst normal, its critical stiffness (the smallest of every direction evaluated)
        and the dense check.

    Raises
    ------
    ValidationError
        When the device has more than 3 axes, or an argument is out of range (as
        :func:`critical_wall_stiffness`).
    """
    model = structural_model(device)
    m = model.axes
    if m not in DEFAULT_DIRECTIONS:
        raise ValidationError("device", "a device of 1, 2 or 3 Cartesian axes for a worst normal", f"{m} axes")
    count = DEFAULT_DIRECTIONS[m] if directions is None or m == 1 else integer("directions", directions, 4, 100000)
    b = nonnegative("damping", damping, "N s/m")
    k_crit = _stiffness_function(model, b, delay_samples, grasp, velocity_filter, k_range)
    dirs = check_directions(m, count)
    P0, P1 = wall_pencil(model, dirs[:, :, None] * dirs[:, None, :], b, delay_samples, grasp, velocity_filter)
    ks = first_crossings(P0, P1, k_range)
    best_u, best_k = dirs[int(np.argmin(ks))], float(ks.min())
    evaluations = len(dirs)
    if m > 1:
        seen: list[tuple[float, np.ndarray]] = []

        def objective(a: np.ndarray) -> float:
            u = _unit(m, np.atleast_1d(a))
            k = k_crit(u)
            seen.append((k, u))
            return k

        step = math.pi / count if m == 2 else math.sqrt(2.0 * math.pi / count)
        for i in _local_minima(ks, m, dirs):
            if m == 2:
                th = math.atan2(dirs[i, 1], dirs[i, 0])
                optimize.minimize_scalar(objective, bounds=(th - step, th + step), method="bounded",
                                         options={"xatol": 1e-7})
            else:
                optimize.minimize(objective, _angles(dirs[i]), method="Nelder-Mead",
                                  options={"xatol": 1e-7, "fatol": 1e-10 * ks[i], "maxfev": 150,
                                           "initial_simplex": _angles(dirs[i]) + np.array([[0, 0], [step, 0],
                                                                                           [0, step]])})
        evaluations += len(seen)
        for k, u in seen:
            if k < best_k:
                best_k, best_u = k, u
    return WorstNormal(normal=np.asarray(best_u, dtype=float), stiffness=best_k, directions=dirs,
                       stiffnesses=ks, evaluations=evaluations)
