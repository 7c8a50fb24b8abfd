"""Live refresh: after an edit, the verdict and the visible tab catch up; hidden tabs stay stale.

Invalidations are coalesced: one refresh per event-loop turn, however many nodes became dirty.
"""

from __future__ import annotations

from PySide6.QtCore import QObject, QTimer, Slot
from PySide6.QtWidgets import QTabWidget
from shiboken6 import isValid

from app.core.compute_graph import ComputeGraph
from app.tabs import AnalysisTab
from app.views.verdict import VerdictView
from app.widgets.text_pacer import TextPacer

__all__ = ["LiveRefresh"]


class LiveRefresh(QObject):
    """Marks tabs stale on invalidation and refreshes the verdict and the current tab."""

    def __init__(self, graph: ComputeGraph, verdict: VerdictView, tabs: QTabWidget,
                 analysis_tabs: list[AnalysisTab], parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.graph, self.verdict, self.tabs, self.analysis_tabs = graph, verdict, tabs, analysis_tabs
        self.verdict_stale = True
        self._scheduled = False
        # the verdict's numbers: every step outside a drag, ten times a second during one
        self.texts = TextPacer(lambda: graph.interactive, self)
        graph.invalidated.connect(self._on_invalidated)
        tabs.currentChanged.connect(lambda _i: self.schedule())

    @Slot(object)
    def _on_invalidated(self, names: set[str]) -> None:
        # an edit: running jobs step aside while the visible views catch up (worker.py)
        self.graph.runner.defer_to_gui(0.05)
        if "stability" in names:
            self.verdict_stale = True
        for tab in self.analysis_tabs:
            if tab.nodes & names:
                tab.stale = True
        self.schedule()

    def schedule(self) -> None:
        """Refresh at the next turn of the event loop (once, however often this is called)."""
        if not self._scheduled:
            self._scheduled = True
            QTimer.singleShot(0, self.refresh_visible)

    @Slot()
    def refresh_visible(self) -> None:
        """Update the verdict and the visible tab from the graph (hidden tabs stay stale)."""
        self._scheduled = False
        if not (isValid(self.tabs) and isValid(self.verdict)):
            return  # the window closed before this queued refresh ran
        if self.verdict_stale:
            result = self.graph.get(self.graph.stability_name)
            self.texts.show("verdict", lambda: self.verdict.update_result(result) if isValid(self.verdict) else None)
            self.verdict_stale = False
        current = self.tabs.currentWidget()
        if isinstance(current, AnalysisTab) and current.stale:
            current.refresh()
