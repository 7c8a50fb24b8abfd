"""Export plots: PNG at a chosen pixel width, SVG, and CSV of the plotted data.

PNG and SVG render the plot's scene with QPainter, so the output size is what was asked for,
independent of the screen's device pixel ratio (HiDPI-correct), through the one export renderer
:func:`app.views.render.render_view` (the plot as on screen, scaled as one picture).  The CSV has one x and one y
column per curve, each headed ``curve: quantity [unit]`` (:data:`HEADER_PATTERN`; the plot's own
spelling: ``ω [rad/s]``, ``b_c [N·s/m]``, ``‖L‖∞ [-]``, ``-`` for a dimensionless number); every
number in the unit its header names (never the log10 a log axis draws), and nothing the view
leaves off-scale is dropped.  An empty field means "not defined here": a curve shorter than
another, or a NaN of the data (no filter has no cut-off, no K is stable at that B); ``inf`` and
``-inf`` are written as such (``float()`` reads them).  A view's notes (an empty result) come
first as ``# note:`` lines.

A table (:func:`table_csv_text`: one row per grid point, as ``zwidth space`` and ``zwidth
workspace`` write) is the same form with one column per quantity, each headed ``quantity [unit]``
(:data:`TABLE_HEADER_PATTERN`); a flag or an index is written as its digits.
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
from collections.abc import Sequence

import numpy as np

from PySide6.QtCore import QByteArray, QBuffer, QIODevice, QRectF, QSize
from PySide6.QtGui import QColor, QImage, QPainter, QPicture

from analysis.profiles import WriteError, atomic_write
from analysis.study.quantities import ascii_numbers

from app.views.base import Axis, PlotView
from app.views.render import render_view, settle_layout

__all__ = ["export_png", "export_svg", "svg_bytes", "export_csv", "csv_text", "render_view", "settle_layout",
           "ExportError", "FORMATS", "HEADER_PATTERN", "DIMENSIONLESS", "column_header", "csv_field",
           "TABLE_HEADER_PATTERN", "table_header", "table_csv_text"]

FORMATS = {"png": "PNG image (*.png)", "svg": "SVG drawing (*.svg)", "csv": "CSV data (*.csv)"}


class ExportError(OSError):
    pass


def _write_atomic(path: str | os.PathLike, data: bytes) -> None:
    """:func:`analysis.profiles.atomic_write`, its error as an :class:`ExportError`."""
    try:
        atomic_write(path, data)
    except WriteError as err:
        raise ExportError(str(err)) from err


def _source(view: PlotView) -> QRectF:
    return QRectF(view.plot_widget.viewport().rect())


def export_png(view: PlotView, path: str | os.PathLike, width: int, height: int | None = None) -> QSize:
    """Write the plot as a PNG ``width`` pixels wide (height keeps the aspect ratio unless given)."""
    src = _source(view)
    if width < 16 or width > 20000:
        raise ExportError("PNG width must be between 16 and 20000 pixels")
    if height is None:
        height = max(1, round(width * src.height() / max(src.width(), 1.0)))
    image = QImage(width, height, QImage.Format.Format_ARGB32_Premultiplied)  # the raster fast path (same pixels: opaque)
    image.setDevicePixelRatio(1.0)
    image.fill(QColor(view.palette_colors()["bg"]))
    painter = QPainter(image)
    try:
        render_view(view, painter, QRectF(0, 0, width, height))
    finally:
        painter.end()
    buf = QByteArray()
    dev = QBuffer(buf)
    dev.open(QIODevice.OpenModeFlag.WriteOnly)
    if not image.save(dev, "PNG"):
        raise ExportError("PNG encoding failed")
    dev.close()
    _write_atomic(path, bytes(buf.data()))
    return QSize(width, height)


def export_svg(view: PlotView, path: str | os.PathLike) -> None:
    """Write the plot as an SVG drawing (vector)."""
    try:
        import PySide6.QtSvg  # noqa: F401
    except ImportError:  # pragma: no cover - PySide6 without QtSvg: pyqtgraph's own exporter
        from pyqtgraph.exporters import SVGExporter

        text = SVGExporter(view.plot.scene()).export(toBytes=True)
        _write_atomic(path, bytes(text))
        return
    _write_atomic(path, svg_bytes(view, view.title, view.palette_colors()["bg"], "zwidth plot"))


def svg_bytes(view: PlotView, title: str, background: str, description: str = "") -> bytes:
    """The plot as an SVG document (QSvgGenerator; vector axes, curves and text).

    The generator's resolution is that of a QPicture: pyqtgraph's axes record their ticks, labels
    and grid in a QPicture, and a QPicture played on a device of another resolution is scaled by
    the ratio (QSvgGenerator's default 72 dpi against the screen's 96 drew the axes at 75 % of
    the curves' scale; pyqtgraph's own exporter sets the screen's dpi for the same reason).
    """
    from PySide6.QtSvg import QSvgGenerator

    src = _source(view)
    buf = QByteArray()
    dev = QBuffer(buf)
    dev.open(QIODevice.OpenModeFlag.WriteOnly)
    gen = QSvgGenerator()
    gen.setOutputDevice(dev)
    gen.setResolution(QPicture().logicalDpiX())
    gen.setSize(src.size().toSize())
    gen.setViewBox(QRectF(0, 0, src.width(), src.height()))
    gen.setTitle(title)
    if description:
        gen.setDescription(description)
    painter = QPainter(gen)
    try:
        painter.fillRect(QRectF(0, 0, src.width(), src.height()), QColor(background))
        render_view(view, painter, QRectF(0, 0, src.width(), src.height()))
    finally:
        painter.end()
    dev.close()
    return bytes(buf.data())


#: the unit a CSV header gives a dimensionless quantity (a plot's axis says "–" or nothing)
DIMENSIONLESS = "-"
_DIMENSIONLESS_UNITS = ("", "–", "-")
#: every CSV column header: ``curve: quantity [unit]`` (the curve's name may hold ": ", the
#: quantity and the unit hold no brackets)
HEADER_PATTERN = re.compile(r"^(?P<curve>.+): (?P<quantity>[^\[\]]+) \[(?P<unit>[^\[\]]+)\]$")
#: every header of a table CSV: ``quantity [unit]`` (no curve: a column is one quantity over the grid)
TABLE_HEADER_PATTERN = re.compile(r"^(?P<quantity>[^\[\]:]+) \[(?P<unit>[^\[\]]+)\]$")


def _unit(axis: Axis) -> str:
    return DIMENSIONLESS if axis.unit.strip() in _DIMENSIONLESS_UNITS else axis.unit


def column_header(curve: str, axis: Axis) -> str:
    """A CSV column's header: ``"Re(1/Z_c): ω [rad/s]"`` (:data:`HEADER_PATTERN`); the curve's own
    name is the quantity where the axis names none (a plot of several dimensionless curves)."""
    return f"{curve}: {axis.quantity.strip() or curve} [{_unit(axis)}]"


def table_header(axis: Axis) -> str:
    """A table column's header: ``"B [N·s/m]"`` (:data:`TABLE_HEADER_PATTERN`)."""
    return f"{axis.quantity.strip()} [{_unit(axis)}]"


def csv_field(value: float) -> str:
    """A number as a CSV field: the shortest text that reads back exactly, ``inf``/``-inf``, and an
    empty field for NaN (not defined here)."""
    x = float(value)
    return "" if math.isnan(x) else repr(x)


def _notes(out: io.StringIO, notes: Sequence[str]) -> None:
    for note in notes:  # e.g. why a chart is empty: "# note: ..." before the header, its numbers in ASCII
        out.write("# note: " + " ".join(ascii_numbers(note).split()) + "\n")


def csv_text(view: PlotView) -> str:
    """The plotted data as CSV text: a header row (:func:`column_header`), then x/y columns per curve."""
    series = view.export_series()
    out = io.StringIO()
    _notes(out, view.export_notes())
    w = csv.writer(out, lineterminator="\n")
    header: list[str] = []
    for s in series:
        header += [column_header(s.name, s.x_label), column_header(s.name, s.y_label)]
    w.writerow(header)
    rows = max((len(s.x) for s in series), default=0)
    for i in range(rows):
        row: list[str] = []
        for s in series:
            if i < len(s.x):
                row += [csv_field(s.x[i]), csv_field(s.y[i])]
            else:
                row += ["", ""]
        w.writerow(row)
    return out.getvalue()


def table_csv_text(columns: Sequence[tuple[Axis, Sequence[float] | np.ndarray]], notes: Sequence[str] = ()) -> str:
    """A table as CSV text: ``# note:`` lines, a header row (:func:`table_header`), one row per point.

    ``columns`` are (axis, values) of equal length (a grid flattened by the caller); a number is
    written as :func:`csv_field` writes it (NaN empty, ``inf`` kept), an integer or boolean column
    (a flag, an index) as its digits.
    """
    arrays = [np.asarray(values).ravel() for _, values in columns]
    if len({a.size for a in arrays}) > 1:
        raise ValueError("table_csv_text: the columns differ in length")
    fields = [[str(int(v)) for v in a] if a.dtype.kind in "biu" else [csv_field(v) for v in a] for a in arrays]
    out = io.StringIO()
    _notes(out, notes)
    w = csv.writer(out, lineterminator="\n")
    w.writerow([table_header(axis) for axis, _ in columns])
    w.writerows(zip(*fields))
    return out.getvalue()


def export_csv(view: PlotView, path: str | os.PathLike) -> None:
    _write_atomic(path, csv_text(view).encode("utf-8"))


