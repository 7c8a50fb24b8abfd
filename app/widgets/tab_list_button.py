"""The list of every tab, at the end of the tab bar (issue 22, laptop sizes).

At 1280 px the nine analysis tabs do not fit the tab bar: Qt scrolls it, and the last tabs sit
behind its arrows.  This button lists every tab by its title, the current one checked; choosing one
shows it.  Like a browser's "list all tabs", it is there at every width.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QActionGroup
from PySide6.QtWidgets import QMenu, QTabWidget, QToolButton

__all__ = ["TabListButton"]


class TabListButton(QToolButton):
    """A tool button in ``tabs``' top-right corner whose menu lists every tab.

    Parameters
    ----------
    tabs : QTabWidget
        The tab widget; the button installs itself as its corner widget.
    """

    def __init__(self, tabs: QTabWidget) -> None:
        super().__init__(tabs)
        self.tabs = tabs
        self.setObjectName("tabList")
        self.setText("All tabs ▾")
        self.setStyleSheet("QToolButton::menu-indicator { image: none; width: 0px; }")  # the ▾ says it
        self.setToolTip("Every analysis tab by name (the tab bar scrolls when they do not fit)")
        self.setPopupMode(QToolButton.ToolButtonPopupMode.InstantPopup)
        self.setAutoRaise(True)
        self.setMenu(QMenu(self))
        self.menu().aboutToShow.connect(self.fill)
        self.fill()
        tabs.setCornerWidget(self, Qt.Corner.TopRightCorner)

    def fill(self) -> None:
        """One checkable entry per tab, in the tab bar's order, the current tab checked."""
        menu = self.menu()
        menu.clear()
        group = QActionGroup(menu)
        for i in range(self.tabs.count()):
            action = QAction(self.tabs.tabText(i), menu, checkable=True)
            action.setChecked(i == self.tabs.currentIndex())
            action.triggered.connect(lambda _checked=False, i=i: self.tabs.setCurrentIndex(i))
            group.addAction(action)
            menu.addAction(action)
