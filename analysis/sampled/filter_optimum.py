"""The optimum velocity filter: the cut-off that maximizes the Z-width area, against no filter.

Chawda, Celik & O'Malley (ASME J. Dyn. Sys. Meas. Control 137(2), 024503, 2015) find that the
Z-width area of a haptic interface has a maximum over the cut-off of the velocity filter (the
finite difference followed by a low-pass): a low cut-off costs phase lag, a high one lets the
encoder's quantization noise through.  :func:`optimal_filter` computes the area of the exact
region (:func:`~analysis.sampled.zwidth.zwidth_region`, :data:`OPTIMIZER_AREA` by default) for
each cut-off of a grid, takes the best, and refines it with a bounded scalar search in
``log(cut-off)`` between the grid neighbours of the best point (Brent's bounded method).  The
area is not unimodal in general (a flexible device shows several local maxima), so the grid
decides the basin and the refinement only polishes it.

The criterion.  Without encoder noise the region is the linear (delay-side) analysis alone: a
filter only adds phase lag, and on the bundled profiles no cut-off beats the backward difference
(the HBFD loses 1.1 %, Eom's device 8.0 %, the rigid mass 2.2 % at the best cut-off); a filter can
still win where the B range reaches past the backward difference's damping limit.  With
``encoder_resolution`` the criterion is the *noise-limited area* of
:func:`~analysis.sampled.zwidth.noise_limited_stiffness`: every B above ``F_noise/sigma_v``
(:func:`~analysis.sampled.velocity_noise.noise_limited_damping`) is not renderable, so the area
falls at high cut-offs too and has the interior optimum of Chawda et al.

The verdict.  :class:`FilterOptimum` carries the unfiltered design's area (``backward_area``) and,
when given, the current filter's (``current_area``), all by the same criterion.  ``best`` is the
better of no filter and the optimum cut-off; ``offer`` is ``best`` only when it beats the current
design by more than :data:`IMPROVEMENT_RTOL` (the precision of the areas), so following the
offer never makes the design worse by the criterion.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.chain.velocity_filter import BACKWARD, FILTER_KINDS, VelocityFilter, highest_cutoff
from analysis.checks import choice
from analysis.errors import ValidationError
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled.velocity_noise import DEFAULT_FORCE_NOISE, noise_limited_damping
from analysis.sampled.zwidth import OPTIMIZER_AREA, check_b_values, noise_limited_stiffness, region_area

__all__ = ["FilterOptimum", "optimal_filter", "filter_area", "IMPROVEMENT_RTOL"]

_AREAS = ("area_linear", "area_log")
#: The relative margin by which a design must beat another to be called better: ten times the
#: 1e-5 relative bracketing of each K_max, so that round-off never makes an offer.
IMPROVEMENT_RTOL = 1e-4


def _better(a: float, b: float) -> bool:
    """``a`` beats ``b`` by more than :data:`IMPROVEMENT_RTOL` (relative; any positive ``a`` beats 0)."""
    return a > b + IMPROVEMENT_RTOL * abs(b)


@dataclass(frozen=True)
class FilterOptimum:
    """The Z-width area against the filter cut-off (rad/s), the maximizing cut-off, and the verdict.

    ``areas[i]`` belongs to ``cutoffs[i]``; ``cutoff``/``area`` is the refined optimum over the
    cut-offs; ``backward_area`` is the area with the raw backward difference (no filter) and
    ``current_area`` the area with ``current``, the design's own filter, both by the same
    criterion (:attr:`criterion`); ``measure`` names the area maximized (``"area_linear"`` or
    ``"area_log"``); ``encoder_resolution`` (m) and ``force_noise`` (N rms) are the noise
    criterion's (:mod:`analysis.sampled.velocity_noise`; ``None`` when off).

    Parameters
    ----------
    kind : str
        The filter kind, ``"lowpass1"`` or ``"butter2"``.
    cutoffs : numpy.ndarray
        The cut-off grid [rad/s], increasing, shape (N,).
    areas : numpy.ndarray
        The area at each cut-off (in the unit of ``measure``), shape (N,).
    cutoff : float
        The refined maximizing cut-off [rad/s].
    area : float
        The area there.
    backward_area : float
        The area with the raw backward difference (no filter).
    measure : str
        ``"area_linear"`` [N^2 s/m^2] or ``"area_log"`` [decades^2].
    encoder_resolution : float or None, optional
        Encoder resolution [m] of the noise criterion; ``None`` when off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` when off.
    current : VelocityFilter or None, optional
        The design's own filter; ``None`` for the backward difference (or not given).
    current_area : float or None, optional
        The area with ``current``; ``None`` when ``current`` is ``None``.
    """

    kind: str
    cutoffs: np.ndarray
    areas: np.ndarray
    cutoff: float
    area: float
    backward_area: float
    measure: str
    encoder_resolution: float | None = None
    force_noise: float | None = None
    current: VelocityFilter | None = None
    current_area: float | None = None

    @property
    def interior(self) -> bool:
        """True when the optimum lies strictly inside the cut-off grid (Chawda et al.'s shape)."""
        return bool(self.cutoffs[0] < self.cutoff < self.cutoffs[-1] and self.area > self.backward_area)

    @property
    def noise_limited(self) -> bool:
        """True when the criterion is the noise-limited area (an encoder resolution is set)."""
        return self.encoder_resolution is not None

    @property
    def criterion(self) -> str:
        """The criterion's name: ``"noise-limited area"`` or ``"area"``."""
        return "noise-limited area" if self.noise_limited else "area"

    @property
    def baseline_area(self) -> float:
        """The current design's area: ``current_area``, or ``backward_area`` without a filter."""
        return self.backward_area if self.current is None or self.current_area is None else self.current_area

    @property
    def best(self) -> VelocityFilter:
        """The better design: the optimum cut-off when it beats no filter, else ``BACKWARD`` (no filter)."""
        return VelocityFilter(self.kind, self.cutoff) if _better(self.area, self.backward_area) else BACKWARD

    @property
    def best_area(self) -> float:
        """The area of :attr:`best`."""
        return self.backward_area if self.best.is_backward else self.area

    @property
    def offer(self) -> VelocityFilter | None:
        """The filter to offer: :attr:`best` when it beats the current design (``BACKWARD``: remove
        the filter), else ``None`` (nothing to gain)."""
        best = self.best
        if best.is_backward and self.current is None:
            return None
        return best if _better(self.best_area, self.baseline_area) else None


@none_if_cancelled
def optimal_filter(device: Device, kind: str = "lowpass1", cutoffs: np.ndarray | None = None, *,
                   b: np.ndarray | None = None, delay_samples: int = 0, measure: str = OPTIMIZER_AREA,
                   k_range: tuple[float, float] = (1.0, 1e9), refine_iterations: int = 6, per_decade: int = 12,
                   progress: Progress | None = None,
                   cancelled: Cancelled | None = None, encoder_resolution: float | None = None,
                   force_noise: float | None = None, current: VelocityFilter | None = None,
                   **region_options) -> FilterOptimum | None:
    """Area of the Z-width region against the cut-off of a ``kind`` filter, its maximum, and the
    areas of no filter and of the ``current`` filter by the same criterion.

    Default cut-offs: 30 from 2 pi 5 rad/s to 0.9 of Nyquist.  ``progress(done, total)`` after
    each region (``total`` = grid + refinement budget); ``None`` once ``cancelled()`` is true.
    ``per_decade`` is the K scan resolution of each region (12 here, half of
    :func:`~analysis.sampled.zwidth.zwidth_region`'s 24, for speed: an unstable window narrower
    than 10^(1/12), 21 %, below the first crossing could be missed; each K_max is bracketed to
    1e-5 relative, plenty for an area).
    ``region_options`` go to :func:`~analysis.sampled.zwidth.stiffness_limits` (termination ...).
    ``encoder_resolution`` (m) turns on the noise criterion of
    :func:`~analysis.sampled.zwidth.zwidth_region` (B above ``F_noise/sigma_v`` not renderable;
    ``force_noise`` N rms, default 0.1): the noise side of Chawda et al.'s trade-off, and the
    criterion with an interior optimum (module docstring).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    kind : str, optional
        The filter kind, ``"lowpass1"`` or ``"butter2"``.
    cutoffs : numpy.ndarray or None, optional
        At least three increasing cut-offs [rad/s] below Nyquist; ``None`` for the default 30.
    b : numpy.ndarray or None, optional
        Wall dampings B [N s/m] of each region; ``None`` for
        :data:`~analysis.sampled.zwidth.DEFAULT_B`.
    delay_samples : int, optional
        Computation delay in samples.
    measure : str, optional
        The area maximized, ``"area_linear"`` or ``"area_log"``.
    k_range : tuple of (float, float), optional
        The scanned K [N/m], ``(low, high)``.
    refine_iterations : int, optional
        Largest number of regions of the refinement.
    per_decade : int, optional
        The K scan resolution of each region [points per decade].
    progress : callable, optional
        ``progress(done, total)``, called after each region.
    cancelled : callable, optional
        ``cancelled() -> bool``, asked before each region.
    encoder_resolution : float or None, optional
        Encoder resolution [m] of the noise criterion; ``None`` turns it off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` for 0.1 (only with ``encoder_resolution``).
    current : VelocityFilter or None, optional
        The design's own filter, whose area is computed too (one more region); ``None`` or the
        backward difference: no filter.
    **region_options
        Keyword arguments of :func:`~analysis.sampled.zwidth.stiffness_limits`
        (``termination``, ``implementation_delay``).

    Returns
    -------
    FilterOptimum or None
        The areas, the optimum and the verdict; ``None`` when cancelled.
    """
    choice("measure", measure, _AREAS, allowed=" or ".join(_AREAS))
    cs = _cutoffs(kind, cutoffs, device.sample_time)
    bs = check_b_values(b)
    if current is not None and current.is_backward:
        current = None
    if current is not None:
        current.check(device.sample_time)
    total = cs.size + refine_iterations + 1 + (current is not None)
    noise_limited_damping(None, device.sample_time, encoder_resolution, force_noise)  # validate once

    def area(vf: VelocityFilter | None) -> float:
        return filter_area(device, vf, b=bs, delay_samples=delay_samples, measure=measure, k_range=k_range,
                           per_decade=per_decade, encoder_resolution=encoder_resolution, force_noise=force_noise,
                           **region_options)

    def cut_area(cutoff: float) -> float:
        return area(VelocityFilter(kind, cutoff))

    areas = np.empty(cs.size)
    for i, c in enumerate(cs.tolist()):
        check_cancelled(cancelled)
        areas[i] = cut_area(c)
        report_progress(progress, i + 1, total)
    best = _refine(cut_area, cs, areas, refine_iterations, total, progress, cancelled)
    check_cancelled(cancelled)
    back = area(None)
    check_cancelled(cancelled)
    now = None if current is None else area(current)
    report_progress(progress, total, total)
    fn = None if encoder_resolution is None else DEFAULT_FORCE_NOISE if force_noise is None else float(force_noise)
    return FilterOptimum(kind=kind, cutoffs=cs, areas=areas, cutoff=best[0], area=best[1], backward_area=back,
                         measure=measure, encoder_resolution=None if encoder_resolution is None
                         else float(encoder_resolution), force_noise=fn, current=current, current_area=now)


def filter_area(device: Device, velocity_filter: VelocityFilter | None, *, b: np.ndarray | None = None,
                delay_samples: int = 0, measure: str = OPTIMIZER_AREA, k_range: tuple[float, float] = (1.0, 1e9),
                per_decade: int = 12, encoder_resolution: float | None = None, force_noise: float | None = None,
                **region_options) -> float:
    """The criterion of :func:`optimal_filter` for one velocity filter: the (noise-limited) area.

    The one computation behind every area of a :class:`FilterOptimum` (the curve, the optimum, no
    filter and the current filter), so that areas computed apart compare exactly.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    velocity_filter : VelocityFilter or None
        The velocity estimate's filter; ``None`` for the backward difference.
    b : numpy.ndarray or None, optional
        Wall dampings B [N s/m]; ``None`` for :data:`~analysis.sampled.zwidth.DEFAULT_B`.
    delay_samples : int, optional
        Computation delay in samples.
    measure : str, optional
        ``"area_linear"`` [N^2 s/m^2] or ``"area_log"`` [decades^2].
    k_range : tuple of (float, float), optional
        The scanned K [N/m], ``(low, high)``.
    per_decade : int, optional
        The K scan resolution [points per decade].
    encoder_resolution : float or None, optional
        Encoder resolution [m] of the noise criterion; ``None`` turns it off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` for 0.1 (only with ``encoder_resolution``).
    **region_options
        Keyword arguments of :func:`~analysis.sampled.zwidth.stiffness_limits`.

    Returns
    -------
    float
        The area, in the unit of ``measure``.
    """
    choice("measure", measure, _AREAS, allowed=" or ".join(_AREAS))
    bs = check_b_values(b)
    bn = noise_limited_damping(velocity_filter, device.sample_time, encoder_resolution, force_noise)
    k = noise_limited_stiffness(device, bs, bn, delay_samples, velocity_filter, k_range=k_range,
                                per_decade=per_decade, rtol=1e-5, **region_options)
    return region_area(bs, k, k_range[0], k_range[1])[_AREAS.index(measure)]


def _cutoffs(kind: str, cutoffs: np.ndarray | None, T: float) -> np.ndarray:
    """The validated cut-off grid (default 30 from 2 pi 5 rad/s to 0.9 of Nyquist)."""
    choice("kind", kind, [k for k in FILTER_KINDS if k != "backward"], allowed="lowpass1 or butter2")
    if cutoffs is None:
        cutoffs = np.geomspace(2 * math.pi * 5, highest_cutoff(T), 30)
    cs = np.asarray(cutoffs, float).reshape(-1)
    for c in cs.tolist():
        VelocityFilter(kind, c).check(T)
    if cs.size < 3 or np.any(np.diff(cs) <= 0):
        raise ValidationError("cutoffs", "at least three increasing cut-offs (rad/s)", cutoffs)
    return cs


def _refine(area: Callable[[float], float], cs: np.ndarray, areas: np.ndarray, iterations: int, total: int,
            progress: Progress | None, cancelled: Cancelled | None) -> tuple[float, float]:
    """Brent's bounded search in log(cut-off) between the grid neighbours of the best point
    (raises :class:`~analysis.progress.OperationCancelled` once ``cancelled()`` is true)."""
    j = int(np.argmax(areas))
    best_c, best_a = float(cs[j]), float(areas[j])
    lo, hi = math.log(cs[max(j - 1, 0)]), math.log(cs[min(j + 1, cs.size - 1)])
    calls = [cs.size]

    def neg(x: float) -> float:
        check_cancelled(cancelled)
        calls[0] += 1
        report_progress(progress, min(calls[0], total - 1), total)
        return -area(math.exp(x))

    r = optimize.minimize_scalar(neg, bounds=(lo, hi), method="bounded",
                                 options={"maxiter": iterations, "xatol": 5e-3})
    if -r.fun > best_a:
        best_c, best_a = math.exp(float(r.x)), float(-r.fun)
    return best_c, best_a
