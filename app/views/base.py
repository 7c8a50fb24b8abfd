"""What every plot view shares: the plot widget, units, crosshair readout, warnings, export data."""

from __future__ import annotations

import html
import math
import re
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QPointF, QRectF, Qt, Signal, Slot
from PySide6.QtGui import QAction, QColor, QFont, QPainter, QPen
from PySide6.QtWidgets import QGraphicsItem, QHBoxLayout, QLabel, QVBoxLayout, QWidget

from analysis.study.displays import DisplayKind
from analysis.study.quantities import format_number, superscript_numbers

from app.widgets.colors import CURSOR_COLORS, PALETTE, WARNING_COLORS
from app.views.legend_row import LegendRow
from app.views.render import render_view

__all__ = ["PlotView", "Series", "Axis", "chart_axes", "clean_xy", "fmt", "PALETTE", "mark_design_point", "rich_label"]


class Axis(NamedTuple):
    """A plotted quantity and its unit, kept apart: the CSV header writes ``quantity [unit]``.

    The spelling is the plot's own (``ω``, ``ρ``, ``‖L‖∞``, ``k_c``; ``N·s/m``, ``N²·s/m²``,
    ``m/(N·s)``); ``""`` or ``"–"`` is a dimensionless unit (written ``-``)."""

    quantity: str
    unit: str


def chart_axes(kind: DisplayKind) -> tuple[Axis, Axis]:
    """The design chart's axes of a display: its two gains (``b_c [N·s/m]``, ``k_c [N/m]`` or
    ``m_c [kg]``, ``b_c [N·s/m]``)."""
    return Axis(kind.chart_x.symbol, kind.chart_x.unit), Axis(kind.chart_y.symbol, kind.chart_y.unit)


@dataclass(frozen=True)
class Series:
    """One plotted curve as exported to CSV: its name (the legend's words), the x and y quantities
    with their units, and the data as drawn."""

    name: str
    x_label: Axis
    y_label: Axis
    x: np.ndarray
    y: np.ndarray


def rich_label(text: str) -> str:
    """A plain-text symbol as Qt rich text: ``Re(1/Z_c)`` -> ``Re(1/Z<sub>c</sub>)``."""
    return re.sub(r"_(\w+)", r"<sub>\1</sub>", text)


def fmt(x: float | None, digits: int = 4) -> str:
    """A number for rich-text labels: :func:`analysis.study.format_number` with ``rich=True``
    (``1.171×10<sup>5</sup>``, a true minus, "∞")."""
    return format_number(x, digits, rich=True)


def plain(x: float | None, digits: int = 4) -> str:
    """A number for plain-text labels a person reads (legends, notes, the cursor's status text):
    :func:`analysis.study.format_number` with ``style="text"`` (``−1.171×10⁵``, a true minus, "∞").
    A CSV's column names use the ASCII form (``format_number(x, digits)``) instead."""
    return format_number(x, digits, style="text")


#: The largest magnitude a plot draws (far beyond any physical value of the app; spans stay finite).
DRAW_LIMIT = 1e100


def clean_xy(x: np.ndarray, y: np.ndarray, log_x: bool = False, log_y: bool = False
             ) -> tuple[np.ndarray, np.ndarray, int]:
    """Drop points that cannot be drawn (non-finite, beyond :data:`DRAW_LIMIT` in magnitude, or <= 0
    on a log axis); returns how many.  A diverged simulation reaches 10^308: the span of such data
    overflows in the view's auto-range and pyqtgraph's axes then raise on a NaN range."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    with np.errstate(invalid="ignore"):
        ok = (np.abs(x) <= DRAW_LIMIT) & (np.abs(y) <= DRAW_LIMIT)
    if log_x:
        ok &= x > 0
    if log_y:
        ok &= y > 0
    return x[ok], y[ok], int(ok.size - np.count_nonzero(ok))


_SUP = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def decade_label(exponent: int) -> str:
    if -2 <= exponent <= 3:
        return f"{10.0 ** exponent:g}"
    return "10" + str(exponent).translate(_SUP)


class LogAxis(pg.AxisItem):
    """An axis whose log-mode labels are decades only (plus 2 and 5 when under two decades show); its
    linear-mode labels typeset as the views' other text (a true minus "−", ``1×10⁵``).

    Its grid lines are opaque, their colour the translucent grid colour already blended over
    :attr:`grid_background` (the plot's background; the view sets it with the theme), and the axis
    lies under the data (``z`` below the view box's): the same pixels where the grid shows, the grid
    hidden under curves and fills as in most plotting tools, and Qt's raster engine draws an opaque
    line about twenty times faster than a translucent one (the grid was most of an axis repaint)."""

    #: The colour the grid lines are blended over; ``None`` keeps pyqtgraph's translucent lines.
    grid_background: QColor | None = None
    #: The geometry and bounding rectangle while the draw specs are built (``None`` otherwise):
    #: pyqtgraph asks for the rectangle again for every tick label (a map of the geometry and of the
    #: linked view's rectangle each time); it is reused while the geometry is the same.
    _held_bounds: tuple[QRectF, QRectF] | None = None

    def generateDrawSpecs(self, p: QPainter):  # noqa: N802 - pyqtgraph API
        self._held_bounds = (self.geometry(), super().boundingRect())
        try:
            specs = super().generateDrawSpecs(p)
        finally:
            self._held_bounds = None
        bg = self.grid_background
        if specs is None or bg is None:
            return specs
        axis_spec, tick_specs, text_specs = specs
        opaque: dict[int, QPen] = {}  # the ticks of a level share one pen: blended once per level
        for pen, _p1, _p2 in tick_specs:
            if id(pen) not in opaque:
                opaque[id(pen)] = opaque_pen(pen, bg)
        return axis_spec, [(opaque[id(pen)], p1, p2) for pen, p1, p2 in tick_specs], text_specs

    def boundingRect(self) -> QRectF:  # noqa: N802 - Qt API
        held = self._held_bounds
        if held is not None and held[0] == self.geometry():
            return QRectF(held[1])
        return super().boundingRect()

    def tickStrings(self, values: list[float], scale: float, spacing: float) -> list[str]:  # noqa: N802
        return [superscript_numbers(text) for text in super().tickStrings(values, scale, spacing)]

    def logTickStrings(self, values: list[float], scale: float, spacing: float) -> list[str]:  # noqa: N802
        vals = np.asarray(values, float) + np.log10(scale)
        span = float(vals.max() - vals.min()) if vals.size else 0.0
        out = []
        for v in vals:
            e = round(v)
            if abs(v - e) < 1e-6:
                out.append(decade_label(int(e)))
                continue
            mant = 10.0 ** (v - np.floor(v))
            if span < 2.0 and any(abs(mant - m) < 1e-6 for m in (2.0, 5.0)):
                e = int(np.floor(v))
                out.append(f"{10.0 ** v:g}" if -2 <= e <= 3 else f"{mant:.0f}·{decade_label(e)}")
            else:
                out.append("")
        return out


def opaque_pen(pen: QPen, background: QColor) -> QPen:
    """``pen`` with its colour blended over ``background`` and made opaque (itself when it is opaque)."""
    c = pen.color()
    a = c.alphaF()
    if a >= 1.0:
        return pen
    out = QPen(pen)
    out.setColor(QColor.fromRgbF(a * c.redF() + (1 - a) * background.redF(), a * c.greenF() + (1 - a) * background.greenF(),
                                 a * c.blueF() + (1 - a) * background.blueF()))
    return out


def mark_design_point(item: pg.PlotDataItem, x: float, y: float, stable: bool | None, pal: dict) -> str:
    """Draw the current design as one point on log-log axes; the note to show when it cannot be."""
    if x > 0 and y > 0 and math.isfinite(x) and math.isfinite(y):
        item.setData([x], [y])
        note = ""
    else:
        item.setData([], [])
        note = "current gains not drawn (zero on a log axis)"
    item.setSymbolBrush(pal["c"] if stable else pal["mark"])
    return note


def header_row(title: str) -> tuple[QHBoxLayout, QLabel, QLabel]:
    """A plot's title (wrapped in a narrow window: never cut, never widening it) and its crosshair
    readout, in one row."""
    header = QLabel(f"<b>{title}</b>")
    header.setMinimumWidth(40)
    header.setWordWrap(True)
    header.setToolTip(title)
    cursor_label = QLabel("")
    cursor_label.setAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
    cursor_label.setMinimumWidth(120)
    cursor_label.setStyleSheet(f"color: {CURSOR_COLORS[0]}; font-family: monospace;")
    head = QHBoxLayout()
    head.setContentsMargins(4, 0, 4, 0)
    head.addWidget(header, 1)
    head.addStretch(0)  # (kept: subclasses set the row's stretches by index: title, spacer, readout)
    head.addWidget(cursor_label)
    return head, header, cursor_label


class PlotView(QWidget):
    """A titled pyqtgraph plot with a crosshair readout and a warning line.

    Subclasses add their items in ``__init__`` and implement :meth:`export_series`.
    """

    exportRequested = Signal(str)  # "png", "svg" or "csv"

    x_name = "x"
    x_unit = ""
    y_name = "y"
    y_unit = ""

    def __init__(self, title: str, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.title = title
        self.revision = 0  # bumps on every data update (tests, benchmarks)
        self._auto_before_hold: tuple | None = None  # the auto-range state a drag's hold keeps
        self._dark = False
        self.legend_row: LegendRow | None = None  # set when the legend is moved below the plot
        self._log_x = self._log_y = False
        head, self.header, self.cursor_label = header_row(title)
        self.warning = QLabel("")
        self.warning.setTextFormat(Qt.TextFormat.RichText)
        self.warning_text = ""  # the warning as plain text (exports, the report)
        self.warning.setWordWrap(True)
        self.warning.setStyleSheet(f"color: {WARNING_COLORS[0]};")
        self.warning.hide()
        self.plot_widget = pg.PlotWidget(axisItems={"bottom": LogAxis("bottom"), "left": LogAxis("left")})
        self.plot_widget.setMinimumSize(200, 160)
        self.plot: pg.PlotItem = self.plot_widget.getPlotItem()
        self.plot.showGrid(x=True, y=True, alpha=0.25)
        self.plot.setMenuEnabled(True)
        self.plot.hideButtons()
        for ax in ("left", "bottom"):
            axis = self.plot.getAxis(ax)
            # the axis (with its grid) is cached as a pixmap: a curve update does not replay its text
            axis.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
            axis.setZValue(-200)  # under the view box (-100): the grid behind the data (LogAxis)
            axis.enableAutoSIPrefix(False)
            axis.setTickFont(QFont(self.font().family(), 9))
        for ax in ("top", "right"):  # hidden on every view: not re-typeset on each range change (SI prefix)
            self.plot.getAxis(ax).enableAutoSIPrefix(False)
        self.legend = self.plot.addLegend(offset=(-10, 10), labelTextSize="9pt")
        # one "Export" in the right-click menu: ours (below), not pyqtgraph's scene exporter dialog
        self.plot_widget.scene().contextMenu = []
        self.empty_message = ""  # said in the plot (see app.views.placement) and in every export

        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(2)
        lay.addLayout(head)
        lay.addWidget(self.plot_widget, 1)
        lay.addWidget(self.warning)

        pen = pg.mkPen((128, 128, 128, 150), width=1, style=Qt.PenStyle.DashLine)
        self._vline = pg.InfiniteLine(angle=90, movable=False, pen=pen)
        self._hline = pg.InfiniteLine(angle=0, movable=False, pen=pen)
        for line in (self._vline, self._hline):
            line.setZValue(50)
            line.hide()
            self.plot.addItem(line, ignoreBounds=True)
        self.plot_widget.scene().sigMouseMoved.connect(self._on_mouse_moved)

        menu = self.plot.getViewBox().menu
        menu.addSeparator()
        for fmt_name, text in (("png", "Export PNG…"), ("svg", "Export SVG…"), ("csv", "Export CSV…")):
            act = QAction(text, self)
            act.triggered.connect(lambda _=False, f=fmt_name: self.exportRequested.emit(f))
            menu.addAction(act)
        self.export_actions = menu.actions()[-3:]

    def render_into(self, painter: QPainter, target: QRectF) -> None:
        """Paint the plot into ``target`` of any painter (PNG, SVG, PDF), vector where it can be:
        :func:`app.views.render.render_view` (the one export renderer)."""
        render_view(self, painter, target)

    # -- helpers for subclasses -----------------------------------------------------------------
    def set_axis_labels(self, x_name: str, x_unit: str, y_name: str, y_unit: str) -> None:
        if (x_name, x_unit, y_name, y_unit) == (self.x_name, self.x_unit, self.y_name, self.y_unit) \
                and self.plot.getAxis("left").labelText:
            return  # relabelling re-lays out the plot: only when it changed
        self.x_name, self.x_unit, self.y_name, self.y_unit = x_name, x_unit, y_name, y_unit
        self._label_axes()

    def export_axes(self) -> tuple[Axis, Axis]:
        """The x and y axes' quantities and units, as the plot labels them (for :class:`Series`)."""
        return Axis(self.x_name, self.x_unit), Axis(self.y_name, self.y_unit)

    def _label_axes(self) -> None:
        """The axis titles in the theme's text colour (pyqtgraph's setLabel forgets the text pen's),
        symbols with subscripts like the legends' (:func:`rich_label`: ``k_c`` -> k<sub>c</sub>)."""
        style = {"font-size": "10pt", "color": self.palette_colors()["fg"]}
        self.plot.setLabel("bottom", f"{rich_label(self.x_name)}  [{self.x_unit}]", **style)
        self.plot.setLabel("left", f"{rich_label(self.y_name)}  [{self.y_unit}]", **style)

    def curve(self, name: str | None, color: str, width: float = 2.0, style: Qt.PenStyle = Qt.PenStyle.SolidLine
              ) -> pg.PlotDataItem:
        item = self.plot.plot([], [], name=name, pen=pg.mkPen(color, width=width, style=style))
        item.setClipToView(True)
        item.setDownsampling(auto=True, method="peak")
        # one stroked polyline: Qt's raster engine draws a wide pen that way about a quarter faster
        # than as separate segments (pyqtgraph's default for solid pens wider than 1 px)
        item.curve.setSegmentedLineMode("off")
        return item

    def legend_outside(self, columns: int = 3) -> None:
        """Move the legend out of the data area into a row below the x axis (small plots; see
        :mod:`app.views.legend_row`)."""
        placer = getattr(self, "legend_placer", None)
        if placer is not None:  # a legend in the layout is not moved around the view box
            placer.deleteLater()
            self.legend_placer = None
        self.legend_row = LegendRow(self.plot, self.legend, self.plot_widget.width, self.fit_scene, columns, self)
        self.legend = self.legend_row.legend

    def fit_scene(self) -> None:
        """Lay the plot out in the widget again after its minimum size shrank.

        pyqtgraph sizes its scene to the widget only when the widget resizes; a scene once wider
        (a longer title, a wider legend) would stay wider and be cut on the right.
        """
        pw = self.plot_widget
        pw.centralWidget.setGeometry(QRectF(pw.range))

    def resizeEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        if self.legend_row is not None:
            self.legend_row.fit()

    def set_legend_text(self, item: pg.GraphicsObject, text: str) -> None:
        label = self.legend.getLabel(item)
        if label is not None and label.text != text:
            label.setText(text)

    def hold_range(self, hold: bool) -> None:
        """Keep the axes still (no auto-range) while a slider is dragged; after it, each axis
        auto-ranges again if it did before (a range the user zoomed to stays)."""
        vb = self.plot.getViewBox()
        if hold:
            if self._auto_before_hold is None:
                self._auto_before_hold = tuple(vb.autoRangeEnabled())
            vb.disableAutoRange()
        elif self._auto_before_hold is not None:
            (x, y), self._auto_before_hold = self._auto_before_hold, None
            vb.enableAutoRange(x=x or False, y=y or False)

    def set_warning(self, messages: list[str]) -> None:
        text = "  ".join(f"⚠ {m}" for m in messages if m)
        if text == self.warning_text:
            return
        self.warning_text = text
        self.warning.setText(rich_label(html.escape(text, quote=False)))
        self.warning.setVisible(bool(text))

    def bump(self) -> None:
        self.revision += 1

    def set_log(self, x: bool, y: bool) -> None:
        if (x, y) != (self._log_x, self._log_y):
            self._log_x, self._log_y = x, y
            self.plot.setLogMode(x=x, y=y)

    def is_log(self) -> tuple[bool, bool]:
        return self._log_x, self._log_y

    def data_point(self, view_point: QPointF) -> tuple[float, float]:
        lx, ly = self.is_log()
        x, y = view_point.x(), view_point.y()
        return (10.0 ** x if lx else x), (10.0 ** y if ly else y)

    # -- crosshair ----------------------------------------------------------------------------------
    @Slot(object)
    def _on_mouse_moved(self, pos: QPointF) -> None:
        vb = self.plot.getViewBox()
        if not vb.sceneBoundingRect().contains(pos):
            self._vline.hide()
            self._hline.hide()
            self.cursor_label.setText("")
            return
        p = vb.mapSceneToView(pos)
        self._vline.setPos(p.x())
        self._hline.setPos(p.y())
        self._vline.show()
        self._hline.show()
        x, y = self.data_point(p)
        self.cursor_label.setText(self.cursor_text(x, y))

    def cursor_text(self, x: float, y: float) -> str:
        return f"{self.x_name} = {plain(x)} {self.x_unit},  {self.y_name} = {plain(y)} {self.y_unit}"

    # -- theme ----------------------------------------------------------------------------------------
    def apply_theme(self, dark: bool) -> None:
        self._dark = dark
        pal = PALETTE["dark" if dark else "light"]
        self.warning.setStyleSheet(f"color: {WARNING_COLORS[1 if dark else 0]};")
        self.cursor_label.setStyleSheet(f"color: {CURSOR_COLORS[1 if dark else 0]}; font-family: monospace;")
        self.plot_widget.setBackground(pal["bg"])
        for ax in ("left", "bottom", "top", "right"):
            axis = self.plot.getAxis(ax)
            if isinstance(axis, LogAxis):
                axis.grid_background = QColor(pal["bg"])
            axis.setPen(pg.mkPen(pal["fg"]))
            axis.setTextPen(pg.mkPen(pal["fg"]))
        if self.plot.getAxis("left").labelText:
            self._label_axes()
        if self.plot.titleLabel.isVisible():
            self.plot.titleLabel.setText(self.plot.titleLabel.text, color=pal["fg"])
        self.legend.setLabelTextColor(QColor(pal["fg"]))
        if self.legend_row is None:
            self.legend.setBrush(pg.mkBrush(QColor(pal["bg"]).red(), QColor(pal["bg"]).green(),
                                            QColor(pal["bg"]).blue(), 210))
            self.legend.setPen(pg.mkPen(pal["muted"]))
        for _sample, label in self.legend.items:
            label.setText(label.text, color=pal["fg"])
        self.restyle(pal)

    def palette_colors(self) -> dict:
        return PALETTE["dark" if self._dark else "light"]

    def restyle(self, pal: dict) -> None:
        """Recolour the subclass's items."""

    def place_legend(self) -> None:
        """Put the legend where it covers no data (views with a LegendPlacer); top right by default."""
        placer = getattr(self, "legend_placer", None)
        if placer is not None:
            placer.place()
        elif self.legend_row is not None:
            self.legend_row.fit()  # a legend in the row below the x axis stays there (legend_outside)
        else:
            self.legend.anchor(itemPos=(1, 0), parentPos=(1, 0), offset=(-10, 10))

    # -- export -----------------------------------------------------------------------------------------
    def export_series(self) -> list[Series]:
        raise NotImplementedError

    def export_notes(self) -> list[str]:
        """Notes an export carries with the data (e.g. why a chart is empty); CSV comment lines."""
        return [self.empty_message] if self.empty_message else []
