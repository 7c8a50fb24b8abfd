"""The current-design marker of a chart (log-log by default), moved on every step of a slider drag.

A one-point ``PlotDataItem`` rebuilds its curve, its scatter item and its spot table on every
``setData`` (about a millisecond); the marker here is a bare ``ScatterPlotItem`` in view
coordinates (log10 of the data: a scatter item has no log mode), moved with one ``setData`` of
one position, and only when the point moved.  ``getData()`` returns the view coordinates, like a
``PlotDataItem``'s display data on log axes (legend placement, tests).
"""

from __future__ import annotations

import math

import pyqtgraph as pg

__all__ = ["design_marker", "move_marker", "marker_xy", "set_marker_brush"]


def design_marker(name: str, symbol: str, size: float, brush: str, pen: object) -> pg.ScatterPlotItem:
    """An empty marker (add it to the plot with ``plot.addItem``; ``name`` is its legend entry)."""
    item = pg.ScatterPlotItem(size=size, symbol=symbol, brush=pg.mkBrush(brush), pen=pen, name=name, pxMode=True)
    item.setZValue(20)
    item.design_xy = None  # the point in data units, or None when not drawn
    return item


def move_marker(item: pg.ScatterPlotItem, x: float, y: float, log: tuple[bool, bool] = (True, True)) -> bool:
    """Put the marker at ``(x, y)`` (data units; ``log``: which axes are logarithmic, both by
    default); hide it where an axis cannot show the point.  Returns whether it is drawn."""
    drawn = math.isfinite(x) and math.isfinite(y) and (x > 0 or not log[0]) and (y > 0 or not log[1])
    xy = (float(x), float(y)) if drawn else None
    if xy != item.design_xy:
        item.design_xy = xy
        item.setData(pos=[(math.log10(x) if log[0] else x, math.log10(y) if log[1] else y)] if xy is not None else [])
    return drawn


def marker_xy(item: pg.ScatterPlotItem) -> tuple[float, float] | None:
    """Where the marker is, in data units (None when not drawn)."""
    return item.design_xy


def set_marker_brush(item: pg.ScatterPlotItem, color: str) -> None:
    """Fill the marker with ``color`` (nothing is redrawn if it has that colour already)."""
    brush = pg.mkBrush(color)
    if item.opts["brush"] != brush:
        item.setBrush(brush)
