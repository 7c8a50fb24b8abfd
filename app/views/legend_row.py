"""A legend below the plot, outside the data area: for small plots where any corner holds data.

The legend is laid out in the plot item's grid (a row under the x axis, the whole width), so it is
part of the scene and PNG/SVG/PDF exports keep it.  :class:`LegendRow` chooses how many entries
share a row so that the legend is never wider than the plot (a wider legend would widen the
scene beyond the widget and cut the plot on the right).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import pyqtgraph as pg
from PySide6.QtCore import QObject
from PySide6.QtWidgets import QGraphicsItem

from app.widgets.settle import settle_later

__all__ = ["BelowLegend", "LegendRow", "HaloSample", "swatch", "set_swatch_brush", "sync_legend"]


class HaloSample(pg.ItemSample):
    """A legend sample that draws a line's ``shadowPen`` (its halo) under its pen, as the plot does:
    pyqtgraph's sample draws the pen only, so the ρ = 1 contour's black line, which shows on the map
    by its white halo, was black on the dark theme's background (1.27:1)."""

    def paint(self, p: object, *args: object) -> None:
        shadow = getattr(self.item, "opts", {}).get("shadowPen")
        if shadow is not None and self.item.isVisible() and not isinstance(self.item, pg.ScatterPlotItem):
            p.setPen(pg.mkPen(shadow))
            p.drawLine(0, 11, 20, 11)
        super().paint(p, *args)


def swatch(brush: object, symbol: str = "s", size: float = 12) -> pg.PlotDataItem:
    """A legend-only sample (no points) showing a shading's ``brush``: add it with ``legend.addItem``."""
    item = pg.PlotDataItem([], [], pen=None, symbol=symbol, symbolSize=size, symbolBrush=brush, symbolPen=None)
    set_swatch_brush(item, brush)
    return item


def set_swatch_brush(item: pg.PlotDataItem, brush: object) -> None:
    """Colour a :func:`swatch` (also after a theme change).

    pyqtgraph's legend sample draws the item's scatter's default brush and pen, which an item
    without points never receives from ``symbolBrush`` (the swatch was pyqtgraph's slate square
    with a grey outline, whatever the shading's colour).
    """
    item.setSymbolBrush(brush)
    item.scatter.setBrush(brush, update=False)
    item.scatter.setPen(pg.mkPen(None), update=False)


def sync_legend(legend: pg.LegendItem, entries: Sequence[tuple[QGraphicsItem, str]]) -> None:
    """Make ``legend`` list exactly ``entries`` (item, text), in this order; nothing is done when
    it does already.  For items that come and go (a curve with no data hidden would show
    pyqtgraph's crossed-eye "hidden" icon, an entry for data not loaded would promise it)."""
    current = [(sample.item, label.text) for sample, label in legend.items]
    if len(current) == len(entries) and all(a is b and s == t for (a, s), (b, t) in zip(current, entries)):
        return
    legend.clear()
    for item, text in entries:
        legend.addItem(item, text)


class BelowLegend(pg.LegendItem):
    """A legend laid out below a plot (no anchor); ``resized()`` is called when its size changes."""

    def __init__(self, resized: Callable[[], None], **kwargs: object) -> None:
        kwargs.setdefault("sampleType", HaloSample)
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
        entries = [(sample.item, label.text) for sample, label in old.items]
        old.clear()
        if old.scene() is not None:
            old.scene().removeItem(old)
        legend = BelowLegend(self.schedule, labelTextSize="8pt", colCount=columns, horSpacing=2,
                             verSpacing=-6)
        legend.setParentItem(plot)
        plot.layout.addItem(legend, 4, 0, 1, 3)  # the whole width, below the x axis
        plot.legend = legend  # curves plotted later join this legend
        for item, text in entries:
            legend.addItem(item, text)
        legend.setBrush(pg.mkBrush(0, 0, 0, 0))
        legend.setPen(pg.mkPen(None))
        self.legend = legend

    def schedule(self) -> None:
        """Refit after the legend's texts or size changed, before the next paint (:func:`settle_later`)."""
        settle_later(self, self.fit)

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
