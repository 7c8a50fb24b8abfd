"""The window at laptop sizes (issue 22): it can be made 1024×700, and at 1280×720 no plot of any tab
is squeezed below a readable height (a tab scrolls instead).

These are checks of the layout sweep over every tab (``test_laptop_layout.py``'s
``test_every_tab_is_laid_out_whole``): its 1024×700 window is asked for its minimum size
(:func:`minimum_size_problems`) before it is made 1024×700, and the sweep asserts at every tab that
no tab widens it again; at 1280×720 it runs :func:`plot_height_problems` and
:func:`scroll_problems` on every tab, once the tab has settled for all the sweep's checks.
"""

from __future__ import annotations

from PySide6.QtWidgets import QScrollArea, QWidget

from app.tabs.base import PLOT_MIN_HEIGHT


def minimum_size_problems(win, size: tuple[int, int]) -> list[str]:
    """The window's minimum size, with every tab built (every tab's contents count towards it),
    within ``size``."""
    for tab in win.analysis_tabs:
        tab.ensure_built()
    hint = win.minimumSizeHint()
    if hint.width() <= size[0] and hint.height() <= size[1]:
        return []
    return [f"the window's minimum size {hint.width()}×{hint.height()} is larger than {size[0]}×{size[1]}"]


def plot_height_problems(where: str, tab: QWidget) -> tuple[list[str], int]:
    """Every visible plot widget of ``tab`` at least PLOT_MIN_HEIGHT tall; and how many were seen."""
    problems, seen = [], 0
    for view in tab.views():
        widget = view.plot_widget
        if widget.isVisible():
            seen += 1
            if widget.height() < PLOT_MIN_HEIGHT:
                problems.append(f"{where} / {view.title}: plot widget {widget.height()} px tall "
                                f"(< {PLOT_MIN_HEIGHT})")
    return problems, seen


def scroll_problems(where: str, tab: QWidget) -> list[str]:
    """The contents keep their minimum size: a tab scrolls rather than squeeze them (once laid out: a
    plot's floor and the labels' heights follow its results over a few turns of the event loop)."""
    out = []
    for area in tab.findChildren(QScrollArea, "tabScroll"):
        body, need = area.widget(), area.widget().minimumSizeHint()
        if body.width() < need.width() - 1 or body.height() < need.height() - 1:
            out.append(f"{where}: the tab's contents squeezed to {body.width()}×{body.height()} "
                       f"(minimum {need.width()}×{need.height()})")
    return out
