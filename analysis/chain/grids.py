"""Frequency grids that do not miss resonant peaks, and local refinement of extrema.

A plain log grid misses the narrow peaks of a lightly damped device (see the design notes:
with damping ratio 0.002 a 100-point grid over-reports the largest coupling stiffness by
587 %).  The device model tells where the peaks are: the undamped modes of the chain under
the relevant boundary conditions, mapped through the Tustin warp
``w = (2/T) arctan(W T / 2)``.  :func:`resonance_grid` clusters points geometrically around
each mapped mode (down to a relative offset of 1e-7), and :func:`refine_minima` zooms in on
every local minimum of a sampled function with vectorized bracketing passes.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from analysis.chain.device import Device

__all__ = ["warp", "log_grid", "resonance_grid", "refine_minima", "device_modes", "band_edges"]

# relative offsets of the points clustered around each resonance
# (the exact mode is left out: on a lossless chain it is a pole, where responses are infinite)
_OFFSETS = np.geomspace(1e-7, 0.3, 24)
_OFFSETS = np.concatenate([-_OFFSETS[::-1], _OFFSETS])


def warp(omega_continuous: np.ndarray, sample_time: float) -> np.ndarray:
    """Discrete frequency whose Tustin image is ``j * omega_continuous``.

    ``w = (2/T) arctan(W T / 2)``, the inverse of :func:`analysis.chain.discretize.tustin_image`.

    Parameters
    ----------
    omega_continuous : array_like
        Continuous-time angular frequencies ``W`` [rad/s], any shape.
    sample_time : float
        Sample period ``T`` [s].

    Returns
    -------
    numpy.ndarray
        Discrete angular frequencies [rad/s] in ``[0, pi/T)``, same shape.
    """
    return (2.0 / sample_time) * np.arctan(0.5 * np.asarray(omega_continuous, float) * sample_time)


def band_edges(device: Device) -> tuple[float, float]:
    """``[band_min, Nyquist)``: the upper edge is the largest double below Nyquist used.

    Parameters
    ----------
    device : Device
        The device (its ``band_min`` and sample period).

    Returns
    -------
    lo, hi : float
        The band's edges [rad/s]: ``band_min`` and ``pi/T (1 - 1e-9)``.
    """
    return device.band_min, device.nyquist * (1.0 - 1e-9)


def log_grid(device: Device, points: int) -> np.ndarray:
    """Plain logarithmic grid over the analysis band.

    Parameters
    ----------
    device : Device
        The device whose band (:func:`band_edges`) is covered.
    points : int
        Number of grid points.

    Returns
    -------
    numpy.ndarray
        Angular frequencies [rad/s], geometrically spaced, shape (points,).
    """
    lo, hi = band_edges(device)
    return np.geomspace(lo, hi, points)


def device_modes(device: Device, actuator_stiffness: float = 0.0) -> np.ndarray:
    """Undamped modes (continuous rad/s) that shape the two-port bounds.

    Free chain (poles of y), handle clamped and actuator clamped (zeros of the driving-point
    admittances), and with ``actuator_stiffness`` to ground at the actuator (the position
    loop of an admittance display), with and without the handle clamped.

    Parameters
    ----------
    device : Device
        The chain.
    actuator_stiffness : float, optional
        Stiffness to ground at the actuator [N/m]; 0 leaves those mode sets out.

    Returns
    -------
    numpy.ndarray
        The sorted, unique undamped modes [rad/s] of every boundary condition, shape (M,);
        empty for a single mass.
    """
    n = device.n
    if n < 2:
        return np.zeros(0)
    sets = [device.undamped_modes(), device.undamped_modes(clamp=(0,)), device.undamped_modes(clamp=(n - 1,))]
    if actuator_stiffness > 0:
        sets.append(device.undamped_modes(extra_stiffness={n - 1: actuator_stiffness}))
        sets.append(device.undamped_modes(extra_stiffness={n - 1: actuator_stiffness}, clamp=(0,)))
    if n > 2:
        se = device.sensor_element
        sets.append(device.undamped_modes(clamp=(se,)))
        sets.append(device.undamped_modes(clamp=(se + 1,)))
    return np.unique(np.concatenate(sets))


def resonance_grid(device: Device, modes: np.ndarray, base_points: int = 300, max_modes: int = 40) -> np.ndarray:
    """Log grid plus geometric clusters on each mode mapped through the Tustin warp.

    At most ``max_modes`` modes are clustered (the lowest ones; higher modes of long chains
    are covered by the base grid and refinement).  Roughly ``base_points + 49 * modes``
    points, all inside the band, sorted and unique.

    Parameters
    ----------
    device : Device
        The device (band and sample period).
    modes : array_like
        Continuous-time modes [rad/s], ascending (for example :func:`device_modes`).
    base_points : int, optional
        Points of the underlying log grid.
    max_modes : int, optional
        Most modes that get a cluster.

    Returns
    -------
    numpy.ndarray
        Angular frequencies [rad/s], sorted and unique, shape (N,).
    """
    lo, hi = band_edges(device)
    parts = [np.geomspace(lo, hi, base_points)]
    wm = warp(np.asarray(modes, float)[:max_modes], device.sample_time)
    wm = wm[(wm > lo) & (wm < hi)]
    if wm.size:
        parts.append((wm[:, None] * (1.0 + _OFFSETS[None, :])).ravel())
    w = np.concatenate(parts)
    w = w[(w >= lo) & (w <= hi)]
    return np.unique(w)


def _lowest_local_minima(vv: np.ndarray, candidates: int) -> np.ndarray:
    """Indices of the ``candidates`` lowest finite local minima of ``vv`` (NaN read as inf), lowest first."""
    left = np.concatenate([[np.inf], vv[:-1]])
    right = np.concatenate([vv[1:], [np.inf]])
    is_min = (vv <= left) & (vv <= right) & np.isfinite(vv)  # an infinite plateau cannot be refined
    idx = np.flatnonzero(is_min)
    return idx[np.argsort(vv[idx])][:candidates]


def _shrink_brackets(sw: np.ndarray, best_w: np.ndarray, a: np.ndarray, b: np.ndarray, lo: float,
                     hi: float) -> tuple[np.ndarray, np.ndarray]:
    """New brackets: the nearest *distinct* neighbours of the best point among the sorted ``sw``.

    An interior point may coincide with the previous best (exactly, or to an ulp after
    exp/log); taking index neighbours would then collapse the bracket onto ``best_w`` and lose
    the side holding the minimum.  Points closer than 1e-3 of the bracket width count as equal.
    """
    eps = (1e-3 * (b - a))[:, None]
    below = np.where(sw < best_w[:, None] - eps, sw, sw[:, :1]).max(axis=1)
    above = np.where(sw > best_w[:, None] + eps, sw, sw[:, -1:]).min(axis=1)
    return np.maximum(below, lo), np.minimum(above, hi)


def refine_minima(
    func: Callable[[np.ndarray], np.ndarray],
    w: np.ndarray,
    values: np.ndarray,
    lo: float,
    hi: float,
    candidates: int = 8,
    rtol: float = 1e-11,
    points: int = 8,
    max_passes: int = 40,
) -> tuple[np.ndarray, np.ndarray]:
    """Refine the ``candidates`` lowest local minima of ``values`` sampled at sorted ``w``.

    ``func`` maps a frequency array to values (vectorized).  Each pass evaluates ``points``
    interior points in every bracket at once and shrinks the bracket to the two
    neighbours of the best point, until the relative bracket width is below ``rtol``.
    Returns the refined frequencies and values (one per candidate), best first.

    Parameters
    ----------
    func : callable
        Vectorized map from angular frequencies [rad/s] (shape (M,)) to real values
        (shape (M,)); NaN reads as +inf.
    w : numpy.ndarray
        Sorted angular frequencies [rad/s] of the samples, shape (N,).
    values : numpy.ndarray
        ``func`` at ``w``, shape (N,).
    lo, hi : float
        Limits of the brackets [rad/s] (the band's edges).
    candidates : int, optional
        Number of lowest local minima refined.
    rtol : float, optional
        Relative bracket width at which a minimum counts as converged.
    points : int, optional
        Interior points evaluated per bracket and pass.
    max_passes : int, optional
        Most passes.

    Returns
    -------
    w_min : numpy.ndarray
        Refined frequencies [rad/s], shape (c,) with ``c <= candidates``, best first.
    v_min : numpy.ndarray
        ``func`` at ``w_min`` (NaN replaced by inf), shape (c,).
    """
    w = np.asarray(w, float)
    v = np.asarray(values, float)
    nw = w.size
    if nw == 0:
        return w, v
    vv = np.where(np.isnan(v), np.inf, v)
    idx = _lowest_local_minima(vv, candidates)
    if idx.size == 0:
        return w[:0], v[:0]
    a = np.where(idx > 0, w[np.maximum(idx - 1, 0)], lo)
    b = np.where(idx < nw - 1, w[np.minimum(idx + 1, nw - 1)], hi)
    best_w = w[idx].copy()
    best_v = vv[idx].copy()
    frac = np.linspace(0.0, 1.0, points + 2)[1:-1]
    rows = np.arange(idx.size)
    for _ in range(max_passes):
        if np.all((b - a) <= rtol * best_w):
            break
        # geometric interior points (brackets may span decades on the base grid)
        la, lb = np.log(a), np.log(b)
        pts = np.exp(la[:, None] + (lb - la)[:, None] * frac[None, :])
        pv = np.asarray(func(pts.ravel()), float).reshape(pts.shape)
        pv = np.where(np.isnan(pv), np.inf, pv)
        # all known points of each bracket; the ends count as +inf so the best is interior
        allw = np.concatenate([a[:, None], pts, b[:, None], best_w[:, None]], axis=1)
        allv = np.concatenate([np.full((idx.size, 1), np.inf), pv, np.full((idx.size, 1), np.inf),
                               best_v[:, None]], axis=1)
        order = np.argsort(allw, axis=1, kind="stable")
        sw = np.take_along_axis(allw, order, axis=1)
        sv = np.take_along_axis(allv, order, axis=1)
        j = np.argmin(sv, axis=1)
        best_w = sw[rows, j]
        best_v = sv[rows, j]
        a, b = _shrink_brackets(sw, best_w, a, b, lo, hi)
    order = np.argsort(best_v)
    return best_w[order], best_v[order]
