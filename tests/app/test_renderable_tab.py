"""The Renderable space tab (issue 24): built lazily, computed on show, the M-width's numbers are
m_width's, a click sets (M, B) in one undo step, progress and cancel on the worker."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt

from analysis.identify import parameter_box
from analysis.profiles import RenderableSection
from analysis.profiles.identification import IdentificationSection
from analysis.sampled import box_corners, box_samples, m_width, robust_renderable_space
from analysis.study import RenderableRequest, damping_axis, format_number, renderable_study
from app.core.nodes_renderable import RENDERABLE_NODE, ROBUST_NODE
from app.tabs.renderable_tab import RenderableTab

#: a coarse grid: these tests check the tab, not the resolution
COARSE = RenderableSection(mass_points=9, damping_points=11, qualities=("stable", "passive"))
#: an identified box of the HBFD: the handle's mass and the motor's damping to ground (4 corners)
INTERVALS = {"masses[0]": (0.1, 0.4), "ground_dampings[3]": (1.0, 10.0)}


@pytest.fixture
def rwin(qtbot, settings, hbfd_profile):
    from conftest import _main_window

    yield from _main_window(qtbot, settings, hbfd_profile.replace(renderable=COARSE))


def _tab(win) -> RenderableTab:
    return next(t for t in win.analysis_tabs if isinstance(t, RenderableTab))


def show(win, qtbot) -> RenderableTab:
    tab = _tab(win)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh(RENDERABLE_NODE) and tab.space_view.study is not None, timeout=60000)
    return tab


def test_the_tab_is_built_and_computed_only_when_shown(rwin, qtbot):
    tab = _tab(rwin)
    assert not tab.is_built()
    assert rwin.graph.calls(RENDERABLE_NODE) == 0  # hidden: nothing computed
    show(rwin, qtbot)
    assert tab.is_built() and rwin.graph.calls(RENDERABLE_NODE) == 1


def test_the_m_width_shown_is_m_widths(rwin, qtbot):
    tab = show(rwin, qtbot)
    p = rwin.model.profile
    req = RenderableRequest.of(p)
    w = m_width(p.device, req.delay_samples, req.velocity_filter, req.acceleration, req.qualities,
                settings=req.settings)
    study = tab.space_view.study
    assert (study.width.m_min, study.width.m_max) == (w.m_min, w.m_max)
    assert w.m_min < 0 < w.m_max
    text = tab.summary.text()
    assert f"{format_number(w.m_min, style='text')} to {format_number(w.m_max, style='text')} kg" in text
    rows = dict((q, (a, b)) for q, a, b in tab.width_view.rows)
    assert rows["all"] == (w.m_min, w.m_max) and rows["stable"] == w.by_quality["stable"]
    np.testing.assert_array_equal(study.space.k_max, renderable_study(req).space.k_max)
    # the quality selector colours the map by one quality's K_max
    tab.select_quality("passive")
    np.testing.assert_array_equal(tab.space_view.shown(), study.space.by_quality["passive"])
    assert "M-width (passive)" in tab.summary.text()


def test_a_click_sets_m_and_b_in_one_undo_step_without_recomputing(rwin, qtbot):
    tab = show(rwin, qtbot)
    qtbot.wait(50)
    view = tab.space_view
    vb = view.plot.getViewBox()
    calls = rwin.graph.calls(RENDERABLE_NODE)
    target = QPointF(0.3, float(damping_axis(20.0)))  # x: M (linear), y: the signed-log damping axis
    pos = view.plot_widget.mapFromScene(vb.mapViewToScene(target))
    n = rwin.undo_stack.count()
    qtbot.mouseClick(view.plot_widget.viewport(), Qt.MouseButton.LeftButton, pos=QPoint(pos))
    qtbot.waitUntil(lambda: rwin.undo_stack.count() == n + 1, timeout=3000)
    sec = rwin.model.profile.renderable
    assert sec.virtual_mass == pytest.approx(0.3, abs=0.02) and sec.virtual_damping == pytest.approx(20.0, rel=0.1)
    where = (sec.virtual_mass, float(damping_axis(sec.virtual_damping)))
    qtbot.waitUntil(lambda: view.point.design_xy == pytest.approx(where), timeout=3000)  # the tab follows
    assert rwin.graph.calls(RENDERABLE_NODE) == calls  # the environment is not in the request
    rwin.undo_stack.undo()
    assert rwin.model.profile.renderable == COARSE


def test_first_edit_creates_the_section_and_undo_removes_it(win, qtbot):
    tab = _tab(win)
    win.tabs.setCurrentWidget(tab)  # built; the default grid's space is not waited for (cancelled at teardown)
    qtbot.waitUntil(tab.is_built, timeout=5000)
    assert win.model.profile.renderable is None
    assert tab.set_environment(-0.1, 5.0) is None
    assert win.model.profile.renderable.virtual_mass == -0.1
    win.undo_stack.undo()
    assert win.model.profile.renderable is None


def test_progress_and_cancel_keep_the_last_result(rwin, qtbot):
    tab = show(rwin, qtbot)
    before = tab.space_view.study
    seen: list[tuple[int, int]] = []
    rwin.graph.progress.connect(lambda name, d, t: seen.append((d, t)) if name == RENDERABLE_NODE else None)
    tab.panel.write("mass_points", 15)  # a new grid: the node runs again on the worker
    widget = tab.progress[RENDERABLE_NODE]
    qtbot.waitUntil(lambda: widget.running or rwin.graph.is_fresh(RENDERABLE_NODE), timeout=10000)
    if widget.running:
        widget.cancel()
        qtbot.waitUntil(lambda: not widget.running, timeout=60000)
        assert tab.space_view.study is before  # the last good result stays
        assert "cancelled" in widget.label.text()
        widget.rerun.emit(RENDERABLE_NODE)
    qtbot.waitUntil(lambda: rwin.graph.is_fresh(RENDERABLE_NODE) and tab.space_view.study is not before, timeout=60000)
    assert tab.space_view.study.space.mass.size == 15
    assert seen and all(0 <= d <= t for d, t in seen)


def test_screenshots_light_and_dark(rwin, qtbot, screenshot):
    """The tab in both themes: the space and the M-width plot show data, the rendered (M, B) marker is
    drawn where it was set, and the window's background follows the theme (saved under tmp_path, checked by
    conftest.screenshot)."""
    from conftest import marker_drawn, background_lightness

    rwin.resize(1280, 800)
    tab = show(rwin, qtbot)
    assert tab.set_environment(0.2, 10.0) is None
    view = tab.space_view
    qtbot.waitUntil(lambda: view.point.design_xy == pytest.approx((0.2, float(damping_axis(10.0)))), timeout=3000)
    lightness = {}
    for theme in ("light", "dark"):
        rwin.theme.set_theme(theme)
        # the application's palette reaches the widgets by events: wait for them, not a fixed time
        qtbot.waitUntil(lambda: (rwin.palette().window().color().lightness() < 100) == (theme == "dark"), timeout=5000)
        image = screenshot(rwin, f"renderable_{theme}", [view, tab.width_view])
        assert (image.width(), image.height()) == (1280, 800)
        assert marker_drawn(view, view.point), theme
        lightness[theme] = background_lightness(image)
    assert lightness["dark"] < 100 < lightness["light"], lightness
    rwin.theme.set_theme("light")


@pytest.fixture
def boxwin(qtbot, settings, hbfd_profile):
    from conftest import _main_window

    profile = hbfd_profile.replace(renderable=COARSE, identification=IdentificationSection(INTERVALS))
    yield from _main_window(qtbot, settings, profile)


def _robust_drawn(win, tab) -> bool:
    return win.graph.is_fresh(ROBUST_NODE) and tab.space_view.robust_drawn


def test_without_a_box_the_robust_overlay_is_not_offered(rwin, qtbot):
    tab = show(rwin, qtbot)
    assert not tab.robust.isEnabled() and "no identified intervals" in tab.robust.toolTip()
    tab.set_robust("corners")
    assert rwin.graph.calls(ROBUST_NODE) == 0 and tab.space_view.robust is None
    assert tab.space_view.legend.getLabel(tab.space_view.robust_legend) is None


def test_the_robust_overlay_over_the_identified_box(boxwin, qtbot, screenshot):
    tab = show(boxwin, qtbot)
    view = tab.space_view
    assert tab.robust.isEnabled() and boxwin.graph.calls(ROBUST_NODE) == 0  # off: nothing computed
    own = view.shown()
    k = float(np.median(own[own > 0]))  # a rendered K inside the space: the box loses some (M, B)
    assert tab.panel.write("virtual_stiffness", k) is None
    calls = boxwin.graph.calls(RENDERABLE_NODE)
    tab.set_robust("corners")
    qtbot.waitUntil(lambda: _robust_drawn(boxwin, tab), timeout=120000)
    req = RenderableRequest.of(boxwin.model.profile)
    corners = box_corners(parameter_box(boxwin.model.profile.device, INTERVALS))
    ref = robust_renderable_space(corners, req.mass, req.damping, req.delay_samples, req.velocity_filter,
                                  req.acceleration, req.qualities, settings=req.settings, workers=1)
    robust = view.robust
    assert robust.devices == 4
    np.testing.assert_array_equal(robust.k_max, ref.k_max)
    assert boxwin.graph.calls(RENDERABLE_NODE) == calls  # the device's own space is not recomputed
    # hatched: this device renders K there, some device of the box does not
    hatched = view.hatched()
    assert np.array_equal(hatched, (own >= k) & (ref.k_max < k))
    assert hatched.any() and not hatched.all()
    assert "4 corners of the identified box" in view.legend.getLabel(view.robust_legend).text
    assert f"volume {format_number(ref.volume)} kg·decades²" in tab.summary.text()
    assert ref.volume < view.study.space.volume
    screenshot(boxwin, "renderable_robust", [view])  # the hatched overlay drawn over the map
    # one quality: the overlay follows the map's quality
    tab.select_quality("passive")
    np.testing.assert_array_equal(view.robust_shown(), ref.by_quality["passive"])
    # samples of the box, then off
    tab.set_robust("samples", 3)
    qtbot.waitUntil(lambda: _robust_drawn(boxwin, tab) and view.robust.devices == 3, timeout=120000)
    drawn = box_samples(parameter_box(boxwin.model.profile.device, INTERVALS), 3, seed=0)
    np.testing.assert_array_equal(view.robust.k_max, robust_renderable_space(
        drawn, req.mass, req.damping, req.delay_samples, req.velocity_filter, req.acceleration, req.qualities,
        settings=req.settings, workers=1).k_max)
    tab.set_robust("off")
    assert not view.robust_drawn and view.hatched() is None
    assert view.legend.getLabel(view.robust_legend) is None
    assert "Robust over" not in tab.summary.text()
