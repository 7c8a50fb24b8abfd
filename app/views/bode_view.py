"""Measured against fitted frequency responses (issue 14): magnitude, phase, and the residual with
the coherence, over ω; plus the parameter table (with 95 % intervals) and the order table.

The curves are :func:`analysis.study.bode_data` of ``(measurement, model response)`` pairs,
several measurements joined by a gap, so every plot has one measured and one fitted curve.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QAbstractItemView, QGridLayout, QHeaderView, QTableWidget, QTableWidgetItem, QWidget

from analysis.identify import ChainFit, OrderSelection
from analysis.study import BodeData, format_number, parameter_rows

from app.views.base import PlotView
from app.views.curves_plot import CurvesPlot

__all__ = ["BodeView", "ParameterTable", "OrderTable", "PARAMETER_COLUMNS", "ORDER_COLUMNS", "unit_of"]

PARAMETER_COLUMNS = ("parameter", "value", "std. error", "95 % low", "95 % high", "interval", "note")
ORDER_COLUMNS = ("n", "AIC", "BIC", "residual", "")


class BodeView(QWidget):
    """A 2×2 grid: |H| and ∠H on top, the residual |ln(H_fit/H_meas)| with the coherence below
    and a free cell beside it (:meth:`set_corner`)."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        w_axis = ("ω", "rad/s")
        self.magnitude = CurvesPlot("Magnitude", w_axis, ("|H|", "m/N"), True, True)
        self.magnitude.add_curve("measured", "measured", "muted", 3.0, export_name="|H| measured")
        self.magnitude.add_curve("fitted", "fitted model", "a", 1.6, Qt.PenStyle.DashLine, export_name="|H| fitted")
        self.phase = CurvesPlot("Phase", w_axis, ("∠H", "°"), True, False)
        self.phase.add_curve("measured", "measured", "muted", 3.0, export_name="phase measured")
        self.phase.add_curve("fitted", "fitted model", "a", 1.6, Qt.PenStyle.DashLine, export_name="phase fitted")
        self.residual = CurvesPlot("Residual and coherence", w_axis, ("", "–"), True, True)
        self.residual.add_curve("residual", "|ln(H<sub>fit</sub>/H<sub>meas</sub>)|", "b", 1.6,
                                export_name="residual |ln(H_fit/H_meas)|")
        self.residual.add_curve("coherence", "coherence γ²", "c", 1.6, Qt.PenStyle.DotLine, export_name="coherence")
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

    def update_data(self, data: BodeData, unit: str = "m/N") -> None:
        """Draw ``data`` (every curve keeps a gap between measurements)."""
        self.data = data
        self.magnitude.set_axis_labels("ω", "rad/s", "|H|", unit)
        self.magnitude.set_curve("measured", data.w, data.measured_mag, gaps=True)
        self.magnitude.set_curve("fitted", data.w, data.model_mag, gaps=True)
        self.phase.set_curve("measured", data.w, data.measured_phase, gaps=True)
        self.phase.set_curve("fitted", data.w, data.model_phase, gaps=True)
        self.residual.set_curve("residual", data.w, data.residual, gaps=True)
        coh = data.coherence if data.has_coherence else np.array([])
        self.residual.set_curve("coherence", data.w[: coh.size], coh, gaps=True)
        for v in self.plot_views():
            v.bump()


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
    """One row per parameter: value, standard error, 95 % interval and how it was found (wald,
    profile, unbounded), fixed / not identifiable."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(PARAMETER_COLUMNS, parent)

    def show_fit(self, fit: ChainFit | None) -> None:
        rows = parameter_rows(fit) if fit is not None else []
        self.setRowCount(len(rows))
        for r, row in enumerate(rows):
            t = row["text"]
            note = "fixed" if row["fixed"] else ("not identifiable" if not row["identifiable"] else "")
            tip = fit.suggestions.get(row["key"], "") if fit is not None else ""
            cells = (row["key"], t["value"], t["std_error"], t["low"], t["high"], row["method"], note)
            for c, text in enumerate(cells):
                self.setItem(r, c, _item(text, tip if c == 6 else ""))


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
            cells = (str(int(n)), format_number(orders.aic[r]), format_number(orders.bic[r]),
                     format_number(orders.residual[r], 4), best if err is None else "not fitted")
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

