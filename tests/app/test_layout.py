"""Layout at laptop sizes: every label, badge and combo box readable, no plot cut, no legend on the data.

The checks of :func:`layout_problems` run in the layout sweep over every tab
(``test_laptop_layout.py``'s ``test_every_tab_is_laid_out_whole``) at 1280×800, 1366×768 and
1600×1000, on every tab in the impedance display and then in the admittance display, with the
verdict badge's text fitting it in both.  The checks are geometric (what Qt laid out), not screenshots:

* a label's text fits its width (a word-wrapped label: its height for that width fits its height);
* a combo box's edit field is as wide as its current text;
* a plot's scene fits the widget (pyqtgraph lays its scene out at its minimum width even when the
  widget is narrower: the right part of the plot -- data, colour bar -- is then simply not shown);
* the view range covers the data's x range (the map: its whole parameter range), and the map's
  colour bar lies inside the widget;
* a legend inside the data area covers few of the curves' points; a legend below the plot lies
  outside the data area and inside the widget.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QTextDocument
from PySide6.QtWidgets import QComboBox, QLabel, QStyle, QStyleOptionComboBox, QWidget

from app.tabs.sampled_tab import SampledTab
from app.views.base import PlotView
from app.views.stability_map import StabilityMapView

#: A legend inside the plot may cover at most this fraction of a curve's points (on screen).
LEGEND_COVER = 0.05


def label_problem(label: QLabel) -> str | None:
    """Why ``label``'s text does not fit (None if it does)."""
    text = label.text()
    if not text or not label.isVisible() or label.width() <= 1:
        return None
    rect = label.contentsRect()
    width = rect.width() - 2 * max(label.margin(), 0) - max(label.indent(), 0)
    if label.wordWrap():
        need = label.heightForWidth(label.width())
        if need > label.height() + 1:
            return f"wrapped text needs {need} px height, has {label.height()}"
        return None
    if label.textFormat() == Qt.TextFormat.PlainText or "<" not in text and "&" not in text:
        need = label.fontMetrics().horizontalAdvance(text)
    else:
        doc = QTextDocument()
        doc.setDefaultFont(label.font())
        doc.setDocumentMargin(0)
        doc.setHtml(text)
        need = math.ceil(doc.idealWidth())
    if need > width + 1:
        return f"text needs {need} px, has {width}"
    return None


def combo_problem(combo: QComboBox) -> str | None:
    if not combo.isVisible() or not combo.currentText():
        return None
    opt = QStyleOptionComboBox()
    combo.initStyleOption(opt)
    field = combo.style().subControlRect(QStyle.ComplexControl.CC_ComboBox, opt,
                                         QStyle.SubControl.SC_ComboBoxEditField, combo)
    need = combo.fontMetrics().horizontalAdvance(combo.currentText())
    if need > field.width() + 1:
        return f"current text needs {need} px, edit field has {field.width()}"
    return None


def curve_points(view: PlotView) -> list[tuple[str, np.ndarray]]:
    """The visible curves' points in scene coordinates, densified along their lines (~3 px)."""
    vb = view.plot.getViewBox()
    out = []
    for item in view.plot.listDataItems():
        if not item.isVisible():
            continue
        x, y = item.getData()
        if x is None or len(x) == 0:
            continue
        pts = np.array([[p.x(), p.y()] for p in (vb.mapViewToScene(pg.Point(float(a), float(b)))
                                                  for a, b in zip(x[:: max(1, len(x) // 400)],
                                                                  y[:: max(1, len(y) // 400)]))
                        if np.isfinite(p.x()) and np.isfinite(p.y())])
        line = item.opts.get("pen") is not None and item.opts.get("symbol") is None
        if line and len(pts) < 3:
            continue  # a two-point reference line (a limit, an asymptote) is not data to keep clear
        if line:  # points along the line, about 3 px apart
            n = np.clip(np.ceil(np.hypot(*(pts[1:] - pts[:-1]).T) / 3.0), 1, 200).astype(int)
            pts = np.vstack([pts[:-1][i] + (pts[1:][i] - pts[:-1][i]) * (np.arange(k) / k)[:, None]
                             for i, k in enumerate(n)] + [pts[-1:]])
        view_rect = vb.sceneBoundingRect()
        inside = ((pts[:, 0] >= view_rect.left()) & (pts[:, 0] <= view_rect.right())
                  & (pts[:, 1] >= view_rect.top()) & (pts[:, 1] <= view_rect.bottom())) if len(pts) else []
        if len(pts) and np.count_nonzero(inside) > 0:
            out.append((item.name() or "curve", pts[inside]))
    return out


def plot_problems(view: PlotView) -> list[str]:
    out = []
    pw = view.plot_widget
    visible = QRectF(pw.viewport().rect()).adjusted(-1, -1, 1, 1)
    need = pw.centralWidget.effectiveSizeHint(Qt.SizeHint.MinimumSize)
    if need.width() > pw.viewport().width() + 1 or need.height() > pw.viewport().height() + 1:
        out.append(f"plot needs {need.width():.0f}×{need.height():.0f} px, widget has "
                   f"{pw.viewport().width()}×{pw.viewport().height()} (cut on the right/bottom)")
    title = view.plot.titleLabel
    if title.isVisible() and not visible.contains(title.item.sceneBoundingRect()):
        out.append(f"plot title {title.item.sceneBoundingRect()} outside the widget {visible}")
    vb = view.plot.getViewBox()
    if not visible.contains(vb.sceneBoundingRect()):
        out.append(f"data area {vb.sceneBoundingRect()} outside the widget {visible}")
    (x0, x1), _ = vb.viewRange()
    if isinstance(view, StabilityMapView):
        m = view.map
        if m is not None:
            lx = np.log10([m.x[0], m.x[-1]])
            ly = np.log10([m.y[0], m.y[-1]])
            (y0, y1) = vb.viewRange()[1]
            if x0 > lx[0] + 1e-9 or x1 < lx[1] - 1e-9 or y0 > ly[0] + 1e-9 or y1 < ly[1] - 1e-9:
                out.append(f"map range {vb.viewRange()} does not cover {lx}, {ly}")
        if not visible.contains(view.bar.sceneBoundingRect()):
            out.append(f"colour bar {view.bar.sceneBoundingRect()} outside the widget {visible}")
    else:
        lx, _ = view.is_log()
        for item in view.plot.listDataItems():
            x, _y = item.getData()
            if not item.isVisible() or x is None or len(x) < 2:
                continue
            lo, hi = float(np.nanmin(x)), float(np.nanmax(x))
            span = hi - lo
            if span > 0 and (x0 > lo + 0.01 * span or x1 < hi - 0.01 * span):
                out.append(f"x range {x0:.3g}..{x1:.3g} does not show {item.name()} ({lo:.3g}..{hi:.3g})")
    legend = view.legend
    if legend.isVisible() and legend.items:
        rect = legend.sceneBoundingRect()
        if not visible.contains(rect):
            out.append(f"legend {rect} outside the widget {visible}")
        if not vb.sceneBoundingRect().intersects(rect):
            return out  # outside the data area
        for name, pts in curve_points(view):
            covered = np.count_nonzero((pts[:, 0] > rect.left()) & (pts[:, 0] < rect.right())
                                       & (pts[:, 1] > rect.top()) & (pts[:, 1] < rect.bottom()))
            if covered > LEGEND_COVER * len(pts):
                out.append(f"legend covers {covered} of {len(pts)} points of {name!r}")
    return out


def layout_problems(window: QWidget, tab: QWidget) -> list[str]:
    out = []
    for label in window.findChildren(QLabel):
        why = label_problem(label)
        if why:
            out.append(f"label {label.text()[:50]!r}: {why}")
    for combo in window.findChildren(QComboBox):
        why = combo_problem(combo)
        if why:
            out.append(f"combo {combo.currentText()!r}: {why}")
    for view in tab.findChildren(PlotView):
        if view.isVisible():
            out.extend(f"{view.title}: {p}" for p in plot_problems(view))
    return out


def test_sampled_settings_panel_collapses(qtbot, win):
    """The sampled-data tab's settings panel is collapsed by default: the plots get the width."""
    tab = win.tab(SampledTab)
    win.tabs.setCurrentWidget(tab)
    # its computations done: while they run, their progress bars widen the plots' column
    qtbot.waitUntil(lambda: not tab.stale and not win.runner.running(), timeout=20000)
    assert not tab.controls.isVisible()
    plots_width = tab.map_view.width() + tab.exact_view.width()
    assert plots_width > 0.85 * tab.width()
    tab.settings_button.click()
    assert tab.controls.isVisible() and tab.settings_button.isChecked()
    assert tab.controls.width() < 0.45 * tab.width()  # its contents' whole width (issue 22), the plots the rest
    assert tab.controls.viewport().width() >= tab.controls.widget().minimumSizeHint().width()  # nothing cut
    tab.settings_button.click()
    assert not tab.controls.isVisible()
