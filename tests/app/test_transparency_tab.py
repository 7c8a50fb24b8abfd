"""The transparency tab: drive its widgets and compare the plotted data with WallDesign."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analysis.transparency.design import WallDesign
from analysis.transparency.settings import WallSettings
from app.tabs.transparency_tab import NODES, TransparencyTab, admittance_grid


@pytest.fixture
def window(eom_win):
    return eom_win


def show(window, qtbot) -> TransparencyTab:
    tab = window.tab(TransparencyTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: window.graph.is_fresh("wall_tradeoff") and not tab.stale
                    and tab.tradeoff_drawn is not None and window.graph.is_fresh("wall_point"), timeout=30000)
    qtbot.waitUntil(lambda: tab.refreshes > 0 and tab.optimum_button.isEnabled(), timeout=30000)
    step_fresh(window, qtbot, tab)
    return tab


def step_fresh(window, qtbot, tab) -> None:
    """The step response (on the worker) is computed for the current B_c and drawn."""
    qtbot.waitUntil(lambda: not tab.stale and window.graph.is_fresh("wall_step")
                    and tab.position_plot.data("position")[0].size > 0, timeout=30000)
    qtbot.wait(20)
    tab.refresh()


def settle(window, qtbot, tab) -> None:
    qtbot.waitUntil(lambda: not tab.stale and window.graph.is_fresh("wall_tradeoff")
                    and tab.tradeoff_drawn is not None
                    and tab.tradeoff_drawn.curves is window.graph.result("wall_tradeoff").curves,
                    timeout=30000)
    step_fresh(window, qtbot, tab)


def check_plots(tab: TransparencyTab, st: WallSettings, bc: float) -> None:
    d = WallDesign(st)
    # markers at the current B_c
    jx, jy = tab.index_plot.data("current")
    px, py = tab.peak_plot.data("current")
    ir, pk = d.index_result(bc), d.robustness_peak(bc)
    assert px[0] == pytest.approx(bc)
    assert py[0] == pytest.approx(20 * math.log10(pk.gain), rel=1e-9, abs=1e-9)
    if ir.finite:
        assert jx[0] == pytest.approx(bc) and jy[0] == pytest.approx(ir.index, rel=1e-9)
    else:
        assert jx.size == 0
    # the step response
    s = d.step_response(bc)
    t, x = tab.position_plot.data("position")
    np.testing.assert_allclose(t, s.t)
    np.testing.assert_allclose(x, 1e3 * s.position, rtol=1e-12, atol=1e-15)
    t, f = tab.force_plot.data("force")
    np.testing.assert_allclose(f, s.force, rtol=1e-12)
    # the admittances
    w = admittance_grid(st)
    yv, yt = d.admittances(w, bc)
    wx, y = tab.admittance_plot.data("yt")
    np.testing.assert_allclose(wx, w)
    np.testing.assert_allclose(y, np.abs(yt), rtol=1e-10)
    np.testing.assert_allclose(tab.admittance_plot.data("yv")[1], np.abs(yv), rtol=1e-12)
    # the curves over B_c and the optimum
    c = d.tradeoff()
    finite = np.isfinite(c.index)
    x, jj = tab.index_plot.data("J")
    np.testing.assert_allclose(x, c.bc[finite])
    np.testing.assert_allclose(jj, c.index[finite], rtol=1e-9)
    x, db = tab.peak_plot.data("peak")
    np.testing.assert_allclose(db, 20 * np.log10(c.peak[finite]), rtol=1e-9, atol=1e-9)
    o = d.optimal_damping()
    ox, oy = tab.peak_plot.data("optimum")
    assert ox[0] == pytest.approx(o.bc, rel=1e-9)
    assert tab.index_plot.data("optimum")[1][0] == pytest.approx(o.index, rel=1e-9)


def test_hidden_tab_computes_nothing(window, qtbot):
    qtbot.wait(50)
    assert all(window.graph.calls(n) == 0 for n in NODES)
    # an edit while hidden still computes nothing
    window.editor.edit("wall", WallSettings(hold="pade"))
    qtbot.wait(50)
    assert all(window.graph.calls(n) == 0 for n in NODES)
    assert window.tab(TransparencyTab).stale
    tab = show(window, qtbot)
    assert all(window.graph.calls(n) == 1 for n in NODES)
    assert tab.refreshes >= 1


def test_default_plots_equal_analysis(window, qtbot):
    tab = show(window, qtbot)
    check_plots(tab, window.model.profile.wall, 15.0)


def test_bc_slider_moves_markers_and_step(window, qtbot):
    tab = show(window, qtbot)
    calls_before = window.graph.calls("wall_tradeoff")
    field = tab.bc_field
    field.slider.setValue(field.value_to_position(6.0))
    bc = field.position_to_value(field.value_to_position(6.0))
    assert tab.bc == pytest.approx(bc)
    step_fresh(window, qtbot, tab)
    check_plots(tab, window.model.profile.wall, bc)
    assert window.graph.calls("wall_tradeoff") == calls_before  # B_c does not redo the curves
    assert window.undo_stack.count() == 0  # B_c is tab state, not a profile edit
    # the spin box too
    field.spin.setValue(22.5)
    step_fresh(window, qtbot, tab)
    check_plots(tab, window.model.profile.wall, 22.5)


@pytest.mark.parametrize("hold", ["discrete", "zoh", "none"])
def test_hold_model_choice(window, qtbot, screenshot, hold):
    """Each hold model recomputes the plots (the analysis' values) and undoes in one step; with the
    discrete one, the finding and the screenshot of that state (every plot shows data: it was a test of
    its own, on the same window and the same edit)."""
    tab = show(window, qtbot)
    tab.fields["hold"].set_value(hold)
    assert window.model.profile.wall.hold == hold
    assert window.undo_stack.count() == 1
    settle(window, qtbot, tab)
    check_plots(tab, window.model.profile.wall, 15.0)
    if hold == "discrete":
        # the finding: B_c = 15 is not robustly stable under the exact sampled loop
        assert tab.peak_plot.data("current")[1][0] == pytest.approx(10.7, abs=0.05)
        assert tab.tradeoff_drawn.optimum.bc == pytest.approx(6.47, abs=0.01)
        assert "NOT robustly stable" in tab.summary.text()
        screenshot(window, "tab_transparency", tab.plot_views())
        tab.optimum_button.click()
        assert tab.bc == pytest.approx(tab.tradeoff_drawn.optimum.bc, rel=1e-5)
    window.undo_stack.undo()
    assert window.model.profile.wall.hold == "lowpass2"


def test_none_section_shows_defaults_and_first_edit_creates_it(window, qtbot):
    window.model.set("wall", None)
    tab = show(window, qtbot)
    assert tab.fields["mass"].spin.value() == WallSettings().mass
    check_plots(tab, WallSettings(), 15.0)
    drag = window.editor.new_drag()
    assert tab.fields["wall_stiffness"].write(2000.0, drag) is None
    assert tab.fields["wall_stiffness"].write(3000.0, drag) is None
    assert window.model.profile.wall == WallSettings(wall_stiffness=3000.0)
    assert window.undo_stack.count() == 1  # one drag, one undo step
    settle(window, qtbot, tab)
    check_plots(tab, window.model.profile.wall, 15.0)
    window.undo_stack.undo()
    assert window.model.profile.wall is None


def test_refused_value_shows_reason(window, qtbot):
    tab = show(window, qtbot)
    tab.fields["alpha"].spin.setValue(1.5)
    assert tab.fields["alpha"].error.isVisibleTo(tab)
    assert window.model.profile.wall.alpha == 0.5
