"""The Workspace tab (issue 25): a multi-DOF linkage over its workspace.

* the critical stiffness of the worst plane wall over the grid of handle positions as a heat map,
  the design bound (the worst point) marked; the linkage drawn at the handle with its inertia
  ellipse and the worst normal as an arrow -- a click on the map moves the handle, one undo step;
* the per-direction limits at the handle as a polar plot;
* the settings panel (:class:`~app.panels.workspace_panel.WorkspacePanel`: the profile's
  ``multidof`` section).

The map is one asynchronous graph node on the worker (:mod:`app.core.nodes_workspace`), with
progress and Cancel; the handle's limits a synchronous one.  A hidden tab computes nothing, and the
tab is built when first shown.  Every number shown comes from :mod:`analysis.study.workspace`.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from typing import Any

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QLabel, QSplitter, QVBoxLayout, QWidget

from analysis.multidof import WorkspaceMap
from analysis.study import WorkspacePoint, format_number, handle_edits, multidof_section
from analysis.study.citations import ADAMS, COLGATE_BROWN

from app.core import nodes_workspace
from app.core.compute_graph import ComputeGraph
from app.core.nodes_workspace import WORKSPACE_MAP_NODE, WORKSPACE_POINT_NODE
from app.panels.workspace_panel import WorkspacePanel
from app.tabs.async_jobs import AsyncJobs
from app.tabs.base import AnalysisTab, settings_beside_plots
from app.widgets.citation_note import CitationNote
from app.views.base import PlotView
from app.views.workspace_view import WorkspaceMapView, WorkspacePolarView
from app.widgets.node_progress import NodeProgress
from app.widgets.task_progress import TASK_TITLES

__all__ = ["WorkspaceTab", "TAB", "summary_text"]

TITLES = {WORKSPACE_MAP_NODE: "Workspace map"}


def _angle(n: Any) -> str:
    return format_number(math.degrees(math.atan2(float(n[1]), float(n[0]))) % 180.0, 3, style='text')


def summary_text(m: WorkspaceMap | None, point: WorkspacePoint | str | None) -> str:
    """The tab's summary: the design bound and the limits at the handle, in words."""
    lines = []
    if m is None:
        lines.append("Computing the workspace map…")
    else:
        b = m.minimum
        lines.append(f"Design bound: {format_number(b.stiffness, style='text')} N/m at "
                     f"({format_number(b.position[0], style='text')}, {format_number(b.position[1], style='text')}) m, "
                     f"wall normal at {_angle(b.normal)}°.")
    if isinstance(point, str):
        lines.append(f"At the handle: {point}")
    elif point is not None:
        wall = "" if point.normal is None else f", the profile's wall {format_number(point.wall, style='text')} N/m"
        lines.append(f"At the handle: isotropic wall {format_number(point.isotropic, style='text')} N/m{wall}, "
                     f"worst plane wall {format_number(point.worst.stiffness, style='text')} N/m with its normal at "
                     f"{_angle(point.worst.normal)}°; effective masses "
                     f"{format_number(point.principal_masses[0], style='text')} to "
                     f"{format_number(point.principal_masses[-1], style='text')} kg.")
    lines.append("Click the map to move the handle.")
    return "\n".join(lines)


class WorkspaceTab(AsyncJobs, AnalysisTab):
    job_titles = TITLES
    title = "Workspace"
    order = 39
    nodes = frozenset({WORKSPACE_MAP_NODE, WORKSPACE_POINT_NODE})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_workspace.register(graph)
        TASK_TITLES.setdefault(WORKSPACE_MAP_NODE, TITLES[WORKSPACE_MAP_NODE])

    def build(self) -> None:
        ctx = self.ctx
        self._held: dict[str, Hashable] = {}
        self._errors: dict[str, str] = {}
        self.panel = WorkspacePanel(ctx.model, ctx.editor)
        self.map_view = WorkspaceMapView()
        self.map_view.pointPicked.connect(self.move_handle)
        self.polar_view = WorkspacePolarView()
        self.progress = {WORKSPACE_MAP_NODE: NodeProgress(ctx.graph, WORKSPACE_MAP_NODE, TITLES[WORKSPACE_MAP_NODE])}
        self.progress[WORKSPACE_MAP_NODE].rerun.connect(self.run_again)
        self.summary = QLabel("")
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        left = QWidget()
        lay = QVBoxLayout(left)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.summary)
        lay.addWidget(self.panel, 1)
        top = QWidget()
        tl = QVBoxLayout(top)
        tl.setContentsMargins(0, 0, 0, 0)
        tl.addWidget(self.map_view, 1)
        tl.addWidget(self.progress[WORKSPACE_MAP_NODE])
        plots = QSplitter(Qt.Orientation.Horizontal)
        plots.addWidget(top)
        plots.addWidget(self.polar_view)
        plots.setSizes([62, 38])
        plots.setChildrenCollapsible(False)
        # the exact sampled loop of the 1-DOF analysis, taken to every wall direction (issue 25)
        settings_beside_plots(self, left, plots, (250, 330), CitationNote(ADAMS, COLGATE_BROWN))
        ctx.graph.ready.connect(self._on_ready)
        ctx.graph.cancelled.connect(self.on_job_cancelled)
        ctx.graph.failed.connect(self.on_job_failed)

    @Slot(float, float)
    def move_handle(self, x: float, y: float) -> str | None:
        """Move the handle to ``(x, y)`` [m]: one undo step; returns the refusal (out of reach), if any."""
        return self.panel.write_many(handle_edits(x, y), "handle position")

    def update_views(self) -> None:
        g = self.ctx.graph
        m = self.pull(WORKSPACE_MAP_NODE)
        busy = self.busy(WORKSPACE_MAP_NODE)
        point = g.get(WORKSPACE_POINT_NODE)
        sec = multidof_section(self.ctx.model.profile)
        if self.map_view.map is not m:
            self.map_view.update_map(m)
        pt = point if isinstance(point, WorkspacePoint) else None
        if self.map_view.point is not pt or self.polar_view.point is not pt:
            self.map_view.update_point(pt, (sec.handle_x, sec.handle_y))
            self.polar_view.update_polar(pt)
        self.map_view.set_busy(busy)
        warnings = [self._errors[WORKSPACE_MAP_NODE]] if WORKSPACE_MAP_NODE in self._errors else []
        self.map_view.set_warning(warnings)
        self.summary.setText(summary_text(m, point))
        self.refreshes += 1
        self.stale = False

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == WORKSPACE_MAP_NODE and self.isVisible():
            self.refresh()

    def views(self) -> list[PlotView]:
        return [self.map_view, self.polar_view]


TAB = WorkspaceTab
