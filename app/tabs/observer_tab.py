"""The observer tab: the disturbance observer of Eom, Suh & Yi (section 2, Fig. 1, eq. 2-5).

Controls (:class:`~app.panels.observer_panel.ObserverPanel`) for the profile's observer section (order r and cutoff ω_Q of Q, the nominal plant, the
α/β/δ perturbation of the real plant, the two-axis five-bar preset).  Plots: the effective plant
through the observer against the nominal and real plants, disturbance to velocity with and
without the observer, the cross-axis coupling |v_y/F_x| of the two-axis device with and without
the observers, and the y answer to a commanded force step on x.  The single-axis node
(:mod:`app.core.nodes_observer`) is synchronous and follows every step of a slider drag; the two
two-axis nodes run on the worker and are held during a drag, catching up when it pauses or ends
(their titles say so).  The axes keep their range during the drag and a plot is redrawn only when
its result changed.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QGridLayout, QLabel, QVBoxLayout

from analysis.study import observer_device_label
from analysis.transparency.observer import ObserverResponse
from analysis.transparency.settings import ObserverSettings

from app.core import nodes_observer
from app.core.compute_graph import ComputeGraph
from app.core.nodes_observer import HELD_NODES, NODES, OBSERVER_W, observer_settings
from app.panels.observer_panel import ObserverPanel
from app.views.base import PlotView, fmt
from app.views.curves_plot import CurvesPlot
from app.widgets.task_progress import TASK_TITLES
from app.tabs.base import AnalysisTab, scroll_body
from app.tabs.held_plots import HeldPlots
from analysis.study.citations import EOM
from app.widgets.citation_note import CitationNote

__all__ = ["ObserverTab", "TAB", "observer_settings", "OBSERVER_W", "NODES"]


class ObserverTab(HeldPlots, AnalysisTab):
    title = "Disturbance observer"
    order = 40
    nodes = frozenset(NODES)

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_observer.register(graph)
        TASK_TITLES.setdefault("observer_coupling", "Two-axis coupling")
        TASK_TITLES.setdefault("observer_step", "Two-axis step")

    def build(self) -> None:
        ctx = self.ctx
        self.panel = ObserverPanel(ctx.model, ctx.editor)
        self.fields = self.panel.fields
        self.init_held_plots()
        self._build_plots()
        grid = QGridLayout()
        grid.setSpacing(6)
        grid.addWidget(self.plant_plot, 0, 0)
        grid.addWidget(self.disturbance_plot, 0, 1)
        grid.addWidget(self.coupling_plot, 1, 0)
        grid.addWidget(self.step_plot, 1, 1)
        for view in (self.plant_plot, self.disturbance_plot, self.coupling_plot, self.step_plot):
            view.legend_outside()  # below the plot: inside, it covers the curves
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(self.panel)
        self.device_label = QLabel()  # which devices the tab analyses (the profile's, or its section's)
        self.device_label.setObjectName("observerDevice")
        self.device_label.setWordWrap(True)
        lay.addWidget(self.device_label)
        lay.addLayout(grid, 1)
        lay.addWidget(CitationNote(EOM))  # the full citation of the tab's equation numbers
        ctx.graph.ready.connect(self._on_ready)

    def _build_plots(self) -> None:
        w_axis, y_axis = ("ω", "rad/s"), ("|v/u|", "m/(N·s)")
        self.plant_plot = CurvesPlot("Effective plant through the observer (eq. 3–5)", w_axis, y_axis, True, True)
        self.plant_plot.add_curve("plant", "real plant P̃ (eq. 13)", "muted", 2.0, Qt.PenStyle.DashLine,
                                  export_name="|P real|")
        self.plant_plot.add_curve("nominal", "nominal P<sub>n</sub>", "c", 2.0, Qt.PenStyle.DotLine,
                                  export_name="|P_n|")
        self.plant_plot.add_curve("effective", "effective plant with observer", "a", export_name="|P effective|")
        self.plant_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.disturbance_plot = CurvesPlot("Disturbance to velocity |v/d|", w_axis, ("|v/d|", "m/(N·s)"),
                                           True, True)
        self.disturbance_plot.add_curve("without", "without observer", "muted", 2.0, Qt.PenStyle.DashLine,
                                        export_name="|v/d| without observer")
        self.disturbance_plot.add_curve("with", "with observer", "a", export_name="|v/d| with observer")
        self.disturbance_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.coupling_plot = CurvesPlot("Cross-axis coupling |v<sub>y</sub>/F<sub>x</sub>| (two axes, eq. 2)",
                                        w_axis, ("|v<sub>y</sub>/F<sub>x</sub>|", "m/(N·s)"), True, True)
        self.coupling_plot.add_curve("without", "without observers", "muted", 2.0, Qt.PenStyle.DashLine,
                                     export_name="|v_y/F_x| without observers")
        self.coupling_plot.add_curve("with", "with observers", "b", export_name="|v_y/F_x| with observers")
        self.coupling_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.step_plot = CurvesPlot("Force step on x: y displacement", ("t", "s"), ("y", "mm"))
        self.step_plot.add_curve("without", "without observers", "muted", 2.0, Qt.PenStyle.DashLine,
                                 export_name="y without observers")
        self.step_plot.add_curve("with", "with observers", "b", export_name="y with observers")

    def views(self) -> list[PlotView]:
        return [self.plant_plot, self.disturbance_plot, self.coupling_plot, self.step_plot]

    def update_views(self) -> None:
        graph = self.ctx.graph
        st = observer_settings(self.ctx.model.profile)
        self.device_label.setText(observer_device_label(self.ctx.model.profile))
        self._hold_ranges(graph.interactive)
        r = graph.get("observer_response")
        c = graph.request("observer_coupling")
        s = graph.request("observer_step")
        if self._drawn.get("response") is not r:
            self._draw_response(r, st)
        if c is not None and self._drawn.get("coupling") is not c:
            self._drawn["coupling"] = c
            self.coupling_plot.set_curve("without", c.w, np.abs(c.coupling_without))
            self.coupling_plot.set_curve("with", c.w, np.abs(c.coupling_with))
            self.coupling_plot.bump()
        if s is not None and self._drawn.get("step") is not s:
            self._drawn["step"] = s
            self.step_plot.set_curve("without", s.t, 1e3 * s.y_without)
            self.step_plot.set_curve("with", s.t, 1e3 * s.y_with)
            self.step_plot.title = f"Force step F<sub>x</sub> = {fmt(s.force)} N on x: y displacement"
            self.step_plot.bump()
        for v in (self.plant_plot, self.disturbance_plot, self.coupling_plot):
            v.set_line("cutoff", st.cutoff)
        waiting = graph.waiting()
        for name, view in zip(HELD_NODES, (self.coupling_plot, self.step_plot)):
            view.set_busy(not graph.is_fresh(name), "updating after the drag…" if name in waiting else "")
        self.refreshes += 1
        self.stale = False

    def _draw_response(self, r: ObserverResponse, st: ObserverSettings) -> None:
        self._drawn["response"] = r
        self.plant_plot.set_curve("plant", r.w, np.abs(r.plant))
        self.plant_plot.set_curve("nominal", r.w, np.abs(r.nominal))
        self.plant_plot.set_curve("effective", r.w, np.abs(r.effective))
        self.plant_plot.set_legend_text("plant", f"real plant P̃: α = {fmt(st.alpha)}, β = {fmt(st.beta)}, "
                                                 f"δ = {fmt(st.delta)}")
        self.disturbance_plot.set_curve("without", r.w, np.abs(r.disturbance_without))
        self.disturbance_plot.set_curve("with", r.w, np.abs(r.disturbance_with))
        self.plant_plot.bump()
        self.disturbance_plot.bump()

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in HELD_NODES and self.isVisible():
            self.refresh()


TAB = ObserverTab
