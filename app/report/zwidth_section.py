"""The report's Z-width part (issue 15), when the profile has a ``controller`` section.

* :func:`zwidth_sections` (Qt-free, called by :func:`app.report.content.gather`): the velocity
  filter, the exact (B, K) region's areas (Colgate & Brown, ICRA 1994), the optimum cut-off
  (Chawda, Celik & O'Malley 2015) and the trials the analysis gets wrong, computed by
  :mod:`analysis.study.zwidth`;
* :func:`zwidth_figure` (needs Qt; a figure builder of :mod:`app.report.figures`): the app's own
  :class:`~app.views.zwidth_region_view.ZWidthRegionView` (``zwidth_region``) and
  :class:`~app.views.filter_optimum_view.FilterOptimumView` (``filter_optimum``).
"""

from __future__ import annotations

import html
import math
from typing import Any

from analysis.errors import ValidationError
from analysis.profiles.io import Profile
from analysis.study import (
    controller_section,
    filter_optimum,
    format_number,
    profile_trials,
    trial_score,
    region_wall,
    zwidth_region,
)

__all__ = ["FIGURE_KEYS", "zwidth_results", "zwidth_sections", "zwidth_figure"]

FIGURE_KEYS = ("zwidth_region", "filter_optimum")
_HZ = 1.0 / (2.0 * math.pi)


def zwidth_results(profile: Profile, res: dict) -> None:
    """Compute the region, the optimum and the scored trials into ``res`` (keys ``zwidth_*``).

    A trials file that cannot be read is reported in ``res["zwidth_trials_error"]``, not raised."""
    region = zwidth_region(profile)
    res["zwidth_region"] = region
    res["zwidth_optimum"] = filter_optimum(profile)
    try:
        trials = profile_trials(profile)
    except ValidationError as err:
        trials, res["zwidth_trials_error"] = None, str(err)
    res["zwidth_study"] = trial_score(region, trials)


def _row(numbers: dict, key: str, label: str, value: float, unit: str) -> Any:
    from app.report.content import Row

    text = format_number(value)
    numbers[key] = (value, text)
    return Row(label, "", text, unit)


def zwidth_sections(profile: Profile, res: dict, numbers: dict) -> list[Any]:
    """The report's section on the controller as built (empty without a ``controller`` section)."""
    from app.report.content import Section

    if profile.controller is None:
        return []
    zwidth_results(profile, res)
    sec, region, opt, study = controller_section(profile), res["zwidth_region"], res["zwidth_optimum"], \
        res["zwidth_study"]
    b, k = region_wall(profile)
    rows = [
        _row(numbers, "zwidth.area_linear", "region area &int;K dB (linear axes)", region.area_linear,
             "N&sup2;&middot;s/m&sup2;"),
        _row(numbers, "zwidth.area_log", "region area on log axes", region.area_log, "decades&sup2;"),
        _row(numbers, "zwidth.optimum_cutoff", f"optimum cut-off ({html.escape(opt.kind)})", opt.cutoff * _HZ, "Hz"),
        _row(numbers, "zwidth.optimum_area", "area at the optimum (linear)", opt.area, "N&sup2;&middot;s/m&sup2;"),
        _row(numbers, "zwidth.backward_area", "area without a filter (linear)", opt.backward_area,
             "N&sup2;&middot;s/m&sup2;"),
    ]
    par = (f"Velocity estimate: {html.escape(sec.velocity_filter.label())}. The exact stable region of the "
           f"virtual wall (B, K) = (b<sub>c</sub>, k<sub>c</sub>) over B from {format_number(sec.b_range[0])} to "
           f"{format_number(sec.b_range[1])} N&middot;s/m (hands-off against the god-object wall, Colgate &amp; "
           f"Brown), with the passive region (Colgate &amp; Schenkel) and eq. (9)'s limit. The optimizer maximizes "
           f"the linear area (Chawda et al.); the optimum is "
           f"{'inside the cut-off grid' if opt.interior else 'at the edge of the cut-off grid'}. The current wall "
           f"({format_number(b)} N&middot;s/m, {format_number(k)} N/m) is "
           f"{'inside' if region.stable(b, k) else 'outside'} the region.")
    after: list[str] = []
    if region.force_noise is not None:
        after.append(f"Noise criterion: encoder resolution {format_number(sec.encoder_resolution)} m, force-noise "
                     f"tolerance {format_number(region.force_noise)} N rms; walls with B above "
                     f"{format_number(region.b_noise)} N&middot;s/m (B&middot;&sigma;<sub>v</sub> of the quantization "
                     f"noise over the tolerance) are counted as not renderable.")
    if study.score is not None and study.trials is not None:
        s = study.score
        numbers["zwidth.trials_wrong"] = (float(s.wrong_count), str(s.wrong_count))
        after.append(f"Hardware trials ({html.escape(study.trials.path)}): {s.wrong_count} of {s.scored} "
                     f"predicted wrong" + (f", {s.outside.size} outside the B range." if s.outside.size else "."))
        after.extend(html.escape(line) for line in s.describe(study.trials))
    if "zwidth_trials_error" in res:
        after.append(f"Trials file not read: {html.escape(res['zwidth_trials_error'])}")
    return [Section("Controller as built: Z-width region and velocity filter", (par,), tuple(rows), tuple(after))]


def zwidth_figure(content: Any, key: str) -> Any:
    """The region (``zwidth_region``) or the area against the cut-off (``filter_optimum``)."""
    from app.report.figures import Figure
    from app.views.filter_optimum_view import FilterOptimumView
    from app.views.zwidth_region_view import ZWidthRegionView

    res = content.results
    if "zwidth_region" not in res:
        return None
    if key == "zwidth_region":
        v = ZWidthRegionView()
        study = res["zwidth_study"]
        v.update_region(res["zwidth_region"], study.trials, study.score)
        b, k = region_wall(content.profile)
        v.update_point(b, k, res["zwidth_region"].stable(b, k))
        cap = ("Exact stable region of the virtual wall in the (B, K) plane (shaded), the passive region "
               "(dashed), eq. (9)'s limit (dash-dotted), the hardware trials and the current wall.")
        return Figure(key, "Z-width region (B, K)", cap, v)
    v2 = FilterOptimumView()
    v2.update_optimum(res["zwidth_optimum"])
    v2.update_filter(controller_section(content.profile).velocity_filter)
    cap = "Area of the stable region against the velocity filter's cut-off; the star is the optimum."
    return Figure(key, "Z-width area against the filter cut-off", cap, v2)
