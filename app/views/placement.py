"""Keep a plot's legend and messages off the data that matters.

:class:`LegendPlacer` moves the legend to the candidate position (corners, then edge centres)
that covers the fewest plotted points -- the curves' points densified to a few pixels apart, the
markers, the sample points of filled areas a view names, and whole rectangles such as a
marker's text label.  :class:`CenterMessage` writes a sentence in the middle of the plot (an
empty result says so where the user looks, not only in the warning line below).
"""

from __future__ import annotations

import html
from collections.abc import Callable

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QObject, QPointF, QRectF, QTimer, Slot
from PySide6.QtGui import QFont
from PySide6.QtWidgets import QGraphicsTextItem

from analysis.study.quantities import rich_numbers
from app.views.base import rich_label

__all__ = ["LegendPlacer", "CenterMessage", "scene_points", "densify"]

#: (legend anchor, view-box anchor, offset in px) in order of preference
CANDIDATES = (((1, 0), (1, 0), (-6, 4)), ((0, 0), (0, 0), (6, 4)), ((1, 1), (1, 1), (-6, -4)),
              ((0, 1), (0, 1), (6, -4)), ((0.5, 0), (0.5, 0), (0, 4)), ((0.5, 1), (0.5, 1), (0, -4)),
              ((1, 0.5), (1, 0.5), (-6, 0)), ((0, 0.5), (0, 0.5), (6, 0)),
              ((0.25, 0), (0.25, 0), (0, 4)), ((0.75, 0), (0.75, 0), (0, 4)),
              ((0.25, 1), (0.25, 1), (0, -4)), ((0.75, 1), (0.75, 1), (0, -4)))


def densify(xy: np.ndarray, step: float = 3.0, limit: int = 40000) -> np.ndarray:
    """Points along a polyline (scene px) no more than ``step`` apart; NaN rows break the line."""
    if len(xy) < 2:
        return xy[np.all(np.isfinite(xy), axis=1)] if len(xy) else xy
    a, b = xy[:-1], xy[1:]
    ok = np.all(np.isfinite(a), axis=1) & np.all(np.isfinite(b), axis=1)
    a, b = a[ok], b[ok]
    n = np.ceil(np.hypot(*(b - a).T) / step).astype(int).clip(1, 200)
    if n.sum() > limit:
        n = np.maximum(1, (n * limit // max(int(n.sum()), 1)))
    idx = np.repeat(np.arange(len(a)), n)
    frac = (np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)) / np.repeat(n, n)
    pts = a[idx] + (b[idx] - a[idx]) * frac[:, None]
    tail = xy[np.all(np.isfinite(xy), axis=1)][-1:]
    return np.vstack([pts, tail])


def scene_points(vb: pg.ViewBox, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """View (data, log10 where the axis is log) coordinates -> scene coordinates, as an (N, 2) array."""
    t = vb.childGroup.sceneTransform()
    x, y = np.asarray(x, float), np.asarray(y, float)
    return np.column_stack([t.m11() * x + t.m21() * y + t.dx(), t.m12() * x + t.m22() * y + t.dy()])


class LegendPlacer(QObject):
    """Moves ``view.legend`` to where it hides the least, whenever the range, size or data change.

    ``areas()`` (optional) returns extra view-coordinate points of filled regions;
    ``rects()`` (optional) returns scene rectangles to keep clear (labels).
    """

    def __init__(self, view: pg.GraphicsObject, areas: Callable[[], np.ndarray] | None = None,
                 rects: Callable[[], list[QRectF]] | None = None) -> None:
        super().__init__(view)
        self.view = view
        self.areas, self.rects = areas, rects
        self.choice = 0
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.place)
        view.legend.layout.setContentsMargins(4, 2, 4, 2)  # compact: less to place
        vb = view.plot.getViewBox()
        vb.sigRangeChanged.connect(self.schedule)
        vb.sigResized.connect(self.schedule)

    @Slot()
    def schedule(self) -> None:
        self._timer.start()

    def obstacles(self) -> np.ndarray:
        """Scene points the legend must not cover: the curves and markers (filled areas: see :meth:`area_points`)."""
        vb = self.view.plot.getViewBox()
        chunks = []
        for item in self.view.plot.listDataItems():
            if not item.isVisible() or getattr(item, "legend_ignore", False):
                continue
            x, y = item.getData()
            if x is None or not len(x):
                continue
            pts = scene_points(vb, x, y)
            chunks.append(densify(pts) if item.opts.get("pen") is not None and len(pts) > 1 else pts)
        return np.vstack(chunks) if chunks else np.empty((0, 2))

    def area_points(self) -> np.ndarray:
        """Scene points of filled areas: better left free, but covering them beats covering a curve."""
        extra = self.areas() if self.areas is not None else np.empty((0, 2))
        if not len(extra):
            return np.empty((0, 2))
        return scene_points(self.view.plot.getViewBox(), extra[:, 0], extra[:, 1])

    def candidate(self, i: int) -> QRectF:
        """The scene rectangle the legend would take at candidate ``i``."""
        item_pos, parent_pos, offset = CANDIDATES[i]
        vb = self.view.plot.getViewBox().sceneBoundingRect()
        size = self.view.legend.sceneBoundingRect().size()
        ax = vb.left() + parent_pos[0] * vb.width() + offset[0] - item_pos[0] * size.width()
        ay = vb.top() + parent_pos[1] * vb.height() + offset[1] - item_pos[1] * size.height()
        return QRectF(ax, ay, size.width(), size.height())

    @staticmethod
    def inside(rect: QRectF, pts: np.ndarray) -> int:
        if not len(pts):
            return 0
        return int(np.count_nonzero((pts[:, 0] >= rect.left()) & (pts[:, 0] <= rect.right())
                                    & (pts[:, 1] >= rect.top()) & (pts[:, 1] <= rect.bottom())))

    def score(self, rect: QRectF, pts: np.ndarray, rects: list[QRectF], area: np.ndarray | None = None) -> float:
        """Covered curve points; covered area points only break ties; a million per covered label."""
        r = rect.adjusted(-2, -2, 2, 2)
        extra = 1e-4 * self.inside(r, area) if area is not None else 0.0
        vb = self.view.plot.getViewBox().sceneBoundingRect().adjusted(-1, -1, 1, 1)
        outside = 0.0 if vb.contains(rect) else 1e5  # a legend wider than the plot is worse than anything
        return self.inside(r, pts) + extra + outside + 1e6 * sum(r.intersects(o) for o in rects)

    @Slot()
    def place(self) -> None:
        legend = self.view.legend
        if not legend.isVisible() or not legend.items:
            return
        vb = self.view.plot.getViewBox()
        if not any(vb.autoRangeEnabled()) and legend.pos() != QPointF(0, 0):
            return  # the axes are held (a slider drag): place again when they are released
        pts, area = self.obstacles(), self.area_points()
        rects = self.rects() if self.rects is not None else []
        best: tuple[float, int, int, int] | None = None
        # one column first; two (a wide, short legend) when no place is free for one column
        for columns in (1, 2) if len(legend.items) >= 3 else (1,):
            if legend.columnCount != columns:
                legend.setColumnCount(columns)
            order = [self.choice, *[i for i in range(len(CANDIDATES)) if i != self.choice]]
            for k, i in enumerate(order):
                cand = (self.score(self.candidate(i), pts, rects, area), columns, k, i)
                best = cand if best is None or cand < best else best
            if best[0] == 0:
                break
        assert best is not None
        if legend.columnCount != best[1]:
            legend.setColumnCount(best[1])
        self.choice = best[3]
        item_pos, parent_pos, offset = CANDIDATES[self.choice]
        legend.anchor(itemPos=item_pos, parentPos=parent_pos, offset=offset)

    def covered(self, areas: bool = True) -> int:
        """How many curve and marker points (and area points) the legend covers now (0 is the aim; tests)."""
        r = self.view.legend.sceneBoundingRect()
        return self.inside(r, self.obstacles()) + (self.inside(r, self.area_points()) if areas else 0)


class CenterMessage:
    """A sentence centred in the plot area (hidden while empty); follows the theme's text colour."""

    def __init__(self, view: pg.GraphicsObject) -> None:
        self.view = view
        vb = view.plot.getViewBox()
        self.item = QGraphicsTextItem()
        self.item.setParentItem(vb)
        self.item.setZValue(100)
        font = QFont()
        font.setPointSize(11)
        self.item.setFont(font)
        self.item.hide()
        self.text = ""
        vb.sigResized.connect(lambda *_: self._center())

    def set_text(self, text: str, color: str = "#222222") -> None:
        self.text = text
        if not text:
            self.item.hide()
            return
        rich = rich_label(rich_numbers(html.escape(text)))  # k_c -> k<sub>c</sub>, 1e+04 -> 1×10<sup>4</sup>
        self.item.setHtml(f"<div align='center' style='color:{color}'>{rich}</div>")
        self.item.show()
        self._center()

    def _center(self) -> None:
        if not self.text:
            return
        rect = self.view.plot.getViewBox().boundingRect()
        self.item.setTextWidth(max(120.0, 0.8 * rect.width()))
        box = self.item.boundingRect()
        self.item.setPos(rect.center().x() - box.width() / 2, rect.center().y() - box.height() / 2)

    def scene_rect(self) -> QRectF:
        return self.item.sceneBoundingRect() if self.text else QRectF()


