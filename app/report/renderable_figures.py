"""The report's renderable-space figures (issue 24; needs Qt): the app's own
:class:`~app.views.renderable_view.RenderableSpaceView` (``renderable_space``: K_max over (M, B)) and
:class:`~app.views.renderable_view.MWidthView` (``m_width``), drawing the study of
:mod:`app.report.renderable_section`; with its robust space (``renderable_robust``), the space view overlays
it as the tab does (:meth:`~app.views.renderable_view.RenderableSpaceView.update_robust`).
"""

from __future__ import annotations

from app import qt_compat  # noqa: F401 - before any Qt call

from analysis.study import renderable_section
from app.report.model import Figure, ReportContent
from app.views.renderable_view import MWidthView, RenderableSpaceView

__all__ = ["FIGURE_KEYS", "renderable_figure"]

FIGURE_KEYS = ("renderable_space", "m_width")


def renderable_figure(content: ReportContent, key: str) -> Figure | None:
    """The space's heat map (``renderable_space``) or the M-width (``m_width``); ``None`` without the section."""
    study = content.results.get("renderable_study")
    if study is None:
        return None
    sec = renderable_section(content.profile)
    if key == "renderable_space":
        v = RenderableSpaceView()
        v.update_space(study, "all", sec.virtual_stiffness)
        v.update_point(sec.virtual_mass, sec.virtual_damping)
        cap = ("Largest renderable K over the virtual mass M and damping B (colour, log scale; grey: none), one "
               "contour per quality where the rendered K is renderable, and the rendered (M, B) (star).")
        robust = content.results.get("renderable_robust")
        if robust is not None:
            label = content.results["renderable_robust_label"]
            v.update_robust(robust, label)
            cap += (f" Dashed: the robust space over the {label}, where every one of those devices renders the "
                    "rendered K; hatched: where this device renders it and the box does not.")
        return Figure(key, "Renderable space K_max(M, B)", cap, v)
    v2 = MWidthView()
    v2.update_width(study, sec.virtual_mass)
    cap = "M-width: the virtual masses renderable at B = K = 0, per quality; the dashed line is the rendered M."
    return Figure(key, "M-width", cap, v2)
