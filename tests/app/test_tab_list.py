"""Every tab is one click away at laptop sizes (issue 22): at 1280 px the tab bar scrolls and the
last tabs sit behind its arrows; the "All tabs" button in its corner lists them all."""

from __future__ import annotations

from PySide6.QtCore import Qt


def test_the_tab_list_names_every_tab_and_shows_the_one_chosen(win, qtbot):
    win.resize(1280, 720)
    qtbot.waitUntil(lambda: (win.width(), win.height()) == (1280, 720), timeout=5000)
    bar = win.tabs.tabBar()
    titles = [win.tabs.tabText(i) for i in range(win.tabs.count())]
    # the case it is for: at 1280 px the bar cannot show every tab whole
    assert sum(bar.tabSizeHint(i).width() for i in range(bar.count())) > bar.width()
    button = win.tabs.cornerWidget(Qt.Corner.TopRightCorner)
    assert button is win.tab_list and button.isVisible() and button.text() == "All tabs ▾"
    button.menu().aboutToShow.emit()
    actions = button.menu().actions()
    assert [a.text() for a in actions] == titles
    assert [a.isChecked() for a in actions] == [i == win.tabs.currentIndex() for i in range(len(titles))]
    actions[-1].trigger()
    assert win.tabs.currentIndex() == len(titles) - 1
    qtbot.waitUntil(lambda: not win.tabs.currentWidget().stale, timeout=60000)
    button.menu().aboutToShow.emit()
    assert [a.isChecked() for a in button.menu().actions()] == [False] * (len(titles) - 1) + [True]
