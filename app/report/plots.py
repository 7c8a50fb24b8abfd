"""The report's plot of named curves (needs Qt), for the report figures the app has no view for:
the transparency curves, the step response, the scenario and the identification fit.  Same axes,
fonts and palette as the app's :class:`~app.views.base.PlotView`; colours are given directly.
"""

from __future__ import annotations

import math
import re

from app import qt_compat  # noqa: F401 - before any Qt call

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt

from app.views.base import PlotView, Series, clean_xy

__all__ = ["CurvesPlot"]


class CurvesPlot(PlotView):
    """Named curves on shared axes (report figures the app has no view for)."""

    def __init__(self, title: str, x: tuple[str, str], y: tuple[str, str], log_x: bool = False,
                 log_y: bool = False) -> None:
        super().__init__(title)
        self.set_log(log_x, log_y)
        self.set_axis_labels(x[0], x[1], y[0], y[1])
        self._series: list[Series] = []

    def add(self, name: str, x, y, color: str, style: Qt.PenStyle = Qt.PenStyle.SolidLine, width: float = 2.0,
            symbol: str | None = None) -> None:
        lx, ly = self.is_log()
        xs, ys, _ = clean_xy(np.asarray(x, float), np.asarray(y, float), lx, ly)
        if symbol:
            item = pg.PlotDataItem(xs, ys, pen=None, symbol=symbol, symbolSize=10, symbolBrush=color,
                                   symbolPen="w", name=name)
            item.setZValue(20)
            self.plot.addItem(item)
        else:
            item = self.curve(name, color, width, style)
            item.setData(xs, ys)
        plain = re.sub(r"<sub>(.*?)</sub>", r"_\1", name)  # a legend's F<sub>d</sub> is F_d in the export
        self._series.append(Series(plain, *self.export_axes(), xs, ys))

    def hline(self, y: float, label: str) -> None:
        pos = math.log10(y) if self.is_log()[1] else y
        line = pg.InfiniteLine(pos=pos, angle=0, movable=False,
                               pen=pg.mkPen("#c92a2a", width=1, style=Qt.PenStyle.DotLine),
                               label=label, labelOpts={"position": 0.03, "color": "#c92a2a",
                                                       "anchors": [(0, 1), (0, 1)]})  # starts at 3 %: never clipped
        self.plot.addItem(line, ignoreBounds=True)

    def export_series(self) -> list[Series]:
        return list(self._series)
