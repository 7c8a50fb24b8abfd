"""The Workspace tab (issue 25): built lazily, the map computed on show, the worst point is
workspace_map's minimum, a click moves the handle in one undo step without recomputing the map."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt

from analysis.multidof import workspace_map
from analysis.profiles import MultiDofSection
from analysis.study import WorkspaceRequest, format_number
from analysis.study.workspace import K_RANGE
from app.core.nodes_workspace import WORKSPACE_MAP_NODE, WORKSPACE_POINT_NODE
from app.tabs.workspace_tab import WorkspaceTab

#: a coarse grid: these tests check the tab, not the resolution
COARSE = MultiDofSection(x_points=6, y_points=5, handle_x=0.03, handle_y=0.22)


@pytest.fixture
def wwin(qtbot, settings, hbfd_profile):
    from conftest import _main_window

    yield from _main_window(qtbot, settings, hbfd_profile.replace(multidof=COARSE))


def _tab(win) -> WorkspaceTab:
    return next(t for t in win.analysis_tabs if isinstance(t, WorkspaceTab))


def show(win, qtbot) -> WorkspaceTab:
    tab = _tab(win)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh(WORKSPACE_MAP_NODE) and tab.map_view.map is not None, timeout=60000)
    return tab


def test_the_tab_is_built_and_computed_only_when_shown(wwin, qtbot):
    tab = _tab(wwin)
    assert not tab.is_built()
    assert wwin.graph.calls(WORKSPACE_MAP_NODE) == 0 and wwin.graph.calls(WORKSPACE_POINT_NODE) == 0
    show(wwin, qtbot)
    assert tab.is_built() and wwin.graph.calls(WORKSPACE_MAP_NODE) == 1


def test_the_worst_point_is_workspace_maps_minimum(wwin, qtbot):
    tab = show(wwin, qtbot)
    req = WorkspaceRequest.of(wwin.model.profile)
    m = workspace_map(req.linkage, req.x, req.y, req.damping, req.delay_samples, sample_time=req.sample_time, k_range=K_RANGE)
    shown = tab.map_view.map
    np.testing.assert_array_equal(shown.minimum.position, m.minimum.position)
    assert shown.minimum.stiffness == m.minimum.stiffness
    np.testing.assert_array_equal(shown.worst_stiffness, m.worst_stiffness)
    assert tab.map_view.worst.design_xy == pytest.approx(tuple(m.minimum.position))
    assert f"Design bound: {format_number(m.minimum.stiffness)} N/m" in tab.summary.text()


def test_a_click_moves_the_handle_in_one_undo_step_without_recomputing_the_map(wwin, qtbot):
    tab = show(wwin, qtbot)
    qtbot.wait(50)
    view = tab.map_view
    vb = view.plot.getViewBox()
    calls = wwin.graph.calls(WORKSPACE_MAP_NODE)
    before = tab.polar_view.point
    pos = view.plot_widget.mapFromScene(vb.mapViewToScene(QPointF(-0.05, 0.27)))
    n = wwin.undo_stack.count()
    qtbot.mouseClick(view.plot_widget.viewport(), Qt.MouseButton.LeftButton, pos=QPoint(pos))
    qtbot.waitUntil(lambda: wwin.undo_stack.count() == n + 1, timeout=3000)
    sec = wwin.model.profile.multidof
    assert sec.handle_x == pytest.approx(-0.05, abs=0.005) and sec.handle_y == pytest.approx(0.27, abs=0.005)
    qtbot.waitUntil(lambda: view.handle.design_xy == pytest.approx((sec.handle_x, sec.handle_y)), timeout=3000)
    assert tab.polar_view.point is not before  # the limits follow the handle
    np.testing.assert_allclose(tab.polar_view.point.position, [sec.handle_x, sec.handle_y])
    assert wwin.graph.calls(WORKSPACE_MAP_NODE) == calls  # the handle is not in the map's request
    wwin.undo_stack.undo()
    assert wwin.model.profile.multidof == COARSE


def test_first_edit_creates_the_section_and_undo_removes_it(win, qtbot):
    tab = _tab(win)
    win.tabs.setCurrentWidget(tab)
    assert win.model.profile.multidof is None
    assert tab.move_handle(0.01, 0.21) is None
    assert win.model.profile.multidof == MultiDofSection(handle_x=0.01, handle_y=0.21)
    win.undo_stack.undo()
    assert win.model.profile.multidof is None
    assert tab.move_handle(0.0, 0.9) is not None and win.model.profile.multidof is None  # out of reach: refused


def test_screenshots_light_and_dark(wwin, qtbot, screenshot):
    """The tab in both themes: the map and the polar plot show data, the handle's marker is drawn
    at the handle, and the window's background follows the theme (saved under tmp_path, checked by conftest.screenshot)."""
    from conftest import marker_drawn, background_lightness

    wwin.resize(1280, 800)
    tab = show(wwin, qtbot)
    qtbot.waitUntil(lambda: tab.polar_view.point is not None and tab.map_view.handle.design_xy is not None,
                    timeout=10000)
    lightness = {}
    for theme in ("light", "dark"):
        wwin.theme.set_theme(theme)
        # the application's palette reaches the widgets by events: wait for them, not a fixed time
        qtbot.waitUntil(lambda: (wwin.palette().window().color().lightness() < 100) == (theme == "dark"), timeout=5000)
        image = screenshot(wwin, f"workspace_{theme}", [tab.map_view, tab.polar_view])
        assert (image.width(), image.height()) == (1280, 800)
        assert marker_drawn(tab.map_view, tab.map_view.handle), theme
        lightness[theme] = background_lightness(image)
    assert lightness["dark"] < 100 < lightness["light"], lightness
    wwin.theme.set_theme("light")
