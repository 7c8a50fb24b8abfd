"""Stability map: the exact spectral radius of the sampled loop over two parameters (a heat map).

Both axes are logarithmic (the sweep grids are geometric, so every pixel has the same width in
log10 units and the image sits on the log axes exactly).  The colour map is diverging with white
at spectral radius 1: blue is stable, red unstable, and a black contour marks rho = 1.  The
current design is marked with a point (or a vertical line when the y parameter of the current
design is zero, e.g. the hands-off grasp mass).
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QFont, QFontMetrics
from PySide6.QtWidgets import QWidget

from analysis.sampled import StabilityMap

from analysis.study.labels import PARAMETER_LABELS
from analysis.study import format_number
from app.views.base import Axis, PlotView, Series, plain
from app.views.marker import design_marker, marker_xy, move_marker, set_marker_brush

__all__ = ["StabilityMapView", "PARAMETER_LABELS", "radius_colormap"]

#: The rho = 1 contour: a dark line on a light halo (visible on blue, white, red and either theme).
CONTOUR_PEN, CONTOUR_HALO = "#000000", "#ffffff"
#: Colour scale capped here so that a few wildly unstable pixels do not wash out the boundary.
RHO_CAP = 1.5


def radius_colormap(lo: float, hi: float) -> pg.ColorMap:
    """Blue (stable) -> white at rho = 1 -> red (unstable), for levels ``(lo, hi)``."""
    f = min(max((1.0 - lo) / (hi - lo), 0.02), 0.98)
    pos = [0.0, f * 0.5, f, f + (1 - f) * 0.5, 1.0]
    colors = [(33, 76, 158), (120, 170, 220), (248, 248, 248), (236, 130, 95), (165, 15, 21)]
    return pg.ColorMap(pos, colors)


class StabilityMapView(PlotView):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Stability map: spectral radius ρ of the sampled loop", parent)
        self.set_log(True, True)
        self.plot.showGrid(x=False, y=False)
        self.image = pg.ImageItem(axisOrder="row-major")
        self.image.setZValue(-10)
        self.plot.addItem(self.image)
        # rho = 1 runs through the white band of the colour map and borders blue and red: a black line
        # on a white halo is visible on all of them, in both themes
        self.contour_halo = pg.IsocurveItem(level=1.0, pen=pg.mkPen(CONTOUR_HALO, width=4.5), axisOrder="row-major")
        self.contour_halo.setParentItem(self.image)
        self.contour = pg.IsocurveItem(level=1.0, pen=pg.mkPen(CONTOUR_PEN, width=2), axisOrder="row-major")
        self.contour.setParentItem(self.image)
        self.bar = pg.ColorBarItem(values=(0.9, 1.1), colorMap=radius_colormap(0.9, 1.1), width=18,
                                   label="spectral radius ρ", interactive=False,
                                   colorMapMenu=False)
        self.bar.setImageItem(self.image, insert_in=self.plot)
        # moved on every step of a slider drag: a bare scatter item (app.views.marker)
        self.point = design_marker("current design", "star", 16, "#ffd43b", pg.mkPen("k", width=1.2))
        self.plot.addItem(self.point)
        self.xline = pg.InfiniteLine(angle=90, movable=False,
                                     pen=pg.mkPen("#212529", width=1.5, style=Qt.PenStyle.DashLine))
        self.xline.setZValue(19)
        self.xline.hide()
        self.plot.addItem(self.xline, ignoreBounds=True)
        self.legend_line = pg.PlotDataItem([], [], pen=pg.mkPen(CONTOUR_PEN, width=2),
                                           shadowPen=pg.mkPen(CONTOUR_HALO, width=4.5))
        self.legend.addItem(self.legend_line, "ρ = 1")
        self.legend_outside(2)  # the map fills the plot: a legend inside would hide part of it
        self.map: StabilityMap | None = None
        self.subtitle = ""
        self.levels = (0.9, 1.1)
        self._notes: list[str] = []
        self._point_note = ""
        self.set_axis_labels("k_c", "N/m", "k_obj", "N/m")
        self.cursor_label.setMinimumWidth(0)
        self.plot_widget.setMinimumSize(180, 170)

    def set_busy(self, busy: bool, text: str = "") -> None:
        self.header.setText(f"<b>{self.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def update_map(self, m: StabilityMap | None, subtitle: str = "") -> None:
        self.map = m
        self._notes = []
        if m is None:
            self.image.clear()
            self.contour.setData(None)
            self.contour_halo.setData(None)
            self.bump()
            return
        xn, xu = PARAMETER_LABELS.get(m.x_name, (m.x_name, ""))
        yn, yu = PARAMETER_LABELS.get(m.y_name, (m.y_name, ""))
        self.set_axis_labels(xn, xu, yn, yu)
        rho = np.asarray(m.spectral_radius, float)
        finite = rho[np.isfinite(rho)]
        lo = float(min(finite.min(), 0.999)) if finite.size else 0.9
        hi = float(max(finite.max(), 1.001)) if finite.size else 1.1
        if hi > RHO_CAP:
            self._notes.append(f"ρ reaches {plain(hi)}; colours saturate at {RHO_CAP}")
            hi = RHO_CAP
        self.levels = (lo, hi)
        self.image.setImage(rho, autoLevels=False, levels=self.levels)
        self.bar.setColorMap(radius_colormap(lo, hi))
        self.bar.setLevels(self.levels)
        lx, ly = np.log10(m.x), np.log10(m.y)
        dx = float(lx[1] - lx[0]) if lx.size > 1 else 1.0
        dy = float(ly[1] - ly[0]) if ly.size > 1 else 1.0
        self.image.setRect(QRectF(lx[0] - dx / 2, ly[0] - dy / 2, dx * lx.size, dy * ly.size))
        self.contour.setData(np.where(np.isfinite(rho), rho, 10.0), 1.0)
        self.contour_halo.setData(np.where(np.isfinite(rho), rho, 10.0), 1.0)
        stable = m.stable
        self.header.setText(f"<b>{self.title}</b>")
        self.subtitle = subtitle
        self._fit_title()
        if stable.all():
            self._notes.append("the whole map is stable (ρ ≤ 1)")
        elif not stable.any():
            self._notes.append("the whole map is unstable (ρ > 1)")
        self.plot.getViewBox().autoRange(padding=0.0)
        self._refresh_warning()
        self.bump()

    def update_point(self, x: float, y: float | None, stable: bool | None) -> None:
        """The current design at ``(x, y)``; ``y`` None or <= 0 draws a vertical line at ``x``."""
        self._point_note = ""
        if not (x > 0 and math.isfinite(x)):
            move_marker(self.point, math.nan, math.nan)
            self.xline.hide()
            self._point_note = "current design not drawn (zero on a log axis)"
        elif y is None or not (y > 0 and math.isfinite(y)):
            move_marker(self.point, math.nan, math.nan)
            self.xline.setPos(math.log10(x))
            self.xline.show()
            self._point_note = "current design: dashed line (its y value is 0, off the log axis)"
        else:
            self.xline.hide()
            move_marker(self.point, x, y)
        if stable is not None:
            set_marker_brush(self.point, "#ffd43b" if stable else "#e03131")
        self._refresh_warning()
        self.bump()

    @property
    def point_xy(self) -> tuple[float, float] | None:
        """The current design's marker in data units (None when not drawn)."""
        return marker_xy(self.point)

    def value_at(self, x: float, y: float) -> float:
        m = self.map
        if m is None or not (x > 0 and y > 0):
            return math.nan
        i = int(np.argmin(np.abs(np.log10(m.x) - math.log10(x))))
        j = int(np.argmin(np.abs(np.log10(m.y) - math.log10(y))))
        return float(m.spectral_radius[j, i])

    def cursor_text(self, x: float, y: float) -> str:
        return super().cursor_text(x, y) + f",  ρ = {plain(self.value_at(x, y), 5)}"

    def _refresh_warning(self) -> None:
        self.set_warning([*self._notes, self._point_note])

    def _fit_title(self) -> None:
        """The subtitle above the map, its "; "-separated parts wrapped to the plot's width.

        The title is part of the plot's scene (exports keep it); one long line would set the plot's
        minimum width beyond the widget and cut the map and its colour bar on the right.
        """
        if not self.subtitle:
            self.plot.setTitle(None)
            return
        metrics = QFontMetrics(QFont(self.font().family(), 9))
        # the title sits above the data area only: not above the y axis, not above the colour bar
        axis = self.plot.getAxis("left")
        avail = max(self.plot_widget.width() - max(axis.width(), 50) - max(self.bar.width(), 80) - 16, 100)
        lines: list[str] = []
        for part in self.subtitle.split("; "):
            if lines and metrics.horizontalAdvance(f"{lines[-1]}; {part}") <= avail:
                lines[-1] = f"{lines[-1]}; {part}"
            else:
                lines.append(part)
        text = "<br>".join(lines)
        if text != self.plot.titleLabel.text:
            self.plot.setTitle(text, size="9pt", color=self.palette_colors()["fg"])
            height = len(lines) * metrics.lineSpacing() + 8  # setTitle fixes one line's 30 px
            self.plot.titleLabel.setMaximumHeight(height)
            self.plot.layout.setRowFixedHeight(0, height)
            self.fit_scene()

    def resizeEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self._fit_title()

    def restyle(self, pal: dict) -> None:
        self.xline.setPen(pg.mkPen(pal["fg"], width=1.5, style=Qt.PenStyle.DashLine))
        for name in ("left", "right"):
            axis = self.bar.getAxis(name)
            axis.setPen(pg.mkPen(pal["fg"]))
            axis.setTextPen(pg.mkPen(pal["fg"]))
        self.bar.getAxis("left").setLabel("spectral radius ρ", color=pal["fg"])
        if self.subtitle:
            self.plot.setTitle(self.plot.titleLabel.text, size="9pt", color=pal["fg"])

    def export_series(self) -> list[Series]:
        m = self.map
        if m is None:
            return []
        xn, xu = PARAMETER_LABELS.get(m.x_name, (m.x_name, ""))
        yn, yu = PARAMETER_LABELS.get(m.y_name, (m.y_name, ""))
        return [Series(f"ρ at {yn} = {format_number(float(yv))} {yu}", Axis(xn, xu), Axis("ρ", ""),
                       np.asarray(m.x, float), np.asarray(m.spectral_radius[j], float))
                for j, yv in enumerate(m.y)]
