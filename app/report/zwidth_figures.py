"""The report's Z-width figures (issue 15; needs Qt): the app's own
:class:`~app.views.zwidth_region_view.ZWidthRegionView` (``zwidth_region``) and
:class:`~app.views.filter_optimum_view.FilterOptimumView` (``filter_optimum``), drawing the results
of :mod:`app.report.zwidth_section`.
"""

from __future__ import annotations

from app import qt_compat  # noqa: F401 - before any Qt call

from analysis.study import controller_section, region_wall
from app.report.model import Figure, ReportContent
from app.views.filter_optimum_view import FilterOptimumView
from app.views.zwidth_region_view import ZWidthRegionView

__all__ = ["FIGURE_KEYS", "zwidth_figure"]

FIGURE_KEYS = ("zwidth_region", "filter_optimum")


def zwidth_figure(content: ReportContent, key: str) -> Figure | None:
    """The region (``zwidth_region``) or the area against the cut-off (``filter_optimum``)."""
    res = content.results
    if ("zwidth_region" if key == "zwidth_region" else "zwidth_optimum") not in res:
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
