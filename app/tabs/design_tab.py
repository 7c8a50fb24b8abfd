"""The design tab: the design chart (computed on the worker) with the current gains on it."""

from __future__ import annotations

from PySide6.QtCore import QTimer, Slot
from PySide6.QtWidgets import QLabel, QVBoxLayout

from analysis.study import display_kind

from app.views.base import PlotView
from app.widgets.colors import CURSOR_COLORS
from app.views.design_chart import DesignChart
from app.tabs.base import AnalysisTab, scroll_body
from analysis.study.citations import ADAMS
from app.widgets.citation_note import CitationNote

__all__ = ["DesignTab", "TAB"]


class DesignTab(AnalysisTab):
    title = "Design chart"
    order = 20
    nodes = frozenset({"design_chart", "stability"})

    def build(self) -> None:
        ctx = self.ctx
        self.chart = DesignChart()
        self._shown: object = None
        self.hint = hint = QLabel("Click the chart to set the coupling gains (one undo step).  The chart is conservative: "
                      "every point in the shaded region satisfies the two-port bound over the analysis band.")
        hint.setWordWrap(True)
        hint.setStyleSheet(f"color: {CURSOR_COLORS[0]};")  # muted, still 4.5:1 on the window colour
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(self.chart, 1)
        lay.addWidget(hint)
        lay.addWidget(CitationNote(ADAMS))  # the full citation of the tab's equation numbers
        self.chart.pointPicked.connect(self._on_pick)
        ctx.graph.ready.connect(self._on_ready)

    def update_views(self) -> None:
        graph = self.ctx.graph
        fresh = graph.is_fresh("design_chart")
        value = graph.result("design_chart")
        if not fresh:
            # start the worker after this frame is painted: the first paint of the tab and a
            # starting worker would otherwise compete for the GIL within one frame
            QTimer.singleShot(20, self._request_chart)
        p = self.ctx.model.profile
        kind = display_kind(p)
        shown = value if value is not None and display_kind(value) is kind else None
        if shown is not self._shown:  # redraw the curves only when the chart itself changed
            self.chart.update_chart(shown)
            self._shown = shown
        self.chart.set_busy(not fresh)
        stable = graph.get(graph.stability_name).stable
        self.chart.update_point(*kind.chart_point(p), stable)
        self.refreshes += 1
        self.stale = False

    @Slot()
    def _request_chart(self) -> None:
        if self.isVisible() and not self.ctx.graph.is_fresh("design_chart"):
            self.ctx.graph.request("design_chart")

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == "design_chart" and self.isVisible():
            self.refresh()

    @Slot(float, float)
    def _on_pick(self, x: float, y: float) -> None:
        x, y = float(f"{x:.4g}"), float(f"{y:.4g}")
        edits = display_kind(self.ctx.model.profile).edits_from_chart(x, y)
        self.ctx.editor.edit_many(edits, "Pick gains on the design chart")

    def views(self) -> list[PlotView]:
        return [self.chart]

    def apply_theme(self, dark: bool) -> None:
        super().apply_theme(dark)
        if self.is_built():
            self.hint.setStyleSheet(f"color: {CURSOR_COLORS[1 if dark else 0]};")


TAB = DesignTab
