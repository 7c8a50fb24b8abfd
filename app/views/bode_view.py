"""Measured against fitted frequency responses (issue 14): magnitude, phase, and the residual with
the coherence, over ω; plus the parameter table (with 95 % intervals) and the order table.

The curves are :func:`analysis.study.bode_data` of ``(measurement, model response)`` pairs,
several measurements joined by a gap.  The magnitude has one measured and one fitted curve per
measured quantity, each quantity in its own colour and named with its unit (an actuator's x/F is
in m/N, a gauge's F_g/F in N/N: one axis unit for both would be wrong for one of them); phase and
residual are dimensionless and keep one measured and one fitted curve.

The bins a fit leaves out (:attr:`analysis.identify.Measurement.informative`: coherence or input
power below the analysis module's thresholds) are drawn apart, greyed, on each plot, with their
own legend entry (:data:`analysis.study.UNUSED_BINS_LABEL`, key :data:`UNUSED_KEY`); the measured
curves hold the fitted bins only.  The plots have that entry only while such bins are drawn.

Every curve is drawn point for point (:func:`exact_curve`): pyqtgraph's clip-to-view presumes x
increasing and its automatic downsampling x evenly spaced, and neither holds for sweeps joined by a
gap and FFT bins on a logarithmic ω axis.  Downsampled, a curve's drawn x extent would depend on the
view's width (the first bin dropped or kept), so the auto-ranged x axis would change the extent,
which changes the range again: the plots repainted without end (issue 23).
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping, Sequence

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtGui import QResizeEvent
from PySide6.QtWidgets import QAbstractItemView, QGridLayout, QHeaderView, QTableWidget, QTableWidgetItem, QWidget

from analysis.identify import ChainFit, Measurement, OrderSelection, parameter_symbol
from analysis.study import UNUSED_BINS_LABEL, BodeData, bode_data, format_number, parameter_rows

from app.views.base import PlotView, rich_label
from app.views.curves_plot import CurvesPlot

__all__ = ["BodeView", "ParameterTable", "OrderTable", "PARAMETER_COLUMNS", "ORDER_COLUMNS", "unit_of",
           "MAGNITUDE_QUANTITIES", "magnitude_keys", "UNUSED_KEY", "NOT_TRUSTWORTHY", "exact_curve"]

#: Each measured quantity's response symbol, unit and colour (a palette key; its pale variant
#: draws the measurement, the full colour the fitted model).
MAGNITUDE_QUANTITIES = {"actuator": ("x/F", "m/N", "a"), "handle": ("x_0/F", "m/N", "c"),
                        "gauge": ("F_g/F", "N/N", "b")}

PARAMETER_COLUMNS = ("parameter", "unit", "value", "std. error", "95 % low", "95 % high", "interval", "note")
ORDER_COLUMNS = ("n", "AIC", "BIC", "residual", "")
#: The curve key of the bins the fit left out, greyed on each plot.
UNUSED_KEY = "not used"
#: How the parameter table labels an interval when the fit fails the goodness-of-fit test.
NOT_TRUSTWORTHY = "not trustworthy"


class BodeView(QWidget):
    """A 2×2 grid: |H| and ∠H on top, the residual |ln(H_fit/H_meas)| with the coherence below
    and a free cell beside it (:meth:`set_corner`)."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        w_axis = ("ω", "rad/s")
        self.magnitude = CurvesPlot("Magnitude", w_axis, ("|x/F|", "m/N"), True, True)
        self.quantities: tuple[str, ...] = ()  # the measured quantities the magnitude plot shows
        self._show_quantities(("actuator",))
        self.phase = CurvesPlot("Phase", w_axis, ("∠H", "°"), True, False)
        exact_curve(self.phase.add_curve("measured", "measured", "muted", 3.0, export_name="phase measured"))
        exact_curve(self.phase.add_curve("fitted", "fitted model", "a", 1.6, Qt.PenStyle.DashLine,
                                         export_name="phase fitted"))
        self.residual = CurvesPlot("Residual and coherence", w_axis, ("", "–"), True, True)
        exact_curve(self.residual.add_curve("residual", "|ln(H<sub>fit</sub>/H<sub>meas</sub>)|", "b", 1.6,
                                            export_name="residual |ln(H_fit/H_meas)|"))
        exact_curve(self.residual.add_curve("coherence", "coherence γ²", "c", 1.6, Qt.PenStyle.DotLine,
                                            export_name="coherence"))
        self.grid = QGridLayout(self)
        self.grid.setContentsMargins(0, 0, 0, 0)
        self.grid.setSpacing(6)
        for view, (r, c) in ((self.magnitude, (0, 0)), (self.phase, (0, 1)), (self.residual, (1, 0))):
            view.legend_outside()
            self.grid.addWidget(view, r, c)
        for i in range(2):
            self.grid.setRowStretch(i, 1)
            self.grid.setColumnStretch(i, 1)
        self.data: BodeData | None = None

    def set_corner(self, widget: QWidget) -> None:
        """Put ``widget`` (e.g. the parameter tables) in the fourth cell, beside the residual."""
        self.grid.addWidget(widget, 1, 1)

    def plot_views(self) -> list[PlotView]:
        return [self.magnitude, self.phase, self.residual]

    def update_data(self, data: BodeData, unit: str = "m/N",
                    magnitudes: Mapping[str, BodeData] | None = None) -> None:
        """Draw ``data`` (every curve keeps a gap between measurements).

        ``magnitudes``: the magnitude data by measured quantity (:data:`MAGNITUDE_QUANTITIES`);
        without it ``data`` is all one quantity, the gauge's if ``unit`` is N/N.
        """
        self.data = data
        if magnitudes is None:
            magnitudes = {"gauge" if unit == "N/N" else "actuator": data}
        self._show_quantities(tuple(magnitudes))
        for q, part in magnitudes.items():
            measured, fitted = magnitude_keys(q)
            self.magnitude.set_curve(measured, part.w, part.where_used(part.measured_mag), gaps=True)
            self.magnitude.set_curve(fitted, part.w, part.model_mag, gaps=True)
        self.phase.set_curve("measured", data.w, data.where_used(data.measured_phase), gaps=True)
        self.phase.set_curve("fitted", data.w, data.model_phase, gaps=True)
        self.residual.set_curve("residual", data.w, data.where_used(data.residual), gaps=True)
        coh = data.coherence if data.has_coherence else np.array([])
        self.residual.set_curve("coherence", data.w[: coh.size], coh, gaps=True)
        self._show_unused(data, magnitudes)
        for v in self.plot_views():
            v.bump()

    def _show_unused(self, data: BodeData, magnitudes: Mapping[str, BodeData]) -> None:
        """The bins the fit left out, greyed, on each plot (the entry only while there are some)."""
        unused = data.has_unused
        for view in self.plot_views():
            if not unused:
                view.remove_curve(UNUSED_KEY)
            elif UNUSED_KEY not in view.items:
                exact_curve(view.add_curve(UNUSED_KEY, html.escape(UNUSED_BINS_LABEL), "muted", 2.0,  # rich text
                                           Qt.PenStyle.DotLine, export_name=UNUSED_BINS_LABEL))
        if not unused:
            return
        # the magnitudes of every quantity on one curve (one axis holds them all), gaps between them
        w = np.concatenate([np.append(part.w, np.nan) for part in magnitudes.values()])
        mag = np.concatenate([np.append(part.where_used(part.measured_mag, False), np.nan)
                              for part in magnitudes.values()])
        self.magnitude.set_curve(UNUSED_KEY, w, mag, gaps=True)
        self.phase.set_curve(UNUSED_KEY, data.w, data.where_used(data.measured_phase, False), gaps=True)
        self.residual.set_curve(UNUSED_KEY, data.w, data.where_used(data.residual, False), gaps=True)

    def show_pairs(self, pairs: Sequence[tuple[Measurement, np.ndarray]]) -> None:
        """Draw ``(measurement, model response)`` pairs: each measured quantity's magnitude apart."""
        order = [q for q in MAGNITUDE_QUANTITIES if any(m.quantity == q for m, _ in pairs)]
        by_quantity = {q: bode_data([p for p in pairs if p[0].quantity == q]) for q in order}
        self.update_data(bode_data(pairs), unit_of(pairs[0][0].quantity) if pairs else "m/N", by_quantity)

    def _show_quantities(self, quantities: tuple[str, ...]) -> None:
        """One measured and one fitted curve per quantity, in the quantity's colour; the y label
        names each quantity's symbol and the units (none of them wrong for any curve)."""
        if quantities == self.quantities:
            return
        mag = self.magnitude
        for q in self.quantities:
            if q not in quantities:
                for key in magnitude_keys(q):
                    mag.remove_curve(key)
        for q in quantities:
            if q in self.quantities:
                continue
            symbol, unit, color = MAGNITUDE_QUANTITIES[q]
            measured, fitted = magnitude_keys(q)
            name = f"{q} {rich_label(symbol)} [{unit}]"
            exact_curve(mag.add_curve(measured, f"{name} measured", f"{color}_pale", 3.0,
                                      export_name=f"|{symbol}| {q} measured"))
            exact_curve(mag.add_curve(fitted, f"{name} fitted", color, 1.6, Qt.PenStyle.DashLine,
                                      export_name=f"|{symbol}| {q} fitted"))
        self.quantities = quantities
        units = list(dict.fromkeys(MAGNITUDE_QUANTITIES[q][1] for q in quantities))
        mag.set_axis_labels("ω", "rad/s", ", ".join(f"|{MAGNITUDE_QUANTITIES[q][0]}|" for q in quantities),
                            ", ".join(units))


def exact_curve(item: pg.PlotDataItem) -> pg.PlotDataItem:
    """Draw ``item`` point for point: no clipping to the view and no automatic downsampling (the
    :class:`~app.views.base.PlotView` default), whose drawn x extent would follow the view's range.

    Both presume x increasing and evenly spaced; a Bode curve joins sweeps (x starts again after each
    gap) of FFT bins, evenly spaced in ω, on a logarithmic axis.  Peak downsampling by ``d`` starts
    at the ``d // 2``-th point: the lowest bin, a third of a decade below the next, comes and goes
    as the auto-ranged x axis widens and narrows, and the range never settles.  A few thousand
    points are drawn at once.
    """
    item.setClipToView(False)
    item.setDownsampling(ds=1, auto=False)
    return item


def magnitude_keys(quantity: str) -> tuple[str, str]:
    """The magnitude plot's curve keys (measured, fitted) of a measured quantity; the actuator's
    are ``"measured"`` and ``"fitted"``, as before there was more than one quantity."""
    return ("measured", "fitted") if quantity == "actuator" else (f"measured {quantity}", f"fitted {quantity}")


def _item(text: str, tip: str = "") -> QTableWidgetItem:
    item = QTableWidgetItem(text)
    item.setFlags(item.flags() & ~Qt.ItemFlag.ItemIsEditable)
    item.setTextAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
    if tip:
        item.setToolTip(tip)
    return item


class _Table(QTableWidget):
    def __init__(self, columns: tuple[str, ...], parent: QWidget | None = None) -> None:
        super().__init__(0, len(columns), parent)
        self.setHorizontalHeaderLabels(list(columns))
        self.verticalHeader().hide()
        self.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        self.horizontalHeader().setStretchLastSection(True)

    def texts(self) -> list[list[str]]:
        """The cells as shown (tests read these)."""
        return [[self.item(r, c).text() if self.item(r, c) else "" for c in range(self.columnCount())]
                for r in range(self.rowCount())]


class ParameterTable(_Table):
    """One row per parameter: its symbol (m₁, k₁, ... 1-based as the device editor shows them; the
    0-based file key in the tooltip and :meth:`keys`), unit, value, standard error, 95 % interval
    and how it was found (wald, profile, unbounded), fixed / not identifiable.

    The numbers are :func:`~analysis.study.format_number`'s.  Every column fits its contents when
    the table is wide enough; else the note column narrows first, then the four number columns,
    which elide ("…") a number that does not fit (its whole text in the tooltip): no column hides
    behind a scroll bar (:meth:`fit_columns`)."""

    NUMBER_COLUMNS = (2, 3, 4, 5)
    INTERVAL_COLUMN = 6
    NOTE_COLUMN = 7

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(PARAMETER_COLUMNS, parent)
        self.setWordWrap(False)
        self.setTextElideMode(Qt.TextElideMode.ElideRight)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        header = self.horizontalHeader()
        header.setStretchLastSection(False)
        header.setSectionResizeMode(QHeaderView.ResizeMode.Interactive)
        header.setTextElideMode(Qt.TextElideMode.ElideRight)  # a narrowed number column says "95 % l…", not "% l"
        for c, name in enumerate(PARAMETER_COLUMNS):
            self.horizontalHeaderItem(c).setToolTip(name)
        header.setMinimumSectionSize(self.fontMetrics().horizontalAdvance("0…") + 8)

    def fit_columns(self) -> None:
        """Each column as wide as its contents (and header) when they fit; else the note column gives
        way first, then the number columns share what is left (their text elided)."""
        header = self.horizontalHeader()
        smallest = header.minimumSectionSize()
        want = [max(self.sizeHintForColumn(c), header.sectionSizeHint(c)) for c in range(self.columnCount())]
        room = self.viewport().width()
        excess = sum(want) - room
        if excess > 0:  # the note first, down to its header's width
            give = min(excess, max(0, want[self.NOTE_COLUMN] - header.sectionSizeHint(self.NOTE_COLUMN)))
            want[self.NOTE_COLUMN] -= give
            excess -= give
        if excess > 0:  # then the numbers, in proportion to their width
            total = sum(want[c] for c in self.NUMBER_COLUMNS)
            for c in self.NUMBER_COLUMNS:
                want[c] = max(smallest, want[c] - math.ceil(excess * want[c] / total))
        elif room > sum(want):
            want[self.NOTE_COLUMN] += room - sum(want)  # the spare width to the last column
        for c, w in enumerate(want):
            self.setColumnWidth(c, w)

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self.fit_columns()

    def show_fit(self, fit: ChainFit | None) -> None:
        """One row per parameter of ``fit``; when the fit fails the goodness-of-fit test
        (:attr:`~analysis.identify.ChainFit.intervals_trustworthy`), the interval column of every
        fitted parameter says :data:`NOT_TRUSTWORTHY` (the test's message in its tooltip)."""
        rows = parameter_rows(fit) if fit is not None else []
        goodness = getattr(fit, "goodness", None)  # (ChainFit.intervals_trustworthy; a table may show a plain record)
        trusted = goodness is None or goodness.passed
        why = "" if trusted else goodness.message
        self.setRowCount(len(rows))
        for r, row in enumerate(rows):
            t = row["text"]
            note = "fixed" if row["fixed"] else ("not identifiable" if not row["identifiable"] else "")
            if not (trusted or row["fixed"]):
                row = {**row, "method": f"{NOT_TRUSTWORTHY} ({row['method']})"}
            tip = fit.suggestions.get(row["key"], "") if fit is not None else ""
            symbol, unit = parameter_symbol(row["key"])
            cells = (symbol, unit, t["value"], t["std_error"], t["low"], t["high"], row["method"], note)
            for c, text in enumerate(cells):
                item = _item(text, (tip or text) if c == self.NOTE_COLUMN else (text if c in self.NUMBER_COLUMNS else ""))
                if c == self.INTERVAL_COLUMN and why and not row["fixed"]:
                    item.setToolTip(why)
                if c == 0:
                    item.setData(Qt.ItemDataRole.UserRole, row["key"])
                    item.setToolTip(f"{row['key']} in profiles and on the command line")
                    item.setTextAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
                elif c == 1:
                    item.setTextAlignment(Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
                self.setItem(r, c, item)
        self.fit_columns()

    def keys(self) -> list[str]:
        """The rows' parameter keys as files and the command line spell them (``masses[0]``)."""
        return [self.item(r, 0).data(Qt.ItemDataRole.UserRole) for r in range(self.rowCount())]


class OrderTable(_Table):
    """AIC, BIC and the residual for each number of masses; the lowest BIC is marked."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(ORDER_COLUMNS, parent)

    def show_orders(self, orders: OrderSelection | None) -> None:
        if orders is None:
            self.setRowCount(0)
            return
        self.setRowCount(len(orders.n))
        for r, n in enumerate(orders.n):
            err = orders.errors[r]
            best = "lowest BIC" if orders.best_bic == int(n) else ""
            cells = (str(int(n)), format_number(orders.aic[r], style="text"), format_number(orders.bic[r], style="text"),
                     format_number(orders.residual[r], 4, style="text"), best if err is None else "not fitted")
            for c, text in enumerate(cells):
                self.setItem(r, c, _item(text, err or ""))

    def best_row(self) -> int | None:
        """The row marked as the lowest BIC, or ``None``."""
        for r in range(self.rowCount()):
            if self.item(r, 4) is not None and self.item(r, 4).text() == "lowest BIC":
                return r
        return None


def unit_of(quantity: str) -> str:
    """The response unit of a measured quantity."""
    return "N/N" if quantity == "gauge" else "m/N"

