"""The plots' grid (app.views.base.LogAxis): opaque lines of the colour the translucent grid had over
the plot's background, under the data.  Same pixels where the grid shows; Qt's raster engine draws an
opaque line about twenty times faster than a translucent one, and the grid was most of an axis's
repaint (issue 21)."""

from __future__ import annotations

import pytest
from PySide6.QtCore import QLineF
from PySide6.QtGui import QColor, QImage, QPainter, QPen
from PySide6.QtWidgets import QApplication

from app.views.base import LogAxis, opaque_pen
from app.views.stability_plot import StabilityPlot
from app.widgets.colors import PALETTE


def _line_pixel(pen: QPen, background: QColor) -> QColor:
    image = QImage(20, 9, QImage.Format.Format_RGB32)
    image.fill(background)
    painter = QPainter(image)
    painter.setPen(pen)
    painter.drawLine(QLineF(0, 4, 19, 4))
    painter.end()
    return image.pixelColor(10, 4)


@pytest.mark.parametrize("theme", ["light", "dark"])
@pytest.mark.parametrize("alpha", [13, 26, 63, 200])
def test_an_opaque_grid_line_has_the_translucent_lines_pixels(theme, alpha):
    background = QColor(PALETTE[theme]["bg"])
    colour = QColor(PALETTE[theme]["fg"])
    colour.setAlpha(alpha)
    pen = QPen(colour, 1.0)
    pen.setCosmetic(True)
    solid = opaque_pen(pen, background)
    assert solid.color().alpha() == 255 and solid.widthF() == pen.widthF() and solid.isCosmetic()
    a, b = _line_pixel(pen, background), _line_pixel(solid, background)
    assert max(abs(a.red() - b.red()), abs(a.green() - b.green()), abs(a.blue() - b.blue())) <= 1, (a.name(), b.name())
    assert a != background  # the line was drawn
    opaque = QPen(QColor(PALETTE[theme]["fg"]))
    assert opaque_pen(opaque, background) is opaque


@pytest.mark.parametrize("dark", [False, True])
def test_a_views_grid_is_opaque_under_the_data(qapp, dark):
    view = StabilityPlot()
    view.apply_theme(dark)
    view.resize(600, 400)
    view.show()
    QApplication.processEvents()
    vb = view.plot.getViewBox()
    for name in ("left", "bottom"):
        axis = view.plot.getAxis(name)
        assert isinstance(axis, LogAxis) and axis.grid_background == QColor(view.palette_colors()["bg"])
        image = QImage(8, 8, QImage.Format.Format_ARGB32_Premultiplied)
        painter = QPainter(image)
        try:
            _axis, ticks, _texts = axis.generateDrawSpecs(painter)
        finally:
            painter.end()
        assert len(ticks) > 3  # the grid lines are there
        assert all(pen.color().alpha() == 255 for pen, _p1, _p2 in ticks), name
        assert axis.zValue() < vb.zValue()  # under the data
    view.deleteLater()


def test_the_hidden_axes_are_not_retypeset_on_a_range_change(qapp):
    """pyqtgraph's hidden top and right axes re-typeset their label (auto SI prefix) on every range
    change: about 6 600 times in five tab test files.  No view shows them; they keep still."""
    view = StabilityPlot()
    view.resize(600, 400)
    view.show()
    QApplication.processEvents()
    changes = {"top": 0, "right": 0}
    for name in changes:
        axis = view.plot.getAxis(name)
        assert not axis.isVisible() and not axis.autoSIPrefix
        axis.label.document().contentsChanged.connect(lambda name=name: changes.__setitem__(name, changes[name] + 1))
    for lo, hi in ((1.0, 10.0), (2.0, 300.0), (0.5, 7.0)):
        view.plot.setXRange(lo, hi, padding=0)
        view.plot.setYRange(lo, hi, padding=0)
        QApplication.processEvents()
    assert changes == {"top": 0, "right": 0}
    view.deleteLater()
