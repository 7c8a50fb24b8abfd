"""Settings beside plots scroll vertically and are never cut at their right edge (issue 22): at
1280×720 the Workspace tab's sentences ("wall norma…") and the Renderable tab's combo boxes were
cut by a fixed maximum width."""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QScrollArea

from app.tabs.renderable_tab import RenderableTab
from app.tabs.workspace_tab import WorkspaceTab


def _cut(tab) -> list[str]:
    """The scroll areas without a horizontal scroll bar whose contents are wider than their view."""
    out = []
    for area in tab.findChildren(QScrollArea):
        if area.horizontalScrollBarPolicy() != Qt.ScrollBarPolicy.ScrollBarAlwaysOff or not area.isVisible():
            continue
        body = area.widget()
        if body is not None and body.width() > area.viewport().width():
            out.append(f"{area.objectName() or type(body).__name__}: {body.width()} > {area.viewport().width()} px")
    return out


@pytest.mark.parametrize("size", [(1280, 720), (1024, 700)], ids=["1280x720", "1024x700"])
def test_settings_are_never_cut_on_the_right(coarse_win, qtbot, size):
    """On coarse grids (conftest.coarse_win): the layout does not depend on the results' resolution."""
    win = coarse_win
    win.resize(*size)
    qtbot.waitUntil(lambda: (win.width(), win.height()) == size, timeout=5000)
    for kind in (RenderableTab, WorkspaceTab):
        tab = win.tab(kind)
        win.tabs.setCurrentWidget(tab)
        qtbot.waitUntil(lambda: tab.is_built() and not tab.stale, timeout=60000)
        qtbot.waitUntil(lambda: not win.runner.running(), timeout=120000)  # the results' sentences shown
        qtbot.wait(200)  # the scroll area refits after the settings' layout settles
        assert tab.findChildren(QScrollArea), kind.__name__
        assert _cut(tab) == [], kind.__name__
