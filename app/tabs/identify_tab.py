"""The Identify tab (issue 14): from measurements of your own device to a chain model with 95 %
intervals, and designs that hold for every model the data allow.

Left: the measurements, how they were taken, the order n, fixed parameters, Fit (on the worker,
with progress and Cancel) and "Use this device" (the profile's device and its identification
section in one undo step).  Right: measured against fitted Bode plots with the residual and the
coherence, the parameter table with intervals, the order table (AIC, BIC, residual for
n = 1..N) and the robust design over the profile's parameter box with the line that says whether
the current coupling holds for the whole box (:func:`analysis.study.robust_designs`).

Issue 23: the bins the fit left out are greyed on the plots (:class:`~app.views.bode_view.BodeView`),
the summary says how many bins of each measurement were used and why
(:func:`analysis.study.bins_summary`), and the goodness-of-fit verdict stands under
it (:attr:`goodness`: a warning when the model does not explain the data, and the intervals in the
parameter table are then labelled "not trustworthy").
"""

from __future__ import annotations

import html
import os
from collections.abc import Sequence

from PySide6.QtCore import Qt, Signal, Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QScrollArea, QTabWidget, QVBoxLayout, QWidget

from analysis.identify import ChainFit
from analysis.study import IdentifyResult, RobustDesigns, bins_summary, fit_curves, profile_with_fit

from app.core import nodes_identify
from app.core.compute_graph import ComputeGraph
from app.core.nodes_identify import FIT_NODE, NODES, ROBUST_NODE, fit_params
from app.panels.identify_panel import IdentifyPanel
from app.tabs.base import AnalysisTab, scroll_body
from app.views.base import PlotView
from app.views.bode_view import BodeView, OrderTable, ParameterTable
from app.views.placement import CenterMessage
from app.widgets.node_progress import NodeProgress
from analysis.study.citations import ADAMS
from analysis.study.quantities import format_number
from app.widgets.citation_note import CitationNote
from app.widgets.colors import for_theme

__all__ = ["IdentifyTab", "TAB"]



def _rich(value: float) -> str:
    """A number as the tab's rich text prints it (the study's one formatter)."""
    return format_number(value, rich=True)

class IdentifyTab(AnalysisTab):
    title = "Identify"
    order = 50
    nodes = frozenset(NODES)
    on_demand_nodes = frozenset({FIT_NODE})  # runs when Fit is pressed: an export never waits for it
    export_hint = "run a fit first"  # why an export before a fit has nothing (app.window.exports)
    fitted = Signal()  # a fit result is shown

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_identify.register(graph)

    def build(self) -> None:
        ctx = self.ctx
        nodes_identify.register(ctx.graph)  # idempotent: the window registers it too
        self.panel = IdentifyPanel(ctx.model.device.sample_time)
        self.fit_progress = NodeProgress(ctx.graph, FIT_NODE, "Fitting")
        self.robust_progress = NodeProgress(ctx.graph, ROBUST_NODE, "Robust design")
        self.bode = BodeView()
        self.parameters = ParameterTable()
        self.orders = OrderTable()
        self.summary = QLabel("Load one or more measurements, choose n and press Fit.")
        self.summary.setObjectName("identifySummary")
        self.summary.setWordWrap(True)
        self.summary.setMinimumWidth(0)
        self.goodness = QLabel()  # the goodness-of-fit verdict of the fit shown (empty before a fit)
        self.goodness.setObjectName("identifyGoodness")
        self.goodness.setWordWrap(True)
        self.goodness.setMinimumWidth(0)
        self.goodness.setTextFormat(Qt.TextFormat.RichText)
        self._goodness_text = ""
        self.robust = QLabel()
        self.robust.setObjectName("robustVerdict")
        self.robust.setWordWrap(True)
        self.robust.setTextFormat(Qt.TextFormat.RichText)
        # its cell does not pass height-for-width on: room for three wrapped lines at any width
        self.robust.setMinimumHeight(3 * self.robust.fontMetrics().lineSpacing() + 4)
        self.result: IdentifyResult | None = None
        self._run = 0
        self._layout()
        self.placeholders = {view: CenterMessage(view) for view in self.bode.plot_views()}
        self._empty: dict[PlotView, bool] = {}  # whether each plot is drawn as empty (no ticks) now
        self.panel.files.model().rowsInserted.connect(self.show_placeholders)
        self.panel.files.model().rowsRemoved.connect(self.show_placeholders)
        self.viewsBuilt.connect(self.show_placeholders)  # after the theme: the message takes its colour
        self.panel.fitRequested.connect(self.fit)
        self.panel.useRequested.connect(self.use_device)
        self.fit_progress.rerun.connect(lambda _name: self.fit())
        self.robust_progress.rerun.connect(lambda _name: ctx.graph.request(ROBUST_NODE))
        ctx.graph.ready.connect(self._on_ready)

    def _layout(self) -> None:
        left = QWidget()
        col = QVBoxLayout(left)
        col.setContentsMargins(0, 0, 0, 0)
        col.addWidget(self.panel, 1)
        col.addWidget(self.fit_progress)
        col.addWidget(self.summary)
        col.addWidget(self.goodness)
        scroll = QScrollArea()
        scroll.setWidget(left)
        scroll.setWidgetResizable(True)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        scroll.setMinimumWidth(300)
        scroll.setMaximumWidth(340)
        tables = QTabWidget()
        tables.addTab(self.parameters, "Parameters (95 % intervals)")
        tables.addTab(self.orders, "Model order")
        self.tables = tables
        corner = QWidget()
        clay = QVBoxLayout(corner)
        clay.setContentsMargins(0, 0, 0, 0)
        clay.addWidget(self.robust)
        clay.addWidget(self.robust_progress)
        clay.addWidget(tables, 1)
        clay.addWidget(CitationNote(ADAMS))  # the full citation of the tab's equation numbers
        self.bode.set_corner(corner)
        lay = QHBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(scroll)
        lay.addWidget(self.bode, 1)

    def views(self) -> list[PlotView]:
        return self.bode.plot_views()

    @Slot()
    def show_placeholders(self) -> None:
        """An empty plot says what to do in its middle, with no axis numbers or grid (a range with no
        data means nothing); a plot with data shows its axes again."""
        waiting = ("Measurements loaded: press Fit to see them against the fitted model." if self.panel.measurements
                   else "No measurements yet: add measurement files, then press Fit.")
        for view, message in self.placeholders.items():
            empty = not view.export_series()
            # in the plot only (not view.empty_message: an export before a fit is refused with the tab's hint)
            message.set_text(waiting if empty else "", view.palette_colors()["fg"])
            if self._empty.get(view) != empty:  # (an axis is laid out again when its ticks change)
                self._empty[view] = empty
                for name in ("left", "bottom"):
                    view.plot.getAxis(name).setTicks([] if empty else None)  # no ticks: no numbers, no grid

    def apply_theme(self, dark: bool) -> None:
        super().apply_theme(dark)
        if self.is_built():
            self.show_placeholders()  # the message in the theme's text colour
            self.goodness.setText(for_theme(self._goodness_text, dark))

    # -- fitting ---------------------------------------------------------------------------------
    def load_files(self, paths: Sequence[str | os.PathLike]) -> list[str]:
        """Load measurement files (what the Add button does after its file dialog)."""
        return self.panel.load_files(paths)

    @Slot()
    def fit(self) -> None:
        """Fit the loaded measurements on the worker (the result arrives by ``graph.ready``)."""
        p = self.panel
        if not p.measurements:
            return
        self._run += 1
        n = p.masses.value()
        top = p.max_order.value() or None
        sampled = [m.sample_time for m in p.measurements if m.sample_time is not None]
        T = sampled[0] if sampled else self.ctx.model.device.sample_time
        params = fit_params(self._run, p.measurements, n, p.fixed(), None, max(top, n) if top else None, T,
                            self.ctx.model.device.band_min)
        self.ctx.graph.set_params(FIT_NODE, **params)
        self.summary.setText(f"Fitting {n} masses to {len(p.measurements)} measurement(s)…")
        self.ctx.graph.request(FIT_NODE)

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == FIT_NODE:
            res = self.ctx.graph.result(FIT_NODE)
            if res is not None:
                self.show_result(res)
        elif name == ROBUST_NODE and self.isVisible():
            self.show_robust(self.ctx.graph.result(ROBUST_NODE)[0])

    def show_result(self, res: IdentifyResult) -> None:
        """Draw a fit: Bode plots, parameter and order tables, notes."""
        self.result = res
        fit = res.fit
        self.bode.show_pairs(list(zip(res.measurements, fit.responses)))  # each quantity in its unit
        self.parameters.show_fit(fit)
        self.orders.show_orders(res.orders)
        notes = [f"Residual {format_number(fit.residual, 3, style='text')} (RMS of the weighted log-response), "
                 f"AIC {format_number(fit.aic, style='text')}, BIC {format_number(fit.bic, style='text')}"
                 + ("" if fit.converged else " — did NOT converge")]
        if fit.bins:
            notes.append(f"Bins: {bins_summary(fit)}")
        notes += [w for w in fit.warnings  # the non-identifiable keys, grouped by what would fix them, among them
                  if fit.goodness is None or w != fit.goodness.message]  # (that one is the verdict below)
        self.summary.setText("\n".join(notes))
        self.show_goodness(fit)
        self.panel.use_button.setEnabled(True)
        self.show_placeholders()
        self.fitted.emit()

    def show_goodness(self, fit: ChainFit | None) -> None:
        """The goodness-of-fit verdict of ``fit``: a warning when the model does not explain the data
        (its intervals are then not trustworthy), a plain line when it does."""
        g = None if fit is None else fit.goodness
        if g is None:
            text = ""
        elif g.passed:
            text = f"<span style='color:#2b8a3e'>Goodness of fit: {html.escape(g.message)}.</span>"
        else:
            text = f"<b style='color:#c92a2a'>Warning: {html.escape(g.message)}.</b>"
        self._goodness_text = text
        self.goodness.setText(for_theme(text, self.dark))
        self.goodness.setVisible(bool(text))

    @Slot()
    def use_device(self) -> str | None:
        """The profile's device := the fitted one, with the identification section, the fit's notes and
        the per-mass lists that no longer fit dropped (one undo step)."""
        if self.result is None:
            return "no fit"
        new = profile_with_fit(self.ctx.model.profile, self.result.fit, self.result.measurements)
        return self.ctx.editor.edit_many({"device": new.device, "identification": new.identification,
                                          "notes": new.notes, "simulation": new.simulation},
                                         "Use identified device")

    # -- robust designs ---------------------------------------------------------------------------
    def show_robust(self, designs: RobustDesigns | None) -> None:
        if designs is None:
            self.robust.setText("No parameter intervals in the profile: fit and press <i>Use this device</i> "
                                "to get robust designs.")
            return
        color = "#237032" if designs.holds else "#c92a2a"
        extra = ""
        beyond = designs.beyond_limits  # a value beyond its field's physical range: the phrase (issue 22)

        def value(key: str, v: float, unit: str) -> str:
            return beyond[key].text(rich=True) if key in beyond else f"{_rich(v)} {unit}"

        if designs.stiffness is not None and designs.stiffness.kc is not None:
            b = ", ".join(f"{k} = {_rich(v)}" for k, v in designs.stiffness.binding.items())
            nominal = designs.stiffness.nominal_kc
            extra = (f"<br>Robust largest k<sub>c</sub> at b<sub>c</sub> = {_rich(designs.stiffness.bc)} N·s/m: "
                     f"{value('kc_max', designs.stiffness.kc, 'N/m')} (nominal {_rich(nominal)} N/m); "
                     f"binding device: {b}")
        elif designs.damping is not None and designs.damping.low is not None:
            extra = (f"<br>Robust b<sub>c</sub> interval for m<sub>c</sub> = {_rich(designs.damping.mc)} kg: "
                     + (f"[{_rich(designs.damping.low)}, {_rich(designs.damping.high)}] N·s/m" if not beyond else
                        f"[{value('bc_low', designs.damping.low, 'N·s/m')}, "
                        f"{value('bc_high', designs.damping.high, 'N·s/m')}]"))
        self.robust.setText(f"<b style='color:{color}'>{designs.verdict()}</b>{extra}")

    def update_views(self) -> None:
        graph = self.ctx.graph
        out = graph.request(ROBUST_NODE)
        if out is not None and graph.is_fresh(ROBUST_NODE):
            self.show_robust(out[0])
        if self.result is None:
            pairs = fit_curves(self.ctx.model.profile)  # the profile's embedded measurements, if any
            if pairs:
                self.bode.show_pairs(pairs)
        self.show_placeholders()
        self.refreshes += 1
        self.stale = False


TAB = IdentifyTab
