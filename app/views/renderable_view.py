"""The renderable (M, B, K) space and the M-width (issue 24; Colonnese & Chan 2016, Colonnese & Okamura 2012).

* :class:`RenderableSpaceView` -- the largest renderable stiffness ``K_max(M, B)`` as a heat map:
  virtual mass M on a linear x axis, virtual damping B on the signed-log y axis of the space's
  volume (``u = sign(B) log10(1 + |B|/1 N s/m)``: :func:`analysis.study.damping_axis`; the grid is
  uniform on it, so the pixels are), colour ``log10 K_max`` with a colour bar, grey where no K has
  the qualities.  One contour per quality: the slice of that quality's space at the rendered
  stiffness K, i.e. the edge of the (M, B) where K is renderable with it (at K = 0, the edge of
  where any K is).  The rendered environment (M, B) is a star; a left click emits
  :attr:`~app.views.pickable.PickablePlotView.pointPicked` ``(M, B)``.  With a robust space (the
  batch of an identified parameter box, :func:`analysis.study.renderable.robust_study`), its edge at
  the rendered K is a dashed contour and the (M, B) that this device renders at K but not every
  device of the box are hatched, with their own legend entry.
* :class:`MWidthView` -- the M-width: the interval of M renderable at B = K = 0, one bar per quality
  and one for all of them, with the rendered M.

Both only draw what :func:`analysis.study.renderable_study` computed.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRectF, Qt
from PySide6.QtWidgets import QWidget

from analysis.study import QUALITY_LABELS, RenderableStudy, damping_axis, damping_from_axis, format_number, k_max_at

from app.views.base import Axis, PlotView, Series, plain
from app.views.marker import design_marker, move_marker
from app.views.pickable import PickablePlotView

if TYPE_CHECKING:
    from analysis.sampled import RobustRenderableSpace

__all__ = ["RenderableSpaceView", "MWidthView", "SignedLogAxis", "QUALITY_COLORS", "NONE_COLOR", "ROBUST_COLOR",
           "HATCH_PIXELS"]

#: One colour per quality's contour and bar (dark enough on the viridis map's light end, with a halo).
QUALITY_COLORS = {"all": "#7048e8", "stable": "#e03131", "passive": "#f08c00", "accurate": "#d6336c",
                  "quiet": "#1c7ed6"}
#: Where no K has the qualities (K_max = 0).
NONE_COLOR = (150, 150, 150, 255)
_HALO = "#ffffff"
#: The robust space's contour and hatching (dark on the whole viridis map, with a white halo).
ROBUST_COLOR = "#212529"
#: The hatching's period in image pixels per grid cell (a diagonal line every this many pixels).
HATCH_PIXELS = 8
M_AXIS, B_AXIS, K_AXIS = Axis("M", "kg"), Axis("B", "N·s/m"), Axis("K_max", "N/m")


class SignedLogAxis(pg.AxisItem):
    """The signed-log damping axis: ticks at B = 0, ±1, ±10, ±100, ... placed at ``u(B)``, labelled in N·s/m."""

    def tickValues(self, minVal: float, maxVal: float, size: float) -> list:  # noqa: N802 - pyqtgraph API
        lo, hi = sorted((minVal, maxVal))
        top = int(math.ceil(max(abs(lo), abs(hi)))) + 1
        bs = [0.0] + [s * 10.0 ** e for e in range(0, top) for s in (1.0, -1.0)]
        us = sorted(float(damping_axis(b)) for b in bs)
        major = [u for u in us if lo <= u <= hi]
        if len(major) > max(2, int(size // 28)):  # crowded: keep every other decade
            major = [u for u in major if round(abs(float(damping_from_axis(u)))) in (0,) or
                     round(math.log10(abs(float(damping_from_axis(u))))) % 2 == 0]
        return [(1.0, major)]

    def tickStrings(self, values: list[float], scale: float, spacing: float) -> list[str]:  # noqa: N802
        return [plain(float(np.round(damping_from_axis(v), 6)), 3) for v in values]


def _log_k(k: np.ndarray) -> np.ndarray:
    """``log10 K_max``, NaN where no K has the qualities (drawn grey)."""
    k = np.asarray(k, float)
    with np.errstate(divide="ignore"):
        return np.where(k > 0, np.log10(np.where(k > 0, k, 1.0)), np.nan)


class RenderableSpaceView(PickablePlotView):
    """``K_max(M, B)`` as a heat map, one contour per quality at the rendered K, the rendered (M, B)."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Renderable space: largest K over (M, B)", parent)
        self.plot.setAxisItems({"left": SignedLogAxis("left")})
        self.plot.showGrid(x=False, y=False)
        self.set_axis_labels("M", "kg", "B", "N·s/m")
        self.empty = pg.ImageItem(axisOrder="row-major")  # grey under the map: where K_max = 0
        self.empty.setZValue(-11)
        self.plot.addItem(self.empty)
        self.image = pg.ImageItem(axisOrder="row-major")
        self.image.setZValue(-10)
        self.plot.addItem(self.image)
        self.bar = pg.ColorBarItem(values=(0.0, 6.0), colorMap=pg.colormap.get("viridis"), width=18,
                                   label="log₁₀ K_max [N/m]", interactive=False, colorMapMenu=False)
        self.bar.setImageItem(self.image, insert_in=self.plot)
        self.contours: dict[str, tuple[pg.IsocurveItem, pg.IsocurveItem]] = {}
        self.legend_lines: dict[str, pg.PlotDataItem] = {}
        for q, color in QUALITY_COLORS.items():
            halo = pg.IsocurveItem(pen=pg.mkPen(_HALO, width=4), axisOrder="row-major")
            line = pg.IsocurveItem(pen=pg.mkPen(color, width=2), axisOrder="row-major")
            for item in (halo, line):
                item.setParentItem(self.image)
            self.contours[q] = (halo, line)
            self.legend_lines[q] = pg.PlotDataItem([], [], pen=pg.mkPen(color, width=2),
                                                   shadowPen=pg.mkPen(_HALO, width=4))
        self.hatch = pg.ImageItem(axisOrder="row-major")  # the robust overlay: lost to the box
        self.hatch.setZValue(-9)
        self.plot.addItem(self.hatch)
        dashed = pg.mkPen(ROBUST_COLOR, width=2, style=Qt.PenStyle.DashLine)
        self.robust_contour = (pg.IsocurveItem(pen=pg.mkPen(_HALO, width=4), axisOrder="row-major"),
                               pg.IsocurveItem(pen=dashed, axisOrder="row-major"))
        for item in self.robust_contour:
            item.setParentItem(self.image)
        self.robust_legend = pg.PlotDataItem([], [], pen=dashed, shadowPen=pg.mkPen(_HALO, width=4))
        self.point = design_marker("rendered (M, B)", "star", 16, "#ffd43b", pg.mkPen("k", width=1.2))
        self.plot.addItem(self.point)
        self.legend_outside(3)
        self.study: RenderableStudy | None = None
        self.quality = "all"
        self.stiffness = 0.0
        self.robust: RobustRenderableSpace | None = None
        self.robust_label = ""
        self.robust_drawn = False
        self._drawn: tuple[str, ...] = ()
        self._rect = QRectF()
        self.plot_widget.setMinimumSize(220, 180)

    def set_busy(self, busy: bool, text: str = "") -> None:
        self.header.setText(f"<b>{self.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def shown(self) -> np.ndarray | None:
        """The ``K_max`` array drawn (the selected quality's, or all of them), shape (NM, NB)."""
        s = self.study
        if s is None:
            return None
        return s.space.k_max if self.quality == "all" else s.space.by_quality[self.quality]

    def update_space(self, study: RenderableStudy | None, quality: str = "all", stiffness: float = 0.0) -> None:
        """Draw ``study``'s space (``quality``: ``"all"`` or one asked) with contours at ``stiffness`` [N/m]."""
        if study is not None and quality != "all" and quality not in study.space.qualities:
            quality = "all"
        self.study, self.quality, self.stiffness = study, quality, float(stiffness)
        if study is None:
            for item in (self.image, self.empty):
                item.clear()
            for halo, line in self.contours.values():
                halo.setData(None)
                line.setData(None)
            self._draw_robust()
            self._sync_legend(())
            self.set_warning([])
            self.bump()
            return
        sp = study.space
        m, u = np.asarray(sp.mass, float), damping_axis(sp.damping)
        dm = float(m[1] - m[0]) if m.size > 1 else 1.0
        du = float(u[1] - u[0]) if u.size > 1 else 1.0
        rect = QRectF(m[0] - dm / 2, u[0] - du / 2, dm * m.size, du * u.size)
        logk = _log_k(self.shown()).T  # rows: dampings (y), columns: masses (x)
        finite = logk[np.isfinite(logk)]
        levels = (float(finite.min()), float(max(finite.max(), finite.min() + 1e-3))) if finite.size else (0.0, 1.0)
        self.image.setImage(logk, autoLevels=False, levels=levels)
        self.bar.setLevels(levels)
        self.empty.setImage(np.full(logk.shape + (4,), NONE_COLOR, dtype=np.ubyte), autoLevels=False, levels=(0, 255))
        for item in (self.image, self.empty):
            item.setRect(rect)
        self._rect = rect
        level = math.log10(max(self.stiffness, sp.settings.k_range[0]))
        drawn = ("all", *sp.qualities) if len(sp.qualities) > 1 else sp.qualities
        for q, (halo, line) in self.contours.items():
            k = None if q not in drawn else (sp.k_max if q == "all" else sp.by_quality[q])
            data = None if k is None else np.where(np.asarray(k).T > 0, _log_k(k).T, level - 10.0)
            for item in (halo, line):
                item.setData(data, level)
        self._draw_robust()
        self._sync_legend(drawn)
        notes = []
        if not finite.size:
            notes.append("no (M, B) of the grid renders any K with these qualities")
        self.set_warning(notes)
        self.plot.getViewBox().autoRange(padding=0.0)
        self.bump()

    def _where(self) -> str:
        return "K" if self.stiffness <= 0 else f"K = {plain(self.stiffness, 6)} N/m"

    def _sync_legend(self, drawn: tuple[str, ...]) -> None:
        self._drawn = tuple(drawn)
        for item in (*self.legend_lines.values(), self.robust_legend):
            if self.legend.getLabel(item) is not None:
                self.legend.removeItem(item)
        for q in drawn:
            self.legend.addItem(self.legend_lines[q], f"{QUALITY_LABELS[q]}: {self._where()} renderable")
        if self.robust_drawn:
            self.legend.addItem(self.robust_legend, f"robust over {self.robust_label}: {self._where()} renderable "
                                "by every device (hatched: by this device only)")

    # -- the robust overlay ------------------------------------------------------------------------
    def update_robust(self, robust: RobustRenderableSpace | None, label: str = "") -> None:
        """Overlay the robust space ``robust`` (``label``: its batch in words) at the rendered K; ``None``
        removes it.  Drawn only on the grid of the space shown (a stale batch on another grid is not)."""
        if robust is self.robust and label == self.robust_label:
            return
        self.robust, self.robust_label = robust, label
        self._draw_robust()
        self._sync_legend(self._drawn)
        self.bump()

    def robust_shown(self) -> np.ndarray | None:
        """The robust ``K_max`` drawn (the selected quality's, or all of them), or ``None``."""
        r = self.robust
        if not self.robust_drawn or r is None:
            return None
        return r.k_max if self.quality == "all" else r.by_quality[self.quality]

    def hatched(self) -> np.ndarray | None:
        """Where the hatching is, shape (NM, NB): this device renders the rendered K, the box does not."""
        robust, own = self.robust_shown(), self.shown()
        if robust is None or own is None:
            return None
        level = max(self.stiffness, self.study.space.settings.k_range[0])
        return (np.asarray(own) >= level) & (np.asarray(robust) < level)

    def _draw_robust(self) -> None:
        s, r = self.study, self.robust
        self.robust_drawn = bool(s is not None and r is not None and np.array_equal(r.mass, s.space.mass)
                                 and np.array_equal(r.damping, s.space.damping)
                                 and (self.quality == "all" or self.quality in r.by_quality))
        if not self.robust_drawn:
            self.hatch.clear()
            for item in self.robust_contour:
                item.setData(None)
            return
        k = self.robust_shown()
        level = math.log10(max(self.stiffness, s.space.settings.k_range[0]))
        data = np.where(np.asarray(k).T > 0, _log_k(k).T, level - 10.0)
        for item in self.robust_contour:
            item.setData(data, level)
        mask = np.kron(self.hatched().T, np.ones((HATCH_PIXELS, HATCH_PIXELS), dtype=bool))
        rows, cols = np.indices(mask.shape)
        stripe = mask & ((rows + cols) % HATCH_PIXELS < 2)
        rgba = np.zeros(mask.shape + (4,), dtype=np.ubyte)
        rgba[stripe] = (33, 37, 41, 200)
        self.hatch.setImage(rgba, autoLevels=False, levels=(0, 255))
        self.hatch.setRect(self._rect)

    def update_point(self, mass: float, damping: float) -> None:
        """The rendered environment's (M, B)."""
        move_marker(self.point, mass, float(damping_axis(damping)), log=(False, False))
        self.bump()

    def data_point(self, view_point) -> tuple[float, float]:
        return float(view_point.x()), float(damping_from_axis(view_point.y()))

    def cursor_text(self, x: float, y: float) -> str:
        k = math.nan if self.study is None else k_max_at(self.study.space, x, y, self.quality)
        return f"M = {plain(x)} kg,  B = {plain(y)} N·s/m,  K_max = {plain(k)} N/m"

    def restyle(self, pal: dict) -> None:
        for name in ("left", "right"):
            axis = self.bar.getAxis(name)
            axis.setPen(pg.mkPen(pal["fg"]))
            axis.setTextPen(pg.mkPen(pal["fg"]))
        self.bar.getAxis("left").setLabel("log₁₀ K_max [N/m]", color=pal["fg"])

    def export_series(self) -> list[Series]:
        k = self.shown()
        if k is None:
            return []
        sp = self.study.space
        out = [Series(f"K_max at M = {format_number(float(mv))} kg ({QUALITY_LABELS[self.quality]})", B_AXIS, K_AXIS,
                      np.asarray(sp.damping, float), np.asarray(k[i], float)) for i, mv in enumerate(sp.mass)]
        robust = self.robust_shown()
        if robust is not None:
            out += [Series(f"robust K_max at M = {format_number(float(mv))} kg ({QUALITY_LABELS[self.quality]}, "
                           f"{self.robust_label})", B_AXIS, K_AXIS, np.asarray(sp.damping, float),
                           np.asarray(robust[i], float)) for i, mv in enumerate(sp.mass)]
        return out


class MWidthView(PlotView):
    """The M-width [kg]: one horizontal bar per quality (and all of them), the rendered M as a line."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("M-width: virtual masses renderable at B = K = 0", parent)
        self.set_axis_labels("M", "kg", "", "")
        self.bars: list[pg.BarGraphItem] = []
        self.zero = pg.InfiniteLine(0.0, angle=90, movable=False, pen=pg.mkPen("#868e96", width=1))
        self.plot.addItem(self.zero, ignoreBounds=True)
        self.mass_line = pg.InfiniteLine(angle=90, movable=False,
                                         pen=pg.mkPen("#ffd43b", width=2.5, style=Qt.PenStyle.DashLine))
        self.mass_line.setZValue(20)
        self.plot.addItem(self.mass_line, ignoreBounds=True)
        self.plot.getViewBox().setMouseEnabled(x=True, y=False)
        self.plot.getAxis("left").setWidth(64)
        self.legend.hide()  # the bars are labelled on the axis
        self.rows: list[tuple[str, float, float]] = []
        self.plot_widget.setMinimumSize(220, 110)

    def _label_axes(self) -> None:
        """Only the mass axis has a title (the rows are labelled by quality)."""
        self.plot.setLabel("bottom", "M  [kg]", **{"font-size": "10pt", "color": self.palette_colors()["fg"]})

    def update_width(self, study: RenderableStudy | None, mass: float = 0.0) -> None:
        """Draw ``study``'s M-width; ``mass`` [kg] is the rendered M."""
        self.rows = []
        for bar in self.bars:
            self.plot.removeItem(bar)
        self.bars = []
        if study is None:
            self.set_warning([])
            self.bump()
            return
        w = study.width
        rows = [("all", w.m_min, w.m_max)] if len(w.qualities) > 1 else []
        rows += [(q, *w.by_quality[q]) for q in w.qualities]
        self.rows = rows
        m = np.asarray(study.space.mass, float)
        span = max(float(m[-1] - m[0]), 1e-9)
        lo_view, hi_view = min(float(m[0]), mass) - 0.05 * span, max(float(m[-1]), mass) + 0.05 * span
        finite = [x for _, a, b in rows for x in (a, b) if math.isfinite(x)]
        lo_view, hi_view = min([lo_view, *finite]), max([hi_view, *finite])
        x0 = [max(a, lo_view) for _, a, _ in rows]
        x1 = [min(b, hi_view) for _, _, b in rows]
        n = len(rows)
        for i, (q, _, _) in enumerate(rows):
            bar = pg.BarGraphItem(x0=[x0[i]], x1=[x1[i]], y=[n - 1 - i], height=0.6, brush=pg.mkBrush(QUALITY_COLORS[q]),
                                  pen=pg.mkPen(QUALITY_COLORS[q]))
            self.plot.addItem(bar)
            self.bars.append(bar)
        self.plot.getAxis("left").setTicks([[(n - 1 - i, "all" if q == "all" else q) for i, (q, _, _) in enumerate(rows)]])
        self.mass_line.setPos(mass)
        self.plot.setXRange(lo_view, hi_view, padding=0.0)
        self.plot.setYRange(-0.6, n - 0.4, padding=0.0)
        notes = [f"{QUALITY_LABELS[q]} reaches {'−∞' if a < 0 else '∞'} (beyond the scanned 1000 kg)"
                 for q, a, b in rows for a in (a, b) if not math.isfinite(a)]
        self.set_warning(notes)
        self.bump()

    def export_series(self) -> list[Series]:
        return [Series(f"M-width ({QUALITY_LABELS[q]})", M_AXIS, Axis("row", ""), np.array([a, b], float),
                       np.full(2, float(len(self.rows) - 1 - i))) for i, (q, a, b) in enumerate(self.rows)]
