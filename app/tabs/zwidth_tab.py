"""The Z-width tab: the controller as built (issue 15).

* the (B, K) region of the virtual wall with the passive region, eq. (9)'s limit and the
  imported hardware trials (Colgate & Brown, ICRA 1994) -- a click sets the wall ``(b_c, k_c)``;
* the region's area against the velocity filter's cut-off, with the optimum marked (Chawda,
  Celik & O'Malley 2015).  "Use the optimum cut-off" is enabled only when the optimum beats the
  current design by the criterion (``FilterOptimum.offer``); it reads "Remove the filter" when no
  filter is best and a filter is set, and its tooltip is the verdict
  (:func:`analysis.study.optimum_verdict`).

Both are asynchronous graph nodes (:mod:`app.core.nodes_zwidth`) on the worker, with progress and
Cancel.  The velocity filter is edited in the parameter panel
(:class:`~app.panels.filter_panel.FilterPanel`); the B range and the trials file are the profile's
``controller`` section too, edited here through undo commands.  This tab computes nothing itself.
"""

from __future__ import annotations

import math
import os
from collections.abc import Hashable
from typing import Any

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QCheckBox,
    QFileDialog,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from analysis import ValidationError
from analysis.chain.velocity_filter import VelocityFilter
from analysis.sampled import DEFAULT_FORCE_NOISE, load_trials
from analysis.study import (controller_section, format_number, optimum_verdict, region_wall, superscript_numbers,
                            trial_score, wall_edits)

from app.core import nodes_zwidth
from app.core.compute_graph import ComputeGraph
from app.core.nodes_zwidth import OPTIMUM_NODE, REGION_NODE, TRIALS_NODE, ZWIDTH_NODES
from app.tabs.async_jobs import AsyncJobs
from app.tabs.base import AnalysisTab, scroll_body
from app.views.base import PlotView
from app.views.filter_optimum_view import FilterOptimumView
from app.views.zwidth_region_view import ZWidthRegionView
from app.widgets.colors import ERROR_STYLE
from app.widgets.node_progress import NodeProgress
from app.widgets.sci_spin_box import SciSpinBox
from app.widgets.section_binding import SectionBinding
from app.widgets.task_progress import TASK_TITLES
from analysis.study.citations import ADAMS, COLGATE_SCHENKEL
from app.widgets.citation_note import CitationNote

__all__ = ["ZWidthTab", "TAB"]

#: the optimum button's text when it offers nothing, and its tooltip before the optimum is computed
APPLY_TEXT, APPLY_TIP = "Use the optimum cut-off", "Set the velocity filter to the cut-off that maximizes the area"
TITLES = {REGION_NODE: "Z-width region", OPTIMUM_NODE: "Optimum filter cut-off"}
SHORT_TITLES = {REGION_NODE: "Z-width region", OPTIMUM_NODE: "Optimum cut-off"}


#: the noise fields' values before the criterion is first switched on: a 10 µm encoder (2¹⁴ counts on a
#: 26 mm radius) and the default force-noise tolerance
NOISE_DEFAULTS = (1e-5, DEFAULT_FORCE_NOISE)


class ZWidthTab(AsyncJobs, AnalysisTab):
    job_titles = TITLES  # the background nodes: cancel, failure and run-again (AsyncJobs)
    title = "Z-width"
    order = 35
    nodes = frozenset({*ZWIDTH_NODES, TRIALS_NODE})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_zwidth.register(graph)
        for name in ZWIDTH_NODES:
            TASK_TITLES.setdefault(name, SHORT_TITLES[name])  # the status bar's label is narrow

    def build(self) -> None:
        ctx = self.ctx
        self._held: dict[str, Hashable] = {}
        self._errors: dict[str, str] = {}
        self._trials_error: str | None = None  # why the profile's trials file cannot be used
        self.section = SectionBinding(ctx.model, ctx.editor, "controller", controller_section, "Z-width")
        self.region_view = ZWidthRegionView()
        self.region_view.pointPicked.connect(self.set_wall)
        self.optimum_view = FilterOptimumView()
        self.progress = {name: NodeProgress(ctx.graph, name, TITLES[name]) for name in ZWIDTH_NODES}
        for w in self.progress.values():
            w.rerun.connect(self.run_again)
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(self._controls())
        right = QSplitter(Qt.Orientation.Vertical)
        right.addWidget(_column(self.region_view, self.progress[REGION_NODE]))
        right.addWidget(_column(self.optimum_view, self.progress[OPTIMUM_NODE]))
        right.setSizes([62, 38])
        right.setChildrenCollapsible(False)
        split.addWidget(right)
        split.setStretchFactor(1, 1)
        split.setChildrenCollapsible(False)
        lay = QVBoxLayout(scroll_body(self))  # scrolls below its minimum size
        lay.setContentsMargins(4, 2, 4, 4)
        lay.addWidget(split, 1)
        lay.addWidget(CitationNote(ADAMS, COLGATE_SCHENKEL))  # the full citation of the tab's equation numbers
        ctx.graph.ready.connect(self._on_ready)
        ctx.graph.cancelled.connect(self.on_job_cancelled)
        ctx.graph.failed.connect(self.on_job_failed)

    def _controls(self) -> QWidget:
        box = QGroupBox("Region and trials")
        form = QFormLayout(box)
        self.b_min, self.b_max = SciSpinBox(suffix=" N·s/m"), SciSpinBox(suffix=" N·s/m")
        for f in (self.b_min, self.b_max):
            f.setMaximumWidth(130)
            f.editingFinished.connect(self._on_b_range)
        form.addRow("B from", self.b_min)
        form.addRow("B to", self.b_max)
        self._noise_controls(form)
        self.import_button = QPushButton("Import trials…")
        self.import_button.setToolTip("A CSV with columns b (N s/m), k (N/m), stable (1/0): hardware trials")
        self.import_button.clicked.connect(self._on_import)
        self.clear_button = QPushButton("Clear")
        self.clear_button.clicked.connect(self.clear_trials)
        row = QHBoxLayout()
        row.addWidget(self.import_button)
        row.addWidget(self.clear_button)
        form.addRow(row)
        self.trials_label = QLabel("No trials imported.")
        self.trials_label.setTextFormat(Qt.TextFormat.PlainText)  # file names and the reader's messages
        self.trials_label.setWordWrap(True)
        self.trials_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        form.addRow(self.trials_label)
        self.apply_button = QPushButton(APPLY_TEXT)
        self.apply_button.setToolTip(APPLY_TIP)
        self.apply_button.clicked.connect(self.apply_optimum)
        self.apply_button.setEnabled(False)
        form.addRow(self.apply_button)
        self.error = QLabel("")
        self.error.setStyleSheet(ERROR_STYLE)
        self.error.setWordWrap(True)
        self.error.hide()
        form.addRow(self.error)
        self.hint = QLabel("Click the region chart to set the virtual wall (b<sub>c</sub>, k<sub>c</sub>). "
                           "The velocity filter is in the parameter panel.")
        self.hint.setWordWrap(True)
        form.addRow(self.hint)
        box.setMinimumWidth(230)
        box.setMaximumWidth(320)
        return box

    def _noise_controls(self, form: QFormLayout) -> None:
        """The encoder-noise criterion (Chawda et al.): B whose quantization force noise exceeds the
        tolerance is not renderable, so the area falls at high cut-offs too."""
        self.noise_box = QCheckBox("Encoder noise limit")
        self.noise_box.setToolTip("Count a wall as unrenderable when its damping turns the encoder's "
                                  "quantization noise into more force noise than the tolerance")
        self.encoder = SciSpinBox(suffix=" m")
        self.encoder.setToolTip("Encoder resolution at the handle (one count), m")
        self.force_noise = SciSpinBox(suffix=" N")
        self.force_noise.setToolTip("Force-noise tolerance, N rms")
        form.addRow(self.noise_box)
        for label, f in (("Encoder q", self.encoder), ("Force noise", self.force_noise)):
            f.setMaximumWidth(130)
            f.editingFinished.connect(self._on_noise)
            form.addRow(label, f)
        self.noise_box.toggled.connect(self._on_noise)

    # -- edits (undo commands) -------------------------------------------------------------------------
    def _refuse(self, reason: str | None) -> str | None:
        self.error.setText(f"refused: {reason}" if reason else "")
        self.error.setVisible(bool(reason))
        return reason

    @Slot(float, float)
    def set_wall(self, b: float, k: float) -> str | None:
        """Set the virtual wall (the impedance coupling ``b_c``, ``k_c``) to ``(B, K)``: one undo step."""
        return self._refuse(self.ctx.editor.edit_many(wall_edits(b, k), "Set wall from the Z-width region"))

    def import_trials(self, path: str | os.PathLike) -> str | None:
        """Read a trials CSV (checked now) and store its path in the profile; returns a refusal."""
        try:
            load_trials(path)
        except ValidationError as err:
            return self._refuse(str(err))  # names the file, the line and the column
        return self._refuse(self.section.write("trials", os.fspath(path), "trials file"))

    @Slot()
    def clear_trials(self) -> str | None:
        if controller_section(self.ctx.model.profile).trials is None:
            return None
        return self._refuse(self.section.write("trials", None, "trials file"))

    def set_b_range(self, lo: float, hi: float) -> str | None:
        """Change the region's B range (N s/m); returns a refusal."""
        return self._refuse(self.section.write("b_range", (lo, hi), "B range"))

    def set_noise(self, resolution: float | None, force_noise: float | None = None) -> str | None:
        """The encoder-noise criterion: resolution (m) and tolerance (N rms), ``None``: off; one undo step."""
        return self._refuse(self.section.write_many(
            {"encoder_resolution": resolution, "force_noise": None if resolution is None else force_noise},
            "encoder noise"))

    @Slot()
    def _on_noise(self) -> None:
        if self.noise_box.isChecked():
            self.set_noise(self.encoder.value(), self.force_noise.value())
        else:
            self.set_noise(None)

    def _offer(self) -> VelocityFilter | None:
        """The optimum's offer for the current design (``None``: nothing better, or not computed yet)."""
        g = self.ctx.graph
        opt = g.result(OPTIMUM_NODE) if g.is_fresh(OPTIMUM_NODE) else None
        return None if opt is None else opt.offer

    @Slot()
    def apply_optimum(self) -> str | None:
        """Set the velocity filter to the optimum's offer, the cut-off or no filter (one undo step);
        nothing when the optimum does not beat the current design."""
        offer = self._offer()
        if offer is None:
            return None
        what = "no velocity filter" if offer.is_backward else "optimum filter"
        return self._refuse(self.section.write("velocity_filter", offer, what))

    def _show_offer(self, opt: Any) -> None:
        """The optimum button: enabled with what it sets only when the fresh optimum beats the design."""
        offer = self._offer()
        self.apply_button.setText(offer_text(offer))
        self.apply_button.setEnabled(offer is not None)
        self.apply_button.setToolTip(APPLY_TIP if opt is None else superscript_numbers(optimum_verdict(opt)))

    @Slot()
    def _on_import(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Import trials", "", "CSV files (*.csv);;All files (*)")
        if path:
            self.import_trials(path)

    @Slot()
    def _on_b_range(self) -> None:
        self.set_b_range(self.b_min.value(), self.b_max.value())

    def _trials(self) -> Any:
        try:
            return self.ctx.graph.get(TRIALS_NODE)
        except (ValidationError, OSError) as err:  # the file, the line and the column (analysis.csvtable)
            self._errors[TRIALS_NODE] = f"trials: {err}"
            self._trials_error = str(err)
            return None

    def update_views(self) -> None:
        p = self.ctx.model.profile
        sec = controller_section(p)
        on = sec.encoder_resolution is not None
        q = sec.encoder_resolution if on else self.encoder.value() or NOISE_DEFAULTS[0]
        fn = sec.force_noise if sec.force_noise is not None else self.force_noise.value() or NOISE_DEFAULTS[1]
        for f, v in ((self.b_min, sec.b_range[0]), (self.b_max, sec.b_range[1]), (self.encoder, q),
                     (self.force_noise, fn), (self.noise_box, on)):
            f.blockSignals(True)
            f.setChecked(v) if f is self.noise_box else f.setValue(v)
            f.blockSignals(False)
        self.encoder.setEnabled(on)
        self.force_noise.setEnabled(on)
        self._errors.pop(TRIALS_NODE, None)
        self._trials_error = None
        region, opt = self.pull(REGION_NODE), self.pull(OPTIMUM_NODE)
        trials = self._trials()
        study = trial_score(region, trials) if region is not None else None
        if self.region_view.region is not region or self.region_view.trials is not trials:
            self.region_view.update_region(region, trials, None if study is None else study.score)
        b, k = region_wall(p)
        self.region_view.update_point(b, k, None if region is None else region.stable(b, k))
        self.region_view.set_busy(self.busy(REGION_NODE))
        if self.optimum_view.optimum is not opt:
            self.optimum_view.update_optimum(opt)
        self.optimum_view.update_filter(sec.velocity_filter)
        self.optimum_view.set_busy(self.busy(OPTIMUM_NODE))
        self._show_offer(opt)
        self._show_trials(trials, study, self._trials_error)
        self.region_view.set_errors([e for n, e in self._errors.items() if n != OPTIMUM_NODE])
        if OPTIMUM_NODE in self._errors:
            self.optimum_view.set_warning([self._errors[OPTIMUM_NODE]])
        self.refreshes += 1
        self.stale = False

    def _show_trials(self, trials: Any, study: Any, error: str | None = None) -> None:
        """The trials line: how many the analysis gets wrong, or why the profile's file is not used."""
        style = ERROR_STYLE if error else ""
        if self.trials_label.styleSheet() != style:  # a new style sheet re-polishes the label
            self.trials_label.setStyleSheet(style)
        if error:
            self.trials_label.setText(f"Trials not drawn: the file cannot be used. {error}")
        elif trials is None:
            self.trials_label.setText("No trials imported.")
        elif study is None or study.score is None:
            self.trials_label.setText(f"{len(trials)} trials from {os.path.basename(trials.path)}")
        else:
            s = study.score
            lines = s.describe(trials)
            text = (f"{len(trials)} trials from {os.path.basename(trials.path)}: {s.wrong_count} of {s.scored} "
                    f"predicted wrong" + (f", {s.outside.size} outside the B range" if s.outside.size else ""))
            self.trials_label.setText(text + ("\n" + "\n".join(lines[:8]) if lines else "")
                                      + ("\n…" if len(lines) > 8 else ""))

    # -- worker reports -----------------------------------------------------------------------------------
    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in ZWIDTH_NODES and self.isVisible():
            self.refresh()

    def views(self) -> list[PlotView]:
        return [self.region_view, self.optimum_view]


def offer_text(offer: VelocityFilter | None) -> str:
    """The optimum button's text for ``offer``: the cut-off it sets, "Remove the filter", or the
    plain :data:`APPLY_TEXT` when it offers nothing (disabled)."""
    if offer is None:
        return APPLY_TEXT
    if offer.is_backward:
        return "Remove the filter"
    return f"{APPLY_TEXT} ({format_number(offer.cutoff / (2 * math.pi), 4, style='text')} Hz)"


def _column(*widgets: QWidget) -> QWidget:
    w = QWidget()
    lay = QVBoxLayout(w)
    lay.setContentsMargins(0, 0, 0, 0)
    lay.setSpacing(2)
    for x in widgets:
        lay.addWidget(x, 1 if isinstance(x, PlotView) else 0)
    return w


TAB = ZWidthTab
