"""During a slider drag the axes stand still (only the data and markers move); after it each axis
auto-ranges again if it did before, and a range the user zoomed to stays."""

from __future__ import annotations

from PySide6.QtWidgets import QApplication

from app.tabs.sampled_tab import ASYNC_NODES, SampledTab
from app.tabs.stability_tab import StabilityTab
from app.views.marker import marker_xy


def _drag(win, qtbot, tab, field, steps: int = 6) -> list:
    """Drag ``field``; the view ranges of the tab's plots after each step."""
    slider = field.slider
    ranges = []
    slider.setSliderDown(True)
    try:
        for _ in range(steps):
            slider.setValue(slider.value() + 4)
            qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
            QApplication.processEvents()
            ranges.append([(v.plot.getViewBox().viewRange(), tuple(v.plot.getViewBox().autoRangeEnabled()))
                           for v in tab.plot_views()])
    finally:
        slider.setSliderDown(False)
    return ranges


def _settled_ranges(tab, views, qtbot) -> list:
    """The views' ranges once painting changes them no more (pyqtgraph applies a pending
    auto-range when it paints; under load the last one can come late)."""
    last = None
    for _ in range(100):
        tab.grab()  # a paint
        QApplication.processEvents()
        ranges = [v.plot.getViewBox().viewRange() for v in views]
        if ranges == last:
            return ranges
        last = ranges
        qtbot.wait(50)
    raise AssertionError(f"the ranges never settled: {last}")


def test_the_sampled_tab_holds_its_map_and_chart_axes_during_a_drag(win, qtbot):
    g = win.graph
    tab = win.tab(SampledTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale and all(g.is_fresh(n) for n in ASYNC_NODES), timeout=120000)
    g.drag.settle_ms = 600_000
    views = (tab.map_view, tab.exact_view)  # the map is framed on its grid; the chart auto-ranges
    auto = [tuple(v.plot.getViewBox().autoRangeEnabled()) for v in views]
    assert not any(auto[0]) and all(auto[1])
    before = _settled_ranges(tab, views, qtbot)
    marker = marker_xy(tab.exact_view.point)
    ranges = _drag(win, qtbot, tab, win.panel.fields["kc"])
    for step in ranges:  # the markers moved, the axes did not: no auto-range while the drag moves
        assert [r for r, _auto in step[:2]] == before and [auto for _r, auto in step[:2]] == [(False, False)] * 2
    assert marker_xy(tab.exact_view.point)[1] > marker[1]  # the current-gains dot moved up with k_c
    assert [tuple(v.plot.getViewBox().autoRangeEnabled()) for v in views] == auto  # as before the drag


def test_a_zoomed_range_survives_a_drag(win, qtbot):
    tab = win.tab(StabilityTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    win.graph.drag.settle_ms = 600_000
    vb = tab.plot_views()[0].plot.getViewBox()
    vb.setRange(xRange=(1.0, 2.0), yRange=(-0.001, 0.002), padding=0)  # the user's zoom: auto-range off
    zoomed = vb.viewRange()
    assert not any(vb.autoRangeEnabled())
    _drag(win, qtbot, tab, win.panel.fields["kc"])
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    assert not any(vb.autoRangeEnabled()) and vb.viewRange() == zoomed
    other = tab.plot_views()[1].plot.getViewBox()  # the plot the user did not zoom follows its data again
    assert all(other.autoRangeEnabled())
