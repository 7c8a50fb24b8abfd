"""Impedance range: |Z_min| and |Z_max| against ω, log-log, the band between them shaded (Fig. 6)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtGui import QPainterPath
from PySide6.QtWidgets import QGraphicsPathItem, QWidget

from analysis import StabilityResult
from analysis.study import display_kind

from app.views.base import PlotView, Series, clean_xy, plain, rich_label

__all__ = ["RangePlot"]


class RangePlot(PlotView):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Impedance range (Z-width)", parent)
        self.set_log(True, True)
        self.set_axis_labels("ω", "rad/s", "|Z|", "N·s/m")
        self.zmax_curve = self.curve("|Z<sub>max</sub>|", "#1f5fbf")
        self.zmin_curve = self.curve("|Z<sub>min</sub>|", "#2b8a3e")
        # the band between the curves, drawn as one polygon in view (log10) coordinates: cheaper than
        # pg.FillBetweenItem, which rebuilds its path from both curves' paths on every change
        self.fill = QGraphicsPathItem()
        self.fill.setPen(pg.mkPen(None))
        self.fill.setBrush(pg.mkBrush(31, 95, 191, 45))
        self.fill.setZValue(-5)
        self.plot.addItem(self.fill, ignoreBounds=True)
        self.kmax_curve = self.curve("k<sub>max</sub>/ω", "#868e96", width=1.2, style=Qt.PenStyle.DashLine)
        self.bmin_curve = self.curve("b<sub>min</sub>", "#868e96", width=1.2, style=Qt.PenStyle.DotLine)
        self._series: list[Series] = []

    def update_result(self, res: StabilityResult) -> None:
        w = res.w
        label_min, label_max = display_kind(res).range_labels()
        x1, y1, h1 = clean_xy(w, np.abs(res.zmin), True, True)
        x2, y2, h2 = clean_xy(w, np.abs(res.zmax), True, True)
        self.zmin_curve.setData(x1, y1)
        self.zmax_curve.setData(x2, y2)
        self._update_fill(x1, y1, x2, y2)
        self.set_legend_text(self.zmin_curve, rich_label(label_min))
        self.set_legend_text(self.zmax_curve, rich_label(label_max))
        self._series = [Series("|Z_min|", "omega (rad/s)", "|Z_min| (N s/m)", x1, y1),
                        Series("|Z_max|", "omega (rad/s)", "|Z_max| (N s/m)", x2, y2)]
        notes = []
        if h1 + h2:
            notes.append(f"{h1 + h2} point(s) not drawn (non-finite or zero)")
        km, bm = res.k_max, res.b_min
        if np.isfinite(km) and km > 0:
            xk, yk, _ = clean_xy(w, km / w, True, True)
            self.kmax_curve.setData(xk, yk)
            self._series.append(Series("k_max/omega", "omega (rad/s)", "k_max/omega (N s/m)", xk, yk))
        else:
            self.kmax_curve.setData([], [])
        self.set_legend_text(self.kmax_curve, f"k<sub>max</sub>/ω, k<sub>max</sub> = {plain(km)} N/m")
        if np.isfinite(bm) and bm > 0:
            self.bmin_curve.setData([w[0], w[-1]], [bm, bm])
            self._series.append(Series("b_min", "omega (rad/s)", "b_min (N s/m)",
                                       np.array([w[0], w[-1]]), np.array([bm, bm])))
        else:
            self.bmin_curve.setData([], [])
        self.set_legend_text(self.bmin_curve, f"b<sub>min</sub> = {plain(bm)} N·s/m")
        self.set_warning(notes)
        self.bump()

    def _update_fill(self, x1: np.ndarray, y1: np.ndarray, x2: np.ndarray, y2: np.ndarray) -> None:
        if x1.size < 2 or x2.size < 2:
            self.fill.setPath(QPainterPath())
            return
        x = np.log10(np.concatenate([x1, x2[::-1]]))
        y = np.log10(np.concatenate([y1, y2[::-1]]))
        path = pg.arrayToQPath(x, y, connect="all")
        path.closeSubpath()
        self.fill.setPath(path)

    def restyle(self, pal: dict) -> None:
        self.zmax_curve.setPen(pg.mkPen(pal["a"], width=2))
        self.zmin_curve.setPen(pg.mkPen(pal["c"], width=2))
        self.fill.setBrush(pg.mkBrush(pal["fill"]))
        self.kmax_curve.setPen(pg.mkPen(pal["muted"], width=1.2, style=Qt.PenStyle.DashLine))
        self.bmin_curve.setPen(pg.mkPen(pal["muted"], width=1.2, style=Qt.PenStyle.DotLine))

    def export_series(self) -> list[Series]:
        return list(self._series)
