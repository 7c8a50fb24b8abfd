"""The optimum velocity filter, and hardware Z-width trials scored against the exact region.

Optimum filter
--------------
Chawda, Celik & O'Malley (ASME J. Dyn. Sys. Meas. Control 137(2), 024503, 2015) find that the
Z-width area of a haptic interface has a maximum over the cut-off of the velocity filter (the
finite difference followed by a low-pass).  :func:`optimal_filter` computes the area of the
exact region (:func:`~analysis.sampled.zwidth.zwidth_region`, :data:`OPTIMIZER_AREA` by default)
for each cut-off of a grid, takes the best, and refines it with a bounded scalar search in
``log(cut-off)`` between the grid neighbours of the best point (Brent's bounded method).  The
area is not unimodal in general (a flexible device shows several local maxima), so the grid
decides the basin and the refinement only polishes it.

Measured trials
---------------
Colgate & Brown (ICRA 1994) measured the Z-width point by point: a wall ``(B, K)`` is tried on
the hardware and judged stable or not.  :func:`load_trials` reads such a CSV with the one CSV reader
(:func:`analysis.csvtable.read_table`: UTF-8, a header row, blank lines and ``#`` comments
skipped): columns ``b`` and ``k`` (finite, >= 0) and ``stable`` (``1`` or ``0``, nothing else),
in any order, other columns ignored; every problem is a :class:`TrialsError` (a
:class:`~analysis.errors.ValidationError`) naming the file, the line and the column.  :func:`score_trials` compares each trial with the region
(:meth:`~analysis.sampled.zwidth.ZWidthRegion.k_limit`) and lists those the analysis gets wrong.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.chain.velocity_filter import FILTER_KINDS, VelocityFilter, highest_cutoff
from analysis.checks import choice
from analysis.csvtable import CsvError, read_table
from analysis.errors import ValidationError
from analysis.sampled.velocity_noise import DEFAULT_FORCE_NOISE, noise_limited_damping
from analysis.sampled.zwidth import (
    OPTIMIZER_AREA,
    ZWidthRegion,
    check_b_values,
    noise_limited_stiffness,
    region_area,
)

__all__ = ["FilterOptimum", "optimal_filter", "MeasuredTrials", "TRIAL_COLUMNS", "STABLE_VALUES", "TrialsError",
           "load_trials", "TrialScore", "score_trials"]

#: The columns of a trials file (any order; other columns are ignored).
TRIAL_COLUMNS = ("b", "k", "stable")

_AREAS = ("area_linear", "area_log")


@dataclass(frozen=True)
class FilterOptimum:
    """The Z-width area against the filter cut-off (rad/s) and the maximizing cut-off.

    ``areas[i]`` belongs to ``cutoffs[i]``; ``cutoff``/``area`` is the refined optimum;
    ``backward_area`` is the area with the raw backward difference, for comparison;
    ``measure`` names the area maximized (``"area_linear"`` or ``"area_log"``);
    ``encoder_resolution`` (m) and ``force_noise`` (N rms) are the noise criterion's
    (:mod:`analysis.sampled.velocity_noise`; ``None`` when off).

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
        The area with the raw backward difference.
    measure : str
        ``"area_linear"`` [N^2 s/m^2] or ``"area_log"`` [decades^2].
    encoder_resolution : float or None, optional
        Encoder resolution [m] of the noise criterion; ``None`` when off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` when off.
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

    @property
    def interior(self) -> bool:
        """True when the optimum lies strictly inside the cut-off grid (Chawda et al.'s shape)."""
        return bool(self.cutoffs[0] < self.cutoff < self.cutoffs[-1] and self.area > self.backward_area)


def optimal_filter(device: Device, kind: str = "lowpass1", cutoffs: np.ndarray | None = None, *,
                   b: np.ndarray | None = None, delay_samples: int = 0, measure: str = OPTIMIZER_AREA,
                   k_range: tuple[float, float] = (1.0, 1e9), refine_iterations: int = 6, per_decade: int = 12,
                   progress: Callable[[int, int], None] | None = None,
                   cancelled: Callable[[], bool] | None = None, encoder_resolution: float | None = None,
                   force_noise: float | None = None, **region_options) -> FilterOptimum | None:
    """Area of the Z-width region against the cut-off of a ``kind`` filter, and its maximum.

    Default cut-offs: 30 from 2 pi 5 rad/s to 0.9 of Nyquist.  ``progress(done, total)`` after
    each region (``total`` = grid + refinement budget); ``None`` once ``cancelled()`` is true.
    ``per_decade`` is the K scan resolution of each region (12 here, half of
    :func:`~analysis.sampled.zwidth.zwidth_region`'s 24, for speed: an unstable window narrower
    than 10^(1/12), 21 %, below the first crossing could be missed; each K_max is bracketed to
    1e-5 relative, plenty for an area).
    ``region_options`` go to :func:`~analysis.sampled.zwidth.stiffness_limits` (termination ...).
    ``encoder_resolution`` (m) turns on the noise criterion of
    :func:`~analysis.sampled.zwidth.zwidth_region` (B above ``F_noise/sigma_v`` not renderable;
    ``force_noise`` N rms, default 0.1): the noise side of Chawda et al.'s trade-off.

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
    **region_options
        Keyword arguments of :func:`~analysis.sampled.zwidth.stiffness_limits`
        (``termination``, ``implementation_delay``).

    Returns
    -------
    FilterOptimum or None
        The areas and the optimum; ``None`` when cancelled.
    """
    choice("measure", measure, _AREAS, allowed=" or ".join(_AREAS))
    cs = _cutoffs(kind, cutoffs, device.sample_time)
    bs = check_b_values(b)
    total = cs.size + refine_iterations + 1
    noise_limited_damping(None, device.sample_time, encoder_resolution, force_noise)  # validate once

    def area(cutoff: float | None) -> float:
        vf = None if cutoff is None else VelocityFilter(kind, cutoff)
        bn = noise_limited_damping(vf, device.sample_time, encoder_resolution, force_noise)
        k = noise_limited_stiffness(device, bs, bn, delay_samples, vf, k_range=k_range, per_decade=per_decade,
                                    rtol=1e-5, **region_options)
        return region_area(bs, k, k_range[0], k_range[1])[_AREAS.index(measure)]

    areas = np.empty(cs.size)
    for i, c in enumerate(cs.tolist()):
        if cancelled is not None and cancelled():
            return None
        areas[i] = area(c)
        if progress is not None:
            progress(i + 1, total)
    best = _refine(area, cs, areas, refine_iterations, total, progress, cancelled)
    if best is None:
        return None
    back = area(None)
    if progress is not None:
        progress(total, total)
    fn = None if encoder_resolution is None else DEFAULT_FORCE_NOISE if force_noise is None else float(force_noise)
    return FilterOptimum(kind=kind, cutoffs=cs, areas=areas, cutoff=best[0], area=best[1], backward_area=back,
                         measure=measure, encoder_resolution=None if encoder_resolution is None
                         else float(encoder_resolution), force_noise=fn)


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
            progress: Callable[[int, int], None] | None,
            cancelled: Callable[[], bool] | None) -> tuple[float, float] | None:
    """Brent's bounded search in log(cut-off) between the grid neighbours of the best point."""
    j = int(np.argmax(areas))
    best_c, best_a = float(cs[j]), float(areas[j])
    lo, hi = math.log(cs[max(j - 1, 0)]), math.log(cs[min(j + 1, cs.size - 1)])
    calls = [cs.size]

    def neg(x: float) -> float:
        if cancelled is not None and cancelled():
            raise _Cancelled
        calls[0] += 1
        if progress is not None:
            progress(min(calls[0], total - 1), total)
        return -area(math.exp(x))

    try:
        r = optimize.minimize_scalar(neg, bounds=(lo, hi), method="bounded",
                                     options={"maxiter": iterations, "xatol": 5e-3})
    except _Cancelled:
        return None
    if -r.fun > best_a:
        best_c, best_a = math.exp(float(r.x)), float(-r.fun)
    return best_c, best_a


class _Cancelled(Exception):
    """Raised inside the refinement when ``cancelled()`` turns true."""


@dataclass(frozen=True)
class MeasuredTrials:
    """Hardware trials: wall damping ``b`` (N s/m), stiffness ``k`` (N/m), ``stable`` flags, file lines.

    Parameters
    ----------
    path : str
        The CSV file read.
    b : numpy.ndarray
        Wall damping of each trial [N s/m], shape (M,).
    k : numpy.ndarray
        Wall stiffness of each trial [N/m], shape (M,).
    stable : numpy.ndarray
        Whether each trial was stable, bool, shape (M,).
    lines : numpy.ndarray
        File line of each trial, shape (M,).
    """

    path: str
    b: np.ndarray
    k: np.ndarray
    stable: np.ndarray
    lines: np.ndarray

    def __len__(self) -> int:
        return int(self.b.size)


class TrialsError(CsvError, ValidationError):
    """A trials file that cannot be used: a :class:`~analysis.csvtable.CsvError` (``file``, ``line``,
    ``column``, ``reason``) that is also a :class:`~analysis.errors.ValidationError` (``field`` is
    the place, ``allowed`` the reason), so that every caller of a validation error shows it."""

    def __init__(self, reason: str, *, file: str | os.PathLike | None = None, line: int | None = None,
                 column: str | None = None):
        CsvError.__init__(self, reason, file=file, line=line, column=column)
        self.field, self.allowed, self.value, self.index, self.within = self.where, reason, None, None, ()


#: The spellings of the ``stable`` column (the guide: "stable (1 or 0)").
STABLE_VALUES = {"1": 1.0, "0": 0.0}


def load_trials(path: str | os.PathLike) -> MeasuredTrials:
    """Read a CSV of trials (module docstring) with :func:`analysis.csvtable.read_table`.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file (relative paths: to the working directory; a profile's is resolved by
        :func:`analysis.study.profile_trials`).

    Returns
    -------
    MeasuredTrials
        The trials in file order, with the file line of each.

    Raises
    ------
    TrialsError
        For every fault, naming the file, the line and the column (a
        :class:`~analysis.errors.ValidationError`).
    """
    t = read_table(path, TRIAL_COLUMNS, required=TRIAL_COLUMNS, other_columns=True,
                   choices={"stable": STABLE_VALUES}, error=TrialsError)
    if not len(t):
        raise t.fail("a header only: at least one trial row is needed")
    for col in ("b", "k"):
        bad = np.flatnonzero(t.columns[col] < 0)
        if bad.size:
            raise t.fail(f"{t.columns[col][bad[0]]!r} is negative: must be >= 0", int(bad[0]), col)
    return MeasuredTrials(path=t.path, b=t.columns["b"], k=t.columns["k"], stable=t.columns["stable"] == 1.0,
                          lines=t.lines)


@dataclass(frozen=True)
class TrialScore:
    """Trials against a region: ``predicted`` stable flags, ``wrong`` indices (analysis disagrees),
    ``outside`` indices (B outside the region's range: not scored).

    Parameters
    ----------
    predicted : numpy.ndarray
        Predicted stable flag of each trial, bool, shape (M,) (False outside the range).
    wrong : numpy.ndarray
        Indices of the scored trials where prediction and measurement disagree.
    outside : numpy.ndarray
        Indices of the trials whose B is outside the region's range.
    scored : int
        Number of trials scored (inside the range).
    """

    predicted: np.ndarray
    wrong: np.ndarray
    outside: np.ndarray
    scored: int

    @property
    def wrong_count(self) -> int:
        return int(self.wrong.size)

    def describe(self, trials: MeasuredTrials) -> list[str]:
        """One line per wrong trial: file line, (B, K), measured and predicted.

        Parameters
        ----------
        trials : MeasuredTrials
            The trials that were scored.

        Returns
        -------
        list of str
            One line per index of ``wrong``.
        """
        word = {True: "stable", False: "unstable"}
        return [f"line {trials.lines[i]}: B = {trials.b[i]:.4g} N s/m, K = {trials.k[i]:.4g} N/m measured "
                f"{word[bool(trials.stable[i])]}, predicted {word[bool(self.predicted[i])]}" for i in self.wrong]


def score_trials(region: ZWidthRegion, trials: MeasuredTrials) -> TrialScore:
    """Predicted stable iff ``k <= K_max(b)`` of the region (interpolated in log B).

    Parameters
    ----------
    region : ZWidthRegion
        The exact region.
    trials : MeasuredTrials
        The hardware trials.

    Returns
    -------
    TrialScore
        The predictions and the disagreements.
    """
    lim = region.k_limit(trials.b)
    outside = np.isnan(lim)
    predicted = np.where(outside, False, trials.k <= np.nan_to_num(lim, nan=0.0))
    wrong = np.flatnonzero(~outside & (predicted != trials.stable))
    return TrialScore(predicted=predicted, wrong=wrong, outside=np.flatnonzero(outside),
                      scored=int(np.count_nonzero(~outside)))
