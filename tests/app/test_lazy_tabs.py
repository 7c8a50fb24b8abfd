"""Tabs are built when first shown (issue 21): a new window builds only its current tab's plots.

Everything that reads a tab's views either builds that tab (File → Export, ``plot_views``,
``refresh``) or skips it while it is not built (the theme, live refresh, drags).
"""

from __future__ import annotations

import numpy as np
from PySide6.QtWidgets import QFileDialog

from app.tabs.design_tab import DesignTab
from app.tabs.observer_tab import ObserverTab
from app.tabs.stability_tab import StabilityTab
from app.tabs.transparency_tab import TransparencyTab
from app.views.base import PALETTE, PlotView
from app.window.menus import plain_title


def _built(win) -> list[bool]:
    return [t.is_built() for t in win.analysis_tabs]


def test_a_new_window_builds_only_its_current_tab(win):
    current = win.tabs.currentWidget()
    assert isinstance(current, StabilityTab)
    assert _built(win) == [True] + [False] * (len(win.analysis_tabs) - 1)
    # the only plot views that exist are the current tab's (two of the window's 22)
    assert len(win.findChildren(PlotView)) == len(current.views()) == 2
    assert all(t.has_plots() for t in win.analysis_tabs)  # known without building a tab


def test_switching_to_a_tab_builds_it_once(win, qtbot):
    tab = next(t for t in win.analysis_tabs if isinstance(t, ObserverTab))
    builds = []
    tab.viewsBuilt.connect(lambda: builds.append(1))
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    assert builds == [1] and tab.is_built()
    views = tab.views()
    assert len(views) == 4 and all(v.isVisible() for v in views)  # built before it was shown
    assert len(win.findChildren(PlotView)) == 2 + 4
    win.tabs.setCurrentIndex(0)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    assert builds == [1] and tab.views() == views  # the same views, not built again
    assert sum(_built(win)) == 2


def test_edits_and_theme_changes_leave_hidden_tabs_unbuilt(win, qtbot):
    win.editor.edit("kc", win.model.profile.kc * 0.9)
    win.set_theme("dark")
    qtbot.waitUntil(lambda: not win.tabs.currentWidget().stale, timeout=10000)
    assert sum(_built(win)) == 1
    tab = next(t for t in win.analysis_tabs if isinstance(t, TransparencyTab))
    assert tab.stale and tab.dark
    # built later, its views take the window's theme
    views = tab.plot_views()
    assert tab.is_built() and len(views) == 5
    assert all(v.palette_colors() is PALETTE["dark"] for v in views)


def test_file_export_of_a_plot_on_a_tab_never_built(win, tmp_path, monkeypatch):
    tab = next(t for t in win.analysis_tabs if isinstance(t, DesignTab))
    win.export_menu.aboutToShow.emit()
    assert not tab.is_built()  # the menu lists the tab without building it
    sub = next(a.menu() for a in win.export_menu.actions() if a.text() == plain_title(tab.title))
    sub.aboutToShow.emit()  # opening its submenu builds the tab and lists its plots
    assert tab.is_built() and tab.stale
    plot = next(a.menu() for a in sub.actions() if a.menu() is not None)
    path = tmp_path / "chart.csv"
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *a, **k: (str(path), ""))
    next(a for a in plot.actions() if a.text().startswith("CSV")).trigger()
    # the export computed the chart first and wrote it
    lines = path.read_text(encoding="utf-8").splitlines()
    header = next(line for line in lines if not line.startswith("#")).split(",")
    assert any(h.startswith("largest k_c") for h in header)
    rows = [line for line in lines if not line.startswith("#")][1:]
    chart = win.graph.result("design_chart").chart
    finite = np.asarray(chart.kc, float)
    assert len(rows) >= np.count_nonzero(np.isfinite(finite) & (finite > 0)) > 10
