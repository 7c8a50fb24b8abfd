"""A shading from a curve down to the lower edge of the plot, at any zoom.

A region "below the curve" (the feasible gains of the design chart, the stable walls of the
Z-width chart) has no lower edge of its own; shading it down to a fixed floor near the data drew
an edge there that looked like a limit (lower gains infeasible).  :class:`FloorFill` keeps a
hidden floor curve on the view's lower edge (following every zoom), and the shading is left out
of the auto-range, so it always reaches the axis.  It stops there, never below: an SVG drawing
has no clipping, so a shading past the edge would cover the axis and its labels.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg

__all__ = ["FloorFill", "axis_floor"]


def axis_floor(view_bottom: float, x: np.ndarray, y: np.ndarray, log_x: bool, log_y: bool
               ) -> tuple[np.ndarray, np.ndarray]:
    """The floor ``(x, y)`` (data units) of a shading "down to the axis" under the curve ``(x, y)``:
    the view's lower edge ``view_bottom`` (view coordinates: log10 on a log axis), or the curve
    itself where it lies below that edge (no shading there: none outside the view).  Where the
    curve crosses the edge a point is added, so that no sliver reaches below it."""
    vx = np.log10(np.asarray(x, float)) if log_x else np.asarray(x, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        vy = np.log10(np.asarray(y, float)) if log_y else np.asarray(y, float)
    if not math.isfinite(view_bottom):
        return np.asarray(x, float), np.asarray(y, float)
    vy = np.where(np.isfinite(vy), vy, view_bottom)
    d = vy - view_bottom
    cross = np.flatnonzero(d[:-1] * d[1:] < 0)
    t = d[cross] / (d[cross] - d[cross + 1])
    fx = np.insert(vx, cross + 1, vx[cross] + t * (vx[cross + 1] - vx[cross]))
    fy = np.insert(np.minimum(vy, view_bottom), cross + 1, view_bottom)
    return (10.0 ** fx if log_x else fx), (10.0 ** fy if log_y else fy)


class FloorFill:
    """Keeps ``floor`` (a curve of the plot, hidden) at :func:`axis_floor` under ``top``'s points.

    ``fill`` (between the two) is left out of the auto-range.  While :attr:`enabled` is false the
    floor is left alone (a view that fills between two real edges sets it itself).
    """

    def __init__(self, plot: pg.PlotItem, floor: pg.PlotDataItem, top: pg.PlotDataItem,
                 fill: pg.FillBetweenItem) -> None:
        self.plot, self.floor, self.top, self.fill = plot, floor, top, fill
        self.enabled = True
        plot.addItem(fill, ignoreBounds=True)
        self.floor.setVisible(False)
        plot.getViewBox().sigYRangeChanged.connect(lambda *_: self.update())

    def set_enabled(self, enabled: bool) -> None:
        self.enabled = enabled
        self.floor.setVisible(not enabled)
        self.update()

    def update(self) -> None:
        """Lay the floor under the top curve's points, on the view's lower edge."""
        if not self.enabled:
            return
        x, y = self.top.getOriginalDataset()
        if x is None or y is None or len(x) < 2:
            if self.floor.getOriginalDataset()[0] is not None:
                self.floor.setData([], [])
            return
        vb = self.plot.getViewBox()
        log_x, log_y = (bool(v) for v in vb.state["logMode"])
        fx, fy = axis_floor(float(vb.viewRange()[1][0]), x, y, log_x, log_y)
        ox, oy = self.floor.getOriginalDataset()
        if ox is not None and np.array_equal(ox, fx) and np.array_equal(oy, fy):
            return
        self.floor.setData(fx, fy)
