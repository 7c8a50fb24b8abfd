"""The report's Z-width part (issue 15), when the profile has a ``controller`` section.

Qt-free: :func:`zwidth_part` (called by :func:`app.report.content.gather`) gives the velocity
filter, the exact (B, K) region's areas (Colgate & Brown, ICRA 1994), the optimum cut-off (Chawda,
Celik & O'Malley 2015) and the trials the analysis gets wrong, computed by
:mod:`analysis.study.zwidth`.  Its figures (needing Qt) are in :mod:`app.report.zwidth_figures`.
"""

from __future__ import annotations

import html
import math
from typing import Any

from analysis.errors import ValidationError
from analysis.profiles import Profile
from analysis.study import (
    controller_section,
    filter_optimum,
    format_number,
    optimum_verdict,
    profile_trials,
    trial_score,
    region_wall,
    rich_numbers,
    zwidth_region_result,
)
from app.report.model import Numbers, Part, Row, Section

__all__ = ["zwidth_results", "zwidth_part"]

_HZ = 1.0 / (2.0 * math.pi)


def zwidth_results(profile: Profile, *, optimum: bool = True) -> dict[str, Any]:
    """The region, the optimum and the scored trials (keys ``zwidth_region``, ``zwidth_optimum``,
    ``zwidth_study``); ``optimum=False``: without the optimum (the region's figure does not draw it).

    A trials file that cannot be read is reported under ``zwidth_trials_error``, not raised."""
    region = zwidth_region_result(profile)
    res: dict[str, Any] = {"zwidth_region": region}
    if optimum:
        res["zwidth_optimum"] = filter_optimum(profile)
    try:
        trials = profile_trials(profile)
    except ValidationError as err:
        trials, res["zwidth_trials_error"] = None, str(err)
    res["zwidth_study"] = trial_score(region, trials)
    return res


def _row(numbers: Numbers, key: str, label: str, value: float, unit: str) -> Row:
    numbers[key] = (value, format_number(value))  # the number table: ASCII, as the CLI prints it
    return Row(label, "", format_number(value, rich=True), unit)


def zwidth_part(profile: Profile) -> Part:
    """The report's section on the controller as built (empty without a ``controller`` section),
    with :func:`zwidth_results` as its results."""
    if profile.controller is None:
        return Part()
    res = zwidth_results(profile)
    numbers: Numbers = {}
    sec, region, opt, study = controller_section(profile), res["zwidth_region"], res["zwidth_optimum"], \
        res["zwidth_study"]
    b, k = region_wall(profile)
    rows = [
        _row(numbers, "zwidth.area_linear", "region area &int;K dB (linear axes)", region.area_linear,
             "N&sup2;&middot;s/m&sup2;"),
        _row(numbers, "zwidth.area_log", "region area on log axes", region.area_log, "decades&sup2;"),
        _row(numbers, "zwidth.optimum_cutoff", f"optimum cut-off ({html.escape(opt.kind)})", opt.cutoff * _HZ, "Hz"),
        _row(numbers, "zwidth.optimum_area", f"{opt.criterion} at the optimum (linear)", opt.area,
             "N&sup2;&middot;s/m&sup2;"),
        _row(numbers, "zwidth.backward_area", f"{opt.criterion} without a filter (linear)", opt.backward_area,
             "N&sup2;&middot;s/m&sup2;"),
    ]
    if opt.current is not None and opt.current_area is not None:
        rows.append(_row(numbers, "zwidth.current_area", f"{opt.criterion} with the current filter (linear)",
                         opt.current_area, "N&sup2;&middot;s/m&sup2;"))
    par = (f"Velocity estimate: {html.escape(sec.velocity_filter.label())}. The exact stable region of the "
           f"virtual wall (B, K) = (b<sub>c</sub>, k<sub>c</sub>) over B from "
           f"{format_number(sec.b_range[0], rich=True)} to {format_number(sec.b_range[1], rich=True)} N&middot;s/m "
           f"(hands-off against the god-object wall, Colgate &amp; Brown), with the passive region (Colgate &amp; "
           f"Schenkel) and eq. (9)'s limit. The optimizer maximizes "
           f"the linear {opt.criterion} over the cut-off (Chawda et al.) and compares it with no filter and the "
           f"current filter: {rich_numbers(html.escape(optimum_verdict(opt)))} The current wall "
           f"({format_number(b, rich=True)} N&middot;s/m, {format_number(k, rich=True)} N/m) is "
           f"{'inside' if region.stable(b, k) else 'outside'} the region.")
    after: list[str] = []
    if region.force_noise is not None:
        after.append(f"Noise criterion: encoder resolution {format_number(sec.encoder_resolution, rich=True)} m, "
                     f"force-noise tolerance {format_number(region.force_noise, rich=True)} N rms; walls with B above "
                     f"{format_number(region.b_noise, rich=True)} N&middot;s/m (B&middot;&sigma;<sub>v</sub> of the "
                     f"quantization noise over the tolerance) are counted as not renderable.")
    if study.score is not None and study.trials is not None:
        s = study.score
        numbers["zwidth.trials_wrong"] = (float(s.wrong_count), str(s.wrong_count))
        after.append(f"Hardware trials ({html.escape(study.trials.path)}): {s.wrong_count} of {s.scored} "
                     f"predicted wrong" + (f", {s.outside.size} outside the B range." if s.outside.size else "."))
        after.extend(html.escape(line) for line in s.describe(study.trials))
    if "zwidth_trials_error" in res:
        after.append(f"Trials file not read: {html.escape(res['zwidth_trials_error'])}")
    return Part((Section("Controller as built: Z-width region and velocity filter", (par,), tuple(rows),
                         tuple(after)),), numbers, res)
