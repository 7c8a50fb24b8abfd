"""The stability tab: the stability plot (Figs. 5, 7) above the impedance range plot (Fig. 6)."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QCheckBox, QHBoxLayout, QLabel, QSplitter, QVBoxLayout, QWidget

from app.views.base import PlotView
from app.views.range_plot import RangePlot
from app.views.stability_plot import StabilityPlot
from app.tabs.base import AnalysisTab, AppContext

__all__ = ["StabilityTab", "TAB"]


class StabilityTab(AnalysisTab):
    title = "Stability and Z-width"
    order = 10
    nodes = frozenset({"stability"})

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(ctx, parent)
        self.stability = StabilityPlot()
        self.range = RangePlot()
        split = QSplitter(Qt.Orientation.Vertical)
        split.addWidget(self.stability)
        split.addWidget(self.range)
        split.setSizes([1, 1])
        split.setChildrenCollapsible(False)
        self.log_y = ctx.settings.log_y()
        self.log_y_box = QCheckBox("Logarithmic y on the stability plot (shows |values|)")
        self.log_y_box.setChecked(self.log_y)
        self.log_y_box.toggled.connect(self.set_log_y)
        tools = QHBoxLayout()
        tools.setContentsMargins(4, 0, 4, 0)
        tools.addWidget(self.log_y_box)
        tools.addStretch(1)
        tools.addWidget(QLabel("Hover a plot to read values; right-click it to export."))
        lay = QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addLayout(tools)
        lay.addWidget(split, 1)

    def set_log_y(self, on: bool) -> None:
        self.log_y = bool(on)
        self.ctx.settings.set_log_y(self.log_y)
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True

    def refresh(self) -> None:
        graph = self.ctx.graph
        res = graph.get(graph.stability_name)
        for view in (self.stability, self.range):  # still axes during a drag: only the curves repaint
            view.hold_range(graph.interactive)
        self.stability.update_result(res, self.log_y)
        self.range.update_result(res)
        self.refreshes += 1
        self.stale = False

    def plot_views(self) -> list[PlotView]:
        return [self.stability, self.range]


TAB = StabilityTab
