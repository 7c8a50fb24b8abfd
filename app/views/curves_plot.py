"""A plot of named curves, point markers and reference lines, configured by the tab that owns it.

The transparency and observer tabs draw several plots of the same kind (magnitudes against ω,
time responses, curves against B_c); this one class draws them all.  Every curve and marker keeps
the data exactly as drawn (after :func:`~app.views.base.clean_xy`), which is what
:meth:`CurvesPlot.export_series` returns and what the tests compare with the analysis results.
"""

from __future__ import annotations

import math
import re

import numpy as np
from numpy.typing import ArrayLike
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QGraphicsItem, QGraphicsTextItem, QSizePolicy, QWidget

from app.views.base import Axis, PlotView, Series, clean_xy
from app.views.marker import design_marker, move_marker

__all__ = ["CurvesPlot"]


class CurvesPlot(PlotView):
    """``add_curve``/``add_marker``/``add_line`` once, then ``set_curve``/``set_marker``/``set_line``.

    Colours are palette keys (``"a"``, ``"b"``, ``"c"``, ``"mark"``, ``"muted"``) so that the
    plot follows the theme.
    """

    def __init__(self, title: str, x: tuple[str, str], y: tuple[str, str], log_x: bool = False,
                 log_y: bool = False, parent: QWidget | None = None) -> None:
        super().__init__(title, parent)
        self.plot_widget.setMinimumSize(240, 170)
        # long titles and the readout may be cut rather than widen the window
        for label in (self.header, self.cursor_label):
            label.setMinimumWidth(0)
            label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        policy = self.header.sizePolicy()
        policy.setHeightForWidth(True)  # the title wraps (PlotView): its height follows its width
        self.header.setSizePolicy(policy)
        head = self.layout().itemAt(0).layout()
        head.setStretch(0, 5)  # the title gets most of the row, the readout the rest
        head.setStretch(1, 0)
        head.setStretch(2, 2)
        self.set_log(log_x, log_y)
        self.set_axis_labels(x[0], x[1], y[0], y[1])
        self._styles: dict[str, tuple] = {}
        self.items: dict[str, pg.PlotDataItem] = {}
        self.lines: dict[str, pg.InfiniteLine] = {}
        self.regions: dict[str, list[pg.LinearRegionItem]] = {}
        self.region_spans: dict[str, list[tuple[float, float]]] = {}
        self._data: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self._raw: dict[str, tuple[np.ndarray, np.ndarray, bool]] = {}  # the last inputs of set_curve
        self._export_names: dict[str, str] = {}
        self.hidden_points: dict[str, int] = {}

    # -- building --------------------------------------------------------------------------------
    def add_curve(self, key: str, name: str, color: str = "a", width: float = 2.0,
                  style: Qt.PenStyle = Qt.PenStyle.SolidLine, export_name: str | None = None) -> pg.PlotDataItem:
        item = self.curve(name, self.palette_colors()[color], width, style)
        self._styles[key] = ("curve", color, width, style)
        self.items[key] = item
        self._export_names[key] = export_name or key
        return item

    def remove_curve(self, key: str) -> None:
        """Take a curve (and its legend entry) out of the plot; unknown keys are ignored."""
        item = self.items.pop(key, None)
        if item is None:
            return
        self.legend.removeItem(item)
        self.plot.removeItem(item)
        for store in (self._styles, self._data, self._raw, self._export_names, self.hidden_points):
            store.pop(key, None)

    def add_marker(self, key: str, name: str, color: str = "mark", symbol: str = "o", size: float = 10.0,
                   export_name: str | None = None) -> pg.ScatterPlotItem:
        """One point, moved on every step of a drag: a bare scatter item in view coordinates (a
        one-point ``PlotDataItem`` rebuilds its curve and scatter on every ``setData``)."""
        c = self.palette_colors()[color]
        item = design_marker(name, symbol, size, c, pg.mkPen(c))
        self.plot.addItem(item)
        self._styles[key] = ("marker", color, size, symbol)
        self.items[key] = item
        self._export_names[key] = export_name or key
        return item

    def add_line(self, key: str, vertical: bool, label: str = "", color: str = "muted",
                 style: Qt.PenStyle = Qt.PenStyle.DashLine) -> pg.InfiniteLine:
        pen = pg.mkPen(self.palette_colors()[color], width=1.2, style=style)
        opts = {"position": 0.92 if vertical else 0.08, "color": self.palette_colors()[color],
                "movable": False, "anchors": [(0, 0), (0, 0)] if vertical else [(0, 1), (0, 1)]}
        line = pg.InfiniteLine(angle=90 if vertical else 0, movable=False, pen=pen, label=label or None,
                               labelOpts=opts if label else None)
        line.setZValue(5)
        line.hide()
        self.plot.addItem(line, ignoreBounds=True)
        self._styles[key] = ("line", color, 1.2, style)
        self.lines[key] = line
        return line

    def add_regions(self, key: str, color: str = "bad") -> None:
        """Shaded x ranges (e.g. where a quantity is not defined)."""
        self._styles[key] = ("regions", color, 0, 0)
        self.regions[key] = []
        self.region_spans[key] = []

    def set_log(self, x: bool, y: bool) -> None:
        if (x, y) != self.is_log():
            self._raw = {}  # the same data is drawn otherwise on other axes
            for key in [k for k, style in getattr(self, "_styles", {}).items() if style[0] == "marker"]:
                self._data.pop(key, None)  # in view coordinates: set again by the next set_marker
                move_marker(self.items[key], math.nan, math.nan)
        super().set_log(x, y)

    def showEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().showEvent(event)
        self.cache_texts()

    def cache_texts(self) -> None:
        """Keep the texts (legend, axis titles, line labels) and legend samples as pixmaps: a
        repaint for a moved curve or marker then copies them instead of laying the text out again
        (exports switch the caches off, :meth:`~app.views.base.PlotView.render_into`)."""
        cache = QGraphicsItem.CacheMode.DeviceCoordinateCache
        for item in self.plot_widget.scene().items():
            if isinstance(item, (QGraphicsTextItem, pg.ItemSample)) and item.cacheMode() != cache:
                item.setCacheMode(cache)

    # -- updating --------------------------------------------------------------------------------
    def set_curve(self, key: str, x: ArrayLike, y: ArrayLike, gaps: bool = False) -> int:
        """Draw ``y`` against ``x`` (values that cannot be drawn are dropped); returns how many.

        With ``gaps`` the line breaks where values are dropped instead of joining across them.
        """
        raw = (np.array(x, float), np.array(y, float), gaps)
        old = self._raw.get(key)
        if old is not None and old[2] == gaps and all(
                a.shape == b.shape and np.array_equal(a, b, equal_nan=True) for a, b in zip(old[:2], raw[:2])):
            return self.hidden_points[key]  # unchanged (e.g. the parts a slider does not move): no redraw
        self._raw[key] = raw
        lx, ly = self.is_log()
        xc, yc, hidden = clean_xy(x, y, lx, ly)
        if gaps and hidden:
            xa, ya = np.asarray(x, float), np.asarray(y, float)
            ok = np.isfinite(xa) & np.isfinite(ya)
            if lx:
                ok &= xa > 0
            if ly:
                ok &= ya > 0
            self.items[key].setData(xa, np.where(ok, ya, np.nan), connect="finite")
        else:
            self.items[key].setData(xc, yc)
        self._data[key] = (xc, yc)
        self.hidden_points[key] = hidden
        return hidden

    def set_marker(self, key: str, x: float | None, y: float | None) -> None:
        """One point (or none when ``x``/``y`` is ``None`` or cannot be drawn)."""
        log = self.is_log()
        xc, yc, hidden = clean_xy([] if x is None or y is None else [x], [] if x is None or y is None else [y], *log)
        move_marker(self.items[key], xc[0] if xc.size else math.nan, yc[0] if yc.size else math.nan, log)
        self._data[key] = (xc, yc)
        self.hidden_points[key] = hidden

    def set_line(self, key: str, pos: float | None) -> None:
        line = self.lines[key]
        lx, ly = self.is_log()
        logged = lx if line.angle == 90 else ly
        if pos is None or not math.isfinite(pos) or (logged and pos <= 0):
            line.hide()
            return
        line.setPos(math.log10(pos) if logged else pos)
        line.show()

    def set_regions(self, key: str, spans: list[tuple[float, float]]) -> None:
        for item in self.regions[key]:
            self.plot.removeItem(item)
        lx = self.is_log()[0]
        brush = pg.mkBrush(self.palette_colors()[self._styles[key][1]])
        items = []
        for lo, hi in spans:
            vals = (math.log10(lo), math.log10(hi)) if lx else (lo, hi)
            item = pg.LinearRegionItem(vals, movable=False, brush=brush, pen=pg.mkPen(None))
            item.setZValue(-10)
            self.plot.addItem(item)
            items.append(item)
        self.regions[key] = items
        self.region_spans[key] = list(spans)

    def set_legend_text(self, key: str, text: str) -> None:
        label = self.legend.getLabel(self.items[key])
        fg = self.palette_colors()["fg"]
        if label is not None and (label.text != text or label.opts.get("color") != fg):
            label.setText(text, color=fg)  # (an unchanged text is not laid out again: drags)

    def set_busy(self, busy: bool, text: str = "") -> None:
        """Say in the title that the plot is being computed (``text``: e.g. that it catches up
        after a slider drag, :meth:`~app.core.compute_graph.ComputeGraph.waiting`)."""
        head = f"<b>{self.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else "")
        if head != self.header.text():
            self.header.setText(head)

    def data(self, key: str) -> tuple[np.ndarray, np.ndarray]:
        """The data of a curve or marker as drawn."""
        return self._data.get(key, (np.empty(0), np.empty(0)))

    # -- theme and export ------------------------------------------------------------------------
    def restyle(self, pal: dict) -> None:
        for _sample, label in self.legend.items:
            label.setText(label.text, color=pal["fg"])
        for key, (kind, color, a, b) in self._styles.items():
            c = pal[color]
            if kind == "curve":
                self.items[key].setPen(pg.mkPen(c, width=a, style=b))
            elif kind == "regions":
                for item in self.regions[key]:
                    item.setBrush(pg.mkBrush(c))
            elif kind == "marker":
                self.items[key].setBrush(pg.mkBrush(c))
                self.items[key].setPen(pg.mkPen(c))
            else:
                self.lines[key].setPen(pg.mkPen(c, width=a, style=b))
                label = getattr(self.lines[key], "label", None)
                if label is not None:
                    label.setColor(c)

    def export_series(self) -> list[Series]:
        xl, yl = (Axis(_plain(a.quantity), a.unit) for a in self.export_axes())
        return [Series(self._export_names[k], xl, yl, x, y) for k, (x, y) in self._data.items() if x.size]


def _plain(text: str) -> str:
    """A label without its rich-text tags (for CSV headers)."""
    return re.sub(r"<[^>]+>", "", text)
