"""The Identify view's plots settle (issue 23): after the curves of a mixed actuator + gauge +
clamped set are drawn, the auto-ranged axes stop changing within a few event-loop turns at every
width, instead of repainting without end.

The cause was pyqtgraph's automatic downsampling on the Bode curves (sweeps joined by a gap, FFT
bins on a logarithmic ω axis): the drawn x extent followed the view's range, which auto-ranges to
that extent.  The test counts (range changes, drawn bounds), never times; a runaway range is stopped
by :class:`_RangeWatch` so that the old code fails here instead of hanging the event loop."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PySide6.QtWidgets import QApplication

from analysis.study.measurement_files import parse_measurement_spec, read_measurement_files
from app.views.bode_view import BodeView
from app.views.curves_plot import CurvesPlot
from tests.identify_files import write_chirp_csv, write_frf_csv

#: BodeView widths: the widths at which the old code never settled (a window about a tenth wide
#: around 650-700 px with the test fonts) lie well inside, whatever the axes' tick label widths.
WIDTHS = list(range(500, 901, 25))
TURNS = 12  # event-loop turns to settle in (the first show and the data take 2-3)
RUNAWAY = 200  # range changes in one run: the loop is broken (auto-range off) and the test fails


@pytest.fixture(scope="module")
def pairs(tmp_path_factory) -> list:
    """The mixed set's measurements, each with its own response as the model's (the curves' x data
    is what matters, no fit needed)."""
    d: Path = tmp_path_factory.mktemp("converge")
    specs = [str(write_chirp_csv(d / "chirp.csv")), f"{write_frf_csv(d / 'gauge.csv', 'gauge')}:gauge",
             f"{write_frf_csv(d / 'clamped.csv', 'actuator', 'clamped', seed=1)}:actuator:clamped"]
    loaded = read_measurement_files([parse_measurement_spec(s) for s in specs], sample_time=1e-3)
    return [(m.measurement, m.measurement.response) for m in loaded]


class _RangeWatch:
    """Counts each plot's x and y range changes; past :data:`RUNAWAY` it switches the plot's
    auto-range off, which ends a range that would change without end."""

    def __init__(self, views: list[CurvesPlot]) -> None:
        self.counts = {id(v): 0 for v in views}
        self.runaway: list[str] = []
        for v in views:
            vb = v.plot.getViewBox()
            vb.sigRangeChanged.connect(lambda *_a, v=v: self._changed(v))

    def _changed(self, view: CurvesPlot) -> None:
        self.counts[id(view)] += 1
        if self.counts[id(view)] > RUNAWAY and view.title not in self.runaway:
            self.runaway.append(view.title)
            view.plot.getViewBox().disableAutoRange()

    def total(self) -> int:
        return sum(self.counts.values())


def _turn(app: QApplication) -> None:
    app.processEvents()


def _drawn(qtbot, pairs: list, width: int) -> tuple[BodeView, _RangeWatch, list[int]]:
    """A BodeView of ``width`` × 640 px showing ``pairs``; the range changes in each of TURNS turns."""
    app = QApplication.instance()
    view = BodeView()
    qtbot.addWidget(view)
    view.resize(width, 640)
    view.show()
    qtbot.waitExposed(view)
    for _ in range(3):
        _turn(app)
    watch = _RangeWatch(view.plot_views())
    view.show_pairs(pairs)
    per_turn = []
    for _ in range(TURNS):
        before = watch.total()
        _turn(app)
        per_turn.append(watch.total() - before)
    return view, watch, per_turn


def _assert_every_curve_drawn_whole(view: BodeView, width: int) -> None:
    """The drawn x extent of each curve is its data's, whatever the view's width (the old automatic
    downsampling left out the lowest bin at some widths and not at others)."""
    checked = 0
    for plot in view.plot_views():
        for key, item in plot.items.items():
            x = np.asarray(item.getOriginalDataset()[0], float)  # as given (a gap's nan y keeps its x)
            x = x[np.isfinite(x) & (x > 0)]
            if x.size < 2:
                continue
            lo, hi = item.dataBounds(0)
            np.testing.assert_allclose([lo, hi], np.log10([x.min(), x.max()]), rtol=0, atol=1e-12,
                                       err_msg=f"{plot.title}: {key} at {width} px")
            checked += 1
    assert checked >= 8  # magnitude (2 quantities x measured/fitted), phase, residual, coherence, ...


@pytest.mark.parametrize("width", WIDTHS)
def test_the_identify_plots_settle_after_a_mixed_set_is_drawn(qtbot, pairs, width):
    """The ranges settle on the data, and every Bode curve is drawn over all its points (checked on
    the same drawn view at every width: it was a separate test drawing the view again at every
    fourth width)."""
    view, watch, per_turn = _drawn(qtbot, pairs, width)
    assert watch.runaway == [], f"ranges never settled at {width} px: {watch.runaway} (turns: {per_turn})"
    assert per_turn[-4:] == [0, 0, 0, 0], f"ranges still changing at {width} px: {per_turn}"
    # settled on the data: every point of the three sweeps inside the x range drawn
    w = np.concatenate([m.frequency for m, _ in pairs])  # rad/s
    for plot in view.plot_views():
        lo, hi = plot.plot.getViewBox().viewRange()[0]
        assert lo <= np.log10(w.min()) and np.log10(w.max()) <= hi, plot.title
    _assert_every_curve_drawn_whole(view, width)
