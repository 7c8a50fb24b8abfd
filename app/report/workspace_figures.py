"""The report's workspace figures (issue 25; needs Qt): the app's own
:class:`~app.views.workspace_view.WorkspaceMapView` (``workspace_map``: the worst wall's critical
stiffness over the workspace, the linkage at the handle) and
:class:`~app.views.workspace_view.WorkspacePolarView` (``workspace_polar``: the limits at the handle
by wall direction), drawing the results of :mod:`app.report.workspace_section`.
"""

from __future__ import annotations

from app import qt_compat  # noqa: F401 - before any Qt call

from analysis.study import multidof_section
from app.report.model import Figure, ReportContent
from app.views.workspace_view import WorkspaceMapView, WorkspacePolarView

__all__ = ["FIGURE_KEYS", "workspace_figure"]

FIGURE_KEYS = ("workspace_map", "workspace_polar")


def workspace_figure(content: ReportContent, key: str) -> Figure | None:
    """The workspace map (``workspace_map``) or the polar limits (``workspace_polar``); ``None`` without them."""
    m = content.results.get("workspace_map")
    point = content.results.get("workspace_point")
    if key == "workspace_map":
        if m is None:
            return None
        sec = multidof_section(content.profile)
        v = WorkspaceMapView()
        v.update_map(m)
        v.update_point(point, (sec.handle_x, sec.handle_y))
        cap = ("Critical stiffness of the worst plane wall over the handle positions (colour; grey: out of reach), "
               "the design bound (star), and at the handle the linkage, its inertia ellipse and the worst normal "
               "(arrow).")
        return Figure(key, "Workspace map", cap, v)
    if point is None:
        return None
    v2 = WorkspacePolarView()
    v2.update_polar(point)
    cap = ("Critical stiffness of a plane wall along each direction at the handle, in polar form, with the isotropic "
           "wall (dashed circle) and the worst normal.")
    return Figure(key, "Limits at the handle by wall direction", cap, v2)
