"""The transparency tab: the wall controller of Eom, Suh & Yi (section 3, Figs. 7-10).

Controls for the wall section of the profile (m, b, K, B, T, the hold model, the weight, α, β)
and for the current controller damping B_c.  Plots: J(B_c) and ‖L‖∞(B_c) (Fig. 8) with the
current B_c and the robust optimum marked, the admittances |Y_v| and |Y_t| (Fig. 9), and the
answer to a human-force step (position and actuator force, Figs. 7 and 10).

During a slider drag the markers at the current B_c, the admittances and the summary follow every
step; the curves over B_c and the step response are held (``live=False`` nodes) and catch up on
the worker when the drag pauses or ends, their titles saying so.  The axes keep their range during
the drag, a plot is redrawn only when its result changed, and the summary sits in a scroll area, so
that a new text does not lay the window out again.

The controls are :class:`~app.panels.wall_panel.WallPanel`.  The current B_c is not a profile
field (``WallSettings`` has none): the panel holds it, starting at the paper's B_c = 15 N·s/m,
and the tab passes it to the graph nodes (:mod:`app.core.nodes_wall`) as a node parameter.
The curves over B_c (up to ~0.2 s for the ``zoh`` and ``discrete`` holds) and the step response
are asynchronous nodes; the point and the admittances at the current B_c are cheap and synchronous.
"""

from __future__ import annotations

import math

import numpy as np
from PySide6.QtCore import Qt, QTimer, Slot
from PySide6.QtWidgets import QGridLayout, QVBoxLayout

from analysis.study import wall_device_label
from analysis.transparency.settings import StepResponse, WallSettings

from app.core import nodes_wall
from app.core.compute_graph import ComputeGraph
from app.core.nodes_wall import (
    AT_BC_NODES,
    DEFAULT_BC,
    HOLD_LABELS,
    NODES,
    WallAdmittances,
    WallPoint,
    WallTradeoff,
    admittance_grid,
    wall_design,
    wall_settings,
)
from app.panels.wall_panel import WallPanel
from app.views.base import PlotView, fmt
from app.widgets.colors import for_theme
from app.views.curves_plot import CurvesPlot
from app.views.wall_summary import inf_spans, wall_summary
from app.widgets.task_progress import TASK_TITLES
from app.tabs.base import AnalysisTab, scroll_body
from app.tabs.held_plots import HeldPlots
from analysis.study.citations import EOM
from analysis.study.quantities import J_UNIT, rich_numbers
from app.widgets.citation_note import CitationNote
from app.widgets.rich_text_pane import RichTextPane, scrolling_pane
from app.widgets.text_pacer import TextPacer

__all__ = ["TransparencyTab", "TAB", "wall_settings", "wall_design", "WallPoint", "WallTradeoff",
           "WallAdmittances", "admittance_grid", "DEFAULT_BC", "NODES", "HOLD_LABELS"]


class TransparencyTab(HeldPlots, AnalysisTab):
    title = "Transparency (wall)"
    order = 30
    nodes = frozenset(NODES)

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_wall.register(graph)
        TASK_TITLES.setdefault("wall_tradeoff", "Computing J(B_c) and ‖L‖∞(B_c)")
        TASK_TITLES.setdefault("wall_step", "Step response")

    def build(self) -> None:
        ctx = self.ctx
        # the numbers in the legends and the summary: ten updates a second during a drag
        self.texts = TextPacer(lambda: ctx.graph.interactive, self)
        self.panel = WallPanel(ctx.model, ctx.editor)
        self.fields = self.panel.fields
        self.bc_field, self.optimum_button = self.panel.bc_field, self.panel.optimum_button
        self.tradeoff_drawn: WallTradeoff | None = None
        self.init_held_plots()
        self._build_plots()
        self.summary = RichTextPane()  # rewritten on every step of a drag: laid out once, in place
        self.summary.setObjectName("wallSummary")
        self.summary_area = scrolling_pane(self.summary)
        grid = QGridLayout()
        grid.setSpacing(6)
        for i, w in enumerate((self.index_plot, self.peak_plot, self.admittance_plot,
                               self.position_plot, self.force_plot, self.summary_area)):
            grid.addWidget(w, i // 3, i % 3)
            if isinstance(w, PlotView):
                w.legend_outside()  # six small plots: a legend inside would cover their curves
        for i in range(3):
            grid.setColumnStretch(i, 1)
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(self.panel)
        lay.addLayout(grid, 1)
        lay.addWidget(CitationNote(EOM))  # the full citation of the tab's equation numbers
        self.panel.bcChanged.connect(self._on_bc)
        self.panel.optimumRequested.connect(self.use_optimum)
        ctx.graph.ready.connect(self._on_ready)

    # -- the current B_c (panel state, a node parameter) -------------------------------------------------
    @property
    def bc(self) -> float:
        return self.panel.bc

    def set_bc(self, value: float) -> None:
        """Set the current B_c and redraw what depends on it if the tab is visible."""
        self.panel.set_bc(value)

    @Slot(float)
    def _on_bc(self, _value: float) -> None:
        self.stale = True
        if self.isVisible():
            QTimer.singleShot(0, self._refresh_if_stale)

    @Slot()
    def use_optimum(self) -> None:
        if self.tradeoff_drawn is not None and self.tradeoff_drawn.optimum.feasible:
            self.set_bc(float(f"{self.tradeoff_drawn.optimum.bc:.6g}"))

    @Slot()
    def _refresh_if_stale(self) -> None:
        if self.stale and self.isVisible():
            self.refresh()

    # -- plots ---------------------------------------------------------------------------------------
    def _build_plots(self) -> None:
        bc_axis = ("B<sub>c</sub>", "N·s/m")
        self.index_plot = CurvesPlot("J(B<sub>c</sub>), eq. 11 (Fig. 8)", bc_axis,
                                     ("J", J_UNIT), log_y=True)
        self.index_plot.add_curve("J", "J(B<sub>c</sub>)", "a", export_name="J")
        self.index_plot.add_marker("current", "current B<sub>c</sub>", "b", "o", export_name="J at current B_c")
        self.index_plot.add_marker("optimum", "robust optimum", "c", "star", 14, export_name="J at optimum")
        self.index_plot.add_line("bc", True)
        self.index_plot.add_regions("inf")

        self.peak_plot = CurvesPlot("‖L‖<sub>∞</sub>(B<sub>c</sub>), eq. 16–17 (Fig. 8)", bc_axis,
                                    ("‖L‖<sub>∞</sub>", "dB"))
        self.peak_plot.add_curve("peak", "‖L‖<sub>∞</sub>", "a", export_name="‖L‖∞")
        self.peak_plot.add_curve("peak_invalid", "‖L‖<sub>∞</sub> where J = ∞ (not a valid bound)", "muted", 1.2,
                                 Qt.PenStyle.DotLine, export_name="‖L‖∞ where J = ∞")
        self.peak_plot.add_regions("inf")
        self.peak_plot.add_marker("current", "current B<sub>c</sub>", "b", "o",
                                  export_name="‖L‖∞ at current B_c")
        self.peak_plot.add_marker("optimum", "robust optimum", "c", "star", 14, export_name="‖L‖∞ at optimum")
        self.peak_plot.add_line("zero", False, "0 dB: robust limit", "mark", Qt.PenStyle.DashLine)
        self.peak_plot.add_line("bc", True)
        self.peak_plot.set_line("zero", 0.0)

        self.admittance_plot = CurvesPlot("Admittances, eq. 8–9 (Fig. 9)",
                                          ("ω", "rad/s"), ("|Y|", "m/(N·s)"), log_x=True, log_y=True)
        self.admittance_plot.add_curve("yv", "|Y<sub>v</sub>| virtual wall", "muted", 2.0, Qt.PenStyle.DashLine,
                                       export_name="|Y_v|")
        self.admittance_plot.add_curve("yt", "|Y<sub>t</sub>| transmitted", "a", export_name="|Y_t|")
        self.admittance_plot.legend.setOffset((-10, -10))  # bottom right: the resonance is at the top
        self.admittance_plot.add_line("nyquist", True, "π/T", "muted", Qt.PenStyle.DotLine)

        self.position_plot = CurvesPlot("Step: handle position (Figs. 7, 10)", ("t", "s"),
                                        ("x", "mm"))
        self.position_plot.add_curve("wall", "ideal wall F/K (1 − e<sup>−Kt/B</sup>)", "muted", 2.0,
                                     Qt.PenStyle.DashLine, export_name="ideal wall position")
        self.position_plot.add_curve("position", "handle x", "a", export_name="handle position")

        self.force_plot = CurvesPlot("Step: wall force (Figs. 7, 10)", ("t", "s"), ("force", "N"))
        self.force_plot.add_curve("human", "human force F<sub>h</sub>", "muted", 2.0, Qt.PenStyle.DashLine,
                                  export_name="human force")
        self.force_plot.add_curve("force", "actuator force u (held)", "b", export_name="actuator force")

    def views(self) -> list[PlotView]:
        return [self.index_plot, self.peak_plot, self.admittance_plot, self.position_plot, self.force_plot]

    # -- refresh ------------------------------------------------------------------------------------
    def update_views(self) -> None:
        graph = self.ctx.graph
        for name in AT_BC_NODES:
            graph.set_params(name, bc=self.bc)
        st = wall_settings(self.ctx.model.profile)
        point: WallPoint = graph.get("wall_point")
        adm: WallAdmittances = graph.get("wall_admittance")
        trade: WallTradeoff | None = graph.request("wall_tradeoff")
        step: StepResponse | None = graph.request("wall_step")
        fresh = graph.is_fresh("wall_tradeoff")
        self._hold_ranges(graph.interactive)
        if self._changed("tradeoff", trade):
            self._draw_tradeoff(trade)
        if trade is not None:  # usable when fresh (not during a drag that changed the wall)
            o = trade.optimum
            self.panel.show_optimum(o.bc if o.feasible else None, fresh)
        self._draw_point(point, trade if fresh else None)
        if self._changed("admittance", adm):
            self._draw_admittance(adm)
        if step is not None and self._changed("step", step, st.step_force):
            self._draw_step(step, st)
        for name, views in (("wall_tradeoff", (self.index_plot, self.peak_plot)),
                            ("wall_step", (self.position_plot, self.force_plot))):
            busy, text = not graph.is_fresh(name), self._busy_text(name)
            for view in views:
                view.set_busy(busy, text)
        label = wall_device_label(self.ctx.model.profile)
        self.texts.show("summary", lambda: self.summary.setText(
            for_theme(wall_summary(st, point, trade if fresh else None, label), self.dark)))
        self.refreshes += 1
        self.stale = False

    def _busy_text(self, name: str) -> str:
        """While a slider drag holds ``name`` back, that it catches up after the drag."""
        return "updating after the drag…" if name in self.ctx.graph.waiting() else ""

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in ("wall_tradeoff", "wall_step") and self.isVisible():
            self.refresh()

    def _draw_tradeoff(self, trade: WallTradeoff | None) -> None:
        if trade is None:
            return
        c, o = trade.curves, trade.optimum
        hidden = self.index_plot.set_curve("J", c.bc, c.index)
        finite = np.isfinite(c.index)
        with np.errstate(divide="ignore"):
            db = 20.0 * np.log10(c.peak)
        self.peak_plot.set_curve("peak", c.bc, np.where(finite, db, np.nan), gaps=True)
        # the invalid part joins its finite neighbours so that the curve reads as one line
        near = ~finite | np.convolve(~finite, [1, 1, 1], "same").astype(bool)
        self.peak_plot.set_curve("peak_invalid", c.bc, np.where(near, db, np.nan), gaps=True)
        spans = inf_spans(c.bc, ~finite)
        self.index_plot.set_regions("inf", spans)
        self.peak_plot.set_regions("inf", spans)
        if o.feasible:
            self.index_plot.set_marker("optimum", o.bc, o.index)
            self.peak_plot.set_marker("optimum", o.bc, 20.0 * math.log10(o.peak))
        else:
            self.index_plot.set_marker("optimum", None, None)
            self.peak_plot.set_marker("optimum", None, None)
        notes = []
        if hidden:
            notes.append(f"shaded: J = ∞ (closed loop unstable, or J unbounded) at {hidden} of {c.bc.size} "
                         "values of B_c")
        self.index_plot.set_warning(notes)
        self.tradeoff_drawn = trade
        self.index_plot.bump()
        self.peak_plot.bump()

    def _draw_point(self, point: WallPoint, trade: WallTradeoff | None) -> None:
        j = point.index.index if point.index.finite else None
        self.index_plot.set_marker("current", point.bc, j)
        self.peak_plot.set_marker("current", point.bc, point.peak.gain_db)
        for v in (self.index_plot, self.peak_plot):
            v.set_line("bc", point.bc)
        self.texts.show("point", lambda: self._point_texts(point, trade))

    def _point_texts(self, point: WallPoint, trade: WallTradeoff | None) -> None:
        self.index_plot.set_legend_text("current", f"B<sub>c</sub> = {fmt(point.bc)}: J = "
                                        f"{fmt(point.index.index) if point.index.finite else '∞'}")
        self.peak_plot.set_legend_text("current", f"B<sub>c</sub> = {fmt(point.bc)}: "
                                       f"{rich_numbers(f'{point.peak.gain_db:+.2f}')} dB")
        if trade is not None and trade.optimum.feasible:
            o = trade.optimum
            self.index_plot.set_legend_text("optimum", f"robust optimum B<sub>c</sub> = {fmt(o.bc)}")
            self.peak_plot.set_legend_text("optimum", f"robust optimum: {rich_numbers(f'{20 * math.log10(o.peak):+.2f}')} dB")

    def _draw_admittance(self, adm: WallAdmittances) -> None:
        self.admittance_plot.set_curve("yv", adm.w, np.abs(adm.yv))
        self.admittance_plot.set_curve("yt", adm.w, np.abs(adm.yt))
        self.admittance_plot.set_line("nyquist", adm.nyquist if adm.nyquist < adm.w[-1] else None)
        self.texts.show("admittance", lambda: self.admittance_plot.set_legend_text(
            "yt", f"|Y<sub>t</sub>| transmitted, B<sub>c</sub> = {fmt(adm.bc)}"))
        self.admittance_plot.bump()

    def _draw_step(self, step: StepResponse, st: WallSettings) -> None:
        self.position_plot.set_curve("wall", step.t, 1e3 * step.wall_position)
        self.position_plot.set_curve("position", step.t, 1e3 * step.position)
        self.force_plot.set_curve("human", step.t, step.human_force)
        self.force_plot.set_curve("force", step.t, step.force)
        self.position_plot.set_legend_text("position", f"handle x, B<sub>c</sub> = {fmt(step.bc)}")
        self.force_plot.set_legend_text("human", f"human force F<sub>h</sub> = {fmt(st.step_force)} N")
        self.position_plot.bump()
        self.force_plot.bump()



TAB = TransparencyTab
