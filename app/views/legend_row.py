"""A legend below the plot, outside the data area: for small plots where any corner holds data.

The legend is laid out in the plot item's grid (a row under the x axis, the whole width), so it is
part of the scene and PNG/SVG/PDF exports keep it.  :class:`LegendRow` chooses how many entries
share a row so that the legend is never wider than the plot (a wider legend would widen the
scene beyond the widget and cut the plot on the right).
"""

from __future__ import annotations

from collections.abc import Callable

import pyqtgraph as pg
from PySide6.QtCore import QObject, QTimer

__all__ = ["BelowLegend", "LegendRow"]


class BelowLegend(pg.LegendItem):
    """A legend laid out below a plot (no anchor); ``resized()`` is called when its size changes."""

    def __init__(self, resized: Callable[[], None], **kwargs: object) -> None:
        super().__init__(offset=None, **kwargs)
        self._resized = resized

    def resizeEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self._resized()


class LegendRow(QObject):
    """Moves ``plot``'s legend ``old`` into a row below the x axis; ``legend`` is the new one.

    ``width()`` gives the widget's width; ``relayout()`` lays the scene out again after a change.
    """

    def __init__(self, plot: pg.PlotItem, old: pg.LegendItem, width: Callable[[], int],
                 relayout: Callable[[], None], columns: int = 3, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.plot, self._width, self._relayout = plot, width, relayout
        self._timer = QTimer(self)  # refits after the legend's texts or size changed
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.fit)
        entries = [(sample.item, label.text) for sample, label in old.items]
        old.clear()
        if old.scene() is not None:
            old.scene().removeItem(old)
        legend = BelowLegend(self._timer.start, labelTextSize="8pt", colCount=columns, horSpacing=2,
                             verSpacing=-6)
        legend.setParentItem(plot)
        plot.layout.addItem(legend, 4, 0, 1, 3)  # the whole width, below the x axis
        plot.legend = legend  # curves plotted later join this legend
        for item, text in entries:
            legend.addItem(item, text)
        legend.setBrush(pg.mkBrush(0, 0, 0, 0))
        legend.setPen(pg.mkPen(None))
        self.legend = legend

    def fit(self) -> None:
        """As many entries per row as fit in the widget's width (at least one)."""
        widths = [s.boundingRect().width() + lab.item.boundingRect().width() + 8 for s, lab in self.legend.items]
        avail = self._width() - 12
        cols, total = 0, 0.0
        for w in sorted(widths, reverse=True):
            if cols and total + w > avail:
                break
            total += w
            cols += 1
        cols = max(1, min(cols, len(widths) or 1))
        if cols != self.legend.columnCount:
            self.legend.setColumnCount(cols)
            self.plot.layout.invalidate()
            self._relayout()
