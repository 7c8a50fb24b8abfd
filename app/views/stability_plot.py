"""Stability plot: the coupling term against the bound on a log-frequency axis (Figs. 5 and 7).

Impedance display: Re(1/Z_c) against the bound of eq. (9); admittance display: Re(Z_cA) against
the bound of eq. (21).  Frequencies with a negative margin are shaded and the binding frequency (smallest reserve) is
marked with its value.

Three view modes (:data:`VIEW_MODES`):

* ``"ratio"`` -- bound / coupling term on a linear axis, with the limit 1: stable where the curve
  stays below 1, and its maximum, at the binding frequency, is 1 - stability reserve.  The reserve
  is read where it matters, however small the two terms are there;
* ``"values"`` -- the two terms themselves, as in the papers' figures (the report's figure);
* ``"log"`` -- |values| on a log axis; where the bound is negative (no constraint) it is drawn
  as a separate dotted curve, so a negative trough does not look like a near-violation.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRectF, Qt
from PySide6.QtWidgets import QGraphicsEllipseItem, QGraphicsItem, QWidget

from analysis import StabilityResult
from analysis.study import display_kind

from app.views.base import Axis, PlotView, Series, clean_xy, plain, rich_label
from app.views.legend_row import set_swatch_brush, swatch
from app.views.placement import LegendPlacer, densify, scene_points

__all__ = ["StabilityPlot", "negative_runs", "VIEW_MODES", "bound_ratio"]

#: view mode -> what the user picks
VIEW_MODES = {"ratio": "Reserve: bound / coupling term (stable below 1)",
              "values": "Values: coupling term and bound (as in the paper)",
              "log": "Log |values| (negative bound dotted)"}
#: where along the binding line its label may sit (fraction of the view's height)
LABEL_POSITIONS = (0.92, 0.78, 0.64, 0.5, 0.36, 0.22, 0.08)


def bound_ratio(res: StabilityResult) -> np.ndarray:
    """bound / coupling term at every frequency (NaN where the term is not positive).

    Stable iff it is at most 1 everywhere; its maximum is 1 - the stability reserve, at the
    binding frequency (eqs. 9 and 21 divided by the coupling term).
    """
    c, b = np.asarray(res.coupling_term, float), np.asarray(res.bound, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(c > 0, b / np.where(c > 0, c, 1.0), np.nan)


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
        self.mode = "values"
        self.coupling_curve = self.curve("Re(1/Z<sub>c</sub>)", "#1f5fbf")
        self.bound_curve = self.curve("bound (eq. 9)", "#d9480f", style=Qt.PenStyle.DashLine)
        self.bound_negative = self.curve("|bound| where bound &lt; 0", "#d9480f", width=1.2,
                                         style=Qt.PenStyle.DotLine)
        self.ratio_curve = self.curve("bound / Re(1/Z<sub>c</sub>)", "#1f5fbf")
        # a 9 px dot moved with setPos (view coordinates), drawn by Qt itself: a one-spot
        # ScatterPlotItem costs about 1 ms of Python on every repaint of a drag step
        self.worst_point = QGraphicsEllipseItem(-4.5, -4.5, 9.0, 9.0)
        self.worst_point.setFlag(QGraphicsItem.GraphicsItemFlag.ItemIgnoresTransformations)
        self.worst_point.setBrush(pg.mkBrush("#c92a2a"))
        self.worst_point.setPen(pg.mkPen("w"))
        self.worst_point.setZValue(25)
        self.worst_point.hide()
        self.plot.addItem(self.worst_point, ignoreBounds=True)
        self.worst_xy = (math.nan, math.nan)  # the marker in data units (tests)
        self.worst_line = pg.InfiniteLine(angle=90, movable=False,
                                          pen=pg.mkPen("#c92a2a", width=1, style=Qt.PenStyle.DotLine),
                                          label="", labelOpts={"position": 0.92, "color": "#c92a2a",
                                                               "fill": None, "movable": True})
        self.plot.addItem(self.worst_line, ignoreBounds=True)
        self.zero_line = pg.InfiniteLine(pos=0, angle=0, movable=False, pen=pg.mkPen((128, 128, 128, 120)))
        self.plot.addItem(self.zero_line, ignoreBounds=True)
        # the limit of the ratio view, in the auto-range so that 1 is always on screen
        self.limit_line = self.curve("limit 1 (margin 0)", "#c92a2a", width=1.2, style=Qt.PenStyle.DashLine)
        # the same dashed line on every step of a drag (held axes): kept as a pixmap, not stroked
        # again (about 1 ms a repaint; exports draw it afresh, PlotView.render_into)
        self.limit_line.curve.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        self._regions: list[pg.LinearRegionItem] = []
        self._bad_brush = (220, 40, 40, 45)
        self._shown: tuple[StabilityResult, str, str, str] | None = None  # what is drawn (exports)
        self._limit_span: tuple[float, float] | None = None
        self.set_log(True, False)
        self.set_axis_labels("ω", "rad/s", "Re(1/Z_c)", "m/(N·s)")
        self.legend_region = swatch(self._bad_brush)  # the shading's pink, not a slate square
        self.legend_placer = LegendPlacer(self, rects=self._label_rects)
        self.plot.getViewBox().sigRangeChanged.connect(lambda *_: self.place_label())
        self._show_items()

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

    def _show_items(self) -> None:
        """Each mode's curves, and only their legend entries."""
        shown = {"ratio": (self.ratio_curve, self.limit_line),
                 "values": (self.coupling_curve, self.bound_curve),
                 "log": (self.coupling_curve, self.bound_curve, self.bound_negative)}[self.mode]
        for item in (self.coupling_curve, self.bound_curve, self.bound_negative, self.ratio_curve, self.limit_line,
                     self.legend_region):
            self.legend.removeItem(item)
            if item is not self.legend_region:
                item.setVisible(item in shown)
                if item not in shown:
                    item.setData([], [])
        self._limit_span = None if self.limit_line not in shown else self._limit_span
        for item in shown:  # the legend in a fixed order: the mode's curves, then the shading
            self.legend.addItem(item, item.opts.get("name") or "")
        self.legend.addItem(self.legend_region, "margin &lt; 0")
        self.zero_line.setVisible(self.mode == "values")

    def update_result(self, res: StabilityResult, log_y: bool = False, mode: str | None = None) -> None:
        """Draw ``res``; ``mode`` is one of :data:`VIEW_MODES` (default: ``"log"`` if ``log_y`` else ``"values"``)."""
        mode = mode or ("log" if log_y else "values")
        if mode not in VIEW_MODES:
            raise ValueError(f"unknown stability view mode {mode!r}")
        if mode != self.mode:
            self.mode = mode
            self._show_items()
        kind = display_kind(res)
        term, unit, bound = kind.coupling_term_label, kind.margin_unit, kind.bound_label()
        self.set_log(True, mode == "log")
        notes = self._draw_ratio(res, term, bound) if mode == "ratio" else self._draw_values(res, term, unit, bound)
        self._shown = (res, term, unit, bound)  # exported on demand (not on every step of a drag)
        self._draw_regions(res)
        self._draw_binding(res, unit)
        self.set_warning(notes)
        self.legend_placer.schedule()
        self.bump()

    def _draw_ratio(self, res: StabilityResult, term: str, bound: str) -> list[str]:
        self.set_axis_labels("ω", "rad/s", f"bound / {term}", "–")
        self.set_legend_text(self.ratio_curve, f"{rich_label(bound)} / {rich_label(term)}")
        r = bound_ratio(res)
        x, y, hidden = clean_xy(res.w, r, True, False)
        self.ratio_curve.setData(x, y)
        span = (float(res.w[0]), float(res.w[-1]))
        if span != self._limit_span:  # the same line on every step of a drag: not set again
            self._limit_span = span
            self.limit_line.setData(list(span), [1.0, 1.0])
        self.set_legend_text(self.limit_line, "limit 1: stable below (margin 0)")
        return [f"{hidden} point(s) not drawn ({term} not positive)"] if hidden else []

    def _draw_values(self, res: StabilityResult, term: str, unit: str, bound: str) -> list[str]:
        log_y = self.mode == "log"
        self.set_axis_labels("ω", "rad/s", f"|{term}|, |bound|" if log_y else f"{term}, bound", unit)
        self.set_legend_text(self.coupling_curve, rich_label(term))
        self.set_legend_text(self.bound_curve, bound)
        w = res.w
        c, b = np.asarray(res.coupling_term, float), np.asarray(res.bound, float)
        notes: list[str] = []
        if log_y:
            neg = b < 0
            notes.append(f"log y shows |values|: the bound is negative (no constraint) at {int(neg.sum())} of "
                         f"{b.size} frequencies, drawn dotted" if np.any(neg) else "log y shows |values|")
            self._draw_pieces(self.bound_negative, w, -b)
            self._draw_pieces(self.bound_curve, w, b)
            c = np.abs(c)
            hb = int(np.count_nonzero(~np.isfinite(b) | (b == 0)))
        else:
            xb, yb, hb = clean_xy(w, b, True, False)
            self.bound_curve.setData(xb, yb)
        xc, yc, hc = clean_xy(w, c, True, log_y)
        self.coupling_curve.setData(xc, yc)
        hidden = hc + hb
        if hidden:
            notes.insert(0, f"{hidden} point(s) not drawn (non-finite{' or zero' if log_y else ''})")
        return notes

    @staticmethod
    def _draw_pieces(item: pg.PlotDataItem, w: np.ndarray, y: np.ndarray) -> None:
        """The positive finite values of ``y`` on a log axis, the line broken where they are not."""
        idx = np.flatnonzero(np.isfinite(y) & (y > 0) & np.isfinite(w) & (w > 0))
        connect = np.append(np.diff(idx) == 1, False) if idx.size else np.zeros(0, bool)
        item.setData(w[idx], y[idx], connect=connect)

    def _draw_regions(self, res: StabilityResult) -> None:
        finite_margin = np.where(np.isfinite(res.margin), res.margin, np.nan)
        runs = negative_runs(res.w, np.where(np.isnan(finite_margin), 1.0, finite_margin))
        for i, (a, z) in enumerate(runs):
            r = self._region(i)
            r.setRegion((math.log10(a), math.log10(z)))
            r.show()
        for r in self._regions[len(runs):]:
            r.hide()

    def _draw_binding(self, res: StabilityResult, unit: str) -> None:
        """The line and point where the bound binds (smallest reserve 1 - bound/term).

        The absolute worst margin usually lies at a band edge, where both curves are near zero and
        nothing is learnt; the binding frequency is where the reserve is smallest.
        """
        w = res.w
        wf, rel = res.binding_frequency, res.relative_margin
        if not (math.isfinite(wf) and wf > 0):
            wf, rel = res.worst_frequency, math.nan
        if not (math.isfinite(wf) and wf > 0):
            self.worst_line.hide()
            self.worst_point.hide()
            self.worst_xy = (math.nan, math.nan)
            return
        self.worst_line.setPos(math.log10(wf))
        wm = float(np.interp(math.log10(wf), np.log10(w), np.where(np.isfinite(res.margin), res.margin, 0.0)))
        reserve = f"reserve {plain(100 * rel, 3)} %" if math.isfinite(rel) else f"margin {plain(wm, 3)} {unit}"
        text = f"binds at {plain(wf)} rad/s\n{reserve}"
        if text != self.worst_line.label.format:
            self.worst_line.label.setFormat(text)
        self.worst_line.show()
        if self.mode == "ratio":
            yw = 1.0 - rel if math.isfinite(rel) else math.nan
        else:
            c = np.asarray(res.coupling_term, float)
            yw = float(np.interp(math.log10(wf), np.log10(w), c)) if np.all(np.isfinite(c)) else math.nan
        log_y = self.mode == "log"
        if math.isfinite(yw) and (yw > 0 or not log_y):
            self.worst_point.setPos(math.log10(wf), math.log10(yw) if log_y else yw)
            self.worst_point.show()
            self.worst_xy = (wf, yw)
        else:
            self.worst_point.hide()
            self.worst_xy = (wf, math.nan)
        if any(self.plot.getViewBox().autoRangeEnabled()):  # held axes (a drag): placed when released
            self.place_label()

    def place_label(self) -> None:
        """Move the binding label along its line to where it covers the fewest curve points."""
        label = self.worst_line.label
        if not self.worst_line.isVisible() or not label.format:
            return
        vb = self.plot.getViewBox()
        chunks = []
        for item in (self.coupling_curve, self.bound_curve, self.bound_negative, self.ratio_curve, self.limit_line):
            x, y = item.getData()
            if item.isVisible() and x is not None and len(x):
                chunks.append(densify(scene_points(vb, x, y)))
        pts = np.vstack(chunks) if chunks else np.empty((0, 2))
        best, best_pos = math.inf, LABEL_POSITIONS[0]
        for p in LABEL_POSITIONS:
            label.setPosition(p)
            r = label.sceneBoundingRect().adjusted(-2, -2, 2, 2)
            n = int(np.count_nonzero((pts[:, 0] >= r.left()) & (pts[:, 0] <= r.right()) & (pts[:, 1] >= r.top())
                                     & (pts[:, 1] <= r.bottom()))) if len(pts) else 0
            if n < best:
                best, best_pos = n, p
        label.setPosition(best_pos)

    def place_legend(self) -> None:
        """The binding label first (at the final size), then the legend around it and the data."""
        self.place_label()
        super().place_legend()

    def _label_rects(self) -> list[QRectF]:
        label = self.worst_line.label
        return [label.sceneBoundingRect()] if self.worst_line.isVisible() and label.format else []

    def restyle(self, pal: dict) -> None:
        self.coupling_curve.setPen(pg.mkPen(pal["a"], width=2))
        self.ratio_curve.setPen(pg.mkPen(pal["a"], width=2))
        self.bound_curve.setPen(pg.mkPen(pal["b"], width=2, style=Qt.PenStyle.DashLine))
        self.bound_negative.setPen(pg.mkPen(pal["b"], width=1.2, style=Qt.PenStyle.DotLine))
        self.limit_line.setPen(pg.mkPen(pal["mark"], width=1.2, style=Qt.PenStyle.DashLine))
        self._bad_brush = pal["bad"]
        for r in self._regions:
            r.setBrush(pg.mkBrush(pal["bad"]))
        set_swatch_brush(self.legend_region, pal["bad"])
        self.worst_line.setPen(pg.mkPen(pal["mark"], width=1, style=Qt.PenStyle.DotLine))
        self.worst_line.label.setColor(pal["mark"])
        self.worst_point.setBrush(pg.mkBrush(pal["mark"]))

    def export_series(self) -> list[Series]:
        """The values (signed, in their units) and the ratio, whatever the view shows."""
        if self._shown is None:
            return []
        res, term, unit, bound = self._shown
        w, r = res.w, bound_ratio(res)
        omega = self.export_axes()[0]  # ω [rad/s] in every mode
        return [Series(term, omega, Axis(term, unit), *clean_xy(w, res.coupling_term, True)[:2]),
                Series(bound, omega, Axis("bound", unit), *clean_xy(w, res.bound, True)[:2]),
                Series(f"bound / {term}", omega, Axis(f"bound / {term}", ""), *clean_xy(w, r, True)[:2])]
