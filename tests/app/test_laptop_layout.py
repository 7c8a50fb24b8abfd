"""Every tab laid out at laptop and desktop sizes (issue 22): each plot's data area (its ViewBox) at
least PLOT_MIN_HEIGHT tall, its legend, title and warning whole and apart, and the settings panels
inside the window with nothing cut on the right.

Measured on the laid-out widgets and the plots' scenes, after every tab's results arrived (a legend
and a warning appear with the data)."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from PySide6.QtCore import QRect, QRectF
from PySide6.QtGui import QImage, QPainter
from PySide6.QtWidgets import QGraphicsTextItem, QLabel, QScrollArea, QWidget

from app.tabs.base import PLOT_MIN_HEIGHT
from app.views.base import PlotView

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


@pytest.mark.parametrize("size", SIZES, ids=[f"{w}x{h}" for w, h in SIZES])
def test_every_tab_is_laid_out_whole(coarse_win, qtbot, size):
    """On coarse grids (conftest.coarse_win): the layout does not depend on the results' resolution."""
    win = coarse_win
    width, height = size
    win.resize(width, height)
    qtbot.waitUntil(lambda: (win.width(), win.height()) == size, timeout=5000)
    problems = _panel_problems(win, "parameter panel", win.panel)
    seen = 0
    for i in range(win.tabs.count()):
        win.tabs.setCurrentIndex(i)
        tab = win.tabs.currentWidget()
        _settle(win, qtbot, tab)
        name = win.tabs.tabText(i)
        seen += sum(v.plot_widget.isVisible() for v in tab.views())
        problems += _settled(qtbot, lambda: _tab_problems(name, tab))
        if hasattr(tab, "show_controls"):  # the Sampled-data tab's loop, scenario and map settings
            tab.show_controls(True)
            problems += _settled(qtbot, lambda: _panel_problems(win, f"{name} settings", tab.controls)
                                 + _tab_problems(f"{name} (settings open)", tab))
            tab.show_controls(False)
            qtbot.wait(50)
    assert seen >= 20
    assert not problems, "\n".join(problems)


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
