"""Both themes: the verdict's numbers and every plot's axis titles are readable (WCAG AA, 4.5:1).

The window is rendered (``grab()``) and the colours are read from the pixels, so what is checked
is what the user sees: in a label's (or an axis title's) rectangle the background is the most
common colour, the text colour is that of the glyphs' cores (the pixels differing most from the
background), and their contrast ratio is computed from relative luminance (WCAG 2.x).
The theme is switched at run time (light -> dark -> light) and the display switched while dark:
both used to leave black text on dark grey.  One window goes through every tab in each state
(the pixels of each grab are converted once and their colours counted as packed integers).
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QRect
from PySide6.QtGui import QColor, QImage
from PySide6.QtWidgets import QLabel

from analysis.profiles.io import bundled_profiles, load_profile

from app.tabs.sampled_tab import ASYNC_NODES, SampledTab
from app.views.base import PlotView
from app.views.stability_map import CONTOUR_HALO, CONTOUR_PEN, StabilityMapView, radius_colormap

AA = 4.5


def luminance(rgb: np.ndarray) -> np.ndarray:
    """WCAG relative luminance of sRGB colours (..., 3) in 0..255."""
    c = np.asarray(rgb, float) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return lin @ np.array([0.2126, 0.7152, 0.0722])


def contrast(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    la, lb = luminance(a), luminance(b)
    return (np.maximum(la, lb) + 0.05) / (np.minimum(la, lb) + 0.05)


_RGB_CACHE: dict[int, np.ndarray] = {}


def rgb_array(image: QImage) -> np.ndarray:
    """The image's RGB pixels as an (H, W, 3) array, converted once per image (by its cacheKey):
    one window grab is read for a few hundred labels."""
    key = image.cacheKey()
    arr = _RGB_CACHE.get(key)
    if arr is None:
        img = image.convertToFormat(QImage.Format.Format_RGB888)
        raw = np.frombuffer(img.constBits(), np.uint8, img.sizeInBytes()).reshape(img.height(), img.bytesPerLine())
        arr = raw[:, : img.width() * 3].reshape(img.height(), img.width(), 3).copy()
        _RGB_CACHE.clear()  # one image at a time: the current grab
        _RGB_CACHE[key] = arr
    return arr


def pixels(image: QImage, rect: QRect) -> np.ndarray:
    """The RGB pixels of ``rect`` in ``image`` (device-independent pixels) as an (N, 3) array."""
    arr = rgb_array(image)
    ratio = image.devicePixelRatio()
    r = QRect(int(rect.x() * ratio), int(rect.y() * ratio), int(rect.width() * ratio), int(rect.height() * ratio))
    r = r.intersected(QRect(0, 0, arr.shape[1], arr.shape[0]))
    assert r.width() > 0 and r.height() > 0, f"{rect} is outside the image"
    return arr[r.top(): r.bottom() + 1, r.left(): r.right() + 1].reshape(-1, 3).astype(int)


def text_contrast(image: QImage, rect: QRect) -> float:
    """Contrast of the text in ``rect`` with its background (most common colour)."""
    px = pixels(image, rect)
    # the distinct colours, packed as 0xRRGGBB: sorted as the RGB rows are (R, then G, then B)
    codes, inverse, counts = np.unique((px[:, 0] << 16) | (px[:, 1] << 8) | px[:, 2],
                                       return_inverse=True, return_counts=True)
    colours = np.stack([codes >> 16, (codes >> 8) & 255, codes & 255], axis=1)
    bg = colours[np.argmax(counts)]
    ratios = contrast(colours, bg[None, :])[inverse.ravel()]  # each pixel's, from its colour's
    ink = ratios[ratios > 1.05]
    assert ink.size >= 10, f"no text found in {rect}"
    # the glyphs' cores: the top few per cent of the pixels that differ from the background
    return float(np.percentile(ink, 97))


def rect_in_window(window, widget, rect: QRect | None = None) -> QRect:
    rect = rect if rect is not None else widget.rect()
    return QRect(widget.mapTo(window, rect.topLeft()), rect.size())


def axis_title_rects(window, view: PlotView) -> dict[str, QRect]:
    out = {}
    for name in ("left", "bottom"):
        axis = view.plot.getAxis(name)
        if not axis.isVisible() or not axis.labelText:
            continue
        scene_rect = axis.label.sceneBoundingRect()
        vp = view.plot_widget.viewport()
        poly = view.plot_widget.mapFromScene(scene_rect).boundingRect()
        top_left = vp.mapTo(window, poly.topLeft())
        out[f"{view.title} {name} axis title"] = QRect(top_left, poly.size()).adjusted(1, 1, -1, -1)
    return out


def settle(window, qtbot) -> None:
    tab = window.tabs.currentWidget()
    if isinstance(tab, SampledTab):
        qtbot.waitUntil(lambda: all(window.graph.is_fresh(n) for n in ASYNC_NODES), timeout=120000)
    qtbot.waitUntil(lambda: not tab.stale, timeout=20000)
    qtbot.wait(100)


def low_contrast(window, qtbot, tabs: list[int] | None = None) -> list[str]:
    """Every verdict value and title, and every visible plot's axis titles, on every tab (or on
    the ``tabs`` given, by index)."""
    problems = []
    for i in range(window.tabs.count()) if tabs is None else tabs:
        window.tabs.setCurrentIndex(i)
        settle(window, qtbot)
        image = window.grab().toImage()
        rects = {}
        for label in (*window.verdict.values, *window.verdict.titles):
            rects[f"verdict {label.text()!r}"] = rect_in_window(window, label, label.contentsRect())
        for label in window.findChildren(QLabel):  # every other text on screen (disabled ones excepted)
            if label.isVisible() and label.isEnabled() and label.text().strip() and label.width() > 4 \
                    and label.visibleRegion().boundingRect() == label.rect():  # not scrolled out of view
                rects.setdefault(f"label {label.text()[:40]!r}", rect_in_window(window, label, label.contentsRect()))
        for view in window.tabs.currentWidget().findChildren(PlotView):
            if view.isVisible():
                rects.update(axis_title_rects(window, view))
        for what, rect in rects.items():
            ratio = text_contrast(image, rect)
            if ratio < AA:
                problems.append(f"{window.tabs.tabText(i)}: {what}: contrast {ratio:.2f} < {AA}")
    return problems


def test_text_contrast_in_both_themes(qtbot, settings):
    """One window through every tab three times: light, dark, and dark again after the display
    switch (admittance: relabels the axes while dark); then back to light on the current tab."""
    from app.window.main_window import MainWindow

    w = MainWindow(settings=settings, profile=load_profile(bundled_profiles()["hbfd"]))
    try:
        w.resize(1400, 900)
        w.show()
        qtbot.waitExposed(w)
        badge = w.verdict.badge
        problems = []
        w.set_theme("light")
        problems += [f"light: {p}" for p in low_contrast(w, qtbot)]
        w.set_theme("dark")
        problems += [f"dark: {p}" for p in low_contrast(w, qtbot)]
        w.editor.edit("display", "admittance")
        problems += [f"dark, admittance: {p}" for p in low_contrast(w, qtbot)]
        assert text_contrast(w.grab().toImage(), rect_in_window(w, badge, badge.contentsRect())) >= AA
        w.set_theme("light")
        problems += [f"light again, admittance: {p}" for p in low_contrast(w, qtbot, [w.tabs.currentIndex()])]
        assert not problems, "\n".join(problems)
        assert text_contrast(w.grab().toImage(), rect_in_window(w, badge, badge.contentsRect())) >= AA
    finally:
        w.undo_stack.setClean()
        w.runner.shutdown()
        w.close()
        w.deleteLater()


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
