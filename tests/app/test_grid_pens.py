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


def _specs(axis, build) -> tuple[list, list]:
    """Tick positions and label rectangles and texts of ``build(axis, painter)``."""
    image = QImage(8, 8, QImage.Format.Format_ARGB32_Premultiplied)
    painter = QPainter(image)
    try:
        _axis, ticks, texts = build(axis, painter)
    finally:
        painter.end()
    return ([(p1.x(), p1.y(), p2.x(), p2.y()) for _pen, p1, p2 in ticks],
            [(r.x(), r.y(), r.width(), r.height(), text) for r, _flags, text in texts])


@pytest.mark.parametrize("log", [False, True])
def test_the_held_bounds_give_pyqtgraphs_own_ticks_and_labels(qapp, log):
    """The axis reuses its bounding rectangle while it builds its draw specs (pyqtgraph asked for it
    once per tick label): the same ticks, labels and places as pyqtgraph's own build, and the rectangle
    is pyqtgraph's again afterwards."""
    import pyqtgraph as pg

    view = StabilityPlot()
    view.resize(700, 420)
    view.show()
    view.plot.setLogMode(log, log)
    view.plot.setXRange(0.3 if log else -3.0, 3.7 if log else 7.0, padding=0)
    view.plot.setYRange(-1.2 if log else -0.5, 2.9 if log else 2.5, padding=0)
    QApplication.processEvents()
    for name in ("left", "bottom"):
        axis = view.plot.getAxis(name)
        ours = _specs(axis, LogAxis.generateDrawSpecs)
        theirs = _specs(axis, pg.AxisItem.generateDrawSpecs)
        assert ours == theirs and len(ours[1]) >= 3, name
        assert axis.boundingRect() == pg.AxisItem.boundingRect(axis)
    view.deleteLater()


def test_a_geometry_change_while_the_specs_are_built_is_not_served_the_old_rectangle(qapp):
    """A label measured after the axis was resized mid-build gets the new rectangle (the held one is
    reused only while the geometry is the one it was taken at)."""
    import pyqtgraph as pg

    class Growing(LogAxis):
        seen: list = []

        def tickStrings(self, values, scale, spacing):  # noqa: N802 - pyqtgraph API
            self.setGeometry(self.geometry().adjusted(0, 0, 0, 40))
            self.seen.append((self.boundingRect(), pg.AxisItem.boundingRect(self)))
            return super().tickStrings(values, scale, spacing)

    widget = pg.PlotWidget(axisItems={"left": Growing("left")})
    widget.resize(500, 300)
    widget.show()
    QApplication.processEvents()
    axis = widget.getPlotItem().getAxis("left")
    _specs(axis, LogAxis.generateDrawSpecs)
    assert axis.seen and all(ours == theirs for ours, theirs in axis.seen)
    widget.deleteLater()
