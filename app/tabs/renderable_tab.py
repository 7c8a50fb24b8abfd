"""The Renderable space tab (issue 24): what (M, B, K) the impedance display renders, and the M-width.

* the largest K over the (M, B) grid as a heat map with one contour per quality (Colonnese & Chan,
  IEEE Haptics Symposium 2016) -- a click sets the rendered environment's (M, B), one undo step;
* the M-width, the masses renderable at B = K = 0 (Colonnese & Okamura, RSS 2012), per quality;
* a quality selector (which K_max the map colours), the settings panel
  (:class:`~app.panels.renderable_panel.RenderablePanel`: the profile's ``renderable`` section).

One asynchronous graph node (:mod:`app.core.nodes_renderable`) on the worker, with progress and
Cancel; a hidden tab computes nothing, and the tab is built when first shown.  Every number shown
comes from :func:`analysis.study.renderable_study`.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from typing import Any

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QComboBox, QFormLayout, QFrame, QLabel, QScrollArea, QSplitter, QVBoxLayout, QWidget

from analysis.study import (
    QUALITY_LABELS,
    RenderableStudy,
    environment_edits,
    format_number,
    k_max_at,
    renderable_section,
)
from analysis.study.citations import COLONNESE_CHAN, COLONNESE_OKAMURA

from app.core import nodes_renderable
from app.core.compute_graph import ComputeGraph
from app.core.nodes_renderable import RENDERABLE_NODE
from app.panels.renderable_panel import RenderablePanel
from app.tabs.async_jobs import AsyncJobs
from app.tabs.base import AnalysisTab, scroll_body
from app.views.base import PlotView
from app.views.renderable_view import MWidthView, RenderableSpaceView
from app.widgets.citation_note import CitationNote
from app.widgets.task_progress import TASK_TITLES
from app.widgets.node_progress import NodeProgress

__all__ = ["RenderableTab", "TAB", "width_text"]

TITLES = {RENDERABLE_NODE: "Renderable space"}


def width_text(study: RenderableStudy, quality: str = "all") -> str:
    """The M-width in words, ``"M-width (stable): −0.2202 to 0.7051 kg (0.9253 kg)"``."""
    w = study.width
    lo, hi = (w.m_min, w.m_max) if quality == "all" else w.by_quality[quality]
    return (f"M-width ({QUALITY_LABELS[quality]}): {format_number(lo)} to {format_number(hi)} kg "
            f"({format_number(hi - lo)} kg)")


class RenderableTab(AsyncJobs, AnalysisTab):
    job_titles = TITLES
    title = "Renderable space"
    order = 38
    nodes = frozenset({RENDERABLE_NODE})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        nodes_renderable.register(graph)
        TASK_TITLES.setdefault(RENDERABLE_NODE, TITLES[RENDERABLE_NODE])

    def build(self) -> None:
        ctx = self.ctx
        self._held: dict[str, Hashable] = {}
        self._errors: dict[str, str] = {}
        self.panel = RenderablePanel(ctx.model, ctx.editor)
        self.space_view = RenderableSpaceView()
        self.space_view.pointPicked.connect(self.set_environment)
        self.width_view = MWidthView()
        self.progress = {RENDERABLE_NODE: NodeProgress(ctx.graph, RENDERABLE_NODE, TITLES[RENDERABLE_NODE])}
        self.progress[RENDERABLE_NODE].rerun.connect(self.run_again)
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
        form = QFormLayout()
        form.addRow("Map shows", self.quality)
        lay.addLayout(form)
        lay.addWidget(self.summary)
        lay.addWidget(self.panel, 1)
        scroll = QScrollArea()  # the settings scroll on their own: the plots keep the tab's height
        scroll.setWidget(left)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        scroll.setMinimumWidth(270)
        scroll.setMaximumWidth(360)
        right = QSplitter(Qt.Orientation.Vertical)
        top = QWidget()
        tl = QVBoxLayout(top)
        tl.setContentsMargins(0, 0, 0, 0)
        tl.addWidget(self.space_view, 1)
        tl.addWidget(self.progress[RENDERABLE_NODE])
        right.addWidget(top)
        right.addWidget(self.width_view)
        right.setSizes([70, 30])
        right.setChildrenCollapsible(False)
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(scroll)
        split.addWidget(right)
        split.setStretchFactor(1, 1)
        split.setChildrenCollapsible(False)
        body = QVBoxLayout(scroll_body(self))
        body.setContentsMargins(4, 2, 4, 4)
        body.addWidget(split, 1)
        body.addWidget(CitationNote(COLONNESE_CHAN, COLONNESE_OKAMURA))
        ctx.graph.ready.connect(self._on_ready)
        ctx.graph.cancelled.connect(self.on_job_cancelled)
        ctx.graph.failed.connect(self.on_job_failed)

    # -- edits ------------------------------------------------------------------------------------------
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

    # -- pulling ------------------------------------------------------------------------------------------
    def _pull(self, name: str) -> Any:
        g = self.ctx.graph
        held = self._held.get(name)
        if held is not None:
            if held == g.key_of(name):
                return g.result(name)
            del self._held[name]
            self._errors.pop(name, None)
        return g.request(name)

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

    def update_views(self) -> None:
        study = self._pull(RENDERABLE_NODE)
        busy = not self.ctx.graph.is_fresh(RENDERABLE_NODE) and RENDERABLE_NODE not in self._held
        self._draw(study)
        self.space_view.set_busy(busy)
        self.width_view.header.setText(f"<b>{self.width_view.title}</b>" + ("  <i>(updating…)</i>" if busy else ""))
        if RENDERABLE_NODE in self._errors:
            self.space_view.set_warning([self._errors[RENDERABLE_NODE]])
        self.refreshes += 1
        self.stale = False

    def _draw(self, study: RenderableStudy | None) -> None:
        sec = renderable_section(self.ctx.model.profile)
        shown = sec.qualities if study is None else study.space.qualities
        self._sync_qualities(tuple(shown))
        quality = self.selected_quality()
        if self.space_view.study is not study or self.space_view.quality != quality \
                or self.space_view.stiffness != sec.virtual_stiffness:
            self.space_view.update_space(study, quality, sec.virtual_stiffness)
        self.space_view.update_point(sec.virtual_mass, sec.virtual_damping)
        self.width_view.update_width(study, sec.virtual_mass)
        self.summary.setText("Computing the renderable space…" if study is None else self._summary(study, quality))

    def _summary(self, study: RenderableStudy, quality: str) -> str:
        sec = renderable_section(self.ctx.model.profile)
        k = k_max_at(study.space, sec.virtual_mass, sec.virtual_damping, quality)
        where = ("outside the grid" if math.isnan(k) else
                 f"K_max = {format_number(k)} N/m at the nearest grid point, so K = "
                 f"{format_number(sec.virtual_stiffness)} N/m is "
                 f"{'renderable' if 0 < sec.virtual_stiffness <= k or (sec.virtual_stiffness == 0 and k > 0) else 'not renderable'}")
        return "\n".join([width_text(study, quality),
                          f"Volume of the space: {format_number(study.space.volume)} kg·decades²",
                          f"Rendered (M, B) = ({format_number(sec.virtual_mass)} kg, "
                          f"{format_number(sec.virtual_damping)} N·s/m): {where}.",
                          "Click the map to set the rendered (M, B)."])

    # -- worker reports -----------------------------------------------------------------------------------
    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == RENDERABLE_NODE and self.isVisible():
            self.refresh()

    def views(self) -> list[PlotView]:
        return [self.space_view, self.width_view]


TAB = RenderableTab
