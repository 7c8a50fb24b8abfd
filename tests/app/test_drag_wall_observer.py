"""A slider drag on the Transparency and Observer tabs: the cheap parts follow it, the rest catches up.

Structural, not timed (the latency figures are in tests/benchmarks/bench_gui.py).  During a drag of
the wall stiffness K (or of the Q-filter cutoff ω_Q) the graph's call counters show that the
expensive nodes -- the curves over B_c and the step response (the two-axis coupling and step) --
are not computed, while the point at the current gains (the single-axis response) is computed on
every edit and drawn exactly; the held plots are not redrawn and say that they catch up; no edit
lays the window out again.  When the drag ends each held node is computed once, and every plot
equals a fresh computation of the analysis for the final values.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from PySide6.QtCore import QCoreApplication, QEvent, QObject

from analysis.study import observer_coupling, observer_response, observer_step, wall_design, wall_tradeoff
from analysis.study.quantities import rich_numbers
from app.tabs.observer_tab import ObserverTab
from app.tabs.transparency_tab import TransparencyTab, admittance_grid

pytestmark = pytest.mark.gui

WALL_HELD = ("wall_tradeoff", "wall_step")
OBSERVER_HELD = ("observer_coupling", "observer_step")


class LayoutRequests(QObject):
    """Counts the layout requests that reach the watched widgets."""

    def __init__(self, *widgets) -> None:
        super().__init__()
        self.count = 0
        self.seen: list[str] = []
        self._widgets = widgets
        for w in widgets:
            w.installEventFilter(self)

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 - Qt API
        if event.type() == QEvent.Type.LayoutRequest:
            self.count += 1
            self.seen.append(type(obj).__name__)
        return False

    def remove(self) -> None:
        for w in self._widgets:
            w.removeEventFilter(self)


def show(win, qtbot, cls, held):
    tab = win.tab(cls)
    win.tabs.setCurrentWidget(tab)
    fresh(win, qtbot, tab, held)
    return tab


def fresh(win, qtbot, tab, held) -> None:
    qtbot.waitUntil(lambda: not tab.stale and all(win.graph.is_fresh(n) for n in held)
                    and not win.runner.is_running(), timeout=60000)
    qtbot.wait(20)


def drag_step(win, qtbot, tab, field, value: float, token: int) -> None:
    """One step of a drag: the edit, then the refresh it schedules."""
    before = tab.refreshes
    assert field.write(value, token) is None
    qtbot.waitUntil(lambda: tab.refreshes > before and not tab.stale, timeout=5000)


def test_wall_stiffness_drag_holds_the_curves_and_the_step(eom_win, qtbot):
    win = eom_win
    g = win.graph
    tab = show(win, qtbot, TransparencyTab, WALL_HELD)
    g.drag.settle_ms = 600_000  # only the release ends the hold here (a loaded machine may pause)
    calls = {n: g.calls(n) for n in (*WALL_HELD, "wall_point")}
    revisions = [v.revision for v in (tab.index_plot, tab.peak_plot, tab.position_plot, tab.force_plot)]
    field = tab.fields["wall_stiffness"]
    token = win.editor.new_drag()
    layouts = LayoutRequests(win, tab, tab.summary_area)
    try:
        for i, k in enumerate((2200.0, 2600.0, 3000.0, 3400.0)):
            drag_step(win, qtbot, tab, field, k, token)
            if i == 0:  # the first step writes "updating after the drag" into the titles: laid out once
                for _ in range(10):
                    QCoreApplication.sendPostedEvents(None, QEvent.Type.LayoutRequest)
                layouts.count = 0
                layouts.seen.clear()
            # the current design follows every step, exactly
            design = wall_design(win.model.profile)
            peak = design.robustness_peak(tab.bc)
            assert tab.peak_plot.data("current")[1][0] == pytest.approx(20 * math.log10(peak.gain), rel=1e-12)
            ir = design.index_result(tab.bc)
            if ir.finite:
                assert tab.index_plot.data("current")[1][0] == pytest.approx(ir.index, rel=1e-12)
            # the numbers in the summary follow at a reading pace (app.widgets.text_pacer): within 0.1 s
            shown = rich_numbers(f"{peak.gain_db:+.2f}") + " dB"  # a negative peak with the minus sign "−"
            qtbot.waitUntil(lambda: shown in tab.summary.text(), timeout=2000)  # noqa: B023
            yt = design.admittances(admittance_grid(design.settings), tab.bc)[1]
            np.testing.assert_allclose(tab.admittance_plot.data("yt")[1], np.abs(yt), rtol=1e-12)
            # the expensive parts wait, and say so
            assert set(g.waiting()) == set(WALL_HELD)
            for view in (tab.index_plot, tab.peak_plot, tab.position_plot, tab.force_plot):
                assert "updating after the drag" in view.header.text()
        assert {n: g.calls(n) for n in WALL_HELD} == {n: calls[n] for n in WALL_HELD}
        assert g.calls("wall_point") == calls["wall_point"] + 4
        assert [v.revision for v in (tab.index_plot, tab.peak_plot, tab.position_plot, tab.force_plot)] \
            == revisions  # the held curves were not drawn again
        assert layouts.count == 0, layouts.seen  # a new summary text (every step) does not lay the window out again
    finally:
        layouts.remove()
        win.editor.end_drag(token)
    fresh(win, qtbot, tab, WALL_HELD)
    assert {n: g.calls(n) for n in WALL_HELD} == {n: calls[n] + 1 for n in WALL_HELD}
    # after the drag the view is a fresh computation for the final K
    assert win.model.profile.wall.wall_stiffness == 3400.0
    trade = wall_tradeoff(win.model.profile)
    c = trade.curves
    finite = np.isfinite(c.index)
    np.testing.assert_allclose(tab.index_plot.data("J")[1], c.index[finite], rtol=1e-12)
    assert tab.peak_plot.data("optimum")[0][0] == pytest.approx(trade.optimum.bc, rel=1e-12)
    step = wall_design(win.model.profile).step_response(tab.bc)
    np.testing.assert_allclose(tab.position_plot.data("position")[1], 1e3 * step.position, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(tab.force_plot.data("force")[1], step.force, rtol=1e-12, atol=1e-15)
    for view in (tab.index_plot, tab.peak_plot, tab.position_plot, tab.force_plot):
        assert "updating" not in view.header.text()
        assert all(view.plot.getViewBox().autoRangeEnabled())  # the axes follow the data again


def test_cutoff_drag_holds_the_two_axis_plots(eom_win, qtbot):
    win = eom_win
    g = win.graph
    tab = show(win, qtbot, ObserverTab, OBSERVER_HELD)
    g.drag.settle_ms = 600_000
    calls = {n: g.calls(n) for n in (*OBSERVER_HELD, "observer_response")}
    revisions = (tab.coupling_plot.revision, tab.step_plot.revision)
    changes = {key: 0 for key in ("plant", "nominal", "effective")}
    for key in changes:
        tab.plant_plot.items[key].sigPlotChanged.connect(lambda *_a, k=key: changes.__setitem__(k, changes[k] + 1))
    field = tab.fields["cutoff"]
    token = win.editor.new_drag()
    try:
        for wq in (150.0, 250.0, 300.0):
            drag_step(win, qtbot, tab, field, wq, token)
            r = observer_response(win.model.profile)
            np.testing.assert_allclose(tab.plant_plot.data("effective")[1], np.abs(r.effective), rtol=1e-12)
            np.testing.assert_allclose(tab.disturbance_plot.data("with")[1], np.abs(r.disturbance_with), rtol=1e-12)
            assert tab.coupling_plot.lines["cutoff"].value() == pytest.approx(math.log10(wq))
            assert set(g.waiting()) == set(OBSERVER_HELD)
            assert "updating after the drag" in tab.coupling_plot.header.text()
            assert "updating after the drag" in tab.step_plot.header.text()
        assert {n: g.calls(n) for n in OBSERVER_HELD} == {n: calls[n] for n in OBSERVER_HELD}
        assert g.calls("observer_response") == calls["observer_response"] + 3
        assert (tab.coupling_plot.revision, tab.step_plot.revision) == revisions
        # the plant curves that ω_Q does not move are not set again
        assert changes == {"plant": 0, "nominal": 0, "effective": 3}
    finally:
        win.editor.end_drag(token)
    fresh(win, qtbot, tab, OBSERVER_HELD)
    assert {n: g.calls(n) for n in OBSERVER_HELD} == {n: calls[n] + 1 for n in OBSERVER_HELD}
    p = win.model.profile
    assert p.observer.cutoff == 300.0
    c, s = observer_coupling(p), observer_step(p)
    np.testing.assert_allclose(tab.coupling_plot.data("with")[1], np.abs(c.coupling_with), rtol=1e-12)
    np.testing.assert_allclose(tab.step_plot.data("with")[1], 1e3 * s.y_with, rtol=1e-12, atol=1e-15)
    assert "updating" not in tab.coupling_plot.header.text() and "updating" not in tab.step_plot.header.text()


def test_a_pause_catches_up_while_the_slider_is_held(eom_win, qtbot):
    win = eom_win
    g = win.graph
    tab = show(win, qtbot, TransparencyTab, WALL_HELD)
    g.drag.settle_ms = 100
    calls = {n: g.calls(n) for n in WALL_HELD}
    token = win.editor.new_drag()
    try:
        drag_step(win, qtbot, tab, tab.fields["wall_stiffness"], 2500.0, token)
        assert set(g.waiting()) == set(WALL_HELD)
        # the drag has not moved: the held nodes are computed once, the slider still down
        fresh(win, qtbot, tab, WALL_HELD)
        assert g.interactive and g.waiting() == []
        assert {n: g.calls(n) for n in WALL_HELD} == {n: calls[n] + 1 for n in WALL_HELD}
        assert "updating" not in tab.position_plot.header.text()
        step = wall_design(win.model.profile).step_response(tab.bc)
        np.testing.assert_allclose(tab.position_plot.data("position")[1], 1e3 * step.position, rtol=1e-12,
                                   atol=1e-15)
    finally:
        win.editor.end_drag(token)
