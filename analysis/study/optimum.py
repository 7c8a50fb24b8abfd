"""The optimum velocity filter of a profile, against no filter and the profile's own (issue 22).

The area of the (B, K) region against the cut-off and its maximum follow Chawda, Celik &
O'Malley (ASME JDSMC 137(2), 2015) (:func:`analysis.sampled.optimal_filter`), with the region of
:mod:`analysis.study.zwidth` (the profile's B grid, delays and noise criterion).  The optimum is
compared with no filter and with the profile's own filter by the same criterion -- the area, or
the noise-limited area when the controller section sets an encoder resolution -- and offered
only when it beats the design (:attr:`analysis.sampled.FilterOptimum.offer`).
:func:`optimum_verdict` is the one sentence that the Z-width tab, the CLI's export and the
report print.
"""

from __future__ import annotations

import dataclasses
import threading
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from analysis.chain.velocity_filter import FILTER_KINDS, VelocityFilter
from analysis.profiles.model import Profile
from analysis.progress import Cancelled, Progress, report_progress
from analysis.sampled import FilterOptimum, filter_area, optimal_filter
from analysis.study.displays import profile_filter
from analysis.study.quantities import format_number
from analysis.study.zwidth import ZWidthRequest, controller_section

__all__ = ["OPTIMUM_CUTOFFS", "OptimumRequest", "filter_optimum", "optimum_kind", "optimum_verdict"]

#: Number of cut-offs of the optimum curve (issue 15: 30 in <= 10 s on the worker).
OPTIMUM_CUTOFFS = 30


@dataclass(frozen=True)
class OptimumRequest:
    """What the optimum cut-off depends on: the region's request without its filter (the cut-off is
    swept), the filter kind optimized, the cut-offs (``None``: the default grid) and the profile's
    own filter (``current``, whose area the optimum is compared with).

    Attributes
    ----------
    region : ZWidthRequest
        The region's request, without its velocity filter.
    kind : str
        The filter kind whose cut-off is optimized, e.g. ``"lowpass1"``.
    cutoffs : tuple of float or None
        The cut-offs [rad/s]; ``None`` for the default grid.
    current : VelocityFilter or None
        The profile's own filter; ``None`` for the backward difference.
    """

    region: ZWidthRequest
    kind: str
    cutoffs: tuple[float, ...] | None = None
    current: VelocityFilter | None = None

    @classmethod
    def of(cls, profile: Profile, kind: str | None = None, cutoffs: np.ndarray | None = None) -> OptimumRequest:
        """The request of ``profile``'s region, for ``kind`` on ``cutoffs``.

        Parameters
        ----------
        profile : Profile
            The device profile.
        kind : str or None, optional
            The filter kind; ``None`` takes :func:`optimum_kind`.
        cutoffs : numpy.ndarray or None, optional
            The cut-offs [rad/s], shape (N,); ``None`` for the default grid.

        Returns
        -------
        OptimumRequest
            The request.
        """
        region = dataclasses.replace(ZWidthRequest.of(profile), velocity_filter=None)
        return cls(region, optimum_kind(profile) if kind is None else kind,
                   None if cutoffs is None else tuple(float(c) for c in cutoffs), profile_filter(profile))


def optimum_kind(profile: Profile) -> str:
    """The filter kind whose cut-off is optimized: the profile's, ``"lowpass1"`` for the backward difference.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    str
        The filter kind.
    """
    vf = controller_section(profile).velocity_filter
    return "lowpass1" if vf.is_backward else vf.kind


def filter_optimum(request: OptimumRequest | Profile, kind: str | None = None, *, cutoffs: np.ndarray | None = None,
                   progress: Progress | None = None, cancelled: Cancelled | None = None) -> FilterOptimum | None:
    """The region's linear area against the cut-off, the maximizing cut-off (Chawda et al.), and the
    areas without a filter and with the profile's filter, by the same criterion.

    The criterion is the noise-limited area when the controller section sets an encoder
    resolution, else the area (:class:`analysis.sampled.FilterOptimum`'s ``criterion``).  The
    default cut-offs are 30 from 5 Hz to 0.9 Nyquist; the default ``kind`` is :func:`optimum_kind`.
    The sweep over the cut-offs does not depend on the profile's own filter: the last four are
    kept, so a new cut-off costs one region (:func:`analysis.sampled.filter_area`, the same
    computation as the sweep's).

    Parameters
    ----------
    request : OptimumRequest or Profile
        The request, or a profile.
    kind : str or None, optional
        With a profile, the filter kind; ``None`` takes :func:`optimum_kind`.
    cutoffs : numpy.ndarray or None, optional
        With a profile, the cut-offs [rad/s], shape (N,); ``None`` for the default grid.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    FilterOptimum or None
        The areas against the cut-offs, the optimum and the offer (``offer``), or ``None`` once
        cancelled.
    """
    req = OptimumRequest.of(request, kind, cutoffs) if isinstance(request, Profile) else request
    r = req.region
    if cancelled is not None and cancelled():
        return None
    bare = dataclasses.replace(req, current=None)
    with _SWEEPS_LOCK:
        sweep = _SWEEPS.get(bare)
    if sweep is None:
        sweep = optimal_filter(r.device, req.kind, None if req.cutoffs is None else np.asarray(req.cutoffs), b=r.b,
                               delay_samples=r.delay_samples, implementation_delay=r.implementation_delay,
                               progress=progress, cancelled=cancelled, **r.noise)
        if sweep is None:
            return None
        with _SWEEPS_LOCK:
            _SWEEPS[bare] = sweep
            while len(_SWEEPS) > _SWEEPS_KEPT:
                _SWEEPS.popitem(last=False)
    cur = None if req.current is None or req.current.is_backward else req.current
    if cur is None:
        report_progress(progress, 1, 1)
        return sweep
    cur.check(r.device.sample_time)
    report_progress(progress, 0, 1)
    area = filter_area(r.device, cur, b=r.b, delay_samples=r.delay_samples,
                       implementation_delay=r.implementation_delay, **r.noise)
    report_progress(progress, 1, 1)
    return None if cancelled is not None and cancelled() else dataclasses.replace(sweep, current=cur,
                                                                                  current_area=area)


#: The last sweeps of :func:`filter_optimum` (the area against the cut-off), by request without the
#: current filter, so that a new cut-off of the profile costs one region, not the whole sweep.
_SWEEPS: OrderedDict[OptimumRequest, FilterOptimum] = OrderedDict()
_SWEEPS_KEPT = 4
_SWEEPS_LOCK = threading.Lock()


def _percent(new: float, old: float) -> str:
    """``new`` against ``old`` in per cent, signed (``+4.1 %``, ``-1.1 %``)."""
    if old <= 0.0:
        return "+∞ %" if new > 0.0 else "+0 %"
    g = new / old - 1.0
    return ("+" if g >= 0.0 else "") + format_number(g, 3, scale=100) + " %"


def optimum_verdict(opt: FilterOptimum) -> str:
    """The optimum's verdict, one plain sentence: what is best by the criterion and what it gains.

    No filter is best when no cut-off beats the unfiltered design (without encoder noise a
    filter only adds phase lag); the optimum cut-off otherwise, against no filter and the
    current filter; and whether there is anything to change (``opt.offer``).

    Parameters
    ----------
    opt : FilterOptimum
        The optimum (:func:`filter_optimum`).

    Returns
    -------
    str
        The sentence, in plain text (numbers by :func:`~analysis.study.quantities.format_number`).
    """
    hz = 1.0 / (2.0 * np.pi)
    unit = "N²·s/m²" if opt.measure == "area_linear" else "decades²"
    crit, best, cur = opt.criterion, opt.best, opt.current
    kind = FILTER_KINDS[opt.kind].split(" + ")[-1]  # "first-order low-pass", without the difference
    grid = f"{format_number(opt.cutoffs[0] * hz, 3)} to {format_number(opt.cutoffs[-1] * hz, 3)} Hz"
    now = None if cur is None or opt.current_area is None else (
        f"the current {FILTER_KINDS[cur.kind].split(' + ')[-1]} at {format_number(cur.cutoff * hz, 4)} Hz")
    if best.is_backward:
        why = ("a filter adds phase lag; without encoder noise nothing is gained" if not opt.noise_limited else
               "the filter's phase lag costs more than its noise reduction gains")
        text = (f"no {kind} cut-off from {grid} beats the unfiltered {crit} {format_number(opt.backward_area, 4)} "
                f"{unit} (the best, {format_number(opt.cutoff * hz, 4)} Hz, gives "
                f"{_percent(opt.area, opt.backward_area)})")
        if now is None:
            return f"No filter is best by the {crit}: {text}: {why}."
        if opt.offer is None:  # the current cut-off, off the grid, beats both: keep it
            return (f"Keep {now[len('the '):]}: it gives {_percent(opt.current_area, opt.backward_area)} against no "
                    f"filter, and {text}; nothing to change.")
        return (f"Remove the filter: {now} gives {_percent(opt.current_area, opt.backward_area)} against no "
                f"filter, and {text}: {why}.")
    text = (f"Optimum cut-off {format_number(opt.cutoff * hz, 4)} Hz ({kind}): {crit} "
            f"{format_number(opt.area, 4)} {unit}, {_percent(opt.area, opt.backward_area)} over no filter")
    if now is not None:
        text += f", {_percent(opt.area, opt.current_area)} over {now}"
    if opt.offer is None:
        text += "; the current filter is already as good: nothing to change"
    return text + "."
