"""The compute graph does only what the visible views need, and long work never blocks the GUI."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt, QTimer

from analysis import ImpedanceDisplay
from app.tabs.design_tab import DesignTab
from app.tabs.stability_tab import StabilityTab


def test_coupling_gain_change_does_not_recompute_device_node(win, qtbot):
    g = win.graph
    dev_calls, stab_calls = g.calls("impedance_display"), g.calls("stability")
    assert dev_calls == 1
    field = win.panel.fields["kc"]
    view = win.tab(StabilityTab).stability
    for step in (5, 10, 15):
        before = view.revision
        field.slider.setValue(field.slider.value() + step)
        qtbot.waitUntil(lambda: view.revision > before, timeout=5000)
    assert g.calls("impedance_display") == dev_calls  # the device two-port was reused
    assert g.calls("stability") == stab_calls + 3
    # a device change does recompute it
    before = view.revision
    win.panel.chain.fields[("masses", 0)].spin.setValue(0.3)
    qtbot.waitUntil(lambda: view.revision > before, timeout=5000)
    assert g.calls("impedance_display") == dev_calls + 1
    # the admittance device node was never needed in the impedance display
    assert g.calls("admittance_display") == 0


def test_hidden_tab_computes_nothing_until_shown(win, qtbot):
    g = win.graph
    design = win.tab(DesignTab)
    assert g.calls("design_chart") == 0
    win.panel.fields["kc"].spin.setValue(60000.0)
    win.panel.chain.fields[("masses", 0)].spin.setValue(0.25)
    qtbot.wait(100)
    assert g.calls("design_chart") == 0 and design.refreshes == 0
    assert not win.runner.is_running()
    win.tabs.setCurrentWidget(design)
    qtbot.waitUntil(lambda: g.is_fresh("design_chart"), timeout=20000)
    assert g.calls("design_chart") == 1
    qtbot.waitUntil(lambda: design.chart.upper.getOriginalDataset()[0] is not None, timeout=5000)
    # the chart equals the core's stiffness chart for the current device
    p = win.model.profile
    bcs = np.geomspace(1.0, 1e4, g.params("design_chart")["points"])
    ref = ImpedanceDisplay(p.device).stiffness_chart(bcs)
    x, y = design.chart.upper.getOriginalDataset()
    ok = np.isfinite(ref.kc)
    np.testing.assert_allclose(x, bcs[ok], rtol=1e-12)
    np.testing.assert_allclose(y, ref.kc[ok], rtol=1e-9)
    # a gain change moves the point only; the chart is not recomputed
    win.panel.fields["kc"].spin.setValue(70000.0)
    qtbot.waitUntil(lambda: list(design.chart.point.getOriginalDataset()[1]) == [70000.0], timeout=5000)
    assert g.calls("design_chart") == 1
    # the stability tab is now hidden: it stays stale until shown again
    stab = win.tab(StabilityTab)
    assert stab.stale
    n = stab.refreshes
    win.tabs.setCurrentWidget(stab)
    qtbot.waitUntil(lambda: not stab.stale, timeout=5000)
    assert stab.refreshes == n + 1


def test_long_chart_runs_off_the_gui_thread_while_edits_are_served(win, qtbot):
    """Structural, not timed (the latency figures are in tests/benchmarks/bench_gui.py): the chart
    runs on a worker thread, the GUI thread's timer keeps firing while it runs, and edits made
    meanwhile reach the verdict before the chart is done.  The chart job is held on its worker
    until the edits were served, so that it surely runs meanwhile on any machine (it used to be
    made long instead: 400 points, seconds of work)."""
    g = win.graph
    win.tabs.setCurrentWidget(win.tab(DesignTab))
    qtbot.waitUntil(lambda: g.is_fresh("design_chart"), timeout=20000)
    inner = g.function("design_chart")
    threads: list[int] = []
    ticks_while_running = [0]
    release = threading.Event()

    def recording(*args):
        threads.append(threading.get_ident())
        release.wait(60)
        return inner(*args)

    g.replace_function("design_chart", recording)

    def tick() -> None:
        if win.runner.is_running("design_chart"):
            ticks_while_running[0] += 1

    timer = QTimer()
    timer.timeout.connect(tick)
    timer.start(5)
    served_while_running = []
    try:
        # a device edit: the verdict and the point update at once, the chart recomputes on the worker
        win.panel.chain.fields[("masses", 0)].spin.setValue(0.25)
        qtbot.waitUntil(lambda: win.progress.active and bool(threads), timeout=5000)
        for kc in (55000.0, 60000.0, 65000.0):
            qtbot.wait(50)
            win.panel.fields["kc"].spin.setValue(kc)
            qtbot.waitUntil(lambda kc=kc: win.model.profile.kc == kc and g.is_fresh(g.stability_name)
                            and not win.verdict_stale, timeout=5000)
            served_while_running.append(win.runner.is_running("design_chart"))
    finally:
        release.set()
    qtbot.waitUntil(lambda: g.is_fresh("design_chart"), timeout=120000)
    timer.stop()
    assert threads and all(t != threading.main_thread().ident for t in threads)
    assert all(served_while_running), served_while_running
    assert ticks_while_running[0] >= 10
    assert not win.progress.active


def test_newer_request_supersedes_and_cancel_keeps_last_result(win, qtbot):
    """The first and third chart jobs are held on the worker until they are stopped (superseded,
    cancelled), so that they surely run meanwhile on any machine, on the default grid (they used to
    be made long instead: 200 points, seconds of work); the second is the real chart."""
    g = win.graph
    inner = g.function("design_chart")
    jobs: list[int] = []

    def held(request, progress, cancelled):
        jobs.append(len(jobs))
        if len(jobs) != 2:
            for _ in range(12000):  # at most a minute: the test stops it long before
                if cancelled():
                    return None
                time.sleep(0.005)
        return inner(request, progress, cancelled)

    g.replace_function("design_chart", held)
    win.tabs.setCurrentWidget(win.tab(DesignTab))
    qtbot.waitUntil(lambda: win.runner.is_running("design_chart") and bool(jobs), timeout=5000)
    # a device change while it runs: the running job is superseded, its result dropped
    win.panel.chain.fields[("masses", 0)].spin.setValue(0.3)
    qtbot.waitUntil(lambda: g.is_fresh("design_chart"), timeout=60000)
    assert g.calls("design_chart") == 2
    qtbot.waitUntil(lambda: win.runner.dropped >= 1 or win.runner.wait(0), timeout=10000)
    value = g.result("design_chart")
    assert g.is_fresh("design_chart")
    # cancel a new computation: the last good chart stays, the progress bar goes away
    win.panel.chain.fields[("masses", 0)].spin.setValue(0.35)
    qtbot.waitUntil(lambda: win.progress.active, timeout=5000)
    win.progress.cancel_button.click()
    assert not win.progress.active
    assert not win.runner.is_running("design_chart")
    assert g.result("design_chart") is value
    win.runner.wait(20000)


def test_clicking_the_design_chart_sets_gains(win, qtbot):
    design = win.tab(DesignTab)
    win.tabs.setCurrentWidget(design)
    qtbot.waitUntil(lambda: win.graph.is_fresh("design_chart"), timeout=20000)
    qtbot.wait(50)
    vb = design.chart.plot.getViewBox()
    from PySide6.QtCore import QPointF

    target = QPointF(np.log10(200.0), np.log10(80000.0))  # log-log axes: view coordinates are log10
    scene_pt = vb.mapViewToScene(target)
    view_pt = design.chart.plot_widget.mapFromScene(scene_pt)
    n = win.undo_stack.count()
    qtbot.mouseClick(design.chart.plot_widget.viewport(), Qt.MouseButton.LeftButton, pos=QPoint(view_pt))
    qtbot.waitUntil(lambda: win.undo_stack.count() == n + 1, timeout=3000)
    p = win.model.profile
    assert p.bc == pytest.approx(200.0, rel=0.03)
    assert p.kc == pytest.approx(80000.0, rel=0.03)
    win.undo_stack.undo()
    assert win.model.profile.kc == 50000.0 and win.model.profile.bc == 100.0
