"""Stability plot: the coupling term against the bound on a log-frequency axis (Figs. 5 and 7).

Impedance display: Re(1/Z_c) against the bound of eq. (9); admittance display: Re(Z_cA) against
the bound of eq. (21).  Frequencies with a negative margin are shaded and the binding frequency (smallest reserve) is
marked with its value.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QWidget

from analysis import StabilityResult
from analysis.study import display_kind

from app.views.base import PlotView, Series, clean_xy, plain, rich_label

__all__ = ["StabilityPlot", "negative_runs"]


def negative_runs(w: np.ndarray, margin: np.ndarray) -> list[tuple[float, float]]:
    """Frequency intervals where the margin is negative (bands reach half-way to the neighbours)."""
    bad = np.asarray(margin) < 0
    if not np.any(bad):
        return []
    lw = np.log10(w)
    edges = np.concatenate([[lw[0]], 0.5 * (lw[1:] + lw[:-1]), [lw[-1]]])
    d = np.diff(np.concatenate([[0], bad.astype(int), [0]]))
    starts, stops = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    return [(10.0 ** edges[a], 10.0 ** edges[b]) for a, b in zip(starts, stops)]


class StabilityPlot(PlotView):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Stability: coupling term against the bound", parent)
        self.coupling_curve = self.curve("Re(1/Z<sub>c</sub>)", "#1f5fbf")
        self.bound_curve = self.curve("bound (eq. 9)", "#d9480f", style=Qt.PenStyle.DashLine)
        # one spot at the item's origin, moved with setPos (view coordinates): rebuilding a
        # scatter's spot table on every slider step costs more than the curves' update
        self.worst_point = pg.ScatterPlotItem(pos=[(0.0, 0.0)], size=9, brush=pg.mkBrush("#c92a2a"),
                                              pen=pg.mkPen("w"), pxMode=True)
        self.worst_point.hide()
        self.plot.addItem(self.worst_point, ignoreBounds=True)
        self.worst_line = pg.InfiniteLine(angle=90, movable=False,
                                          pen=pg.mkPen("#c92a2a", width=1, style=Qt.PenStyle.DotLine),
                                          label="", labelOpts={"position": 0.92, "color": "#c92a2a",
                                                               "fill": (255, 255, 255, 200), "movable": True})
        self.plot.addItem(self.worst_line, ignoreBounds=True)
        self.zero_line = pg.InfiniteLine(pos=0, angle=0, movable=False, pen=pg.mkPen((128, 128, 128, 120)))
        self.plot.addItem(self.zero_line, ignoreBounds=True)
        self._regions: list[pg.LinearRegionItem] = []
        self._bad_brush = (220, 40, 40, 45)
        self._series: list[Series] = []
        self.set_log(True, False)
        self.set_axis_labels("ω", "rad/s", "Re(1/Z_c)", "m/(N·s)")
        self.legend_region = pg.PlotDataItem([], [], pen=None, symbol="s", symbolSize=12,
                                             symbolBrush=self._bad_brush, symbolPen=None)
        self.legend.addItem(self.legend_region, "margin &lt; 0")

    def _region(self, i: int) -> pg.LinearRegionItem:
        while len(self._regions) <= i:
            r = pg.LinearRegionItem(movable=False, brush=pg.mkBrush(self._bad_brush),
                                    pen=pg.mkPen(None))
            r.setZValue(-10)
            for line in r.lines:
                line.setPen(pg.mkPen(None))
            self.plot.addItem(r, ignoreBounds=True)
            self._regions.append(r)
        return self._regions[i]

    def update_result(self, res: StabilityResult, log_y: bool = False) -> None:
        kind = display_kind(res)
        term, unit, bound = kind.coupling_term_label, kind.margin_unit, kind.bound_label()
        self.set_log(True, log_y)
        self.set_axis_labels("ω", "rad/s", f"|{term}|, |bound|" if log_y else f"{term}, bound", unit)
        self.set_legend_text(self.coupling_curve, rich_label(term))
        self.set_legend_text(self.bound_curve, bound)

        w = res.w
        c, b = np.asarray(res.coupling_term, float), np.asarray(res.bound, float)
        notes: list[str] = []
        if log_y:
            neg = int(np.count_nonzero(b < 0))
            c, b = np.abs(c), np.abs(b)
            notes.append(f"log y shows |values|: the bound is negative at {neg} of {b.size} frequencies"
                         if neg else "log y shows |values|")
        xc, yc, hc = clean_xy(w, c, True, log_y)
        xb, yb, hb = clean_xy(w, b, True, log_y)
        self.coupling_curve.setData(xc, yc)
        self.bound_curve.setData(xb, yb)
        self._series = [Series(term, "omega (rad/s)", f"{term} ({unit})", xc, yc),
                        Series(bound, "omega (rad/s)", f"bound ({unit})", xb, yb)]
        hidden = hc + hb
        if hidden:
            notes.insert(0, f"{hidden} point(s) not drawn (non-finite{' or zero' if log_y else ''})")

        finite_margin = np.where(np.isfinite(res.margin), res.margin, np.nan)
        runs = negative_runs(w, np.where(np.isnan(finite_margin), 1.0, finite_margin))
        for i, (a, z) in enumerate(runs):
            r = self._region(i)
            r.setRegion((math.log10(a), math.log10(z)))
            r.show()
        for r in self._regions[len(runs):]:
            r.hide()

        # the marker sits where the bound binds (smallest reserve 1 - bound/term): the absolute worst
        # margin usually lies at a band edge, where both curves are near zero and nothing is learnt
        wf, rel = res.binding_frequency, res.relative_margin
        if not (math.isfinite(wf) and wf > 0):
            wf, rel = res.worst_frequency, math.nan
        if math.isfinite(wf) and wf > 0:
            self.worst_line.setPos(math.log10(wf))
            wm = float(np.interp(math.log10(wf), np.log10(w), np.where(np.isfinite(res.margin), res.margin, 0.0)))
            reserve = f"reserve {100 * rel:.3g} %" if math.isfinite(rel) else f"margin {plain(wm, 3)} {unit}"
            text = f"binds at {plain(wf)} rad/s\n{reserve}"
            if text != self.worst_line.label.format:
                self.worst_line.label.setFormat(text)
            self.worst_line.show()
            yw = float(np.interp(math.log10(wf), np.log10(w), c)) if np.all(np.isfinite(c)) else math.nan
            if math.isfinite(yw) and (yw > 0 or not log_y):
                self.worst_point.setPos(math.log10(wf), math.log10(yw) if log_y else yw)
                self.worst_point.show()
            else:
                self.worst_point.hide()
        else:
            self.worst_line.hide()
            self.worst_point.hide()
        self.zero_line.setVisible(not log_y)
        self.set_warning(notes)
        self.bump()

    def restyle(self, pal: dict) -> None:
        self.coupling_curve.setPen(pg.mkPen(pal["a"], width=2))
        self.bound_curve.setPen(pg.mkPen(pal["b"], width=2, style=Qt.PenStyle.DashLine))
        self._bad_brush = pal["bad"]
        for r in self._regions:
            r.setBrush(pg.mkBrush(pal["bad"]))
        self.legend_region.setSymbolBrush(pal["bad"])
        self.worst_line.setPen(pg.mkPen(pal["mark"], width=1, style=Qt.PenStyle.DotLine))
        self.worst_line.label.setColor(pal["mark"])
        self.worst_line.label.fill = pg.mkBrush(pal["bg"])
        self.worst_point.setBrush(pg.mkBrush(pal["mark"]))

    def export_series(self) -> list[Series]:
        return list(self._series)
