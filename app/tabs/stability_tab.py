"""The stability tab: the stability plot (Figs. 5, 7) above the impedance range plot (Fig. 6)."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QComboBox, QHBoxLayout, QLabel, QSplitter, QVBoxLayout

from app.views.base import PlotView
from app.views.range_plot import RangePlot
from app.views.stability_plot import VIEW_MODES, StabilityPlot
from app.tabs.base import AnalysisTab, scroll_body
from analysis.study.citations import ADAMS
from app.widgets.citation_note import CitationNote

__all__ = ["StabilityTab", "TAB"]


class StabilityTab(AnalysisTab):
    title = "Stability and Z-width"
    order = 10
    nodes = frozenset({"stability"})

    def build(self) -> None:
        ctx = self.ctx
        self.stability = StabilityPlot()
        self.range = RangePlot()
        split = QSplitter(Qt.Orientation.Vertical)
        split.addWidget(self.stability)
        split.addWidget(self.range)
        split.setSizes([1, 1])
        split.setChildrenCollapsible(False)
        self.view_mode = ctx.settings.stability_view()
        if self.view_mode not in VIEW_MODES:
            self.view_mode = "ratio"
        self.mode_box = QComboBox()  # the reserve view by default: the margin where the bound binds
        for mode, text in VIEW_MODES.items():
            self.mode_box.addItem(text, mode)
        self.mode_box.setCurrentIndex(list(VIEW_MODES).index(self.view_mode))
        self.mode_box.setToolTip("What the stability plot shows: the reserve (bound / coupling term, stable below "
                                 "1), the two terms as in the paper, or their magnitudes on a log axis")
        self.mode_box.currentIndexChanged.connect(lambda i: self.set_view_mode(self.mode_box.itemData(i)))
        tools = QHBoxLayout()
        tools.setContentsMargins(4, 0, 4, 0)
        tools.addWidget(QLabel("Stability plot:"))
        tools.addWidget(self.mode_box)
        tools.addStretch(1)
        tools.addWidget(QLabel("Hover a plot to read values; right-click it to export."))
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addLayout(tools)
        lay.addWidget(split, 1)
        lay.addWidget(CitationNote(ADAMS))  # the full citation of the tab's equation numbers

    @property
    def log_y(self) -> bool:
        return self.view_mode == "log"

    def set_log_y(self, on: bool) -> None:
        """Log |values| (on) or the values (off)."""
        self.set_view_mode("log" if on else "values")

    def set_view_mode(self, mode: str) -> None:
        """One of :data:`~app.views.stability_plot.VIEW_MODES`."""
        if mode not in VIEW_MODES:
            raise ValueError(f"unknown stability view mode {mode!r}")
        self.view_mode = mode
        self.ctx.settings.set_stability_view(mode)
        if self.mode_box.currentData() != mode:
            self.mode_box.setCurrentIndex(list(VIEW_MODES).index(mode))
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True

    def update_views(self) -> None:
        graph = self.ctx.graph
        res = graph.get(graph.stability_name)
        for view in (self.stability, self.range):  # still axes during a drag: only the curves repaint
            view.hold_range(graph.interactive)
        self.stability.update_result(res, mode=self.view_mode)
        self.range.update_result(res)
        self.refreshes += 1
        self.stale = False

    def views(self) -> list[PlotView]:
        return [self.stability, self.range]


TAB = StabilityTab
