"""A shading from a curve down to the lower edge of the plot, at any zoom.

A region "below the curve" (the feasible gains of the design chart, the stable walls of the
Z-width chart) has no lower edge of its own; shading it down to a fixed floor near the data drew
an edge there that looked like a limit (lower gains infeasible).  :class:`FloorFill` keeps a
hidden floor curve at or below the view's lower edge, and the shading is left out of the
auto-range, so it always reaches the axis.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg

__all__ = ["FloorFill", "axis_floor", "FLOOR_DECADES"]

#: how far below the lowest data point the floor lies at least (decades on a log axis)
FLOOR_DECADES = 3.0


def axis_floor(view_bottom: float, y: np.ndarray, log_y: bool, decades: float = FLOOR_DECADES) -> float:
    """Where a shading "down to the axis" ends, in data units: at or below the view's lower edge
    ``view_bottom`` (view coordinates: log10 on a log axis) and, on a log axis, at least ``decades``
    below the lowest positive value of ``y``."""
    y = np.asarray(y, float)
    if log_y:
        y = y[np.isfinite(y) & (y > 0)]
        edge = 10.0 ** view_bottom if math.isfinite(view_bottom) else math.inf
        low = float(y.min()) / 10.0 ** decades if y.size else math.inf
        value = min(edge, low)
        return value if math.isfinite(value) and value > 0 else 1e-300
    y = y[np.isfinite(y)]
    value = min(view_bottom, float(y.min()) if y.size else view_bottom)
    return value if math.isfinite(value) else 0.0


class FloorFill:
    """Keeps ``floor`` (a curve of the plot, hidden) at :func:`axis_floor` under ``top``'s points.

    ``fill`` (between the two) is left out of the auto-range.  While :attr:`enabled` is false the
    floor is left alone (a view that fills between two real edges sets it itself).
    """

    def __init__(self, plot: pg.PlotItem, floor: pg.PlotDataItem, top: pg.PlotDataItem,
                 fill: pg.FillBetweenItem) -> None:
        self.plot, self.floor, self.top, self.fill = plot, floor, top, fill
        self.enabled = True
        self.value = math.nan  # the floor last drawn (data units), for tests
        plot.addItem(fill, ignoreBounds=True)
        self.floor.setVisible(False)
        plot.getViewBox().sigYRangeChanged.connect(lambda *_: self.update())

    def set_enabled(self, enabled: bool) -> None:
        self.enabled = enabled
        self.floor.setVisible(not enabled)
        self.update()

    def update(self) -> None:
        """Lay the floor under the top curve's points, at or below the view's lower edge."""
        if not self.enabled:
            return
        x, y = self.top.getOriginalDataset()
        if x is None or y is None or len(x) < 2:
            if self.floor.getOriginalDataset()[0] is not None:
                self.floor.setData([], [])
            return
        log_y = bool(self.plot.getViewBox().state["logMode"][1])
        value = axis_floor(float(self.plot.getViewBox().viewRange()[1][0]), y, log_y)
        if value == self.value and np.array_equal(self.floor.getOriginalDataset()[0], x):
            return
        self.value = value
        self.floor.setData(np.asarray(x, float), np.full(len(x), value))
