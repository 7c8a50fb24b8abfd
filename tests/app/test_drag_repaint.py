"""What keeps a slider drag at 60 fps on the Stability and Sampled-data tabs, checked structurally.

Not timed (the latency figures are in tests/benchmarks/bench_gui.py).  These tests catch a
regression of each mechanism:

* texts rewritten on every drag step (the verdict's values, the sampled-data summary) never lay the
  window out again: a ``LayoutRequest`` reaching the main window relayouts every widget in it;
* the refined two-port design at the current b_c (``max_stiffness``, tens of ms) is held back while
  the drag moves, like the sampled-data map, and computed once when it pauses or ends -- except
  for an action that needs the current value (``get(..., hold=False)``);
* the current-design markers are moved, not rebuilt, and not at all when they did not move.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
import pytest
from PySide6.QtCore import QEvent, QObject
from PySide6.QtGui import QUndoStack
from PySide6.QtWidgets import QApplication, QGridLayout, QWidget

from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import display_kind
from app.core.commands import Editor
from app.core.model import ProfileModel
from app.core.nodes_stability import build_graph
from app.core.worker import TaskRunner
from app.tabs.sampled_tab import ASYNC_NODES, SampledTab
from app.tabs.stability_tab import StabilityTab
from app.views.marker import design_marker, marker_xy, move_marker
from app.views.sampled_summary import CATCHING_UP
from app.views.verdict import VerdictView
from app.widgets.steady_label import SteadyLabel


class LayoutRequests(QObject):
    """Counts the ``LayoutRequest`` events that reach each of ``widgets``."""

    def __init__(self, *widgets: QWidget) -> None:
        super().__init__()
        self.widgets = widgets
        self.counts = {w: 0 for w in widgets}
        QApplication.instance().installEventFilter(self)

    def eventFilter(self, obj: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() == QEvent.Type.LayoutRequest and obj in self.counts:
            self.counts[obj] += 1
        return False

    def total(self) -> int:
        return sum(self.counts.values())

    def remove(self) -> None:
        QApplication.instance().removeEventFilter(self)


def test_a_steady_label_grows_once_and_then_lays_nothing_out(qtbot):
    host = QWidget()
    grid = QGridLayout(host)
    label = SteadyLabel("–", template="88.888 %")
    grid.addWidget(label, 0, 0)
    qtbot.addWidget(host)
    host.show()
    qtbot.waitExposed(host)
    for _ in range(5):
        QApplication.processEvents()  # the first layout of the shown window
    start = label.size()
    assert label.minimumSize() == label.maximumSize() == start  # fixed: Qt skips the layout
    assert start.width() >= label.sizeHint().width()  # the template's width, not the dash's
    requests = LayoutRequests(host)
    try:
        for text in ("12.5 %", "7.06 %", "76.24 %", "3.1 %"):  # narrower than the template
            label.setText(text)
            QApplication.processEvents()
        assert requests.total() == 0 and label.size() == start and label.relayouts == 1
        wide = "−4.52×10<sup>4</sup> % (a much longer value)"
        label.setText(wide)
        QApplication.processEvents()
        assert label.relayouts == 2 and requests.total() >= 1  # grown once ...
        assert label.width() >= label.sizeHint().width()  # ... to fit
        grown, before = label.size(), requests.total()
        label.setText("7.06 %")  # ... and never shrinks back (no layout pass per step)
        QApplication.processEvents()
        assert label.size() == grown and requests.total() == before and label.relayouts == 2
    finally:
        requests.remove()


def test_the_plain_text_width_bounds_the_rich_text_width(qtbot):
    """``fits`` skips the exact (document-layout) size hint only when the text surely fits."""
    label = SteadyLabel("", template="8.88888×10<sup>−8</sup> m/(N·s)")
    qtbot.addWidget(label)
    for text in ("4.79784×10<sup>−8</sup> m/(N·s)", "2.455×10<sup>4</sup> N/m", "80.26 rad/s (12.8 Hz)"):
        if label.fits(text):
            label.setText(text)
            assert label.sizeHint().width() <= label.width()
    assert not label.fits("x" * 200)
    assert not label.fits("two<br>lines")


def test_the_verdict_values_are_steady_labels():
    assert all(isinstance(v, SteadyLabel) for v in VerdictView().values)


@pytest.fixture
def graph_setup(qapp):
    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    editor = Editor(model, QUndoStack())
    runner = TaskRunner()
    graph = build_graph(model, runner, chart_points=8)
    editor.dragChanged.connect(graph.set_interactive)
    graph.drag.settle_ms = 600_000  # only the release ends the hold here (not timed)
    yield model, editor, graph
    runner.shutdown()


def test_the_refined_design_waits_for_the_end_of_the_drag(graph_setup):
    model, editor, graph = graph_setup
    first = graph.get("max_stiffness")
    assert graph.calls("max_stiffness") == 1
    token = editor.new_drag()
    for bc in (55.0, 60.0, 65.0):
        assert editor.edit("bc", bc, token) is None
        assert graph.get("max_stiffness") is first  # held: the last value, nothing computed
        assert "max_stiffness" in graph.waiting() and not graph.is_fresh("max_stiffness")
        graph.get("stability_preview")  # the live part of the drag is computed on every step
    assert graph.calls("max_stiffness") == 1
    assert graph.calls("stability_preview") == 3
    # an action that needs the current design computes it, drag or not
    now = graph.get("max_stiffness", hold=False)
    assert now.bc == 65.0 and graph.calls("max_stiffness") == 2 and graph.is_fresh("max_stiffness")
    assert "max_stiffness" not in graph.waiting()
    editor.edit("bc", 70.0, token)
    graph.get("max_stiffness")
    assert graph.waiting() == ["max_stiffness"]
    seen: list[set] = []
    graph.invalidated.connect(lambda names: seen.append(set(names)))
    editor.end_drag(token)
    assert seen and "max_stiffness" in seen[-1] and graph.waiting() == []
    d = graph.get("max_stiffness")
    assert d.bc == 70.0 and graph.calls("max_stiffness") == 3
    # the design the analysis core gives for the final profile, computed without the graph
    ref = display_kind("impedance").build(model.profile).max_stiffness(70.0)
    assert d.kc == ref.kc and d.frequency == ref.frequency


def test_a_marker_moves_without_rebuilding(qtbot):
    plot = pg.PlotWidget()
    qtbot.addWidget(plot)
    plot.getPlotItem().setLogMode(True, True)
    item = design_marker("current gains", "o", 12, "#c92a2a", pg.mkPen("w"))
    plot.addItem(item)
    calls = []
    set_data = item.setData
    item.setData = lambda *a, **k: (calls.append(1), set_data(*a, **k))
    assert move_marker(item, 50e3, 100.0)
    x, y = item.getData()
    np.testing.assert_allclose((10 ** x[0], 10 ** y[0]), (50e3, 100.0), rtol=1e-12)
    assert marker_xy(item) == (50e3, 100.0) and len(calls) == 1
    assert move_marker(item, 50e3, 100.0) and len(calls) == 1  # the same point: nothing redrawn
    assert not move_marker(item, 0.0, 100.0)  # zero on a log axis: not drawn
    assert marker_xy(item) is None and len(item.getData()[0]) == 0 and len(calls) == 2
    assert not move_marker(item, math.nan, 1.0) and len(calls) == 2


@pytest.fixture
def window(win):
    win.maybe_save = lambda: True
    return win


def drag(window, qtbot, tab, field, steps: int = 8) -> LayoutRequests:
    """Drag ``field``'s slider ``steps`` steps (after one step that may size things once)."""
    slider = field.slider
    slider.setSliderDown(True)
    slider.setValue(slider.value() + 2)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    qtbot.wait(200)  # what the first step (and the tab's first show) laid out ...
    for _ in range(10):  # ... to the end, also on a loaded machine (whose timers fire late)
        QApplication.sendPostedEvents(None, QEvent.Type.LayoutRequest)
        qtbot.wait(30)
    requests = LayoutRequests(window, window.centralWidget(), tab, window.verdict)
    try:
        for _ in range(steps):
            slider.setValue(slider.value() + 2)
            qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
            QApplication.processEvents()
    finally:
        requests.remove()
    return requests


def test_a_drag_on_the_stability_tab_lays_nothing_out(window, qtbot):
    tab = window.tab(StabilityTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    window.graph.drag.settle_ms = 600_000
    for field in (window.panel.fields["kc"], window.panel.chain.fields[("masses", 0)]):
        revision = window.verdict.revision
        requests = drag(window, qtbot, tab, field)
        field.slider.setSliderDown(False)
        assert window.verdict.revision > revision  # the verdict followed the drag ...
        # ... in place: a text laid out again would reach the window on every step (3 per step
        # before); at most a one-off (a value wider than any before) is allowed
        assert requests.total() <= 2, requests.counts


def test_a_drag_on_the_sampled_tab_lays_nothing_out_and_holds_the_bound(coarse_grids, window, qtbot):
    """The map and exact chart on the coarse grids (``coarse_grids``): the test counts layouts and
    calls during a drag, not the grids' resolution."""
    g = window.graph
    tab = window.tab(SampledTab)
    window.tabs.setCurrentWidget(tab)
    done = (*ASYNC_NODES, "design_chart", "max_stiffness")  # no result arrives during the drag
    qtbot.waitUntil(lambda: not tab.stale and all(g.is_fresh(n) for n in done), timeout=120000)
    g.drag.settle_ms = 600_000  # only the release ends the hold (a loaded machine may pause)
    calls = g.calls("max_stiffness")
    field = window.panel.chain.fields[("masses", 0)]
    requests = drag(window, qtbot, tab, field)
    # the summary is rewritten in place (a new line count may resize it once; 13 per step before)
    assert requests.total() <= 2, requests.counts
    assert g.calls("max_stiffness") == calls  # held back during the drag ...
    assert "two-port bound (eq. 9, delay-free model): " + CATCHING_UP in tab.summary.text()
    field.slider.setSliderDown(False)
    qtbot.waitUntil(lambda: CATCHING_UP not in tab.summary.text(), timeout=20000)
    assert g.calls("max_stiffness") == calls + 1  # ... and computed once at the end
    kc = g.result("max_stiffness").kc
    assert g.is_fresh("max_stiffness") and kc > 0
    assert "two-port bound (eq. 9, delay-free model): " in tab.summary.text()


def test_the_verdict_numbers_follow_a_drag_at_a_reading_pace_and_end_exact(window, qtbot):
    """Ten drag steps (no pause): the plots follow each, the verdict's numbers are paced (here at
    one update per 10 s, so that a slow machine counts the same); the release shows the verdict of
    the final gains at once."""
    from analysis.study import Headline, stability

    tab = window.tab(StabilityTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    window.graph.drag.settle_ms = 600_000
    window.live.texts.interval_ms = 10_000
    slider = window.panel.fields["kc"].slider
    revision, plots = window.verdict.revision, tab.plot_views()[0].revision
    slider.setSliderDown(True)
    try:
        for _ in range(10):
            slider.setValue(slider.value() + 3)
            QApplication.processEvents()
        assert tab.plot_views()[0].revision >= plots + 10  # the plot followed every step
        assert window.verdict.revision - revision == 1  # the numbers: the first step only
        assert window.live.texts.pending == ["verdict"]
    finally:
        slider.setSliderDown(False)
    qtbot.waitUntil(lambda: not window.live.texts.pending and not tab.stale, timeout=5000)
    QApplication.processEvents()
    h = Headline.from_result(stability(window.model.profile))
    assert window.verdict.margin.text() == h.text("worst_margin", rich=True)
    assert window.verdict.reserve.text() == h.text("stability_reserve", rich=True)
