"""The sampled-data tab: the exact loop behind the two-port bounds.

* a stability map -- the spectral radius of the real sampled loop over two parameters;
* the exact stability limit over b_c overlaid on the two-port design chart;
* the scenario runner -- the nonlinear simulator's positions, forces and energy, and its verdict.

All three run as asynchronous graph nodes (:mod:`app.core.nodes_sampled`, which calls the study
layer) on the worker, with progress and Cancel; like every tab, nothing is pulled while the tab is
hidden.  The delays, the scenario and the simulator options are the profile's ``simulation``
section (:class:`~app.panels.simulation_panel.SimulationPanel`, undo commands); the map's axes and
ranges are view settings (:class:`~app.panels.map_panel.MapPanel`, passed as node parameters).
This tab lays the panels and views out and refreshes them; it computes nothing itself.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from typing import Any

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QScrollArea, QSplitter, QToolButton, QVBoxLayout, QWidget

from analysis.profiles.io import Profile
from analysis.sampled import StabilityMap, is_stable
from analysis.study import display_kind

from app.core import nodes_sampled
from app.core.compute_graph import ComputeGraph
from app.core.nodes_sampled import (
    ASYNC_NODES,
    DEFAULT_RANGES,
    EXACT_NODE,
    LIMIT_NODE,
    MAP_AXES,
    MAP_NODE,
    POINT_NODE,
    SIM_NODE,
    current_section,
    delays,
    exact_grid,
    map_arguments,
)
from app.panels.map_panel import MapPanel
from app.panels.simulation_panel import SimulationPanel
from app.views.base import PlotView
from app.widgets.colors import for_theme
from app.views.exact_limit_chart import ExactLimitChart
from app.views.sampled_summary import design_on_map, exact_summary, map_subtitle, scenario_note
from app.views.stability_map import StabilityMapView
from app.views.time_response import TimeResponse
from app.widgets.node_progress import NodeProgress
from app.widgets.rich_text_pane import RichTextPane
from app.widgets.task_progress import TASK_TITLES
from app.tabs.async_jobs import AsyncJobs
from app.tabs.base import AnalysisTab, scroll_body
from app.tabs.held_plots import HeldPlots
from app.widgets.text_pacer import TextPacer
from analysis.study.citations import ADAMS, HANNAFORD_RYU
from app.widgets.citation_note import CitationNote

__all__ = ["SampledTab", "TAB", "MAP_AXES", "DEFAULT_RANGES", "map_arguments", "exact_grid", "ASYNC_NODES",
           "MAP_NODE", "EXACT_NODE", "LIMIT_NODE", "SIM_NODE"]

TITLES = {MAP_NODE: "Stability map", EXACT_NODE: "Exact limit chart", LIMIT_NODE: "Exact limit at current b_c",
          SIM_NODE: "Simulation"}


def _column(*widgets: QWidget) -> QWidget:
    w = QWidget()
    lay = QVBoxLayout(w)
    lay.setContentsMargins(0, 0, 0, 0)
    lay.setSpacing(2)
    for x in widgets:
        lay.addWidget(x, 1 if isinstance(x, (PlotView, TimeResponse)) else 0)
    return w


class SampledTab(HeldPlots, AsyncJobs, AnalysisTab):
    job_titles = TITLES  # the background nodes: cancel, failure and run-again (AsyncJobs)
    title = "Sampled-data"
    order = 30
    nodes = frozenset({*ASYNC_NODES, POINT_NODE, "design_chart", "stability", "max_stiffness"})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_sampled.register(graph)
        for name in ASYNC_NODES:
            TASK_TITLES.setdefault(name, f"Computing {TITLES[name].lower()}")

    def build(self) -> None:
        ctx = self.ctx
        self.init_held_plots()
        self.texts = TextPacer(lambda: ctx.graph.interactive, self)  # the summary: 10 Hz during a drag
        self._held: dict[str, Hashable] = {}  # node -> key not to restart (cancelled or failed)
        self._errors: dict[str, str] = {}
        self.map_view = StabilityMapView()
        self.exact_view = ExactLimitChart()
        self.time_view = TimeResponse()
        self.summary = RichTextPane()  # rewritten on every step of a drag: laid out in place
        self.progress = {name: NodeProgress(ctx.graph, name, TITLES[name]) for name in ASYNC_NODES}
        for w in self.progress.values():
            w.rerun.connect(self.run_again)
        self.panel = SimulationPanel(ctx.model, ctx.editor)
        self.map_panel = MapPanel(ctx.model.profile.display)
        self.map_panel.changed.connect(self._on_map_changed)
        self.controls = self._controls()
        self.settings_button = QToolButton()
        self.settings_button.setCheckable(True)
        self.settings_button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextBesideIcon)
        self.settings_button.setArrowType(Qt.ArrowType.RightArrow)
        self.settings_button.setText("Loop, scenario and map settings")
        self.settings_button.setToolTip("Show or hide the delays, the simulated scenario and the map's axes "
                                        "(hidden, the plots get the width)")
        self.settings_button.toggled.connect(self.show_controls)
        self.split = QSplitter(Qt.Orientation.Horizontal)
        self.split.addWidget(self.controls)
        self.split.addWidget(self._views())
        self.split.setStretchFactor(1, 1)
        self.split.setChildrenCollapsible(False)
        self.controls.hide()
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 2, 4, 4)
        lay.setSpacing(2)
        lay.addWidget(self.settings_button, 0, Qt.AlignmentFlag.AlignLeft)
        lay.addWidget(self.split, 1)
        lay.addWidget(CitationNote(ADAMS, HANNAFORD_RYU))  # the full citation of the tab's equation numbers
        ctx.graph.ready.connect(self._on_ready)
        ctx.graph.cancelled.connect(self.on_job_cancelled)
        ctx.graph.failed.connect(self.on_job_failed)

    def _controls(self) -> QWidget:
        controls = QWidget()
        cl = QVBoxLayout(controls)
        cl.setContentsMargins(0, 0, 4, 0)
        cl.addWidget(self.panel)
        cl.addWidget(self.map_panel)
        cl.addStretch(1)
        scroll = QScrollArea()
        scroll.setWidget(controls)
        scroll.setWidgetResizable(True)
        scroll.setMinimumWidth(270)
        # as wide as its fields and check boxes want (with the vertical scroll bar), never cut on the right:
        # narrower (a small window), it scrolls sideways
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
        scroll.setMaximumWidth(self._controls_width(scroll))
        return scroll

    @staticmethod
    def _controls_width(scroll: QScrollArea) -> int:
        """The settings panel's width with nothing cut: its contents, the vertical scroll bar, the frame."""
        inner = scroll.widget()
        return (inner.minimumSizeHint().expandedTo(inner.minimumSize()).width()
                + scroll.verticalScrollBar().sizeHint().width() + 2 * scroll.frameWidth())

    @Slot(bool)
    def show_controls(self, show: bool) -> None:
        """Show or collapse the settings panel (collapsed, the plots take the tab's whole width); shown,
        it gets its whole width if the plots keep theirs."""
        if show and self.controls.isHidden():
            want = self._controls_width(self.controls)
            self.controls.setMaximumWidth(want)
            self.controls.setVisible(True)
            total = sum(self.split.sizes())
            plots = self.split.widget(1).minimumSizeHint().width()
            width = max(self.controls.minimumWidth(), min(want, total - plots - self.split.handleWidth()))
            self.split.setSizes([width, max(0, total - width)])
        self.controls.setVisible(show)
        if self.settings_button.isChecked() != show:
            self.settings_button.setChecked(show)
        self.settings_button.setArrowType(Qt.ArrowType.LeftArrow if show else Qt.ArrowType.RightArrow)

    def _views(self) -> QWidget:
        top = QSplitter(Qt.Orientation.Horizontal)
        top.addWidget(_column(self.map_view, self.progress[MAP_NODE]))
        top.addWidget(_column(self.exact_view, self.progress[EXACT_NODE], self.progress[LIMIT_NODE]))
        top.setChildrenCollapsible(False)
        split = QSplitter(Qt.Orientation.Vertical)
        split.addWidget(top)
        split.addWidget(_column(self.summary, self.time_view, self.progress[SIM_NODE]))
        split.setChildrenCollapsible(False)
        split.setSizes([45, 55])  # the text and the three time plots below need a little more
        return split

    # -- map settings (view state, not the profile) --------------------------------------------------
    @property
    def map_settings(self) -> dict[str, dict[str, Any]]:
        return self.map_panel.all_settings

    def set_map(self, x: str | None = None, y: str | None = None, x_range: tuple[float, float] | None = None,
                y_range: tuple[float, float] | None = None, points: int | None = None) -> str | None:
        """Change the map's axes, ranges or resolution; returns the reason if refused."""
        self.map_panel.show_display(self.ctx.model.profile.display)
        return self.map_panel.set_map(x, y, x_range, y_range, points)

    @Slot()
    def _on_map_changed(self) -> None:
        self._held.pop(MAP_NODE, None)
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True

    def _busy_text(self, name: str) -> str:
        """"updating…" while computing; while a slider drag holds it back, that it catches up."""
        return "updating after the drag…" if name in self.ctx.graph.waiting() else ""

    def update_views(self) -> None:
        g, p = self.ctx.graph, self.ctx.model.profile
        if self.map_panel.display != p.display:  # (rebuilding its fields on every drag step costs)
            self.map_panel.show_display(p.display)
        settings = self.map_panel.settings(p.display)
        g.set_params(MAP_NODE, **settings)
        g.set_params(POINT_NODE, x=settings["x"], y=settings["y"])
        m, chart, limit, sim = (self.pull(name) for name in ASYNC_NODES)
        self._hold_ranges(g.interactive)  # still axes during a drag: only the markers repaint
        # the two-port chart behind the exact limit: not restarted on every step of a drag
        bound_chart = g.result("design_chart") if g.holding else g.request("design_chart")
        self._draw_map(p, m)
        self._draw_exact(p, chart, bound_chart)
        # the two-port bound at the current b_c (its refinement is held back while a drag moves)
        design = g.get("max_stiffness") if display_kind(p).is_impedance else None
        bound = design.kc if design is not None and g.is_fresh("max_stiffness") else None
        text = exact_summary(p, limit if g.is_fresh(LIMIT_NODE) else None, bound, *delays(p),
                             bound_pending="max_stiffness" in g.waiting())
        self.texts.show("summary", lambda: self.summary.setText(for_theme(text, self.dark)))
        self._draw_simulation(sim)
        self.refreshes += 1
        self.stale = False

    def _draw_map(self, p: Profile, m: StabilityMap | None) -> None:
        if m is not None and m.x_name == self.map_panel.settings(p.display)["x"]:
            subtitle = map_subtitle(p, m, *delays(p))
            if self._changed("map", m, subtitle):
                self.map_view.update_map(m, subtitle)
            px, py = design_on_map(p, m)
            rho = self.ctx.graph.get(POINT_NODE)  # exact at the current gains, live during a drag
            self.map_view.update_point(px, py, None if rho is None or math.isnan(rho) else is_stable(rho))
        elif m is not None and self._changed("map", None):
            self.map_view.update_map(None)
        self.map_view.set_busy(self.busy(MAP_NODE), self._busy_text(MAP_NODE))
        if MAP_NODE in self._errors:
            self.map_view.set_warning([self._errors[MAP_NODE]])

    def _draw_exact(self, p: Profile, chart: Any, bound: Any) -> None:
        g = self.ctx.graph
        kind = display_kind(p)
        bound = bound if bound is not None and display_kind(bound) is kind else None
        if self._changed("bound", bound):
            self.exact_view.update_bound(bound)
        chart = chart if isinstance(chart, kind.exact_chart_type) else None
        if self._changed("exact", chart, kind):
            self.exact_view.update_exact(chart, kind)
        self.exact_view.update_point(*kind.chart_point(p), g.get(g.stability_name).stable)
        self.exact_view.set_busy(self.busy(EXACT_NODE) or not g.is_fresh("design_chart"), self._busy_text(EXACT_NODE))
        if EXACT_NODE in self._errors:
            self.exact_view.set_warning([self._errors[EXACT_NODE]])

    def _draw_simulation(self, sim: Any) -> None:
        sec = current_section(self.ctx.model.profile)
        if sim is not None:
            sc = sec.scenario
            note = scenario_note(sec, self.ctx.graph.is_fresh(SIM_NODE), self.ctx.model.profile.display)
            wall = sc.wall_position if sc.wall else None
            if self._changed("simulation", sim, str(wall), note):
                self.time_view.update_result(sim, wall, note)
        if SIM_NODE in self._errors:
            self.time_view.verdict.setText(for_theme(f"<span style='color:#c92a2a'>{self._errors[SIM_NODE]}</span>",
                                                     self.dark))
        self.time_view.set_busy(self.busy(SIM_NODE), self._busy_text(SIM_NODE))

    # -- worker reports -------------------------------------------------------------------------------
    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in self.nodes and self.isVisible():
            self.refresh()

    def cancel(self, name: str) -> None:
        self.ctx.graph.cancel(name)

    def views(self) -> list[PlotView]:
        return [self.map_view, self.exact_view, *self.time_view.plot_views()]

    def held_views(self) -> list[PlotView]:
        """The map and the exact chart, whose current-design markers move during a drag (the
        simulation's plots keep their result then, and their axes with it)."""
        return [self.map_view, self.exact_view]



TAB = SampledTab
