"""The one export renderer: a plot view painted into any painter (PNG, SVG, the PDF report).

:func:`render_view` draws the plot as it looks on screen, scaled as one picture.  The layout first
catches up with the tick labels (pyqtgraph's axes learn how wide their labels are only when they
paint, so a plot not yet painted at its current range had its axis title over the tick labels),
and the items pyqtgraph draws at a fixed pixel size (the legend, markers) are scaled with the rest
(they were drawn at screen size: half the axis text's size in a 2x PNG).  Issue 22.

Duck-typed on the view (``plot_widget``, ``plot``): :mod:`app.views.base` delegates to it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pyqtgraph as pg
from PySide6.QtCore import QRectF
from PySide6.QtGui import QPainter, QPicture, QTransform
from PySide6.QtWidgets import QGraphicsItem

__all__ = ["render_view", "settle_layout"]


def _source(view: Any) -> QRectF:
    return QRectF(view.plot_widget.viewport().rect())


#: How many times the layout may change after the axes measured their labels (each pass can
#: change the other axis's ticks: a wider y axis shortens the x axis).
_SETTLE_PASSES = 4


def _axes(view: Any) -> list[pg.AxisItem]:
    return [it for it in view.plot_widget.scene().items() if isinstance(it, pg.AxisItem) and it.isVisible()]


def settle_layout(view: Any) -> int:
    """Lay the plot out for the tick labels it will draw; the number of passes that changed it.

    A pyqtgraph axis measures its tick labels while it paints and only then widens itself (the
    next layout pass moves its title out of the labels' way).  An export drawn before that pass
    (a view never painted at its current range: the command line's, or a tab's plot just
    updated) drew the title over the tick labels.  Each pass lets the view boxes take their
    pending ranges, measures the labels as a paint would (into a QPicture, as the axis does) and
    lays the plot out again, until nothing moves.
    """
    changed = 0
    for _ in range(_SETTLE_PASSES):
        view.plot_widget.scene().prepareForPaint()  # a deferred auto-range sets the axes' ranges
        before = [ax.geometry() for ax in _axes(view)]
        for ax in _axes(view):
            picture = QPicture()  # kept referenced while painted on
            painter = QPainter(picture)
            try:
                ax.paint(painter, None, None)
            finally:
                painter.end()
        view.plot.layout.activate()
        top = view.plot_widget.centralWidget
        if top is not view.plot and top.layout() is not None:
            top.layout().activate()
        if [ax.geometry() for ax in _axes(view)] == before:
            break
        changed += 1
    return changed


def _fixed_size_items(items: list[QGraphicsItem]) -> list[QGraphicsItem]:
    """The items drawn at a fixed pixel size (ItemIgnoresTransformations), outermost only."""
    flag = QGraphicsItem.GraphicsItemFlag.ItemIgnoresTransformations
    fixed = [it for it in items if it.flags() & flag]
    return [it for it in fixed if not any(a in fixed for a in _ancestors(it))]


def _ancestors(item: QGraphicsItem) -> Iterator[QGraphicsItem]:
    parent = item.parentItem()
    while parent is not None:
        yield parent
        parent = parent.parentItem()


@contextmanager
def _scaled_fixed_items(items: list[QGraphicsItem], scale: float) -> Iterator[None]:
    """Draw the fixed-pixel-size items at ``scale``, like the rest of the picture.

    An item whose parent is not scaled (the legend, in the view box or in the plot's layout)
    takes the scene's scale: the flag is cleared, its geometry in the scene is the one on screen.
    Any other (a marker in data coordinates) is scaled about its own origin, its centre.
    """
    flag = QGraphicsItem.GraphicsItemFlag.ItemIgnoresTransformations
    cleared: list[QGraphicsItem] = []
    rescaled: list[tuple[QGraphicsItem, float]] = []
    for it in _fixed_size_items(items):
        parent = it.parentItem()
        if parent is None or parent.sceneTransform().type().value <= QTransform.TransformationType.TxTranslate.value:
            it.setFlag(flag, False)
            cleared.append(it)
        elif scale != 1.0:
            rescaled.append((it, it.scale()))
            it.setScale(it.scale() * scale)
    try:
        yield
    finally:
        for it in cleared:
            it.setFlag(flag, True)
        for it, old in rescaled:
            it.setScale(old)


def render_view(view: Any, painter: QPainter, target: QRectF) -> None:
    """Paint ``view``'s plot into ``target`` of any painter (PNG, SVG, PDF) as one picture.

    The plot as laid out on screen (its viewport), scaled to ``target``: text, legend, markers
    and lines keep their proportions at any export size.  The layout is settled first
    (:func:`settle_layout`).  On screen the axes are cached as pixmaps and scatter markers come
    from a pixmap atlas; for the length of this call both are switched off, so an SVG or PDF
    gets paths and text.
    """
    settle_layout(view)
    pw = view.plot_widget
    src = _source(view)
    scale = math.sqrt(max(target.width(), 1e-9) * max(target.height(), 1e-9)
                      / max(src.width() * src.height(), 1.0))  # markers stay round when x, y differ
    items = pw.scene().items()
    scatters = [it for it in items if isinstance(it, pg.ScatterPlotItem)]
    cached = [(it, it.cacheMode()) for it in items if it.cacheMode() != QGraphicsItem.CacheMode.NoCache]
    for it in scatters:  # pxMode markers: drawn in device pixels, resolutionScale sizes them
        it.setExportMode(True, {"antialias": True, "resolutionScale": scale})
    for it, _mode in cached:
        it.setCacheMode(QGraphicsItem.CacheMode.NoCache)
    try:
        with _scaled_fixed_items(items, scale):
            painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
            painter.setRenderHint(QPainter.RenderHint.TextAntialiasing, True)
            pw.render(painter, target, pw.viewport().rect())
    finally:
        for it in scatters:
            it.setExportMode(False)
        for it, mode in cached:
            it.setCacheMode(mode)


