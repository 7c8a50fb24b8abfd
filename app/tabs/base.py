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

from PySide6.QtCore import QEvent, QObject, QSize, QTimer, Signal
from PySide6.QtGui import QResizeEvent, QShowEvent
from PySide6.QtWidgets import QAbstractScrollArea, QFrame, QLabel, QScrollArea, QVBoxLayout, QWidget

from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel
from app.core.settings import Settings
from app.views.base import PlotView

__all__ = ["AppContext", "AnalysisTab", "scroll_body", "PLOT_MIN_HEIGHT"]

#: The least height of a plot (its PlotWidget) on any tab: below it a tab scrolls instead.
PLOT_MIN_HEIGHT = 120


class _TabScroll(QScrollArea):
    """A scroll area that gives its body the viewport's size, never less than the body's minimum.

    Not ``widgetResizable``: that sizes a body with word-wrapped labels (height-for-width) by its
    preferred height, so that a tab would scroll at any window height.
    """

    def __init__(self, parent: QWidget) -> None:
        super().__init__(parent)
        self.setObjectName("tabScroll")
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setWidgetResizable(False)

    def set_body(self, body: QWidget) -> None:
        self.setWidget(body)
        body.installEventFilter(self)
        self.viewport().installEventFilter(self)

    def fit_body(self) -> None:
        body = self.widget()
        if body is None:
            return
        least = body.minimumSizeHint().expandedTo(body.minimumSize())
        view = self.maximumViewportSize()  # the viewport's size without scroll bars
        width = max(least.width(), view.width())
        if least.height() > view.height():  # a vertical scroll bar takes part of the width
            width = max(least.width(), view.width() - self.verticalScrollBar().sizeHint().width())
        height = max(least.height(), view.height())
        if width > view.width():
            height = max(least.height(), view.height() - self.horizontalScrollBar().sizeHint().height())
        if body.size() != QSize(width, height):
            body.resize(width, height)
        deficit = self._wrapped_deficit()  # word-wrapped labels at this width need more than the minimum said
        if deficit > 0:
            body.resize(width, height + deficit)

    def _wrapped_deficit(self) -> int:
        """How many pixels the body's word-wrapped labels lack at their laid-out width (not those in a
        scroll area of their own)."""
        body = self.widget()
        layout = body.layout()
        if layout is None:
            return 0
        layout.activate()
        missing = 0
        for label in body.findChildren(QLabel):
            if not (label.wordWrap() and label.isVisibleTo(body) and label.width() > 1):
                continue
            parent = label.parentWidget()
            while parent is not None and parent is not body and not isinstance(parent, QAbstractScrollArea):
                parent = parent.parentWidget()
            if parent is body:
                missing += max(0, label.heightForWidth(label.width()) - label.height())
        return missing

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self.fit_body()

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() in (QEvent.Type.LayoutRequest, QEvent.Type.Resize) and watched is not None:
            if watched is self.widget() and event.type() == QEvent.Type.LayoutRequest:
                QTimer.singleShot(0, self, self.fit_body)  # after the layout took the new minimum
            elif watched is self.viewport():
                self.fit_body()
        return super().eventFilter(watched, event)


def scroll_body(tab: QWidget) -> QWidget:
    """The widget a tab lays its contents on: inside a scroll area that fills ``tab``.

    A tab's contents keep their minimum size (every plot at least :data:`PLOT_MIN_HEIGHT` tall, every
    label whole); on a window smaller than that the tab scrolls instead of making the window's
    minimum size larger than a laptop screen (1024×700 fits).
    """
    area = _TabScroll(tab)
    body = QWidget()
    body.setObjectName("tabBody")
    area.set_body(body)
    outer = QVBoxLayout(tab)
    outer.setContentsMargins(0, 0, 0, 0)
    outer.addWidget(area)
    return body


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
        for view in self.views():  # a plot never shrinks below a readable height: the tab scrolls
            view.plot_widget.setMinimumHeight(max(view.plot_widget.minimumHeight(), PLOT_MIN_HEIGHT))
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
