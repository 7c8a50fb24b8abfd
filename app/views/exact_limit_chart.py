"""The exact sampled-data limit overlaid on the two-port design chart.

Impedance display: largest stable k_c against b_c -- the two-port bound (eq. 9, conservative
over every passive termination) and the exact limit of the sampled loop (hands-off against a
rigid god-object wall, with the chosen computation delay).  Admittance display: the two-port
feasible (m_c, b_c) edges and the exact smallest stable m_c against b_c (rigid grasp, free motion).
"""

from __future__ import annotations


import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QWidget

from analysis.sampled import CriticalChart, CriticalMassChart

from analysis.study import IMPEDANCE, ChartResult, DisplayKind, display_kind
from app.views.base import PlotView, Series, chart_axes, clean_xy, plain
from app.views.marker import design_marker, marker_xy, move_marker, set_marker_brush
from app.views.placement import CenterMessage

__all__ = ["ExactLimitChart"]


class ExactLimitChart(PlotView):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Exact limit vs two-port bound", parent)
        self.set_log(True, True)
        self.kind: DisplayKind = IMPEDANCE
        self.bound = self.curve("two-port bound (eq. 9)", "#1f5fbf", 2.0, Qt.PenStyle.DashLine)
        self.bound_low = self.curve(None, "#1f5fbf", 2.0, Qt.PenStyle.DashLine)
        self.exact = self.curve("exact sampled limit", "#d9480f", 2.5)
        self.exact.setSymbol("o")
        self.exact.setSymbolSize(5)
        self.exact.setSymbolBrush("#d9480f")
        self.exact.setSymbolPen(None)
        # moved on every step of a slider drag: a bare scatter item (app.views.marker)
        self.point = design_marker("current gains", "o", 12, "#c92a2a", pg.mkPen("w", width=1.5))
        self.plot.addItem(self.point)
        # A small chart (360 x 170 px at 1280 x 800) has no free corner for three entries: the legend
        # sits in a row below the x axis, where it covers neither curve nor the current gains.
        self.legend_outside(columns=3)
        self.message = CenterMessage(self)
        self._point_xy: tuple[float, float] | None = None
        self.chart: CriticalChart | CriticalMassChart | None = None
        self._bound_series: list[Series] = []
        self._exact_series: list[Series] = []
        self._notes: dict[str, list[str]] = {"bound": [], "exact": []}
        self._point_note = ""
        self.set_axis_labels("b_c", "N·s/m", "k_c", "N/m")
        self.cursor_label.setMinimumWidth(0)
        self.plot_widget.setMinimumSize(240, 180)

    def set_busy(self, busy: bool, text: str = "") -> None:
        self.header.setText(f"<b>{self.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def _set_display(self, display: DisplayKind | str) -> None:
        self.kind = display_kind(display)
        if self.kind.is_impedance:
            self.set_axis_labels("b_c", "N·s/m", "k_c", "N/m")
            self.title = "Largest stable k_c: exact sampled loop vs two-port bound"
        else:
            self.set_axis_labels("m_c", "kg", "b_c", "N·s/m")
            self.title = "Admittance (m_c, b_c): exact smallest m_c vs two-port region"

    def update_bound(self, res: ChartResult | None) -> None:
        """The two-port design chart (the ``design_chart`` node's value)."""
        notes: list[str] = []
        if res is None:
            self.bound.setData([], [])
            self.bound_low.setData([], [])
            self._bound_series = []
        elif display_kind(res).is_impedance:
            ch = res.chart
            kc = np.asarray(ch.kc, float)
            if np.any(np.isinf(kc)):
                notes.append("two-port bound unlimited at some b_c (not drawn)")
            x, y, _ = clean_xy(ch.bc, kc, True, True)
            self.bound.setData(x, y)
            self.bound_low.setData([], [])
            self._bound_series = [Series("two-port largest k_c", *chart_axes(display_kind(res)), x, y)]
        else:
            ch = res.chart
            xl, yl, _ = clean_xy(ch.mc, ch.low, True, True)
            xh, yh, _ = clean_xy(ch.mc, ch.high, True, True)
            self.bound.setData(xh, yh)
            self.bound_low.setData(xl, yl)
            axes = chart_axes(display_kind(res))
            self._bound_series = [Series("two-port b_c high", *axes, xh, yh),
                                  Series("two-port b_c low", *axes, xl, yl)]
        self._notes["bound"] = notes
        self._update_empty()
        self._refresh_warning()
        self._range_to_data()
        self.bump()

    def update_exact(self, chart: CriticalChart | CriticalMassChart | None, display: DisplayKind | str) -> None:
        self._set_display(display)
        self.chart = chart
        notes: list[str] = []
        if chart is None:
            self.exact.setData([], [])
            self._exact_series = []
        elif isinstance(chart, CriticalChart):
            kc = np.asarray(chart.kc, float)
            bc = np.asarray(chart.bc, float)
            if np.any(kc == 0):
                notes.append(f"exact: unstable for every k_c at b_c ≥ {plain(float(bc[kc == 0].min()))} N·s/m "
                             "(the virtual damper alone destabilizes the loop; not drawn)")
            if np.any(np.isinf(kc)):
                notes.append("exact: no instability up to 10⁹ N/m at some b_c (not drawn)")
            x, y, _ = clean_xy(bc, kc, True, True)
            self.exact.setData(x, y)
            self._exact_series = [Series(f"exact largest k_c (delay {chart.delay_samples})", *chart_axes(self.kind),
                                         x, y)]
        else:
            mc = np.asarray(chart.mc, float)
            bc = np.asarray(chart.bc, float)
            if np.any(np.isinf(mc)):
                notes.append(f"exact: no stable m_c at b_c = {plain(float(bc[np.isinf(mc)].min()))} N·s/m and "
                             "similar (not drawn)")
            if np.any(mc == 0):
                notes.append("exact: every m_c ≥ 1 g stable at some b_c (not drawn)")
            x, y, _ = clean_xy(mc, bc, True, True)
            self.exact.setData(x, y)
            self._exact_series = [Series(f"exact smallest m_c (delay {chart.delay_samples})", *chart_axes(self.kind),
                                         x, y)]
        self.legend.getLabel(self.bound).setText(self.kind.chart_note)
        self._notes["exact"] = notes
        self._update_empty()
        self.header.setText(f"<b>{self.title}</b>")
        self._refresh_warning()
        self._range_to_data()
        self.bump()

    def _range_to_data(self) -> None:
        """Auto-range now on the curves just set (both, whichever came last).

        pyqtgraph auto-ranges only when the view is next painted: until then the range was the one
        of the curve drawn first -- in the admittance display the exact m_c (kilograms) without the
        two-port region's edges (tens to a thousand kilograms), which arrive later.  An axis the user
        zoomed or a drag holds (auto-range off) keeps its range.
        """
        self.plot.getViewBox().updateAutoRange()

    def _update_empty(self) -> None:
        """An empty chart says so in the plot (and in exports) once the exact limit is known."""
        empty = (self.chart is not None and not any(len(s.x) for s in self._bound_series)
                 and not any(len(s.x) for s in self._exact_series))
        self.empty_message = (f"Nothing to show: neither the two-port bound nor the exact sampled limit has a "
                              f"stable {self.kind.exact_y.symbol} in this b_c range." if empty else "")
        self.message.set_text(self.empty_message, self.palette_colors()["fg"])

    def update_point(self, x: float, y: float, stable: bool | None) -> None:
        drawn = move_marker(self.point, x, y)
        pal = self.palette_colors()
        set_marker_brush(self.point, pal["c"] if stable else pal["mark"])
        self._point_note = "" if drawn else "current gains not drawn (zero on a log axis)"
        self._point_xy = marker_xy(self.point)
        self._refresh_warning()
        self.bump()

    def _refresh_warning(self) -> None:
        self.set_warning([*self._notes["bound"], *self._notes["exact"], self._point_note])

    def restyle(self, pal: dict) -> None:
        for c in (self.bound, self.bound_low):
            c.setPen(pg.mkPen(pal["a"], width=2, style=Qt.PenStyle.DashLine))
        self.exact.setPen(pg.mkPen(pal["b"], width=2.5))
        self.exact.setSymbolBrush(pal["b"])
        self.point.setPen(pg.mkPen(pal["bg"], width=1.5))
        self.message.set_text(self.empty_message, pal["fg"])

    def export_series(self) -> list[Series]:
        rows = [*self._bound_series, *self._exact_series]
        if self._point_xy is not None:  # the gains themselves, not the log10 the plot draws
            rows.append(Series("current gains", *chart_axes(self.kind), np.array([self._point_xy[0]]),
                               np.array([self._point_xy[1]])))
        return rows
