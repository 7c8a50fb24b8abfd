"""The window at laptop sizes (issue 22): it can be made 1024×700, and at 1280×720 no plot of any tab
is squeezed below a readable height (a tab scrolls instead)."""

from __future__ import annotations

from PySide6.QtWidgets import QScrollArea

from app.tabs.base import PLOT_MIN_HEIGHT


def test_the_window_fits_1024_by_700(win, qtbot):
    for tab in win.analysis_tabs:
        tab.ensure_built()  # every tab's contents count towards the minimum size
    hint = win.minimumSizeHint()
    assert hint.width() <= 1024 and hint.height() <= 700, hint
    win.resize(1024, 700)
    qtbot.waitUntil(lambda: (win.width(), win.height()) == (1024, 700), timeout=5000)
    for i in range(win.tabs.count()):
        win.tabs.setCurrentIndex(i)
        qtbot.wait(20)
        assert (win.width(), win.height()) == (1024, 700), win.tabs.tabText(i)  # no tab widens it again


def test_every_plot_is_readable_at_1280_by_720(coarse_win, qtbot):
    """On coarse grids (conftest.coarse_win): the layout does not depend on the results' resolution."""
    win = coarse_win
    win.resize(1280, 720)
    qtbot.waitUntil(lambda: (win.width(), win.height()) == (1280, 720), timeout=5000)
    seen = 0
    for i in range(win.tabs.count()):
        win.tabs.setCurrentIndex(i)
        tab = win.tabs.currentWidget()
        qtbot.waitUntil(lambda: tab.is_built(), timeout=5000)
        qtbot.wait(50)
        for view in tab.views():
            widget = view.plot_widget
            if widget.isVisible():
                seen += 1
                assert widget.height() >= PLOT_MIN_HEIGHT, (win.tabs.tabText(i), view.title, widget.height())
        # the contents keep their minimum size: a tab scrolls rather than squeeze them (once laid out: a
        # plot's floor and the labels' heights follow its results over a few turns of the event loop)
        for area in tab.findChildren(QScrollArea, "tabScroll"):
            body = area.widget()
            qtbot.waitUntil(lambda: body.width() >= body.minimumSizeHint().width() - 1
                            and body.height() >= body.minimumSizeHint().height() - 1, timeout=3000)
    assert seen >= 20
