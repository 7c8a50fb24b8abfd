"""Every tab laid out at laptop and desktop sizes (issue 22): each plot's data area (its ViewBox) at
least PLOT_MIN_HEIGHT tall, its legend, title and warning whole and apart, and the settings panels
inside the window with nothing cut on the right.

Measured on the laid-out widgets and the plots' scenes, after every tab's results arrived (a legend
and a warning appear with the data).

:func:`test_every_tab_is_laid_out_whole` is the one sweep over every tab (issue 21): one window per
size (parametrized, so that xdist spreads them), each tab settled once per pass and every check made
at that size run on it: this file's, test_layout's (labels, combos, plot ranges and legends, in both
displays), test_laptop_size's (the 1024×700 minimum size, the plots' heights at 1280×720) and
test_contrast's WCAG AA measures in both themes (at 1600×1000).  The sizes are the union of the
sweeps': 1024×700, 1280×720, 1280×800, 1366×768 and 1600×1000 (:data:`SWEEPS`)."""

from __future__ import annotations

from collections.abc import Callable

from dataclasses import dataclass

import pytest
from conftest import coarse_profile
from PySide6.QtCore import QRect, QRectF, Qt
from PySide6.QtGui import QImage, QPainter
from PySide6.QtWidgets import QGraphicsTextItem, QLabel, QScrollArea, QWidget

from analysis.profiles.io import bundled_profiles, load_profile

from app.tabs.base import PLOT_MIN_HEIGHT
from app.tabs.sampled_tab import ASYNC_NODES, SampledTab
from app.views.base import PlotView
from test_contrast import low_contrast, tab_contrast
from test_laptop_size import minimum_size_problems, plot_height_problems, scroll_problems
from test_layout import layout_problems

SIZES = [(1280, 720), (1024, 700), (1600, 1000)]


def _settle(win, qtbot, tab) -> None:
    """The tab built, refreshed, its background results drawn and the layout done."""
    qtbot.waitUntil(lambda: tab.is_built() and not tab.stale, timeout=10000)
    qtbot.waitUntil(lambda: not win.runner.running(), timeout=120000)
    qtbot.wait(150)  # the deferred refits (tab scroll area, legend rows, data-area floors)


def _visible_scene_rect(view: PlotView) -> QRectF:
    pw = view.plot_widget
    return pw.mapToScene(pw.viewport().rect()).boundingRect()


def _texts(view: PlotView) -> list[QGraphicsTextItem]:
    """The plot's visible texts outside its legend: axis titles, line labels, centred messages."""
    legend = view.legend
    return [it for it in view.plot_widget.scene().items()
            if isinstance(it, QGraphicsTextItem) and it.isVisible() and it.toPlainText().strip()
            and not legend.isAncestorOf(it)]


def _text_rect(item: QGraphicsTextItem) -> QRectF:
    """Where a text's lines are drawn, in scene coordinates (its bounding rectangle less the document's
    margin, which is blank)."""
    m = item.document().documentMargin()
    return item.mapRectToScene(item.boundingRect().adjusted(m, m, -m, -m))


def _whole(label: QLabel) -> bool:
    """A word-wrapped label has the height its text needs at its width."""
    return not label.isVisible() or not label.wordWrap() or label.height() >= label.heightForWidth(label.width()) - 1


def _plot_problems(where: str, view: PlotView) -> list[str]:
    out = []
    pw, vb = view.plot_widget, view.plot.getViewBox()
    if vb.size().height() < PLOT_MIN_HEIGHT - 0.5:
        out.append(f"{where}: data area {vb.size().height():.0f} px tall")
    # the plot widget gets the height it asks for (its parent's layout does not overlap it with the labels)
    if pw.geometry().bottom() > view.rect().bottom():
        out.append(f"{where}: the plot is cut at the bottom ({pw.geometry()} in {view.rect()})")
    for label in (view.header, view.warning):
        if label.isVisible() and label.geometry().intersects(pw.geometry()):
            out.append(f"{where}: {label.text()[:30]!r} overlaps the plot")
        if not _whole(label):
            out.append(f"{where}: {label.text()[:30]!r} cut ({label.height()} of {label.heightForWidth(label.width())} px)")
    shown = _visible_scene_rect(view).adjusted(-1, -1, 1, 1)
    for text in _texts(view):
        r = _text_rect(text)
        if not shown.contains(r):
            out.append(f"{where}: text {text.toPlainText()[:30]!r} cut ({r} outside {shown})")
    legend = view.legend
    if legend.isVisible() and legend.items:
        r = legend.sceneBoundingRect()
        if not shown.contains(r) or not view.plot.sceneBoundingRect().adjusted(-1, -1, 1, 1).contains(r):
            out.append(f"{where}: legend {r} not inside the plot {shown}")
        for text in _texts(view):
            if r.adjusted(1, 1, -1, -1).intersects(_text_rect(text)):
                out.append(f"{where}: legend covers {text.toPlainText()[:30]!r}")
    return out


def _in_window(win, widget: QWidget) -> QRect:
    return QRect(widget.mapTo(win, widget.rect().topLeft()), widget.size())


def _panel_problems(win, where: str, panel: QScrollArea) -> list[str]:
    """A settings panel inside the window (its left, right and top edges) with its contents' width
    shown, or a scroll bar to reach the rest."""
    out = []
    r = _in_window(win, panel)
    if r.left() < 0 or r.right() > win.rect().right() or r.top() < 0 or r.top() > win.rect().bottom():
        out.append(f"{where}: {r} outside the window {win.rect()}")
    need = panel.widget().minimumSizeHint().width()
    if panel.viewport().width() < need and not panel.horizontalScrollBar().isVisible():
        out.append(f"{where}: {panel.viewport().width()} px shown of {need}, cut on the right")
    return out


def _side_problems(where: str, tab: QWidget) -> list[str]:
    """Every visible scroll area of the tab that scrolls vertically only (the settings beside the
    plots of Renderable space and Workspace, the text panes) shows its contents' whole width (the tab
    itself may scroll: where the area sits is not checked here)."""
    out = []
    for area in tab.findChildren(QScrollArea):
        if (not area.isVisible() or area.widget() is None
                or area.horizontalScrollBarPolicy() != Qt.ScrollBarPolicy.ScrollBarAlwaysOff):
            continue
        need = area.widget().minimumSizeHint().width()
        if area.viewport().width() < need:
            out.append(f"{where} {area.objectName() or 'settings'}: {area.viewport().width()} px shown of "
                       f"{need}, cut on the right")
    return out


def _tab_problems(name: str, tab: QWidget) -> list[str]:
    return [p for v in tab.views() if v.plot_widget.isVisible() for p in _plot_problems(f"{name} / {v.title}", v)]


def _settled(qtbot, problems: Callable[[], list[str]], timeout_ms: int = 3000) -> list[str]:
    """The problems once the layout has settled: a change is laid out over a few turns of the event
    loop (a label's new width, its new minimum height, the scroll area's refit), so the check is
    repeated until it passes or ``timeout_ms`` have passed; then the last problems found."""
    found = problems()
    waited = 0
    while found and waited < timeout_ms:
        qtbot.wait(100)
        waited += 100
        found = problems()
    return found


@dataclass(frozen=True)
class Sweep:
    """A window size and the checks run on every tab at it (the union of what the sweeps that
    went through every tab at this size checked, each of them settling every tab again)."""

    size: tuple[int, int]
    #: test_layout's checks (labels, combos, plots' ranges and legends, the verdict badge), in the
    #: impedance and then the admittance display
    readable: bool = False
    #: this file's checks (data areas, legends, titles, warnings, settings panels)
    whole: bool = False
    #: test_laptop_size's: the window's minimum size fits (every tab built), asked before it is resized
    fits: bool = False
    #: test_laptop_size's: every plot widget at least PLOT_MIN_HEIGHT tall, tabs scroll instead
    tall: bool = False
    #: test_contrast's WCAG AA sweep: every tab dark (as stored), light, dark in the admittance
    #: display, then light on the current tab
    contrast: bool = False

    @property
    def id(self) -> str:
        return f"{self.size[0]}x{self.size[1]}"


SWEEPS = (Sweep((1024, 700), whole=True, fits=True), Sweep((1280, 720), whole=True, tall=True),
          Sweep((1280, 800), readable=True), Sweep((1366, 768), readable=True),
          Sweep((1600, 1000), readable=True, whole=True, contrast=True))
assert {s.size for s in SWEEPS if s.whole} == set(SIZES)


@dataclass(frozen=True)
class Pass:
    """One pass over every tab: the theme (None: as stored), the display, and which of the sweep's
    checks run in it (``readable``: test_layout's; ``whole``: this file's and test_laptop_size's,
    which were made in the impedance display only; ``contrast``)."""

    theme: str | None
    display: str
    readable: bool
    whole: bool
    contrast: bool


def passes(sweep: Sweep) -> list[Pass]:
    """The passes of ``sweep``: with contrast, dark (as stored: every tab built dark), light (the
    layout checks), dark again with the display switched while dark (test_layout's checks in the
    admittance display); else the impedance display, and the admittance display for test_layout's
    checks."""
    if sweep.contrast:
        return [Pass(None, "impedance", False, False, True),
                Pass("light", "impedance", sweep.readable, True, True),
                Pass("dark", "admittance", sweep.readable, False, True)]
    return [Pass(None, "impedance", sweep.readable, True, False)] + \
        ([Pass(None, "admittance", True, False, False)] if sweep.readable else [])


def _sweep_settle(win, qtbot, tab) -> None:
    """The union of the old sweeps' settling: the tab built and refreshed, the Sampled-data tab's
    background results fresh, the worker idle, and the deferred layout done."""
    qtbot.waitUntil(lambda: tab.is_built() and not tab.stale, timeout=20000)
    if isinstance(tab, SampledTab):
        g = win.graph
        qtbot.waitUntil(lambda: all(g.is_fresh(n) for n in ASYNC_NODES if n in g), timeout=120000)
    qtbot.waitUntil(lambda: not win.runner.running(), timeout=120000)
    qtbot.waitUntil(lambda: not tab.stale, timeout=20000)
    qtbot.wait(150)  # the deferred refits (tab scroll area, legend rows, data-area floors)


def _check_tab(win, qtbot, sweep: Sweep, run: Pass, where: str, tab: QWidget,
               first: bool) -> tuple[list[str], int, int]:
    """Every check of ``sweep`` in ``run`` on the current, settled ``tab``: the problems, the visible
    plot widgets (counted by the ``whole`` and ``tall`` checks) and the contrasts measured (the rest of
    the window's on the ``first`` tab of the pass only: it is the same on every tab)."""
    problems, seen, measured = [], 0, 0
    if run.readable:
        # retried like this file's checks: a window made at this size lays a tab out over a few turns
        # of the event loop when it first shows it (a wrapped label's height follows its new text)
        problems += _settled(qtbot, lambda: [f"{where}: {p}" for p in layout_problems(win, tab)])
    if run.whole and sweep.whole:
        problems += _settled(qtbot, lambda: _tab_problems(where, tab) + _side_problems(where, tab))
    if run.whole and sweep.tall:
        problems += _settled(qtbot, lambda: plot_height_problems(where, tab)[0] + scroll_problems(where, tab))
    if run.whole and (sweep.whole or sweep.tall):
        seen = sum(v.plot_widget.isVisible() for v in tab.views())
    if run.contrast:
        found, measured = tab_contrast(win, qtbot, where, whole=first)
        problems += found
    if run.whole and sweep.whole and hasattr(tab, "show_controls"):  # the Sampled-data tab's settings
        tab.show_controls(True)
        problems += _settled(qtbot, lambda: _panel_problems(win, f"{where} settings", tab.controls)
                             + _tab_problems(f"{where} (settings open)", tab))
        tab.show_controls(False)
        qtbot.wait(50)
    return problems, seen, measured


def _sweep_pass(win, qtbot, sweep: Sweep, run: Pass) -> list[str]:
    """Every tab settled once and checked as ``run`` says."""
    if run.theme is not None:
        win.set_theme(run.theme)
    if win.model.profile.display != run.display:
        win.editor.edit("display", run.display)
    # the contrast sweep's window starts dark (the stored theme)
    label = f"{sweep.id} {run.display}" + (f" {run.theme or 'dark'}" if run.contrast else "")
    problems, seen, measured = [], 0, 0
    if run.whole and sweep.whole:
        problems += _panel_problems(win, f"{label} parameter panel", win.panel)
    for i in range(win.tabs.count()):
        win.tabs.setCurrentIndex(i)
        tab = win.tabs.currentWidget()
        _sweep_settle(win, qtbot, tab)
        where = f"{label} {win.tabs.tabText(i)}"
        assert (win.width(), win.height()) == sweep.size, f"{where}: the window grew to fit its contents"
        found, n, m = _check_tab(win, qtbot, sweep, run, where, tab, first=i == 0)
        problems += found
        seen += n
        measured += m
    if run.whole and (sweep.whole or sweep.tall):
        assert seen >= 20, f"{label}: {seen} plots seen"
    if run.contrast:
        assert measured > 500, f"{label}: {measured} contrasts measured"  # every tab's widgets were found
    if run.readable:
        badge = win.verdict.badge
        assert badge.fontMetrics().horizontalAdvance(badge.text()) <= badge.contentsRect().width(), label
    return problems


@pytest.mark.parametrize("sweep", SWEEPS, ids=[s.id for s in SWEEPS])
def test_every_tab_is_laid_out_whole(qtbot, settings, coarse_grids, sweep: Sweep):
    """One window per size, every tab settled once per pass and every check of the size run on it
    (:class:`Sweep`, :func:`passes`): this file's, test_layout's (both displays), test_laptop_size's
    and, at 1600×1000, test_contrast's in both themes.  On coarse grids (conftest.coarse_profile,
    coarse_grids): the layout and the colours do not depend on the results' resolution, and every
    curve, map, legend and warning is still drawn."""
    from app.window.main_window import MainWindow

    if sweep.contrast:
        settings.set_theme("dark")
    win = MainWindow(settings=settings, profile=coarse_profile(load_profile(bundled_profiles()["hbfd"])))
    try:
        win.resize(1400, 900)
        win.show()
        qtbot.waitExposed(win)
        qtbot.waitUntil(lambda: not win.tabs.currentWidget().stale, timeout=5000)
        if sweep.fits:
            assert not minimum_size_problems(win, sweep.size), minimum_size_problems(win, sweep.size)
        win.resize(*sweep.size)
        qtbot.waitUntil(lambda: (win.width(), win.height()) == sweep.size, timeout=5000)
        problems = []
        for run in passes(sweep):
            problems += _sweep_pass(win, qtbot, sweep, run)
        if sweep.contrast:  # back to light on the current tab
            win.set_theme("light")
            found, _n = low_contrast(win, qtbot, [win.tabs.currentIndex()])
            problems += [f"{sweep.id} light, back from dark: {p}" for p in found]
        assert not problems, "\n".join(problems)
    finally:
        win.undo_stack.setClean()
        win.runner.shutdown()
        win.close()
        win.deleteLater()


def _ticks(axis) -> tuple[list, list[str]]:
    """The tick lines (the grid with them) and numbers the axis draws at its current range."""
    image = QImage(8, 8, QImage.Format.Format_ARGB32)
    painter = QPainter(image)
    try:
        specs = axis.generateDrawSpecs(painter)
    finally:
        painter.end()
    return (list(specs[1]), [text for _rect, _flags, text in specs[2]]) if specs else ([], [])


def _placeholder(tab, view) -> str:
    message = tab.placeholders[view]
    return message.item.toPlainText() if message.item.isVisible() else ""


def test_empty_identify_plots_say_what_to_do_and_show_no_ranges(win, qtbot, tmp_path):
    from test_identify_tab import fit, show, write_frf

    tab = show(win, qtbot)
    views = tab.bode.plot_views()
    for view in views:
        assert "add measurement files" in _placeholder(tab, view), view.title
        # centred in the data area, and no axis numbers or grid for a range that holds no data
        vb = view.plot.getViewBox().sceneBoundingRect()
        box = tab.placeholders[view].scene_rect()
        assert vb.contains(box) and abs(box.center().x() - vb.center().x()) < 2, (view.title, box, vb)
        assert abs(box.center().y() - vb.center().y()) < 2, (view.title, box, vb)
        for name in ("left", "bottom"):
            assert _ticks(view.plot.getAxis(name)) == ([], []), (view.title, name)
    tab.panel.sampled.setChecked(True)
    tab.load_files([write_frf(tmp_path / "a.csv", win.model.device, points=120)])
    assert all("press Fit" in _placeholder(tab, v) for v in views)
    tab.panel.masses.setValue(2)
    tab.panel.max_order.setValue(0)
    fit(tab, qtbot, win)
    for view in views:
        assert _placeholder(tab, view) == "", view.title
        assert view.export_series()
        lines, numbers = _ticks(view.plot.getAxis("bottom"))
        assert lines and any(numbers), view.title  # the axes are back
