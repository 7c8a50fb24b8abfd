"""The base class of analysis tabs and the context they are built with.

A tab names the graph nodes it pulls (:attr:`AnalysisTab.nodes`).  The main window calls
:meth:`AnalysisTab.refresh` only while the tab is visible; a hidden tab is marked stale and
refreshed when shown, so it computes nothing meanwhile.  A tab may add its own nodes to the graph
in :meth:`AnalysisTab.register_nodes`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from PySide6.QtWidgets import QWidget

from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel
from app.core.settings import Settings
from app.views.base import PlotView

__all__ = ["AppContext", "AnalysisTab"]


@dataclass(frozen=True)
class AppContext:
    model: ProfileModel
    graph: ComputeGraph
    editor: Editor
    settings: Settings


class AnalysisTab(QWidget):
    title: ClassVar[str] = ""
    order: ClassVar[int] = 100
    nodes: ClassVar[frozenset[str]] = frozenset()

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.ctx = ctx
        self.stale = True
        self.refreshes = 0
        self.dark = False  # the theme, for the rich texts a tab writes (app.views.base.for_theme)

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        """Add this tab's own nodes to the graph (none by default)."""

    def refresh(self) -> None:
        """Pull the nodes this tab shows and update its views (only called while visible)."""
        raise NotImplementedError

    def plot_views(self) -> list[PlotView]:
        return []

    def apply_theme(self, dark: bool) -> None:
        changed = dark != self.dark
        self.dark = dark
        for v in self.plot_views():
            v.apply_theme(dark)
        if changed:  # the tab's texts are written again in the theme's colours
            self.stale = True
            if self.isVisible():
                self.refresh()
