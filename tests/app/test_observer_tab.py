"""The observer tab: drive its widgets and compare the plotted data with the observer analysis."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.transparency.observer import DisturbanceObserver, ObserverSettings, TwoAxisObserver
from app.tabs.observer_tab import NODES, OBSERVER_W, ObserverTab


@pytest.fixture
def window(eom_win):
    return eom_win


def show(window, qtbot) -> ObserverTab:
    tab = window.tab(ObserverTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale and tab.refreshes > 0, timeout=10000)
    settle(qtbot, tab)
    return tab


def settle(qtbot, tab) -> None:
    """The tab refreshed and the two-axis nodes (on the worker) are fresh."""
    graph = tab.ctx.graph
    qtbot.waitUntil(lambda: not tab.stale and all(graph.is_fresh(n) for n in NODES), timeout=10000)
    qtbot.wait(20)


def check_plots(tab: ObserverTab, st: ObserverSettings) -> None:
    r = DisturbanceObserver.from_settings(st).response(OBSERVER_W, None, st.alpha, st.beta, st.delta)
    for key, values in (("plant", r.plant), ("nominal", r.nominal), ("effective", r.effective)):
        w, y = tab.plant_plot.data(key)
        np.testing.assert_allclose(w, OBSERVER_W)
        np.testing.assert_allclose(y, np.abs(values), rtol=1e-12)
    np.testing.assert_allclose(tab.disturbance_plot.data("with")[1], np.abs(r.disturbance_with), rtol=1e-12)
    np.testing.assert_allclose(tab.disturbance_plot.data("without")[1], np.abs(r.disturbance_without), rtol=1e-12)
    two = TwoAxisObserver.from_settings(st)
    c = two.coupling(OBSERVER_W)
    np.testing.assert_allclose(tab.coupling_plot.data("with")[1], np.abs(c.coupling_with), rtol=1e-12)
    np.testing.assert_allclose(tab.coupling_plot.data("without")[1], np.abs(c.coupling_without), rtol=1e-12)
    s = two.step_response(st.step_force, st.step_duration)
    t, y = tab.step_plot.data("with")
    np.testing.assert_allclose(t, s.t)
    np.testing.assert_allclose(y, 1e3 * s.y_with, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(tab.step_plot.data("without")[1], 1e3 * s.y_without, rtol=1e-12, atol=1e-15)


def test_hidden_tab_computes_nothing(window, qtbot):
    qtbot.wait(50)
    assert all(window.graph.calls(n) == 0 for n in NODES)
    window.editor.edit("observer", ObserverSettings(order=3))
    qtbot.wait(50)
    assert all(window.graph.calls(n) == 0 for n in NODES)
    show(window, qtbot)
    assert all(window.graph.calls(n) == 1 for n in NODES)


def test_default_plots_equal_analysis_and_screenshot(window, qtbot, screenshot):
    """The default plots equal the analysis, and the screenshot of that state shows data in every plot
    (one window for both: the same state)."""
    tab = show(window, qtbot)
    check_plots(tab, window.model.profile.observer)
    # the observer reduces the coupling below its cutoff
    w, with_ = tab.coupling_plot.data("with")
    without = tab.coupling_plot.data("without")[1]
    assert np.all(with_[w < 20] < 0.2 * without[w < 20])
    qtbot.wait(50)
    screenshot(window, "tab_observer", tab.plot_views())


def test_widgets_drive_the_plots(window, qtbot):
    tab = show(window, qtbot)
    tab.fields["order"].spin.setValue(3)
    settle(qtbot, tab)
    tab.fields["cutoff"].spin.setValue(500.0)
    settle(qtbot, tab)
    tab.fields["preset"].set_value("five_bar_offset")
    settle(qtbot, tab)
    f = tab.fields["delta"]
    drag = window.editor.new_drag()
    assert f.write(-0.5, drag) is None and f.write(-0.8, drag) is None
    settle(qtbot, tab)
    st = window.model.profile.observer
    assert (st.order, st.cutoff, st.preset, st.delta) == (3, 500.0, "five_bar_offset", -0.8)
    assert window.undo_stack.count() == 4  # one drag is one undo step
    tab.refresh()
    check_plots(tab, st)
    assert tab.coupling_plot.lines["cutoff"].value() == pytest.approx(np.log10(500.0))
    # only the single-axis node depends on delta
    calls = {n: window.graph.calls(n) for n in NODES}
    tab.fields["alpha"].spin.setValue(0.2)
    settle(qtbot, tab)
    assert window.graph.calls("observer_response") == calls["observer_response"] + 1
    assert window.graph.calls("observer_coupling") == calls["observer_coupling"]
    assert window.graph.calls("observer_step") == calls["observer_step"]


def test_none_section_shows_defaults(window, qtbot):
    window.model.set("observer", None)
    tab = show(window, qtbot)
    check_plots(tab, ObserverSettings())
    tab.fields["order"].spin.setValue(4)
    assert window.model.profile.observer == ObserverSettings(order=4)
    window.undo_stack.undo()
    assert window.model.profile.observer is None
