"""Exported PNGs (issue 22): the y-axis title clear of the tick labels, the legend at the axis text's
size, the map's subtitle inside the image -- at the export's scale, for the plots of every kind.

The geometry is read from the pyqtgraph items as the export drew them: the tick label boxes are
the axis's own draw specs at the geometry it had during the render, and each item's scale is
the painter's while it painted (a legend drawn at screen size in a 2x image was half the size
of the axis text; a plot whose ticks had just changed drew its y title over them).
"""

from __future__ import annotations

from pathlib import Path

import pyqtgraph as pg
import pytest
from PySide6.QtCore import QRectF
from PySide6.QtGui import QColor, QImage, QPainter, QPicture
from PySide6.QtWidgets import QApplication

from analysis.profiles.io import bundled_profiles, load_profile
from app.report.content import gather
from app.views import export
from app.views.base import PlotView
from app.views.range_plot import RangePlot
from app.views.sampled_summary import map_subtitle
from app.views.stability_map import StabilityMapView
from app.views.stability_plot import StabilityPlot

SIZE = (520, 360)


@pytest.fixture(scope="module")
def contents():
    """The report's results of the HBFD and Eom presets (the map only for the HBFD)."""
    return {name: gather(load_profile(bundled_profiles()[name]), source=name, sampled=name == "hbfd")
            for name in ("hbfd", "eom")}


def legend_box_width(image: QImage, view: PlotView, scale: float) -> float:
    """The legend's frame in the PNG: the distance between its left and right border lines (the
    columns where a grey line runs down most of the legend's height), in image pixels."""
    r = view.legend.sceneBoundingRect()
    x0, y0 = max(0, int(r.left() * scale) - 4), max(0, int(r.top() * scale) - 4)
    x1, y1 = min(image.width(), int(r.right() * scale) + 5), min(image.height(), int(r.bottom() * scale) + 5)
    columns = []
    for x in range(x0, x1):
        run = sum(1 for y in range(y0, y1) if _frame_grey(QColor(image.pixel(x, y))))
        if run >= 0.5 * r.height():
            columns.append(x)
    assert len(columns) >= 2, "no legend frame found"
    return float(columns[-1] - columns[0])


def _frame_grey(c: QColor) -> bool:
    """A pixel of the legend's grey frame (antialiased): grey, darker than the grid lines."""
    return max(c.red(), c.green(), c.blue()) < 190 and max(c.red(), c.green(), c.blue()) - min(
        c.red(), c.green(), c.blue()) < 40


def show(view: PlotView) -> PlotView:
    view.apply_theme(False)
    view.resize(*SIZE)
    view.show()
    QApplication.processEvents()
    return view


def tick_label_boxes(axis: pg.AxisItem) -> list[QRectF]:
    """The axis's tick labels as drawn at its current geometry, in scene coordinates."""
    picture = QPicture()
    painter = QPainter(picture)
    try:
        painter.setFont(axis.style["tickFont"])
        specs = axis.generateDrawSpecs(painter)
    finally:
        painter.end()
    assert specs is not None
    return [axis.mapRectToScene(rect) for rect, _flags, text in specs[2] if text]


def title_box(axis: pg.AxisItem) -> QRectF:
    """The axis title's text (its document margin taken off) in scene coordinates."""
    margin = axis.label.document().documentMargin()
    return axis.label.mapRectToScene(axis.label.boundingRect().adjusted(margin, margin, -margin, -margin))


def export_at(view: PlotView, path: Path, scale: int = 2) -> QImage:
    width = view.plot_widget.viewport().width() * scale
    export.export_png(view, path, width)
    image = QImage(str(path))
    assert image.width() == width
    return image


def check_y_title_clear(view: PlotView) -> None:
    axis = view.plot.getAxis("left")
    title = title_box(axis)
    boxes = tick_label_boxes(axis)
    assert len(boxes) >= 2
    overlaps = [b for b in boxes if b.intersects(title)]
    assert not overlaps, f"y title {title} over tick labels {overlaps}"
    assert title.right() < min(b.left() for b in boxes)


def _stability_then_other_ticks(contents) -> StabilityPlot:
    view = show(StabilityPlot())
    view.update_result(contents["eom"].results["stability"])
    QApplication.processEvents()  # laid out for the Eom's ticks ...
    view.update_result(contents["hbfd"].results["stability"])  # ... then new ticks, exported at once
    return view


def _range_then_other_ticks(contents) -> RangePlot:
    view = show(RangePlot())
    view.update_result(contents["eom"].results["stability"])
    QApplication.processEvents()
    view.update_result(contents["hbfd"].results["stability"])
    return view


@pytest.mark.parametrize("build", [_stability_then_other_ticks, _range_then_other_ticks], ids=["bound", "range"])
def test_y_title_clears_the_tick_labels_of_a_just_updated_plot(contents, tmp_path, build):
    view = build(contents)
    export_at(view, tmp_path / "plot.png")
    check_y_title_clear(view)


@pytest.mark.parametrize("scale", [1, 2, 3])
def test_legend_text_is_the_axis_text_size_at_any_export_scale(contents, tmp_path, scale):
    """The legend is drawn at the export's scale, like the axes: its frame in the PNG is the scene's
    width times the scale (it was the screen's width at any scale, its 9 pt text half the 9 pt tick
    labels' size at 2x), and its text's size is the tick labels' within 10 %."""
    view = show(StabilityPlot())
    view.update_result(contents["hbfd"].results["stability"])
    QApplication.processEvents()
    image = export_at(view, tmp_path / "plot.png", scale)
    drawn = legend_box_width(image, view, scale)
    expected = view.legend.sceneBoundingRect().width() * scale
    assert drawn == pytest.approx(expected, rel=0.05, abs=3)
    legend_scale = drawn / view.legend.sceneBoundingRect().width()
    axis = view.plot.getAxis("left")
    tick_px = axis.style["tickFont"].pointSizeF() * scale
    label = view.legend.items[0][1]
    legend_px = float(str(label.opts["size"]).removesuffix("pt")) * legend_scale
    assert legend_px == pytest.approx(tick_px, rel=0.10)


@pytest.mark.parametrize("width", [300, 520, 900])
def test_map_subtitle_is_inside_the_image(contents, tmp_path, width):
    hbfd = contents["hbfd"]
    m = hbfd.results["map"]
    view = StabilityMapView()
    view.apply_theme(False)
    view.resize(width, SIZE[1])
    view.show()
    QApplication.processEvents()
    view.update_map(m, map_subtitle(hbfd.profile, m, 1, True))
    image = export_at(view, tmp_path / "map.png", 2)
    title = view.plot.titleLabel
    assert title.isVisible() and title.text
    item = title.item
    margin = item.document().documentMargin()
    box = item.mapRectToScene(item.boundingRect().adjusted(margin, margin, -margin, -margin))
    src = QRectF(view.plot_widget.viewport().rect())
    assert src.contains(box), f"subtitle {box} outside the exported area {src}"
    # and the axes' titles stay clear of their ticks in the same export
    check_y_title_clear(view)
    assert image.height() == round(src.height() * image.width() / src.width())


def test_cli_exports_keep_the_y_title_clear(tmp_path):
    """Every plot the command line exports from the HBFD preset that has a y axis with labels."""
    from app.cli import PLOTS
    from app.report.figures import figure_parts, make_view

    plots = ("bound", "reserve", "range", "chart", "map", "scenario-position")
    # only what these figures draw, as export-plot gathers (not the Z-width region and its optimum)
    content = gather(load_profile(bundled_profiles()["hbfd"]), source="hbfd", sampled=True,
                     parts=figure_parts(PLOTS[p] for p in plots))
    for plot in plots:
        fig = make_view(content, PLOTS[plot])
        assert fig is not None, plot
        export_at(fig.view, tmp_path / f"{plot}.png", 2)
        check_y_title_clear(fig.view)
