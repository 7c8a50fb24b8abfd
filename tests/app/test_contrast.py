"""Both themes: everything on every tab is readable at WCAG AA (issue 22).

Normal text needs 4.5:1 against its background, large text (18 pt, or 14 pt bold) 3:1, and
graphics (curves, markers, legend lines, check-box and radio-button indicators) 3:1.  Inactive
(disabled) controls are exempt, as WCAG exempts them.

What is checked is what the user sees: widgets are rendered (``grab()``) and their colours read from
the pixels.  In a text's rectangle the background is the most common colour and the text colour
that of the glyphs' cores (the pixels differing most from the background); an indicator is compared
with the colour around it.  A widget inside a scroll area is measured on a grab of the scroll
area's contents, so that the parts scrolled out of view are checked too.  Curves are checked by
their pens' colours (composited over the plot's background: a thin antialiased line has few pure
pixels).  Shadings (translucent fills and their legend swatches) are exempt: each is bounded by a
curve that is checked.

The kinds: labels, rich text panes, check boxes and radio buttons (text and indicator), group box
titles, spin boxes, combo boxes, table cells and headers, list items, tab titles, buttons, plot
titles, axis text (tick numbers and titles), text items in plots, legend texts, legend samples and
curves.  The theme is switched at run time (light -> dark -> light) and the display switched while
dark: both used to leave dark text on dark grey.

The sweep over every tab runs in the layout sweep's window at 1600×1000
(``test_laptop_layout.py``'s ``test_every_tab_is_laid_out_whole``, on coarse grids): every tab dark
(the stored theme: every tab is built dark), light, dark again after the display switch
(admittance), then light on the current tab, each pass measuring more than 500 things; each tab is
settled once for the layout checks and :func:`tab_contrast` together.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QRect, QRectF
from PySide6.QtGui import QColor, QFont, QImage
from PySide6.QtWidgets import (QAbstractButton, QAbstractItemView, QAbstractSpinBox, QCheckBox, QComboBox,
                               QGraphicsTextItem, QGroupBox, QHeaderView, QLabel, QPushButton, QRadioButton,
                               QScrollArea, QStyle, QStyleOptionButton, QTabBar, QWidget)

from app.tabs.sampled_tab import ASYNC_NODES, SampledTab
from app.views.base import PlotView
from app.views.stability_map import CONTOUR_HALO, CONTOUR_PEN, StabilityMapView, radius_colormap
from app.widgets.colors import AA_GRAPHICS, AA_LARGE, AA_TEXT, contrast_ratio
from app.widgets.rich_text_pane import RichTextPane

AA = AA_TEXT
contrast = contrast_ratio


# -- reading colours off a rendered image ------------------------------------------------------------
def rgb_array(image: QImage) -> np.ndarray:
    """The image's RGB pixels as an (H, W, 3) array."""
    img = image.convertToFormat(QImage.Format.Format_RGB888)
    raw = np.frombuffer(img.constBits(), np.uint8, img.sizeInBytes()).reshape(img.height(), img.bytesPerLine())
    return raw[:, : img.width() * 3].reshape(img.height(), img.width(), 3).copy()


class Surface:
    """A grabbed widget (the window, or a scroll area's contents) and its pixels."""

    def __init__(self, widget: QWidget) -> None:
        self.widget = widget
        image = widget.grab().toImage()
        self.ratio = image.devicePixelRatio()
        self.rgb = rgb_array(image)

    def rect_of(self, widget: QWidget, rect: QRect | None = None) -> QRect:
        """``rect`` (default: the widget's) of ``widget`` in this surface's coordinates."""
        rect = widget.rect() if rect is None else rect
        return QRect(widget.mapTo(self.widget, rect.topLeft()), rect.size())

    def block(self, rect: QRect) -> np.ndarray:
        """The RGB pixels of ``rect`` (device-independent pixels) as an (H, W, 3) array (may be empty)."""
        r = self.ratio
        r = QRect(int(rect.x() * r), int(rect.y() * r), int(rect.width() * r), int(rect.height() * r))
        r = r.intersected(QRect(0, 0, self.rgb.shape[1], self.rgb.shape[0]))
        if r.isEmpty():
            return np.zeros((0, 0, 3), np.uint8)
        return self.rgb[r.top(): r.bottom() + 1, r.left(): r.right() + 1]

    def pixels(self, rect: QRect) -> np.ndarray:
        """The RGB pixels of ``rect`` as an (N, 3) array (may be empty)."""
        return self.block(rect).reshape(-1, 3).astype(int)


def _colours(px: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    codes, inverse, counts = np.unique((px[:, 0] << 16) | (px[:, 1] << 8) | px[:, 2],
                                       return_inverse=True, return_counts=True)
    return np.stack([codes >> 16, (codes >> 8) & 255, codes & 255], axis=1), inverse.ravel(), counts


def ink_contrast(px: np.ndarray, background: np.ndarray | None = None) -> float | None:
    """Contrast of the ink in ``px`` (N, 3) with ``background`` (default: the most common colour):
    the top few per cent of the pixels that differ from it (the glyphs' cores); None without ink."""
    if len(px) == 0:
        return None
    colours, inverse, counts = _colours(px)
    bg = colours[np.argmax(counts)] if background is None else background
    ratios = contrast(colours, bg[None, :])[inverse]
    ink = ratios[ratios > 1.05]
    if ink.size < 4:
        return None
    return float(np.percentile(ink, 97))


def _runs(mask: np.ndarray, gap: int) -> list[tuple[int, int]]:
    """The runs of True in ``mask`` (start, stop), runs closer than ``gap`` merged."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > gap + 1)
    starts = np.r_[idx[0], idx[breaks + 1]]
    stops = np.r_[idx[breaks], idx[-1]] + 1
    return list(zip(starts.tolist(), stops.tolist()))


def words_contrast(block: np.ndarray, gap: int) -> float | None:
    """The lowest contrast of any word in ``block`` (H, W, 3): rich text mixes colours (a muted
    note under a verdict), so each line of ink, and each word of a line, is measured on its own
    against the block's background, by its strongest pixel (a subscript's thin strokes never reach
    the full colour).  A lone small glyph (a full stop, ⚠) is not measured alone."""
    px = block.reshape(-1, 3).astype(int)
    if len(px) == 0:
        return None
    colours, inverse, counts = _colours(px)
    bg = colours[np.argmax(counts)]
    ratios = contrast(colours, bg[None, :])[inverse].reshape(block.shape[:2])
    ink = ratios > 1.05
    worst = None
    for top, bottom in _runs(ink.any(axis=1), 0):
        for left, right in _runs(ink[top:bottom].any(axis=0), gap):
            word = ratios[top:bottom, left:right][ink[top:bottom, left:right]]
            if word.size < 12 or right - left < bottom - top:
                continue  # a lone small glyph (⚠, a bracket): its thin strokes never reach the colour
            value = float(word.max())  # a word is one colour: antialiasing only lightens small glyphs
            worst = value if worst is None else min(worst, value)
    return worst if worst is not None else ink_contrast(px)  # a one-letter label


def dominant(px: np.ndarray) -> np.ndarray:
    colours, _inverse, counts = _colours(px)
    return colours[np.argmax(counts)]


def is_large(font: QFont) -> bool:
    """WCAG's large text: 18 pt, or 14 pt bold."""
    pt = font.pointSizeF() if font.pointSizeF() > 0 else font.pixelSize() * 0.75
    return pt >= 18 or (font.bold() and pt >= 14)


# -- what to measure -----------------------------------------------------------------------------------
class Probe:
    """Collects (what, contrast, required) for every widget of a window, on its surfaces."""

    def __init__(self, window: QWidget) -> None:
        self.window = window
        self._surfaces: dict[int, Surface] = {}
        self.results: list[tuple[str, float | None, float]] = []

    def surface(self, widget: QWidget) -> Surface:
        """The grab ``widget`` is measured on: its innermost scroll area's contents, or the window."""
        host: QWidget = self.window
        w: QWidget | None = widget
        while w is not None and w is not self.window:
            viewport = w.parentWidget()
            area = viewport.parentWidget() if viewport is not None else None
            if isinstance(area, QScrollArea) and area.widget() is w:
                host = w
                break
            w = viewport
        key = id(host)
        if key not in self._surfaces:
            self._surfaces[key] = Surface(host)
        return self._surfaces[key]

    def shown(self, widget: QWidget, rect: QRect | None = None) -> QRect:
        """The part of ``rect`` (default: the widget's) that its parents up to the surface do not clip
        (a table's cell widget scrolled out of the table), in the surface's coordinates."""
        s = self.surface(widget)
        out = s.rect_of(widget, rect)
        w = widget.parentWidget()
        while w is not None and w is not s.widget:
            out = out.intersected(s.rect_of(w))
            w = w.parentWidget()
        return out

    def text(self, what: str, widget: QWidget, rect: QRect | None = None, font: QFont | None = None,
             words: bool = False) -> None:
        """The text in ``rect`` of ``widget``: its ink as a whole, or (``words``: rich text, which
        mixes colours) each word's."""
        s = self.surface(widget)
        full = s.rect_of(widget, rect)
        shown = self.shown(widget, rect)
        if shown.width() * shown.height() < 0.8 * full.width() * full.height():
            return  # mostly clipped: measured where it is shown
        gap = max(2, int(widget.fontMetrics().height() * s.ratio / 4))
        ratio = words_contrast(s.block(shown), gap) if words else ink_contrast(s.pixels(shown))
        self.results.append((what, ratio, AA_LARGE if is_large(font or widget.font()) else AA_TEXT))

    def indicator(self, what: str, widget: QWidget, rect: QRect) -> None:
        """A check box's or radio button's indicator against the colour around it (3:1)."""
        s = self.surface(widget)
        inner = s.rect_of(widget, rect)
        if self.shown(widget, rect) != inner:
            return
        ring = s.pixels(inner.adjusted(-2, -2, 2, 2))
        around = dominant(np.concatenate([s.pixels(QRect(inner.left() - 2, inner.top(), 2, inner.height())),
                                          s.pixels(QRect(inner.right() + 1, inner.top(), 2, inner.height()))]))
        self.results.append((what, ink_contrast(ring, around), AA_GRAPHICS))

    def colour(self, what: str, color: QColor, background: QColor, required: float = AA_GRAPHICS) -> None:
        """A pen's or brush's colour, composited over ``background``."""
        a = color.alphaF()
        fg = np.array(color.getRgb()[:3], float) * a + np.array(background.getRgb()[:3], float) * (1 - a)
        self.results.append((what, float(contrast(fg, np.array(background.getRgb()[:3]))), required))

    # -- widget kinds ---------------------------------------------------------------------------------
    def widgets(self, root: QWidget) -> None:
        for w in root.findChildren(QWidget):
            if not w.isVisible() or not w.isEnabled() or w.width() < 4 or w.height() < 4:
                continue
            if isinstance(w, QLabel) and w.text().strip():
                self.text(f"label {w.text()[:40]!r}", w, w.contentsRect(), words=True)
            elif isinstance(w, RichTextPane) and w.text().strip():
                self.text(f"rich text {w.text()[:40]!r}", w, words=True)
            elif isinstance(w, (QCheckBox, QRadioButton)):
                self.check(w)
            elif isinstance(w, QGroupBox) and w.title():
                fm = w.fontMetrics()
                self.text(f"group title {w.title()!r}", w, QRect(0, 0, fm.horizontalAdvance(w.title()) + 16,
                                                                   fm.height() + 2))
            elif isinstance(w, QAbstractSpinBox) and w.lineEdit() is not None and w.text():
                self.text(f"spin box {w.text()!r}", w.lineEdit())
            elif isinstance(w, QComboBox) and w.currentText():
                self.text(f"combo box {w.currentText()[:30]!r}", w, w.rect().adjusted(3, 3, -22, -3))
            elif isinstance(w, QPushButton) and w.text():
                self.text(f"button {w.text()!r}", w, w.rect().adjusted(3, 3, -3, -3))
            elif isinstance(w, QTabBar):
                for i in range(w.count()):
                    if w.isTabEnabled(i) and w.isTabVisible(i) and w.tabRect(i).width() > 8:
                        self.text(f"tab title {w.tabText(i)!r}", w, w.tabRect(i).adjusted(4, 3, -4, -3))
            elif isinstance(w, QHeaderView) and not w.isHidden():
                self.header(w)
            elif isinstance(w, QAbstractItemView):
                self.cells(w)

    def check(self, w: QAbstractButton) -> None:
        opt = QStyleOptionButton()
        opt.initFrom(w)
        opt.text = w.text()
        radio = isinstance(w, QRadioButton)
        style = w.style()
        ind = style.subElementRect(QStyle.SubElement.SE_RadioButtonIndicator if radio
                                   else QStyle.SubElement.SE_CheckBoxIndicator, opt, w)
        kind = "radio button" if radio else "check box"
        self.indicator(f"{kind} {w.text()!r} indicator", w, ind)
        if w.text():
            contents = style.subElementRect(QStyle.SubElement.SE_RadioButtonContents if radio
                                            else QStyle.SubElement.SE_CheckBoxContents, opt, w)
            self.text(f"{kind} {w.text()!r}", w, contents.intersected(w.rect()))

    def header(self, h: QHeaderView) -> None:
        model = h.model()
        if model is None:
            return
        for i in range(h.count()):
            if h.isSectionHidden(i) or h.sectionSize(i) < 12:
                continue
            text = model.headerData(i, h.orientation())
            if not text:
                continue
            pos = h.sectionViewportPosition(i)
            rect = QRect(pos + 2, 2, h.sectionSize(i) - 4, h.height() - 4) if h.orientation().name == "Horizontal" \
                else QRect(2, pos + 2, h.width() - 4, h.sectionSize(i) - 4)
            if rect.intersected(h.viewport().rect()) == rect:
                self.text(f"header {text!r}", h.viewport(), rect)

    def cells(self, view: QAbstractItemView) -> None:
        model = view.model()
        if model is None:
            return
        vp = view.viewport()
        for r in range(model.rowCount()):
            for c in range(model.columnCount()):
                index = model.index(r, c)
                text = model.data(index)
                if not text or view.indexWidget(index) is not None:
                    continue
                rect = view.visualRect(index).adjusted(2, 1, -2, -1)
                if rect.width() > 6 and rect.intersected(vp.rect()) == rect:
                    self.text(f"cell {str(text)[:30]!r}", vp, rect)

    # -- plots ----------------------------------------------------------------------------------------
    def scene_rect(self, view: PlotView, rect: QRectF) -> QRect:
        """A scene rectangle in the plot widget's viewport coordinates."""
        return view.plot_widget.mapFromScene(rect).boundingRect().adjusted(1, 1, -1, -1)

    def plot(self, view: PlotView) -> None:
        vp = view.plot_widget.viewport()
        bg = QColor(view.palette_colors()["bg"])
        name = view.title
        for side in ("left", "bottom"):
            axis = view.plot.getAxis(side)
            if axis.isVisible():  # the tick numbers, the axis line and the title (not the grid the
                # axis draws over the data area: its bounding rectangle covers that too)
                self.text(f"{name}: {side} axis", vp, self.scene_rect(view, axis.mapRectToScene(axis.rect())))
                if axis.labelText and axis.label.isVisible():
                    self.text(f"{name}: {side} axis title", vp,
                              self.scene_rect(view, axis.label.sceneBoundingRect()))
        if view.plot.titleLabel.isVisible() and view.plot.titleLabel.text:
            self.text(f"{name}: plot title", vp, self.scene_rect(view, view.plot.titleLabel.sceneBoundingRect()))
        for item in view.plot.scene().items():
            if isinstance(item, QGraphicsTextItem) and item.isVisible() and item.toPlainText().strip() \
                    and item.opacity() > 0.5:
                self.text(f"{name}: text {item.toPlainText()[:30]!r}", vp,
                          self.scene_rect(view, item.sceneBoundingRect()))
        legend = view.legend
        if legend is not None and legend.isVisible():
            for sample, label in legend.items:
                if not label.isVisible():
                    continue
                self.text(f"{name}: legend {label.text[:30]!r}", vp, self.scene_rect(view, label.sceneBoundingRect()))
                if not is_shading_swatch(sample.item):
                    s = self.surface(vp)
                    px = s.pixels(s.rect_of(vp, self.scene_rect(view, sample.sceneBoundingRect())))
                    self.results.append((f"{name}: legend sample {label.text[:30]!r}",
                                         ink_contrast(px, np.array(bg.getRgb()[:3])), AA_GRAPHICS))
        for item in view.plot.listDataItems():
            if not item.isVisible():
                continue
            x, _y = item.getData()
            if x is None or len(x) == 0:
                continue
            label = item.name() or type(item).__name__
            pen = None if isinstance(item, pg.ScatterPlotItem) else item.opts.get("pen")
            if pen is not None and pg.mkPen(pen).style() != pg.QtCore.Qt.PenStyle.NoPen:
                self.colour(f"{name}: curve {label!r}", pg.mkPen(pen).color(), bg)
            elif isinstance(item, pg.ScatterPlotItem):
                self.marker(f"{name}: markers {label!r}", item.opts["brush"], item.opts["pen"], bg)
            elif item.opts.get("symbol") is not None and not is_shading_swatch(item):
                self.marker(f"{name}: markers {label!r}", item.opts.get("symbolBrush"), item.opts.get("symbolPen"), bg)

    def marker(self, what: str, brush: object, pen: object, bg: QColor) -> None:
        """A marker shows by its fill or by its outline, whichever stands out more."""
        colours = [pg.mkBrush(brush).color()] if pg.mkBrush(brush).style() != pg.QtCore.Qt.BrushStyle.NoBrush else []
        if pen is not None and pg.mkPen(pen).style() != pg.QtCore.Qt.PenStyle.NoPen:
            colours.append(pg.mkPen(pen).color())
        before = len(self.results)
        for c in colours:
            self.colour(what, c, bg)
        best = max((r for _w, r, _q in self.results[before:]), default=None)
        del self.results[before:]
        self.results.append((what, best, AA_GRAPHICS))


def is_shading_swatch(item: object) -> bool:
    """A legend-only sample of a translucent shading (app.views.legend_row.swatch): exempt, as the
    shading is (bounded by a checked curve)."""
    if not isinstance(item, pg.PlotDataItem) or item.opts.get("pen") is not None:
        return False
    brush = pg.mkBrush(item.opts.get("symbolBrush"))
    return brush.color().alpha() < 255


def settle(window, qtbot) -> None:
    tab = window.tabs.currentWidget()
    if isinstance(tab, SampledTab):
        qtbot.waitUntil(lambda: all(window.graph.is_fresh(n) for n in ASYNC_NODES), timeout=120000)
    qtbot.waitUntil(lambda: not tab.stale, timeout=20000)
    qtbot.wait(100)


def tab_contrast(window, qtbot, where: str | None = None, whole: bool = True) -> tuple[list[str], int]:
    """Every widget and plot of the current tab (settled), and with ``whole`` the rest of the window
    (the verdict bar, the parameter panel, the tab bar): the ones below AA (named by ``where``, default
    the tab's title), and how many were measured.  A sweep over the tabs in one theme measures the
    rest of the window once (it is the same on every tab)."""
    window.grab()  # lays out and polishes whatever the last refresh changed, before any rectangle is read
    qtbot.wait(50)
    name = window.tabs.tabText(window.tabs.currentIndex()) if where is None else where
    probe = Probe(window)
    probe.widgets(window if whole else window.tabs.currentWidget())
    for view in window.tabs.currentWidget().findChildren(PlotView):
        if view.isVisible():
            probe.plot(view)
    problems = []
    for what, ratio, required in probe.results:
        if ratio is not None and ratio < required:
            problems.append(f"{name}: {what}: contrast {ratio:.2f} < {required}")
        elif ratio is None and what.startswith(("label", "rich text", "tab title", "legend", "cell")):
            problems.append(f"{name}: {what}: no text found")
    return problems, len(probe.results)


def low_contrast(window, qtbot, tabs: list[int] | None = None) -> tuple[list[str], int]:
    """Every widget and plot of every tab (or of the ``tabs`` given, by index), the verdict bar and the
    parameter panel: the ones below AA, and how many were measured.

    The sweep of every tab in both themes (dark as stored, light, dark again after the display
    switch, then light on the current tab) runs :func:`tab_contrast` in the layout sweep's pass
    over every tab at 1600×1000 (``test_laptop_layout.py``), which settles each tab once for all
    its checks."""
    problems, measured = [], 0
    for i in range(window.tabs.count()) if tabs is None else tabs:
        window.tabs.setCurrentIndex(i)
        settle(window, qtbot)
        found, n = tab_contrast(window, qtbot)
        problems += found
        measured += n
    return problems, measured


def test_rho_one_contour_shows_on_the_map_and_both_backgrounds():
    """The ρ = 1 contour runs through the map's white band: a dark line on a light halo."""
    cmap = radius_colormap(0.8, 1.2)
    white = np.array(cmap.map(0.5, mode="byte")[:3])  # the colour at rho = 1
    ends = [np.array(cmap.map(t, mode="byte")[:3]) for t in (0.0, 1.0)]
    line, halo = (np.array(QColor(c).getRgb()[:3]) for c in (CONTOUR_PEN, CONTOUR_HALO))
    assert contrast(line, white) >= AA
    assert all(contrast(halo, end) >= 3.0 for end in ends)  # the halo shows beside deep blue and red
    assert contrast(line, halo) >= AA
    view = StabilityMapView()
    assert QColor(view.contour.pen.color()).name() == QColor(CONTOUR_PEN).name()
    for dark in (False, True):
        view.apply_theme(dark)  # the theme does not make the contour light
        assert QColor(view.contour.pen.color()).name() == QColor(CONTOUR_PEN).name()
        assert view.contour_halo.pen.widthF() > view.contour.pen.widthF()
