"""The Z-width area against the velocity filter's cut-off, with the optimum marked.

Chawda, Celik & O'Malley (ASME JDSMC 137(2), 2015) show that the Z-width of a haptic display
has a maximum over the velocity filter's cut-off.  The curve is the linear area of the
(B, K) region (:data:`analysis.sampled.OPTIMIZER_AREA`, the measure the optimizer maximizes)
at each cut-off, in Hz on a log axis -- the noise-limited area when the encoder-noise criterion is
on; the refined optimum is a star, the raw backward difference's area a dashed horizontal line,
and the profile's own cut-off a vertical line.  The header prints the verdict of
:func:`analysis.study.optimum_verdict` (the report and the CLI's export print the same sentence):
no filter is best when no cut-off beats it.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QWidget

from analysis.chain.velocity_filter import FILTER_KINDS, VelocityFilter
from analysis.sampled import FilterOptimum
from analysis.study import optimum_verdict
from analysis.study.quantities import superscript_numbers

from app.views.base import Axis, PlotView, Series

__all__ = ["FilterOptimumView", "CUTOFF_LABEL", "AREA_LABEL"]

#: The export's x and y: the axes' quantities and units.
CUTOFF_LABEL, AREA_LABEL = Axis("cut-off f_c", "Hz"), Axis("area ∫K dB", "N²·s/m²")
_HZ = 1.0 / (2.0 * math.pi)


class FilterOptimumView(PlotView):
    """Area of the stable region against the cut-off (Hz), the optimum and the current filter."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Z-width area vs filter cut-off", parent)
        self.set_log(True, False)
        self.set_axis_labels(*CUTOFF_LABEL, *AREA_LABEL)
        self.area = self.curve("area", "#1f5fbf", 2.0)
        self.area.setSymbol("o")
        self.area.setSymbolSize(5)
        self.area.setSymbolBrush("#1f5fbf")
        self.area.setSymbolPen(None)
        self.backward = pg.InfiniteLine(angle=0, movable=False,
                                        pen=pg.mkPen("#868e96", width=1.5, style=Qt.PenStyle.DashLine))
        self.current = pg.InfiniteLine(angle=90, movable=False,
                                       pen=pg.mkPen("#7048e8", width=1.5, style=Qt.PenStyle.DotLine))
        for line in (self.backward, self.current):
            line.hide()
            self.plot.addItem(line, ignoreBounds=True)
        self.best = pg.PlotDataItem([], [], pen=None, symbol="star", symbolSize=18, symbolBrush="#d9480f",
                                    symbolPen=pg.mkPen("w", width=1), name="optimum")
        self.best.setZValue(20)
        self.plot.addItem(self.best)
        self.legend_outside(2)
        self.backward_legend = pg.PlotDataItem([], [], pen=pg.mkPen("#868e96", width=1.5, style=Qt.PenStyle.DashLine),
                                               name="backward difference (no filter)")
        self.plot.addItem(self.backward_legend)
        self.optimum: FilterOptimum | None = None
        self.summary = ""
        self._series: list[Series] = []
        self.plot_widget.setMinimumSize(260, 180)

    def set_busy(self, busy: bool, text: str = "") -> None:
        head = f"<b>{self.title}</b>" + (f"  {superscript_numbers(self.summary)}" if self.summary else "")
        self.header.setText(head + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def update_optimum(self, opt: FilterOptimum | None) -> None:
        """Draw the area curve of ``opt`` (``None`` clears it)."""
        self.optimum = opt
        if opt is None:
            self.area.setData([], [])
            self.best.setData([], [])
            self.backward.hide()
            self.summary = ""
            self._series = []
        else:
            f = np.asarray(opt.cutoffs, float) * _HZ
            self.area.setData(f, np.asarray(opt.areas, float))
            self.best.setData([opt.cutoff * _HZ], [opt.area])
            self.backward.setPos(opt.backward_area)
            self.backward.show()
            legend = f"{opt.criterion}, {FILTER_KINDS[opt.kind]}"
            self.set_legend_text(self.area, legend)
            # the star is the optimum only where it beats no filter; else it is the best cut-off,
            # which the verdict says is worse than no filter
            star = "best cut-off (worse than no filter)" if opt.best.is_backward else "optimum"
            self.set_legend_text(self.best, star)
            self.summary = optimum_verdict(opt)
            self._series = [Series(legend, CUTOFF_LABEL, AREA_LABEL, f,
                                   np.asarray(opt.areas, float)),
                            Series(star, CUTOFF_LABEL, AREA_LABEL, np.array([opt.cutoff * _HZ]),
                                   np.array([opt.area])),
                            Series("backward difference (no filter)", CUTOFF_LABEL, AREA_LABEL,
                                   np.array([math.nan]), np.array([opt.backward_area]))]
        self.set_busy(False)
        self.bump()

    def update_filter(self, vf: VelocityFilter) -> None:
        """Mark the profile's own cut-off (nothing for the backward difference)."""
        if vf.is_backward:
            self.current.hide()
        else:
            self.current.setPos(math.log10(vf.cutoff * _HZ))
            self.current.show()
        self.bump()

    def restyle(self, pal: dict) -> None:
        self.area.setPen(pg.mkPen(pal["a"], width=2))
        self.area.setSymbolBrush(pal["a"])
        self.best.setSymbolBrush(pal["b"])
        self.best.setSymbolPen(pg.mkPen(pal["bg"], width=1))

    def export_series(self) -> list[Series]:
        return list(self._series)

    def export_notes(self) -> list[str]:
        notes = super().export_notes()
        if self.summary:
            notes.append(self.summary.replace("<sub>", "_").replace("</sub>", ""))
        return notes
