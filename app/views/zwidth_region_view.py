"""The classic Z-width picture: the stable (B, K) region of the virtual wall (Colgate & Brown 1994).

Drawn on log axes: the exact largest stable K over B (the region below it shaded), the passive
region of Colgate & Schenkel, eq. (9)'s two-port limit, the imported hardware trials (stable:
filled green circles, unstable: red crosses; those the analysis gets wrong ringed) and the
current wall ``(b_c, k_c)``.  A click in the plot emits :attr:`ZWidthRegionView.pointPicked`
with ``(B, K)``: the tab sets the wall to it in one undo step.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QWidget

from analysis.sampled import MeasuredTrials, TrialScore, ZWidthRegion
from analysis.study.quantities import format_number, superscript_numbers

from app.views.pickable import PickablePlotView
from app.views.base import Axis, Series, clean_xy, mark_design_point
from app.views.floor_fill import FloorFill
from app.views.legend_row import sync_legend

__all__ = ["ZWidthRegionView", "B_LABEL", "K_LABEL"]

#: The export's x and y: the axes' quantities and units.
B_LABEL, K_LABEL = Axis("B", "N·s/m"), Axis("K", "N/m")


class ZWidthRegionView(PickablePlotView):
    """Region, passive region, eq. 9 limit, trials and the current wall on one (B, K) chart."""


    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__("Z-width: stable virtual walls (B, K)", parent)
        self.set_log(True, True)
        self.set_axis_labels(*B_LABEL, *K_LABEL)
        self.floor = self.curve(None, "#2b8a3e", 0.0)
        self.floor.setPen(None)  # only the shading's lower edge: at the axis (every lower K is stable too)
        self.exact = self.curve("exact largest stable K", "#2b8a3e", 2.5)
        self.fill = pg.FillBetweenItem(self.floor, self.exact, brush=pg.mkBrush(43, 138, 62, 45))
        self.fill.setZValue(-5)
        self.floor_fill = FloorFill(self.plot, self.floor, self.exact, self.fill)
        self.passive = self.curve("passive (Colgate–Schenkel)", "#1f5fbf", 2.0, Qt.PenStyle.DashLine)
        self.twoport = self.curve("two-port limit (eq. 9)", "#d9480f", 2.0, Qt.PenStyle.DashDotLine)
        self.stable_trials = pg.PlotDataItem([], [], pen=None, symbol="o", symbolSize=8, symbolBrush="#2b8a3e",
                                             symbolPen=pg.mkPen("#1b5e20", width=1), name="trial: stable")
        self.unstable_trials = pg.PlotDataItem([], [], pen=None, symbol="x", symbolSize=10, symbolBrush="#c92a2a",
                                               symbolPen=pg.mkPen("#c92a2a", width=2), name="trial: unstable")
        self.wrong = pg.PlotDataItem([], [], pen=None, symbol="o", symbolSize=18, symbolBrush=None,
                                     symbolPen=pg.mkPen("#e8590c", width=2.5), name="predicted wrong")
        self.point = pg.PlotDataItem([], [], pen=None, symbol="s", symbolSize=12, symbolBrush="#7048e8",
                                     symbolPen=pg.mkPen("w", width=1.5), name="current wall (b<sub>c</sub>, k<sub>c</sub>)")
        for z, item in enumerate((self.stable_trials, self.unstable_trials, self.wrong, self.point)):
            item.setZValue(10 + z)
            self.plot.addItem(item)
        self.legend_outside(3)
        self._sync_legend()  # no trial entries before trials are loaded
        self.region: ZWidthRegion | None = None
        self.score: TrialScore | None = None
        self.trials: MeasuredTrials | None = None
        self._series: list[Series] = []
        self._point_note = ""
        self._notes: list[str] = []
        self.errors: list[str] = []  # why an input was left out (a trials file that cannot be used)
        self.summary = ""
        self.plot_widget.setToolTip("Click to set the virtual wall (b_c, k_c)")
        self.plot_widget.setMinimumSize(260, 200)

    def set_busy(self, busy: bool, text: str = "") -> None:
        # exponents as Unicode superscripts: a <sup> in the one-line title is cut at its top (×10⁷ read ×10')
        head = f"<b>{self.title}</b>" + (f"  {superscript_numbers(self.summary)}" if self.summary else "")
        self.header.setText(head + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def update_region(self, region: ZWidthRegion | None, trials: MeasuredTrials | None = None,
                      score: TrialScore | None = None) -> None:
        """Draw ``region`` and the ``trials`` scored against it (``score``)."""
        self.region, self.trials, self.score = region, trials, score
        self._series = []
        notes: list[str] = []
        if region is None:
            for c in (self.exact, self.passive, self.twoport):
                c.setData([], [])
            self.floor_fill.update()
            self.summary = ""
        else:
            self._draw_curves(region, notes)
            self.summary = (f"area {format_number(region.area_linear, 4)} N²·s/m² (linear), "
                            f"{format_number(region.area_log, 4)} decades² (log)")
        self._draw_trials(trials, score)
        if score is not None and trials is not None:
            self.summary += (f";  trials: {score.wrong_count} of {score.scored} predicted wrong"
                             + (f", {score.outside.size} outside the B range" if score.outside.size else ""))
        self._notes = notes
        self._show_warnings()
        self.set_busy(False)
        self.bump()

    def _draw_curves(self, r: ZWidthRegion, notes: list[str]) -> None:
        k = np.minimum(np.asarray(r.k_max, float), r.k_ceiling)
        x, y, _ = clean_xy(r.b, k, True, True)
        self.exact.setData(x, y)
        self.floor_fill.update()
        if np.any(np.asarray(r.k_max) <= r.k_floor):
            notes.append("no stable K ≥ 1 N/m at some B (not drawn)")
        xp, yp, _ = clean_xy(r.b, r.k_passive, True, True)
        self.passive.setData(xp, yp)
        x2, y2, _ = clean_xy(r.b, r.k_twoport, True, True)
        self.twoport.setData(x2, y2)
        self._series = [Series(f"exact largest stable K (delay {r.delay_samples}, {r.velocity_filter.label()})",
                               B_LABEL, K_LABEL, np.asarray(r.b, float), np.asarray(r.k_max, float)),
                        Series("passive K (Colgate-Schenkel)", B_LABEL, K_LABEL, np.asarray(r.b, float),
                               np.asarray(r.k_passive, float)),
                        Series("two-port limit K (eq. 9)", B_LABEL, K_LABEL, np.asarray(r.b, float),
                               np.asarray(r.k_twoport, float))]

    def _draw_trials(self, trials: MeasuredTrials | None, score: TrialScore | None) -> None:
        if trials is None:
            for item in (self.stable_trials, self.unstable_trials, self.wrong):
                item.setData([], [])
            self._sync_legend()
            return
        st = np.asarray(trials.stable, bool)
        ok = (trials.b > 0) & (trials.k > 0)  # log axes
        self.stable_trials.setData(trials.b[st & ok], trials.k[st & ok])
        self.unstable_trials.setData(trials.b[~st & ok], trials.k[~st & ok])
        wrong = np.zeros(st.size, bool)
        if score is not None:
            wrong[score.wrong] = True
        self.wrong.setData(trials.b[wrong & ok], trials.k[wrong & ok])
        self._sync_legend()
        for name, mask in (("trials measured stable", st), ("trials measured unstable", ~st),
                           ("trials predicted wrong", wrong)):
            self._series.append(Series(name, B_LABEL, K_LABEL, trials.b[mask], trials.k[mask]))

    def _sync_legend(self) -> None:
        """The legend lists the trial markers only when there are such trials to see."""
        trials = [item for item in (self.stable_trials, self.unstable_trials, self.wrong)
                  if item.getData()[0] is not None and len(item.getData()[0])]
        items = [self.exact, self.passive, self.twoport, *trials, self.point]
        sync_legend(self.legend, [(item, item.opts["name"]) for item in items])

    def update_point(self, b: float, k: float, stable: bool | None) -> None:
        """The current wall ``(b_c, k_c)`` (``stable``: inside the region)."""
        self._point_note = mark_design_point(self.point, b, k, stable, self.palette_colors())
        self._show_warnings()
        self.bump()

    def set_errors(self, errors: list[str]) -> None:
        """Say why an input is not drawn (e.g. the trials file's fault: file, line, column), above the
        region's own notes, which stay; ``[]`` clears them."""
        self.errors = [e for e in errors if e]
        self._show_warnings()

    def _show_warnings(self) -> None:
        self.set_warning([*self.errors, *self._notes, self._point_note])

    def restyle(self, pal: dict) -> None:
        self.exact.setPen(pg.mkPen(pal["c"], width=2.5))
        self.passive.setPen(pg.mkPen(pal["a"], width=2, style=Qt.PenStyle.DashLine))
        self.twoport.setPen(pg.mkPen(pal["b"], width=2, style=Qt.PenStyle.DashDotLine))
        self.point.setSymbolPen(pg.mkPen(pal["bg"], width=1.5))

    def export_series(self) -> list[Series]:
        return list(self._series)

    def export_notes(self) -> list[str]:
        notes = [*super().export_notes(), *self.errors]
        if self.summary:
            notes.append(self.summary)
        if self.score is not None and self.trials is not None:
            notes.extend(self.score.describe(self.trials))
        return notes
