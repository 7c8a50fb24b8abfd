"""Design chart: largest k_c against b_c (impedance), or the feasible (m_c, b_c) region (admittance).

Shows the current gains as a point.  A left click emits :attr:`DesignChart.pointPicked` with the
data coordinates; the tab turns it into an undo command.
"""

from __future__ import annotations


import numpy as np
import pyqtgraph as pg
from PySide6.QtWidgets import QWidget

from analysis import MassChart, StiffnessChart
from analysis.study import IMPEDANCE, ChartResult, DisplayKind, display_kind
from app.views.pickable import PickablePlotView
from app.views.base import Series, chart_axes, clean_xy, mark_design_point, plain
from app.views.floor_fill import FloorFill
from app.views.legend_row import swatch
from app.views.placement import CenterMessage, LegendPlacer

__all__ = ["DesignChart"]


class DesignChart(PickablePlotView):

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Design chart", parent)
        self.set_log(True, True)
        self.kind: DisplayKind = IMPEDANCE
        self.upper = self.curve("largest k<sub>c</sub> (eq. 9)", "#1f5fbf")
        self.lower = self.curve(None, "#1f5fbf")
        self.fill = pg.FillBetweenItem(self.lower, self.upper, brush=pg.mkBrush(43, 138, 62, 50))
        self.fill.setZValue(-5)
        # impedance: the feasible gains reach down to the axis (no edge of their own below)
        self.floor_fill = FloorFill(self.plot, self.lower, self.upper, self.fill)
        self.point = pg.PlotDataItem([], [], pen=None, symbol="o", symbolSize=12, symbolBrush="#c92a2a",
                                     symbolPen=pg.mkPen("w", width=1.5), name="current gains")
        self.point.setZValue(20)
        self.plot.addItem(self.point)
        self.legend_fill = swatch(self.fill.brush())  # the shading's own green, not a slate square
        self.legend.addItem(self.legend_fill, "feasible (unconditionally stable)")
        # keeps the requested b_c (m_c) range on the axes when nothing is feasible (invisible)
        self.span = self.plot.plot([], [], pen=pg.mkPen((0, 0, 0, 0)))
        self.span.legend_ignore = True
        self._span_x: tuple[float, float] | None = None
        self.message = CenterMessage(self)
        self.legend_placer = LegendPlacer(self, areas=self.feasible_area)
        self._point_xy: tuple[float, float] | None = None
        self.status = ""
        self._series: list[Series] = []
        self._chart: ChartResult | None = None
        self._notes: list[str] = []
        self._point_note = ""
        self.set_axis_labels("b_c", "N·s/m", "k_c", "N/m")
        self.plot_widget.setToolTip("Click to set the coupling gains")

    def set_busy(self, busy: bool) -> None:
        self.header.setText(f"<b>{self.title}</b>" + ("  <i>(updating…)</i>" if busy else ""))

    def update_chart(self, res: ChartResult | None) -> None:
        self._chart = res
        self._notes = []
        if res is None:
            self.upper.setData([], [])
            self.lower.setData([], [])
            self._series = []
            self._set_empty("")
            self._refresh_warning()
            self.bump()
            return
        self.kind = display_kind(res)
        if self.kind.is_impedance:
            self._draw_stiffness(res.chart)
        else:
            self._draw_mass(res.chart)
        self.header.setText(f"<b>{self.title}</b>")
        self._refresh_warning()
        self.bump()

    def _draw_stiffness(self, ch: StiffnessChart) -> None:
        """Largest k_c over b_c (eq. 9), filled down to the axis (every lower k_c is feasible too)."""
        self.set_axis_labels("b_c", "N·s/m", "k_c", "N/m")
        self.title = "Design chart: largest stable k_c against b_c"
        kc = np.asarray(ch.kc, float)
        unlimited = np.isinf(kc)
        finite = kc[np.isfinite(kc) & (kc > 0)]
        top = float(finite.max()) * 10 if finite.size else 1e6
        if np.any(unlimited):
            self._notes.append(f"k_c unlimited at {int(unlimited.sum())} b_c value(s), drawn clipped at "
                               f"{plain(top)} N/m")
        kc = np.where(unlimited, top, kc)
        infeasible = np.isnan(kc)
        if np.any(infeasible):
            self._notes.append(f"no k_c ≥ 0 satisfies eq. 9 for b_c ≥ {plain(float(ch.bc[infeasible].min()))} "
                               "N·s/m (not drawn)")
        x, y, _ = clean_xy(ch.bc, kc, True, True)
        self.upper.setData(x, y)
        self.floor_fill.set_enabled(True)
        self.legend.getLabel(self.upper).setText("largest k<sub>c</sub> (eq. 9)")
        self._series = [Series("largest k_c", *self.export_axes(), x, y)]
        self._set_empty("" if x.size else
                        f"Nothing is feasible: no k_c ≥ 0 satisfies eq. 9 at any b_c from "
                        f"{plain(float(np.min(ch.bc)))} to {plain(float(np.max(ch.bc)))} N·s/m. "
                        "This device and coupling cannot be made unconditionally stable.", ch.bc)

    def _draw_mass(self, ch: MassChart) -> None:
        """The feasible b_c interval over m_c (eq. 21), filled between its edges."""
        self.set_axis_labels("m_c", "kg", "b_c", "N·s/m")
        self.title = "Design chart: feasible (m_c, b_c) region"
        low, high = np.asarray(ch.low, float), np.asarray(ch.high, float)
        fin = high[np.isfinite(high)]
        top = float(max(fin.max() if fin.size else 0, np.nanmax(low) if np.any(np.isfinite(low)) else 1)) * 10
        if np.any(np.isinf(high)):
            self._notes.append(f"upper b_c edge unbounded at {int(np.isinf(high).sum())} m_c value(s), drawn "
                               f"clipped at {plain(top)} N·s/m")
        high = np.where(np.isinf(high), top, high)
        ok = np.isfinite(low) & np.isfinite(high) & (low > 0)
        if not np.all(ok):
            self._notes.append(f"no b_c satisfies eq. 21 at {int((~ok).sum())} of {ok.size} m_c value(s)")
        x = np.asarray(ch.mc, float)[ok]
        self.floor_fill.set_enabled(False)
        self.upper.setData(x, high[ok])
        self.lower.setData(x, low[ok])
        self.legend.getLabel(self.upper).setText("b<sub>c</sub> edges (eq. 21)")
        self._series = [Series("b_c low", *self.export_axes(), x, low[ok]),
                        Series("b_c high", *self.export_axes(), x, high[ok])]
        self._set_empty("" if x.size else
                        f"Nothing is feasible: no b_c satisfies eq. 21 at any m_c from "
                        f"{plain(float(np.min(ch.mc)))} to {plain(float(np.max(ch.mc)))} kg.", ch.mc)

    def _set_empty(self, message: str, x_range: np.ndarray | None = None) -> None:
        """Say in the plot that nothing is feasible, keeping the requested x range on the axes."""
        self.empty_message = message
        self.message.set_text(message, self.palette_colors()["fg"])
        if message and x_range is not None and np.size(x_range):
            self._span_x = (float(np.min(x_range)), float(np.max(x_range)))
        else:
            self._span_x = None
        self._update_span()

    def _update_span(self) -> None:
        span = self._span_x
        if span is None:
            self.span.setData([], [])
            return
        y = self._point_xy[1] if self._point_xy is not None else 1.0
        self.span.setData([span[0], span[1]], [y, y])

    def feasible_area(self) -> np.ndarray:
        """Sample points (view coordinates) inside the shaded feasible region, for the legend placer."""
        ux, uy = self.upper.getData()
        if ux is None or len(ux) < 2:
            return np.empty((0, 2))
        lx, ly = self.lower.getData()
        xs = np.linspace(ux[0], ux[-1], 48)
        top = np.interp(xs, ux, uy)
        if self.kind.is_impedance or ly is None or len(ly) < 2:
            bottom = np.full(xs.size, float(self.plot.getViewBox().viewRange()[1][0]))
        else:
            bottom = np.interp(xs, lx, ly)
        f = np.linspace(0.0, 1.0, 24)
        xx = np.repeat(xs, f.size)
        yy = (bottom[:, None] + (top - bottom)[:, None] * f[None, :]).ravel()
        return np.column_stack([xx, yy])

    def update_point(self, x: float, y: float, stable: bool | None) -> None:
        self._point_note = mark_design_point(self.point, x, y, stable, self.palette_colors())
        drawn = x > 0 and y > 0 and np.isfinite(x) and np.isfinite(y)
        self._point_xy = (float(x), float(y)) if drawn else None
        self._update_span()
        self._refresh_warning()
        self.bump()

    def _refresh_warning(self) -> None:
        self.set_warning([*self._notes, self._point_note])

    def restyle(self, pal: dict) -> None:
        self.upper.setPen(pg.mkPen(pal["a"], width=2))
        self.lower.setPen(pg.mkPen(pal["a"], width=2))
        self.point.setSymbolPen(pg.mkPen(pal["bg"], width=1.5))
        self.message.set_text(self.empty_message, pal["fg"])

    def export_series(self) -> list[Series]:
        rows = list(self._series)
        if self._point_xy is not None:  # the gains themselves, not the log10 the plot draws
            rows.append(Series("current gains", *chart_axes(self.kind), np.array([self._point_xy[0]]),
                               np.array([self._point_xy[1]])))
        return rows
