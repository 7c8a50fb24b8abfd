"""The window's actions and menus: File, Edit, View, Design, Help.

The menus call the window's public methods (``new_profile``, ``open_dialog``, ``save``,
``export_view``, ``load_preset``, ...); they hold no logic of their own.
"""

from __future__ import annotations

import html
import re
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QMainWindow, QMenu, QMenuBar

from analysis.profiles.io import ProfileError, bundled_profiles, load_profile

__all__ = ["make_action", "WindowActions", "build_menus", "EXPORT_FORMATS", "plain_title", "export_entries",
           "tab_export_entries", "fill_export_menu", "fill_tab_export_menu"]

EXPORT_FORMATS = (("png", "PNG image…"), ("svg", "SVG drawing…"), ("csv", "CSV data…"))


def make_action(parent: QMainWindow, text: str, slot: Callable[[], Any],
                shortcut: QKeySequence | QKeySequence.StandardKey | str | None = None, tip: str = "") -> QAction:
    """A QAction calling ``slot()`` (without the ``checked`` argument)."""
    act = QAction(text, parent)
    if shortcut is not None:
        act.setShortcut(QKeySequence(shortcut))
    if tip:
        act.setStatusTip(tip)
        act.setToolTip(tip)
    act.triggered.connect(lambda _=False: slot())
    return act


class WindowActions:
    """The window's standing actions (``new``, ``open``, ``save``, ``undo``, ``maximize``, ...)."""

    def __init__(self, window: Any) -> None:
        K = QKeySequence.StandardKey
        w = window
        self.new = make_action(w, "&New", w.new_profile, K.New, "Start from the default profile")
        self.open = make_action(w, "&Open…", w.open_dialog, K.Open, "Open a profile file")
        self.save = make_action(w, "&Save", w.save, K.Save, "Save the profile")
        self.save_as = make_action(w, "Save &As…", w.save_as, K.SaveAs, "Save the profile to a new file")
        self.quit = make_action(w, "&Quit", w.close, K.Quit)
        self.undo = w.undo_stack.createUndoAction(w, "&Undo")
        self.undo.setShortcut(QKeySequence(K.Undo))
        self.redo = w.undo_stack.createRedoAction(w, "&Redo")
        self.redo.setShortcut(QKeySequence(K.Redo))
        self.maximize = QAction("Maximize k_c", w)
        self.maximize.setShortcut(QKeySequence("Ctrl+M"))
        self.maximize.setStatusTip("Set k_c to the largest value satisfying eq. (9) for the current b_c")
        self.minimize = QAction("Minimize m_c", w)
        self.minimize.setShortcut(QKeySequence("Ctrl+Shift+M"))
        self.minimize.setStatusTip("Set (m_c, b_c) to the smallest m_c satisfying eq. (21)")
        for act in (self.maximize, self.minimize):
            act.setToolTip(act.statusTip())
        self.about = make_action(w, "&About zwidth", w.show_about)


def _presets_menu(window: Any, menu: QMenu) -> None:
    for name, path in bundled_profiles().items():
        try:
            title = load_profile(path).name
        except ProfileError:
            title = name
        act = menu.addAction(title.replace("&", "&&"))  # "&" is a mnemonic marker
        act.triggered.connect(lambda _=False, n=name: window.load_preset(n))


def plain_title(text: str) -> str:
    """A plot title as plain text for a menu: ``J(B<sub>c</sub>)`` -> ``J(B_c)``, entities decoded."""
    text = re.sub(r"<sub>(.*?)</sub>", r"_\1", text)
    text = re.sub(r"<sup>(.*?)</sup>", r"^\1", text)
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", text)).split())


def tab_export_entries(tab: Any) -> list[tuple[str, Any]]:
    """[(unique plain plot title, view), ...] for one tab's plots (builds the tab)."""
    names: list[tuple[str, Any]] = []
    seen: dict[str, int] = {}
    for view in tab.plot_views():
        name = plain_title(view.title) or type(view).__name__
        seen[name] = seen.get(name, 0) + 1
        names.append((name if seen[name] == 1 else f"{name} ({seen[name]})", view))
    return names


def export_entries(window: Any) -> list[tuple[str, list[tuple[str, Any]]]]:
    """(tab title, [(unique plain plot title, view), ...]) for every tab with plots, in tab order (this
    builds every tab)."""
    out = []
    for tab in window.analysis_tabs:
        names = tab_export_entries(tab)
        if names:
            out.append((plain_title(tab.title), names))
    return out


def _clear_menu(menu: QMenu) -> None:
    for old in menu.findChildren(QMenu, options=Qt.FindChildOption.FindDirectChildrenOnly):
        old.deleteLater()  # the last fill's submenus (clear() keeps them)
    menu.clear()


def fill_tab_export_menu(window: Any, tab: Any, menu: QMenu) -> None:
    """One tab's submenu of File → Export: one submenu per plot, then PNG / SVG / CSV.  Filled when it
    is shown: a tab never opened is built then, not with the window."""
    _clear_menu(menu)
    for name, view in tab_export_entries(tab):
        sub = menu.addMenu(name.replace("&", "&&"))
        for fmt, label in EXPORT_FORMATS:
            act = sub.addAction(label)
            act.triggered.connect(lambda _=False, v=view, f=fmt: window.export_view(v, f))


def fill_export_menu(window: Any, menu: QMenu) -> None:
    """File → Export: one submenu per tab with plots, in tab order, each filled when shown (so a title
    that follows the display is current, and a tab is built only when its submenu opens)."""
    _clear_menu(menu)
    for tab in window.analysis_tabs:
        if not tab.has_plots():
            continue
        tab_menu = menu.addMenu(plain_title(tab.title).replace("&", "&&"))
        tab_menu.aboutToShow.connect(lambda t=tab, m=tab_menu: fill_tab_export_menu(window, t, m))


def _export_menu(window: Any, menu: QMenu) -> None:
    fill_export_menu(window, menu)
    menu.aboutToShow.connect(lambda: fill_export_menu(window, menu))


def _file_menu(window: Any, bar: QMenuBar, acts: WindowActions) -> None:
    file = bar.addMenu("&File")
    file.addAction(acts.new)
    file.addAction(acts.open)
    window.recent_menu = file.addMenu("Open &Recent")
    window.recent_menu.aboutToShow.connect(window.fill_recent_menu)
    window.presets_menu = file.addMenu("&Presets")
    _presets_menu(window, window.presets_menu)
    file.addSeparator()
    file.addAction(acts.save)
    file.addAction(acts.save_as)
    file.addSeparator()
    window.export_menu = file.addMenu("&Export")
    _export_menu(window, window.export_menu)
    from app.report.action import export_report  # File → Export Report… (issue 6)

    window.act_export_report = file.addAction("Export &Report…", lambda: export_report(window))
    file.addSeparator()
    file.addAction(acts.quit)


def build_menus(window: Any, acts: WindowActions) -> None:
    """Fill the window's menu bar; sets ``recent_menu``, ``presets_menu``, ``export_menu`` on it."""
    bar = window.menuBar()
    _file_menu(window, bar, acts)
    edit = bar.addMenu("&Edit")
    edit.addAction(acts.undo)
    edit.addAction(acts.redo)
    view = bar.addMenu("&View")
    window.theme.fill_menu(view.addMenu("&Theme"))
    design = bar.addMenu("&Design")
    design.addAction(acts.maximize)
    design.addAction(acts.minimize)
    bar.addMenu("&Help").addAction(acts.about)
