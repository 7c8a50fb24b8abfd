"""Impedance range: |Z_min| and |Z_max| against ω, log-log, the band between them shaded (Fig. 6).

The default view shows the data of interest: just below the Nyquist frequency the range
(eqs. 11-12, 23-24) shoots up by many decades (|Z_min| ~ 10¹¹ N·s/m for the HBFD), and in the
admittance display b_min can be ~10⁻⁷ N·s/m.  Those parts are still drawn (and exported), but
the auto-range (each curve's ``dataBounds`` in y) covers the data of interest only, and a label
says where the curves go.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtGui import QPainterPath
from PySide6.QtWidgets import QGraphicsPathItem, QWidget

from analysis import StabilityResult
from analysis.study import display_kind, superscript_numbers

from app.views.base import Axis, PlotView, Series, clean_xy, fmt, plain, rich_label

__all__ = ["RangePlot", "band_segments", "interest_mask", "set_data", "set_text", "TAIL_FRACTION", "TAIL_JUMP", "BMIN_DECADES"]

#: the last part of the band (fraction of its top frequency) that may leave the default view ...
TAIL_FRACTION = 0.98
#: ... when it rises above this multiple of everything else
TAIL_JUMP = 10.0
#: a b_min asymptote further below the data than this many decades is drawn off-scale
BMIN_DECADES = 1.5


def interest_mask(w: np.ndarray, *curves: np.ndarray) -> np.ndarray:
    """The frequencies of interest: all, unless the top of the band blows up (just below Nyquist)."""
    w = np.asarray(w, float)
    tail = w > TAIL_FRACTION * w[-1] if w.size else np.zeros(0, bool)
    if not np.any(tail) or np.all(tail):
        return np.ones(w.size, bool)
    ys = np.vstack([np.abs(np.asarray(c)).astype(float) for c in curves])
    with np.errstate(invalid="ignore"):
        head = np.nanmax(np.where(np.isfinite(ys[:, ~tail]), ys[:, ~tail], np.nan))
        top = np.nanmax(np.where(np.isfinite(ys[:, tail]), ys[:, tail], np.nan))
    if not (np.isfinite(head) and np.isfinite(top)) or top <= TAIL_JUMP * head:
        return np.ones(w.size, bool)
    return ~tail


def set_data(item: pg.PlotDataItem, x: np.ndarray, y: np.ndarray) -> None:
    """``item.setData(x, y)`` unless it shows these points already (the same on most drag steps)."""
    ox, oy = item.getOriginalDataset()
    if ox is None or oy is None or not (np.array_equal(ox, x) and np.array_equal(oy, y)):
        item.setData(x, y)


def set_text(item: pg.TextItem, text: str) -> None:
    """``item.setText(text)`` unless it shows ``text`` already (a new text is laid out and repainted)."""
    if item.textItem.toPlainText() != text:
        item.setText(text)


def band_segments(x1: np.ndarray, lo: np.ndarray, x2: np.ndarray, hi: np.ndarray
                  ) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The stretches of x where the curve ``lo`` lies below ``hi``: ``(x, lo, hi)`` each.

    Both curves are taken on the union of their (increasing) x where both are defined, linearly
    between points; a stretch starts and ends where the curves cross.  Where ``lo >= hi`` the
    range is empty and no stretch covers it.
    """
    x = np.union1d(x1, x2)
    x = x[(x >= max(x1[0], x2[0])) & (x <= min(x1[-1], x2[-1]))]
    if x.size < 2:
        return []
    a, b = np.interp(x, x1, lo), np.interp(x, x2, hi)
    d = b - a
    cross = np.flatnonzero(d[:-1] * d[1:] < 0)
    t = d[cross] / (d[cross] - d[cross + 1])
    at = a[cross] + t * (a[cross + 1] - a[cross])  # lo == hi where they cross
    xs = np.insert(x, cross + 1, x[cross] + t * (x[cross + 1] - x[cross]))
    a_s, b_s = np.insert(a, cross + 1, at), np.insert(b, cross + 1, at)
    d_s = np.insert(d, cross + 1, 0.0)
    ok = np.concatenate([[False], d_s >= 0, [False]])
    edges = np.flatnonzero(np.diff(ok.astype(np.int8)))  # run starts and stops, alternately
    return [(xs[i:j], a_s[i:j], b_s[i:j]) for i, j in zip(edges[::2], edges[1::2])
            if j - i >= 2 and np.any(d_s[i:j] > 0)]


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
        for item in (self.zmin_curve, self.zmax_curve, self.kmax_curve, self.bmin_curve):
            item.dataBounds = self._bounds_of(item)  # the auto-range sees the data of interest only
        self.off_scale = pg.TextItem("", color="#c92a2a", anchor=(1, 0))
        self.off_scale.setParentItem(self.plot.getViewBox())
        self.off_scale.setZValue(60)
        self.below_scale = pg.TextItem("", color="#868e96", anchor=(1, 1))
        self.below_scale.setParentItem(self.plot.getViewBox())
        self.below_scale.setZValue(60)
        self.plot.getViewBox().sigResized.connect(lambda *_: self._place_notes())
        # four long entries: at laptop size no corner of the data area is free, so the legend
        # sits in a row below the x axis, where it covers neither the curves nor the notes
        self.legend_outside(columns=2)
        self.default_y: tuple[float, float] | None = None  # data range of interest (N·s/m), for tests
        self._series: list[Series] = []

    def _bounds_of(self, item: pg.PlotDataItem):  # noqa: ANN202 - replaces a pyqtgraph method
        own = item.dataBounds

        def bounds(ax: int, frac: float = 1.0, orthoRange: tuple[float, float] | None = None):  # noqa: N803
            x, _y = item.getData()
            if ax == 1 and self.default_y is not None and x is not None and len(x) \
                    and all(np.isfinite(self.default_y)):
                return math.log10(self.default_y[0]), math.log10(self.default_y[1])
            return own(ax, frac=frac, orthoRange=orthoRange)

        return bounds

    def _place_notes(self) -> None:
        r = self.plot.getViewBox().boundingRect()
        self.off_scale.setPos(r.right() - 6, r.top() + 2)
        self.below_scale.setPos(r.right() - 6, r.bottom() - 2)

    def update_result(self, res: StabilityResult) -> None:
        w = res.w
        label_min, label_max = display_kind(res).range_labels()
        x1, y1, h1 = clean_xy(w, np.abs(res.zmin), True, True)
        x2, y2, h2 = clean_xy(w, np.abs(res.zmax), True, True)
        keep = interest_mask(w, res.zmin, res.zmax)
        self.default_y = self._interest_range(w, res, keep)
        self.zmin_curve.setData(x1, y1)
        self.zmax_curve.setData(x2, y2)
        self._update_fill(x1, y1, x2, y2)
        self.set_legend_text(self.zmin_curve, rich_label(label_min))
        self.set_legend_text(self.zmax_curve, rich_label(label_max))
        omega, z = self.export_axes()  # ω [rad/s], |Z| [N·s/m]
        self._series = [Series("|Z_min|", omega, Axis("|Z_min|", z.unit), x1, y1),
                        Series("|Z_max|", omega, Axis("|Z_max|", z.unit), x2, y2)]
        notes = []
        if h1 + h2:
            notes.append(f"{h1 + h2} point(s) not drawn (non-finite or zero)")
        km, bm = res.k_max, res.b_min
        if np.isfinite(km) and km > 0:
            xk, yk, _ = clean_xy(w, km / w, True, True)
            self.kmax_curve.setData(xk, yk)
            self._series.append(Series("k_max/ω", omega, Axis("k_max/ω", z.unit), xk, yk))
        else:
            self.kmax_curve.setData([], [])
        self.set_legend_text(self.kmax_curve, f"k<sub>max</sub>/ω ({fmt(km)} N/m)")
        lo, hi = self.default_y
        below = bool(np.isfinite(bm) and bm > 0 and np.isfinite(lo)
                     and math.log10(lo) - math.log10(bm) > BMIN_DECADES)
        if np.isfinite(bm) and bm > 0:
            if not below and np.isfinite(lo):
                self.default_y = (min(lo, bm), hi)
            set_data(self.bmin_curve, np.array([w[0], w[-1]]), np.array([bm, bm]))
            self._series.append(Series("b_min", omega, Axis("b_min", z.unit),
                                       np.array([w[0], w[-1]]), np.array([bm, bm])))
        else:
            self.bmin_curve.setData([], [])
        self.set_legend_text(self.bmin_curve,
                             f"b<sub>min</sub> ({fmt(bm)} N·s/m)" + (", below" if below else ""))
        set_text(self.below_scale, f"↓ b_min = {plain(bm)} N·s/m lies below the axis" if below else "")
        self._off_scale_text(w, res, keep)
        self._place_notes()
        self.set_warning(notes)
        self.bump()

    def _interest_range(self, w: np.ndarray, res: StabilityResult, keep: np.ndarray) -> tuple[float, float]:
        """Smallest and largest value the default view shows (the curves of interest and k_max/ω)."""
        vals = [np.abs(res.zmin[keep]), np.abs(res.zmax[keep])]
        if np.isfinite(res.k_max) and res.k_max > 0:
            vals.append(res.k_max / w[keep])
        v = np.concatenate(vals)
        v = v[np.isfinite(v) & (v > 0)]
        return (float(v.min()), float(v.max())) if v.size else (math.nan, math.nan)

    def _off_scale_text(self, w: np.ndarray, res: StabilityResult, keep: np.ndarray) -> None:
        if np.all(keep):
            set_text(self.off_scale, "")
            return
        z = np.abs(np.concatenate([res.zmin[~keep], res.zmax[~keep]]))
        z = z[np.isfinite(z)]
        top = plain(float(z.max()), 3) if z.size else "∞"
        set_text(self.off_scale, superscript_numbers(
            f"↑ off-scale: |Z| rises to {top} N·s/m above ω = {plain(float(w[keep][-1]))} rad/s"))

    def _update_fill(self, x1: np.ndarray, y1: np.ndarray, x2: np.ndarray, y2: np.ndarray) -> None:
        """Shade the band where |Z_min| < |Z_max| only: one polygon per stretch where the range
        exists, each ending where the curves cross (an empty range is not shaded)."""
        path = QPainterPath()
        if x1.size >= 2 and x2.size >= 2:
            for x, lo, hi in band_segments(np.log10(x1), np.log10(y1), np.log10(x2), np.log10(y2)):
                piece = pg.arrayToQPath(np.concatenate([x, x[::-1]]), np.concatenate([lo, hi[::-1]]),
                                        connect="all")
                piece.closeSubpath()
                path.addPath(piece)
        self.fill.setPath(path)

    def restyle(self, pal: dict) -> None:
        self.zmax_curve.setPen(pg.mkPen(pal["a"], width=2))
        self.zmin_curve.setPen(pg.mkPen(pal["c"], width=2))
        self.fill.setBrush(pg.mkBrush(pal["fill"]))
        self.kmax_curve.setPen(pg.mkPen(pal["muted"], width=1.2, style=Qt.PenStyle.DashLine))
        self.bmin_curve.setPen(pg.mkPen(pal["muted"], width=1.2, style=Qt.PenStyle.DotLine))
        self.off_scale.setColor(pal["mark"])
        self.below_scale.setColor(pal["fg"])

    def export_series(self) -> list[Series]:
        return list(self._series)
