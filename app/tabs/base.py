"""The base class of analysis tabs and the context they are built with.

A tab names the graph nodes it pulls (:attr:`AnalysisTab.nodes`).  The main window calls
:meth:`AnalysisTab.refresh` only while the tab is visible; a hidden tab is marked stale and
refreshed when shown, so it computes nothing meanwhile.  A tab may add its own nodes to the graph
in :meth:`AnalysisTab.register_nodes`.

A tab is built lazily: its widgets and plot views are created by :meth:`AnalysisTab.build` when the
tab is first shown, refreshed or asked for its views (:meth:`AnalysisTab.plot_views`), not when the
window is made; a tab that is never opened builds nothing.  What reads the views of every tab either
builds the tab (``plot_views``, ``refresh``) or skips the tabs not built yet (:meth:`is_built`, the
theme).  A subclass creates its widgets in ``build``, returns its views from ``views`` and updates
them in ``update_views``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from PySide6.QtCore import Signal
from PySide6.QtGui import QShowEvent
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
    viewsBuilt = Signal()  # the tab's widgets and views were just built (once per tab)

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.ctx = ctx
        self.stale = True
        self.refreshes = 0
        self.dark = False  # the theme, for the rich texts a tab writes (app.views.base.for_theme)
        self._built = False

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        """Add this tab's own nodes to the graph (none by default)."""

    @classmethod
    def has_plots(cls) -> bool:
        """Whether the tab shows plot views (known without building it)."""
        return cls.views is not AnalysisTab.views

    # -- lazy construction ----------------------------------------------------------------------------
    def is_built(self) -> bool:
        """Whether the tab's widgets and views exist (it was shown, refreshed or asked for its views)."""
        return self._built

    def ensure_built(self) -> None:
        """Build the tab's widgets and views now, unless built already; they take the current theme."""
        if self._built:
            return
        self._built = True
        self.build()
        self.apply_theme(self.dark)
        self.viewsBuilt.emit()

    def build(self) -> None:
        """Create the tab's widgets, views and connections (called once, by :meth:`ensure_built`)."""

    def setVisible(self, visible: bool) -> None:  # noqa: N802 - Qt API: a tab page is built before it shows
        if visible:
            self.ensure_built()
        super().setVisible(visible)

    def showEvent(self, event: QShowEvent) -> None:  # noqa: N802 - Qt API
        self.ensure_built()  # the window's first show reaches its current page without setVisible
        super().showEvent(event)

    # -- refresh and views ------------------------------------------------------------------------------
    def refresh(self) -> None:
        """Pull the nodes this tab shows and update its views (only called while visible); builds the tab."""
        self.ensure_built()
        self.update_views()

    def update_views(self) -> None:
        """What :meth:`refresh` does once the tab is built."""
        raise NotImplementedError

    def plot_views(self) -> list[PlotView]:
        """The tab's plot views (the tab is built first)."""
        self.ensure_built()
        return self.views()

    def views(self) -> list[PlotView]:
        """The plot views of a built tab (none by default)."""
        return []

    def apply_theme(self, dark: bool) -> None:
        changed = dark != self.dark
        self.dark = dark
        if not self._built:  # the views take the theme when they are built
            return
        for v in self.views():
            v.apply_theme(dark)
        if changed:  # the tab's texts are written again in the theme's colours
            self.stale = True
            if self.isVisible():
                self.refresh()
