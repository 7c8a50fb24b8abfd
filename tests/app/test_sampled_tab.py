"""The sampled-data tab: map, exact limit and simulation equal the analysis; lazy; cancellable."""

from __future__ import annotations

import time

import numpy as np
import pytest

from analysis.profiles.sections import SimulationSection
from analysis.sampled import (
    SimulationOptions,
    critical_stiffness,
    critical_stiffness_chart,
    scenario,
    simulate,
    stability_map,
)
from app.tabs.sampled_tab import (
    ASYNC_NODES,
    EXACT_NODE,
    LIMIT_NODE,
    MAP_NODE,
    SIM_NODE,
    SampledTab,
    exact_grid,
)

ALL = (*ASYNC_NODES, "design_chart")


@pytest.fixture
def full_window(win):
    """The shared main window (tests/app/conftest.py) on the HBFD profile, with the tab's default
    grids (the map's 48 points per axis, the exact chart's 24 b_c points).

    These tests leave edits on the undo stack; pytest-qt closes the window before the shared
    fixture marks the stack clean, so the "unsaved changes" question is answered here.
    """
    win.maybe_save = lambda: True
    return win


@pytest.fixture
def window(coarse_grids, full_window):
    """:func:`full_window` with the map and the exact chart on the coarse grids
    (tests/app/conftest.py ``coarse_grids``, set before the window registers its nodes): for the
    tests that are not about the grids' resolution (they compare with the analysis on the grid the
    node holds, count calls, edit, cancel or take a screenshot); the default grids are checked by
    :func:`test_map_equals_stability_map`."""
    return full_window


def show_tab(window, qtbot, names=ALL, timeout=60000) -> SampledTab:
    tab = window.tab(SampledTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: all(window.graph.is_fresh(n) for n in names), timeout=timeout)
    qtbot.wait(20)
    return tab


def set_section(window, **options) -> None:
    p = window.model.profile
    sec = p.simulation
    new = SimulationSection(options=SimulationOptions(**{**sec.options.__dict__, **options}), scenario=sec.scenario)
    assert window.editor.edit_many({"simulation": new}, "test") is None


def test_hidden_tab_computes_nothing_until_shown(window, qtbot):
    """Counts the node calls (coarse grids: not about their resolution)."""
    g = window.graph
    assert window.tabs.currentWidget() is not window.tab(SampledTab)
    window.editor.edit("kc", 60e3)
    set_section(window, delay_samples=1)
    qtbot.wait(100)
    assert all(g.calls(n) == 0 for n in ASYNC_NODES)
    show_tab(window, qtbot)
    assert all(g.calls(n) == 1 for n in ASYNC_NODES)
    # back to another tab: edits mark it stale and compute nothing
    window.tabs.setCurrentIndex(0)
    window.editor.edit("kc", 70e3)
    qtbot.wait(100)
    assert all(g.calls(n) == 1 for n in ASYNC_NODES)
    tab = show_tab(window, qtbot)
    # the exact chart does not depend on k_c: reused; the others recompute once
    assert g.calls(EXACT_NODE) == 1 and g.calls(LIMIT_NODE) == 1
    assert g.calls(MAP_NODE) == 2 and g.calls(SIM_NODE) == 2
    assert tab.refreshes >= 2


def test_map_equals_stability_map(full_window, qtbot):
    """The default map (48 x 48, on the default window's grid), then a re-ranged one, equal the analysis."""
    window = full_window
    tab = show_tab(window, qtbot)
    p = window.model.profile
    n = 48
    ref = stability_map(p.device, ("kc", np.geomspace(1e3, 1e6, n)), ("kobj", np.geomspace(1e3, 1e7, n)),
                        display="impedance", coupling=(p.kc, p.bc), pd=(p.kp, p.kd), delay_samples=0)
    img = tab.map_view.image.image
    assert img.shape == (n, n)
    np.testing.assert_allclose(img, ref.spectral_radius, rtol=1e-12, atol=0)
    assert tab.map_view.map.x_name == "kc" and tab.map_view.map.y_name == "kobj"
    # the current design is marked at (k_c, paper wall 500 kN/m)
    assert tab.map_view.point_xy == (p.kc, 500e3)
    x, y = tab.map_view.point.getData()  # drawn there (view coordinates: log10 on the log axes)
    np.testing.assert_allclose((10 ** x[0], 10 ** y[0]), (p.kc, 500e3), rtol=1e-12)
    # change axes and range, with one sample of delay: still the analysis values
    set_section(window, delay_samples=1)
    assert tab.set_map(x="kc", y="grasp_mass") is None
    assert tab.set_map(x_range=(2e4, 2e5), points=12) is None
    show_tab(window, qtbot)
    ref = stability_map(p.device, ("kc", np.geomspace(2e4, 2e5, 12)), ("grasp_mass", np.geomspace(1e-2, 10, 12)),
                        display="impedance", coupling=(p.kc, p.bc), pd=(p.kp, p.kd), delay_samples=1)
    np.testing.assert_allclose(tab.map_view.image.image, ref.spectral_radius, rtol=1e-12, atol=0)
    assert tab.map_view.xline.isVisible()  # hands-off: grasp mass 0 is off the log axis
    assert tab.set_map(x_range=(5.0, 1.0)) is not None  # refused, nothing changes
    assert window.graph.params(MAP_NODE)["x_range"] == (2e4, 2e5)


def test_exact_limit_equals_critical_stiffness_chart_and_screenshot(window, qtbot, screenshot):
    """The chart equals the analysis on the b_c grid the node holds (coarse: not about its resolution);
    then the screenshot of that state: every plot shows data (one window for both: the same edit and
    the same computations)."""
    set_section(window, delay_samples=1)
    tab = show_tab(window, qtbot)
    p = window.model.profile
    bcs = exact_grid(window.graph.params(EXACT_NODE))
    ref = critical_stiffness_chart(p.device, bcs, delay_samples=1)
    np.testing.assert_array_equal(tab.exact_view.chart.kc, ref.kc)
    ok = np.isfinite(ref.kc) & (ref.kc > 0)
    x, y = tab.exact_view.exact.xData, tab.exact_view.exact.yData
    np.testing.assert_array_equal(x, bcs[ok])
    np.testing.assert_array_equal(y, ref.kc[ok])
    # the headline numbers: ~85.6 kN/m exact with one sample of delay against the 117 kN/m bound
    limit = window.graph.result(LIMIT_NODE)
    assert limit == critical_stiffness(p.device, 100.0, 1)
    assert limit == pytest.approx(85.6e3, rel=1e-2)
    text = tab.summary.text()
    assert "85.58 kN/m" in text and "117.1 kN/m" in text and "not safe" in text
    # the two-port bound drawn is the design chart node's
    chart = window.graph.result("design_chart").chart
    okb = np.isfinite(chart.kc) & (chart.kc > 0)
    np.testing.assert_array_equal(tab.exact_view.bound.xData, chart.bc[okb])
    # the screenshot (coarse grids: the default grids are drawn by the map test)
    qtbot.wait(50)
    screenshot(window, "tab_sampled", [tab.map_view, tab.exact_view, *tab.time_view.plot_views()])
    assert tab.map_view.export_series() and tab.exact_view.export_series() and tab.time_view.energy.export_series()


def test_simulation_plots_and_verdict(window, qtbot):
    """The simulation traces and verdict (the map and chart on coarse grids: not checked here)."""
    tab = show_tab(window, qtbot)
    p = window.model.profile
    sec = p.simulation
    ref = simulate(p, sec.scenario, options=sec.options)
    tv = tab.time_view
    t, x = tv.positions.data("handle x₁")
    np.testing.assert_array_equal(t, ref.t)
    np.testing.assert_array_equal(x, ref.positions[:, 0] * 1e3)
    np.testing.assert_array_equal(tv.positions.data("actuator xₙ")[1], ref.positions[:, -1] * 1e3)
    np.testing.assert_array_equal(tv.forces.data("F_d actuator")[1], ref.f_d)
    np.testing.assert_array_equal(tv.forces.data("F_h human")[1], ref.f_h)
    np.testing.assert_array_equal(tv.energy.data("absorbed by controller")[1], ref.energy * 1e3)
    assert tv.kind == ref.verdict.kind == "stable"
    assert "Stable" in tv.verdict.text()
    # an unstable design: k_c = 200 kN/m held against the wall with one sample of delay, ideal
    # sensors (the firm grasp damps the 110 kN/m of the paper's experiment in this scenario)
    window.editor.edit("kc", 200e3)
    new = SimulationSection(options=SimulationOptions(delay_samples=1), scenario=scenario("wall_push"))
    assert window.editor.edit_many({"simulation": new}, "test") is None
    show_tab(window, qtbot)
    p = window.model.profile
    ref = simulate(p, p.simulation.scenario, options=p.simulation.options)
    assert ref.verdict.kind == "sustained oscillation"
    assert tv.kind == ref.verdict.kind
    assert ref.verdict.kind.capitalize() in tv.verdict.text()
    np.testing.assert_array_equal(tv.forces.data("F_d actuator")[1], ref.f_d)


def test_edits_go_through_undo(window, qtbot):
    """The panel's edits and undo (coarse grids: not about their resolution)."""
    tab = show_tab(window, qtbot)
    panel = tab.panel
    before = window.model.profile.simulation
    panel.delay.setValue(2)
    assert window.model.profile.simulation.options.delay_samples == 2
    panel.preset.setCurrentIndex(panel.preset.findData("wall_push"))
    panel.preset.activated.emit(panel.preset.currentIndex())
    assert window.model.profile.simulation.scenario == scenario("wall_push")
    f = panel.fields["push_force"]
    f.setText("-3")
    f.setModified(True)
    f.editingFinished.emit()
    assert window.model.profile.simulation.scenario.push_force == -3.0
    f.setText("abc")
    f.setModified(True)
    f.editingFinished.emit()
    assert panel.error.isVisibleTo(panel) and window.model.profile.simulation.scenario.push_force == -3.0
    for _ in range(3):
        window.undo_stack.undo()
    assert window.model.profile.simulation == before
    assert panel.delay.value() == before.options.delay_samples
    # no section yet: created from the defaults
    window.editor.edit_many({"simulation": None}, "clear")
    panel.delay.setValue(1)
    sec = window.model.profile.simulation
    assert sec.options == SimulationOptions(delay_samples=1)
    assert sec.scenario == scenario("impedance_worst_case")


def test_cancel_keeps_last_result_and_can_rerun(window, qtbot):
    """Cancel and rerun of the exact chart (coarse grids: not about their resolution)."""
    tab = show_tab(window, qtbot)
    g = window.graph
    old_chart = tab.exact_view.chart
    # the first restart is held on the worker until it is cancelled: the test does not depend on
    # how long the real chart takes
    real = g.function(EXACT_NODE)
    held = []

    def held_once(request, progress, cancelled):
        if not held:
            held.append(True)
            for _ in range(2000):
                if cancelled():
                    return None
                progress(0, 1)
                time.sleep(0.005)
        return real(request, progress, cancelled)

    g.replace_function(EXACT_NODE, held_once)
    set_section(window, delay_samples=2)  # the exact chart restarts
    qtbot.waitUntil(lambda: window.runner.is_running(EXACT_NODE), timeout=5000)
    assert tab.progress[EXACT_NODE].running
    tab.progress[EXACT_NODE].cancel_button.click()
    assert not window.runner.is_running(EXACT_NODE)
    qtbot.wait(300)
    assert not window.runner.is_running(EXACT_NODE)  # not restarted by other nodes finishing
    calls = g.calls(EXACT_NODE)
    assert tab.exact_view.chart is old_chart  # the last good result stays
    assert tab.progress[EXACT_NODE].rerun_button.isVisibleTo(tab.progress[EXACT_NODE])
    tab.progress[EXACT_NODE].rerun_button.click()
    qtbot.waitUntil(lambda: g.is_fresh(EXACT_NODE), timeout=60000)
    assert g.calls(EXACT_NODE) == calls + 1
    qtbot.wait(20)
    assert tab.exact_view.chart.delay_samples == 2
