"""The workspace of a multi-DOF linkage (issue 25): the map, the linkage at the handle, the polar limits.

* :class:`WorkspaceMapView` -- the critical stiffness of the worst plane wall over the grid of handle
  positions as a heat map (colour bar, grey where the linkage does not reach), the design bound (the
  worst point, a star), the linkage drawn at the handle, the inertia ellipse there and the worst
  normal there as an arrow.  A left click emits
  :attr:`~app.views.pickable.PickablePlotView.pointPicked` ``(x, y)`` [m].
* :class:`WorkspacePolarView` -- the critical stiffness of a plane wall along each direction at the
  handle, in polar form (``x = k cos θ``, ``y = k sin θ``), with the isotropic wall's circle and the
  worst normal.

Both only draw what :mod:`analysis.study.workspace` computed.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRectF
from PySide6.QtWidgets import QWidget

from analysis.multidof import WorkspaceMap
from analysis.study import WorkspacePoint, format_number, inertia_ellipse, polar_curve

from app.views.base import Axis, PlotView, Series, plain
from app.views.marker import design_marker, move_marker
from app.views.pickable import PickablePlotView

__all__ = ["WorkspaceMapView", "WorkspacePolarView", "UNREACHABLE_COLOR", "ELLIPSE_FRACTION", "nearest_value"]

#: Where the linkage does not reach (or is singular).
UNREACHABLE_COLOR = (150, 150, 150, 255)
#: The inertia ellipse's larger semi-axis, as a fraction of the map's smaller side.
ELLIPSE_FRACTION = 0.12
_LINKAGE, _ELLIPSE, _ARROW, _HANDLE = "#212529", "#1c7ed6", "#e03131", "#ffd43b"
X_AXIS, Y_AXIS, K_AXIS = Axis("x", "m"), Axis("y", "m"), Axis("k_worst", "N/m")


def nearest_value(m: WorkspaceMap, x: float, y: float) -> float:
    """The worst plane-wall stiffness [N/m] at the grid point nearest ``(x, y)`` (NaN off the grid)."""
    if not (m.x[0] - 1e-12 <= x <= m.x[-1] + 1e-12 and m.y[0] - 1e-12 <= y <= m.y[-1] + 1e-12):
        return math.nan
    i, j = int(np.argmin(np.abs(m.x - x))), int(np.argmin(np.abs(m.y - y)))
    return float(m.worst_stiffness[j, i])


class WorkspaceMapView(PickablePlotView):
    """The worst plane wall's critical stiffness over the workspace, the bound, the linkage at the handle."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Workspace: critical stiffness of the worst wall", parent)
        self.set_axis_labels("x", "m", "y", "m")
        self.plot.showGrid(x=False, y=False)
        self.plot.getViewBox().setAspectLocked(True)
        self.empty = pg.ImageItem(axisOrder="row-major")
        self.empty.setZValue(-11)
        self.image = pg.ImageItem(axisOrder="row-major")
        self.image.setZValue(-10)
        for item in (self.empty, self.image):
            self.plot.addItem(item)
        self.bar = pg.ColorBarItem(values=(0.0, 1.0), colorMap=pg.colormap.get("viridis"), width=18,
                                   label="k_worst [N/m]", interactive=False, colorMapMenu=False)
        self.bar.setImageItem(self.image, insert_in=self.plot)
        self.linkage = pg.PlotDataItem([], [], pen=pg.mkPen(_LINKAGE, width=3), symbol="o", symbolSize=7,
                                       symbolBrush=_LINKAGE, symbolPen=pg.mkPen("w", width=1), name="linkage")
        self.ellipse = pg.PlotDataItem([], [], pen=pg.mkPen(_ELLIPSE, width=2), name="inertia ellipse")
        self.normal = pg.PlotDataItem([], [], pen=pg.mkPen(_ARROW, width=2.5), name="worst normal")
        self.arrow = pg.ArrowItem(angle=0, headLen=14, tipAngle=30, pen=pg.mkPen(_ARROW), brush=_ARROW)
        self.arrow.setVisible(False)
        self.handle = design_marker("handle", "o", 12, _HANDLE, pg.mkPen("k", width=1.2))
        self.worst = design_marker("design bound (worst point)", "star", 18, "#f783ac", pg.mkPen("k", width=1.2))
        for item in (self.linkage, self.ellipse, self.normal, self.arrow, self.handle, self.worst):
            self.plot.addItem(item)
        self.legend_outside(3)
        # the legend row spans the colour bar's column too: LegendRow fits its columns to the widget's
        # whole width, which under the axes' columns alone it would overflow by the bar (cut on the right)
        layout = self.plot.layout
        layout.removeItem(self.legend)
        layout.addItem(self.legend, 4, 0, 1, layout.columnCount())
        self.map: WorkspaceMap | None = None
        self.point: WorkspacePoint | None = None
        self.plot_widget.setMinimumSize(240, 200)

    def set_busy(self, busy: bool, text: str = "") -> None:
        self.header.setText(f"<b>{self.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def update_map(self, m: WorkspaceMap | None) -> None:
        """Draw the map (``None``: none yet) and mark its design bound."""
        self.map = m
        if m is None:
            for item in (self.image, self.empty):
                item.clear()
            self.worst.setData([], [])
            self.bump()
            return
        dx = float(m.x[1] - m.x[0]) if m.x.size > 1 else 1e-3
        dy = float(m.y[1] - m.y[0]) if m.y.size > 1 else 1e-3
        rect = QRectF(m.x[0] - dx / 2, m.y[0] - dy / 2, dx * m.x.size, dy * m.y.size)
        k = np.where(np.isfinite(m.worst_stiffness), m.worst_stiffness, np.nan)
        finite = k[np.isfinite(k)]
        levels = (float(finite.min()), float(max(finite.max(), finite.min() * (1 + 1e-9) + 1e-9))) if finite.size \
            else (0.0, 1.0)
        self.image.setImage(k, autoLevels=False, levels=levels)
        self.bar.setLevels(levels)
        self.empty.setImage(np.full(k.shape + (4,), UNREACHABLE_COLOR, dtype=np.ubyte), autoLevels=False,
                            levels=(0, 255))
        for item in (self.image, self.empty):
            item.setRect(rect)
        move_marker(self.worst, float(m.minimum.position[0]), float(m.minimum.position[1]), log=(False, False))
        self._fit()
        self.bump()

    def update_point(self, point: WorkspacePoint | None, handle: tuple[float, float]) -> None:
        """Draw the linkage, the inertia ellipse and the worst normal at the handle (``point``: its limits)."""
        self.point = point
        move_marker(self.handle, float(handle[0]), float(handle[1]), log=(False, False))
        if point is None:
            for item in (self.linkage, self.ellipse, self.normal):
                item.setData([], [])
            self.arrow.setVisible(False)
            self.bump()
            return
        self.linkage.setData(point.joints[:, 0], point.joints[:, 1])
        side = self._side()
        scale = ELLIPSE_FRACTION * side / float(point.principal_masses[-1])
        self.ellipse.setData(*inertia_ellipse(point, scale))
        n = np.asarray(point.worst.normal, float)
        tip = point.position + 0.8 * ELLIPSE_FRACTION * side * n * 1.6
        self.normal.setData([point.position[0], tip[0]], [point.position[1], tip[1]])
        self.arrow.setPos(float(tip[0]), float(tip[1]))
        self.arrow.setStyle(angle=180.0 - math.degrees(math.atan2(n[1], n[0])))
        self.arrow.setVisible(True)
        self._fit()
        self.bump()

    def _side(self) -> float:
        m = self.map
        if m is None:
            return 0.2 if self.point is None else float(np.ptp(self.point.joints, axis=0).max())
        return float(min(np.ptp(m.x), np.ptp(m.y)) or 0.2)

    def _fit(self) -> None:
        pts = []
        if self.map is not None:
            pts += [(self.map.x[0], self.map.y[0]), (self.map.x[-1], self.map.y[-1])]
        if self.point is not None:
            pts += [tuple(p) for p in self.point.joints]
        if pts:
            a = np.asarray(pts, float)
            self.plot.setXRange(a[:, 0].min(), a[:, 0].max(), padding=0.04)
            self.plot.setYRange(a[:, 1].min(), a[:, 1].max(), padding=0.04)

    def cursor_text(self, x: float, y: float) -> str:
        k = math.nan if self.map is None else nearest_value(self.map, x, y)
        return f"x = {plain(x)} m,  y = {plain(y)} m,  k_worst = {plain(k)} N/m"

    def restyle(self, pal: dict) -> None:
        for name in ("left", "right"):
            axis = self.bar.getAxis(name)
            axis.setPen(pg.mkPen(pal["fg"]))
            axis.setTextPen(pg.mkPen(pal["fg"]))
        self.bar.getAxis("left").setLabel("k_worst [N/m]", color=pal["fg"])
        self.linkage.setPen(pg.mkPen(pal["fg"], width=3))
        self.linkage.setSymbolBrush(pal["fg"])

    def export_series(self) -> list[Series]:
        m = self.map
        if m is None:
            return []
        return [Series(f"k_worst at y = {format_number(float(yv))} m", X_AXIS, K_AXIS, np.asarray(m.x, float),
                       np.asarray(m.worst_stiffness[j], float)) for j, yv in enumerate(m.y)]

    def export_notes(self) -> list[str]:
        m = self.map
        if m is None:
            return []
        b = m.minimum
        return [f"design bound {format_number(b.stiffness)} N/m at (x, y) = ({format_number(b.position[0])}, "
                f"{format_number(b.position[1])}) m, normal ({format_number(b.normal[0])}, "
                f"{format_number(b.normal[1])})"]


class WorkspacePolarView(PlotView):
    """The critical stiffness of a plane wall along each direction at the handle, in polar form [N/m]."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Limits at the handle by wall direction", parent)
        self.set_axis_labels("k cos θ", "N/m", "k sin θ", "N/m")
        self.plot.getViewBox().setAspectLocked(True)
        self.iso = pg.PlotDataItem([], [], pen=pg.mkPen("#868e96", width=1.5, dash=[4, 3]), name="isotropic wall")
        self.curve = pg.PlotDataItem([], [], pen=pg.mkPen("#1c7ed6", width=2.5), name="plane wall along θ")
        self.worst = pg.PlotDataItem([], [], pen=pg.mkPen(_ARROW, width=2.5), symbol="o", symbolSize=8,
                                     symbolBrush=_ARROW, name="worst normal")
        self.wall = pg.PlotDataItem([], [], pen=None, symbol="d", symbolSize=11, symbolBrush="#f08c00",
                                    symbolPen=pg.mkPen("k", width=1), name="the profile's wall")
        for item in (self.iso, self.curve, self.worst, self.wall):
            self.plot.addItem(item)
        self.legend_outside(2)
        self.point: WorkspacePoint | None = None
        self.plot_widget.setMinimumSize(200, 200)

    def update_polar(self, point: WorkspacePoint | None) -> None:
        """Draw ``point``'s per-direction limits (``None``: clear)."""
        self.point = point
        if point is None:
            for item in (self.iso, self.curve, self.worst, self.wall):
                item.setData([], [])
            self.set_warning([])
            self.bump()
            return
        self.curve.setData(*polar_curve(point))
        t = np.linspace(0.0, 2.0 * math.pi, 181)
        r = point.isotropic if math.isfinite(point.isotropic) else math.nan
        self.iso.setData(r * np.cos(t), r * np.sin(t))
        n, k = np.asarray(point.worst.normal, float), point.worst.stiffness
        self.worst.setData([-k * n[0], k * n[0]], [-k * n[1], k * n[1]])
        if point.normal is not None and math.isfinite(point.wall):
            self.wall.setData([point.wall * point.normal[0]], [point.wall * point.normal[1]])
        else:
            self.wall.setData([], [])
        notes = [] if np.all(np.isfinite(point.stiffness)) else ["no instability below 1e9 N/m along some directions"]
        self.set_warning(notes)
        self.plot.getViewBox().autoRange(padding=0.08)
        self.bump()

    def cursor_text(self, x: float, y: float) -> str:
        return f"k = {plain(math.hypot(x, y))} N/m,  θ = {plain(math.degrees(math.atan2(y, x)))}°"

    def export_series(self) -> list[Series]:
        if self.point is None:
            return []
        x, y = polar_curve(self.point)
        return [Series("plane wall along θ", Axis("k cos θ", "N/m"), Axis("k sin θ", "N/m"), x, y)]
