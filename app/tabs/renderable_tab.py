"""The Renderable space tab (issue 24): what (M, B, K) the impedance display renders, and the M-width.

* the largest K over the (M, B) grid as a heat map with one contour per quality (Colonnese & Chan,
  IEEE Haptics Symposium 2016) -- a click sets the rendered environment's (M, B), one undo step;
* the M-width, the masses renderable at B = K = 0 (Colonnese & Okamura, RSS 2012), per quality;
* a quality selector (which K_max the map colours), the settings panel
  (:class:`~app.panels.renderable_panel.RenderablePanel`: the profile's ``renderable`` section);
* when the profile's identified intervals bound a parameter box, "Robust over": off, the box's
  corners or N samples of it -- the space every device of that batch has, overlaid on the map
  (a dashed contour at the rendered K, hatching where this device renders K and the box does not).

Two asynchronous graph nodes (:mod:`app.core.nodes_renderable`) on the worker, with progress and
Cancel; a hidden tab computes nothing, and the tab is built when first shown.  Every number shown
comes from :func:`analysis.study.renderable_study` and :func:`analysis.study.renderable.robust_study`.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from typing import Any

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QComboBox,
    QFormLayout,
    QLabel,
    QSpinBox,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from analysis.study import (
    QUALITY_LABELS,
    RenderableStudy,
    environment_edits,
    format_number,
    k_max_at,
    renderable_section,
)
from analysis.sampled.batch import MAX_DEVICES
from analysis.study.citations import COLONNESE_CHAN, COLONNESE_OKAMURA
from analysis.study.renderable import ROBUST_KINDS, RenderableRequest, robust_box_reason

from app.core import nodes_renderable
from app.core.compute_graph import ComputeGraph
from app.core.nodes_renderable import RENDERABLE_NODE, ROBUST_NODE, ROBUST_PARAMS
from app.panels.renderable_panel import RenderablePanel
from app.tabs.async_jobs import AsyncJobs
from app.tabs.base import AnalysisTab, settings_beside_plots
from app.views.base import PlotView
from app.views.renderable_view import MWidthView, RenderableSpaceView
from app.widgets.citation_note import CitationNote
from app.widgets.task_progress import TASK_TITLES
from app.widgets.node_progress import NodeProgress

__all__ = ["RenderableTab", "TAB", "width_text"]

#: ``_draw``'s robust argument when the overlay stays as it is (a quality change)
_KEEP = object()
TITLES = {RENDERABLE_NODE: "Renderable space", ROBUST_NODE: "Robust space over the identified box"}


def width_text(study: RenderableStudy, quality: str = "all") -> str:
    """The M-width in words, ``"M-width (stable): −0.2202 to 0.7051 kg (0.9253 kg)"``."""
    w = study.width
    lo, hi = (w.m_min, w.m_max) if quality == "all" else w.by_quality[quality]
    return (f"M-width ({QUALITY_LABELS[quality]}): {format_number(lo, style='text')} to "
            f"{format_number(hi, style='text')} kg ({format_number(hi - lo, style='text')} kg)")


class RenderableTab(AsyncJobs, AnalysisTab):
    job_titles = TITLES
    title = "Renderable space"
    order = 38
    nodes = frozenset({RENDERABLE_NODE, ROBUST_NODE})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_renderable.register(graph)
        for name, title in TITLES.items():
            TASK_TITLES.setdefault(name, title)

    def build(self) -> None:
        ctx = self.ctx
        self._held: dict[str, Hashable] = {}
        self._errors: dict[str, str] = {}
        self.panel = RenderablePanel(ctx.model, ctx.editor)
        self.space_view = RenderableSpaceView()
        self.space_view.pointPicked.connect(self.set_environment)
        self.width_view = MWidthView()
        self.progress = {name: NodeProgress(ctx.graph, name, title) for name, title in TITLES.items()}
        for widget in self.progress.values():
            widget.rerun.connect(self.run_again)
        self.quality = QComboBox()
        self.quality.setObjectName("renderable_quality")
        self.quality.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.quality.setToolTip("Which largest K the map colours: with every quality asked, or with one")
        self.quality.currentIndexChanged.connect(self._on_quality)
        self.summary = QLabel("")
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        left = QWidget()
        lay = QVBoxLayout(left)
        lay.setContentsMargins(0, 0, 0, 0)
        self._robust_controls()
        form = QFormLayout()
        form.addRow("Map shows", self.quality)
        form.addRow("Robust over", self.robust)
        form.addRow("Samples", self.samples)
        lay.addLayout(form)
        lay.addWidget(self.summary)
        lay.addWidget(self.panel, 1)
        right = QSplitter(Qt.Orientation.Vertical)
        top = QWidget()
        tl = QVBoxLayout(top)
        tl.setContentsMargins(0, 0, 0, 0)
        tl.addWidget(self.space_view, 1)
        tl.addWidget(self.progress[RENDERABLE_NODE])
        tl.addWidget(self.progress[ROBUST_NODE])
        right.addWidget(top)
        right.addWidget(self.width_view)
        right.setSizes([70, 30])
        right.setChildrenCollapsible(False)
        # the settings scroll on their own: the plots keep the tab's height
        settings_beside_plots(self, left, right, (270, 360), CitationNote(COLONNESE_CHAN, COLONNESE_OKAMURA))
        ctx.graph.ready.connect(self._on_ready)
        ctx.graph.cancelled.connect(self.on_job_cancelled)
        ctx.graph.failed.connect(self.on_job_failed)

    def _robust_controls(self) -> None:
        """The robust overlay's choice (the robust node's parameters; view state, not the profile's)."""
        self.robust = QComboBox()
        self.robust.setObjectName("renderable_robust")
        self.robust.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        for key, text in ROBUST_KINDS.items():
            self.robust.addItem(text, key)
        self.robust.currentIndexChanged.connect(self._on_robust)
        self.samples = QSpinBox()
        self.samples.setObjectName("renderable_robust_samples")
        self.samples.setRange(1, MAX_DEVICES)
        self.samples.setValue(ROBUST_PARAMS["samples"])
        self.samples.setKeyboardTracking(False)
        self.samples.setToolTip("Devices drawn uniformly from the identified box (seeded: the same each time)")
        self.samples.valueChanged.connect(self._on_robust)

    # -- edits ------------------------------------------------------------------------------------------
    def set_robust(self, kind: str, samples: int | None = None) -> None:
        """Overlay the robust space over the identified box: ``kind`` a key of ROBUST_KINDS."""
        if samples is not None:
            self.samples.setValue(samples)
        self.robust.setCurrentIndex(max(0, self.robust.findData(kind)))

    @Slot()
    def _on_robust(self) -> None:
        kind = self.robust.currentData() or "off"
        self.samples.setEnabled(kind == "samples" and self.robust.isEnabled())
        if self.ctx.graph.set_params(ROBUST_NODE, robust=kind, samples=int(self.samples.value())):
            self.stale = True
            if self.isVisible():
                self.refresh()

    @Slot(float, float)
    def set_environment(self, mass: float, damping: float) -> str | None:
        """Set the rendered environment's (M, B) (kg, N s/m): one undo step; returns a refusal."""
        return self.panel.write_many(environment_edits(mass, damping), "rendered environment (M, B)")

    @Slot()
    def _on_quality(self) -> None:
        if self.isVisible() or self.is_built():
            self._draw(self.ctx.graph.result(RENDERABLE_NODE) if self.ctx.graph.is_fresh(RENDERABLE_NODE)
                       else self.space_view.study)

    def selected_quality(self) -> str:
        return self.quality.currentData() or "all"

    def select_quality(self, quality: str) -> None:
        """Colour the map by ``quality`` (``"all"`` or one asked)."""
        i = self.quality.findData(quality)
        if i >= 0:
            self.quality.setCurrentIndex(i)

    def _sync_qualities(self, qualities: tuple[str, ...]) -> None:
        keys = ("all", *qualities) if len(qualities) > 1 else qualities
        if tuple(self.quality.itemData(i) for i in range(self.quality.count())) == keys:
            return
        current = self.selected_quality()
        self.quality.blockSignals(True)
        self.quality.clear()
        for q in keys:
            self.quality.addItem(QUALITY_LABELS[q], q)
        self.quality.setCurrentIndex(max(0, self.quality.findData(current)))
        self.quality.blockSignals(False)

    def _robust_on(self) -> bool:
        """Whether the robust overlay is asked and the profile has a box (the combo says why not)."""
        reason = robust_box_reason(self.ctx.model.profile)
        self.robust.setEnabled(reason is None)
        self.robust.setToolTip("The space every device of the identified parameter box renders" if reason is None
                               else f"No robust space: {reason}")
        self.samples.setEnabled(reason is None and self.robust.currentData() == "samples")
        return reason is None and self.ctx.graph.params(ROBUST_NODE)["robust"] != "off"

    def update_views(self) -> None:
        study = self.pull(RENDERABLE_NODE)
        busy = self.busy(RENDERABLE_NODE)
        robust_on = self._robust_on()
        robust = self.pull(ROBUST_NODE) if robust_on else None
        robust_busy = robust_on and self.busy(ROBUST_NODE)
        if not robust_on:
            self.progress[ROBUST_NODE].hide()
        self._draw(study, robust)
        self.space_view.set_busy(busy or robust_busy, "" if busy else "robust space updating…")
        self.width_view.header.setText(f"<b>{self.width_view.title}</b>" + ("  <i>(updating…)</i>" if busy else ""))
        errors = [self._errors[n] for n in (RENDERABLE_NODE, ROBUST_NODE) if n in self._errors]
        if errors:
            self.space_view.set_warning(errors)
        self.refreshes += 1
        self.stale = False

    def _draw(self, study: RenderableStudy | None, robust: Any = _KEEP) -> None:
        sec = renderable_section(self.ctx.model.profile)
        shown = sec.qualities if study is None else study.space.qualities
        self._sync_qualities(tuple(shown))
        quality = self.selected_quality()
        if robust is not _KEEP:
            self.space_view.update_robust(robust, self._robust_label() if robust is not None else "")
        if self.space_view.study is not study or self.space_view.quality != quality \
                or self.space_view.stiffness != sec.virtual_stiffness:
            self.space_view.update_space(study, quality, sec.virtual_stiffness)
        self.space_view.update_point(sec.virtual_mass, sec.virtual_damping)
        self.width_view.update_width(study, sec.virtual_mass)
        self.summary.setText("Computing the renderable space…" if study is None else self._summary(study, quality))

    def _robust_label(self) -> str:
        params = self.ctx.graph.params(ROBUST_NODE)
        req = RenderableRequest.of(self.ctx.model.profile, robust=params["robust"], samples=params["samples"])
        return "" if req.robust is None else req.robust.label(req.device)

    def _summary(self, study: RenderableStudy, quality: str) -> str:
        sec = renderable_section(self.ctx.model.profile)
        k = k_max_at(study.space, sec.virtual_mass, sec.virtual_damping, quality)
        where = ("outside the grid" if math.isnan(k) else
                 f"K_max = {format_number(k, style='text')} N/m at the nearest grid point, so K = "
                 f"{format_number(sec.virtual_stiffness, style='text')} N/m is "
                 f"{'renderable' if 0 < sec.virtual_stiffness <= k or (sec.virtual_stiffness == 0 and k > 0) else 'not renderable'}")
        lines = [width_text(study, quality),
                 f"Volume of the space: {format_number(study.space.volume, style='text')} kg·decades²",
                 f"Rendered (M, B) = ({format_number(sec.virtual_mass, style='text')} kg, "
                 f"{format_number(sec.virtual_damping, style='text')} N·s/m): {where}."]
        robust = self.space_view.robust if self.space_view.robust_drawn else None
        if robust is not None:
            kr = k_max_at(robust, sec.virtual_mass, sec.virtual_damping, quality)
            lines.append(f"Robust over {self.space_view.robust_label}: volume "
                         f"{format_number(robust.volume, style='text')} kg·decades²"
                         + ("" if math.isnan(kr) else f", K_max = {format_number(kr, style='text')} N/m there") + ".")
        elif self._robust_on():
            lines.append("Computing the robust space over the identified box…")
        return "\n".join([*lines, "Click the map to set the rendered (M, B)."])

    # -- worker reports -----------------------------------------------------------------------------------
    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in TITLES and self.isVisible():
            self.refresh()

    def views(self) -> list[PlotView]:
        return [self.space_view, self.width_view]


TAB = RenderableTab
