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

import math
from dataclasses import dataclass
from typing import ClassVar

import pyqtgraph as pg
from PySide6.QtCore import QEvent, QObject, QSize, Qt, Signal
from PySide6.QtGui import QResizeEvent, QShowEvent
from PySide6.QtWidgets import (
    QAbstractScrollArea,
    QFrame,
    QLabel,
    QScrollArea,
    QSizePolicy,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel
from app.core.settings import Settings
from app.views.base import PlotView
from app.widgets.settle import settle_later

__all__ = ["AppContext", "AnalysisTab", "scroll_body", "PLOT_MIN_HEIGHT", "DataAreaFloor", "SettingsScroll",
           "settings_beside_plots"]

#: The least height of a plot's data area (its ViewBox) on any tab: below it a tab scrolls instead.
PLOT_MIN_HEIGHT = 120


class DataAreaFloor(QObject):
    """Keeps a plot view's data area (the ViewBox) at least :data:`PLOT_MIN_HEIGHT` tall, as tall as its y
    axis's title is long, and the plot as wide as its axes and colour bar beside a data area that wide.

    The plot widget's minimum height is the data area's floor plus what the plot item lays out around
    it (title, x axis and its label, a legend row below the axis: their height changes with the
    legend's columns, so it is measured again whenever the view box is resized).  (The title and the
    warning above and below the plot are kept whole by the tab's scroll area: :func:`fit_wrapped_labels`.)
    """

    def __init__(self, view: PlotView) -> None:
        super().__init__(view)
        self.view = view
        view.plot.getViewBox().sigResized.connect(self.schedule)
        view.plot_widget.installEventFilter(self)
        self._own_width = view.plot_widget.minimumWidth()
        self.fit()

    def overhead(self) -> int:
        """The plot widget's height that is not data area (frame, title, axes, legend row)."""
        pw = self.view.plot_widget
        item = self.view.plot
        item.layout.activate()
        vb = self.view.plot.getViewBox()
        outside = max(0.0, pw.height() - item.size().height())  # the view's frame (the item may overflow it)
        return math.ceil(outside + item.size().height() - vb.size().height())

    def row_width(self) -> float:
        """The least width of the plot item's row that holds the data area (axes, colour bar, margins)."""
        item = self.view.plot
        layout = item.layout
        vb = item.getViewBox()
        row = next((r for r in range(layout.rowCount()) for c in range(layout.columnCount())
                    if layout.itemAt(r, c) is vb), None)
        if row is None:
            return 0.0
        cells = [layout.itemAt(row, c) for c in range(layout.columnCount())]
        shown = [c for c in cells if c is not None and c is not vb and c.isVisible()]
        margins = layout.getContentsMargins()
        spacing = layout.horizontalSpacing() * max(0, len(shown))
        return sum(c.effectiveSizeHint(Qt.SizeHint.MinimumSize).width() for c in shown) + spacing + margins[0] + margins[2]

    def y_titles(self) -> int:
        """The data area's height that the vertical axes' titles need (each title runs along its axis,
        whose height differs from the data area's by a fixed amount: a colour bar's axis is shorter)."""
        vb = self.view.plot.getViewBox()
        need = 0.0
        for item in self.view.plot_widget.scene().items():
            if not (isinstance(item, pg.AxisItem) and item.orientation in ("left", "right") and item.isVisible()
                    and item.label.isVisible() and item.labelText):
                continue
            margin = item.label.document().documentMargin()
            length = item.label.boundingRect().width() - 2 * margin  # the title is turned a quarter
            need = max(need, length + 4 + vb.size().height() - item.size().height())
        return math.ceil(need)

    def schedule(self, *_args: object) -> None:
        """Fit once the layouts took the change, before the next paint (:func:`settle_later`)."""
        settle_later(self, self.fit)

    def fit(self) -> None:
        pw = self.view.plot_widget
        least = max(PLOT_MIN_HEIGHT, self.y_titles()) + self.overhead()
        if pw.minimumHeight() != least:
            pw.setMinimumHeight(least)
        # never narrower than the axes, colour bar and their titles beside a data area PLOT_MIN_HEIGHT wide
        # (else they are cut on the right); the plot's title is not counted: a view may break it into lines
        # when narrow, and its width when wide would keep the plot wide
        width = max(self._own_width, math.ceil(self.row_width()) + PLOT_MIN_HEIGHT + pw.width() - pw.viewport().width())
        if pw.minimumWidth() != width:
            pw.setMinimumWidth(width)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() in (QEvent.Type.Resize, QEvent.Type.Show, QEvent.Type.LayoutRequest):
            self.schedule()
        return super().eventFilter(watched, event)


def fit_wrapped_labels(body: QWidget) -> bool:
    """Give each word-wrapped label of ``body`` (not those in a scroll area of their own) the height its
    text needs at its laid-out width as its minimum height; whether any changed.

    Qt computes a wrapped label's minimum height for another width, and a layout in height-for-width
    mode then gives the label its height by taking it from the plots beside it (a splitter does not
    pass height-for-width on at all).  With the label's own height as its minimum, and height-for-width
    off, every layout and splitter keeps both whole; a label's own minimum height stays its floor.
    """
    changed = False
    for label in body.findChildren(QLabel):
        if not (label.wordWrap() and label.isVisibleTo(body) and label.width() > 1):
            continue
        parent = label.parentWidget()
        while parent is not None and parent is not body and not isinstance(parent, QAbstractScrollArea):
            parent = parent.parentWidget()
        if parent is not body:
            continue
        policy = label.sizePolicy()
        if policy.hasHeightForWidth():  # (QLabel turns it on again with every new text)
            policy.setHeightForWidth(False)
            label.setSizePolicy(policy)
        floor = label.property("ownMinimumHeight")
        if floor is None:
            floor = label.minimumHeight()
            label.setProperty("ownMinimumHeight", floor)
        need = max(int(floor), label.heightForWidth(label.width()) if label.text() else 0)
        if label.minimumHeight() != need:
            label.setMinimumHeight(need)
            changed = True
        grows = bool(policy.verticalPolicy().value & QSizePolicy.PolicyFlag.ExpandFlag.value)
        if not grows and label.maximumHeight() != need:  # no blank lines (they would misalign plots' titles)
            label.setMaximumHeight(need)
            changed = True
    return changed


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
        view = self.maximumViewportSize()  # the viewport's size without scroll bars
        fit_wrapped_labels(body)  # their minimum heights for their widths, before the body's minimum is read
        least = body.minimumSizeHint().expandedTo(body.minimumSize())
        width = max(least.width(), view.width())
        if least.height() > view.height():  # a vertical scroll bar takes part of the width
            width = max(least.width(), view.width() - self.verticalScrollBar().sizeHint().width())
        height = max(least.height(), view.height())
        if width > view.width():
            height = max(least.height(), view.height() - self.horizontalScrollBar().sizeHint().height())
        if body.size() != QSize(width, height):
            body.resize(width, height)

    def resizeEvent(self, event: QResizeEvent) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self.fit_body()

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() in (QEvent.Type.LayoutRequest, QEvent.Type.Resize) and watched is not None:
            if watched is self.widget():  # after the layout took the new minimum, or the labels their widths
                settle_later(self, self.fit_body)
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


class SettingsScroll(QScrollArea):
    """A tab's settings beside its plots: they scroll vertically, never horizontally, and the area
    is at least as wide as their minimum width plus the vertical scroll bar, so that no field or
    sentence is cut at its right edge (a fixed maximum width used to cut them at 1280×720)."""

    def __init__(self, settings: QWidget, minimum: int, maximum: int) -> None:
        super().__init__()
        self._limits = (minimum, maximum)
        self.setWidget(settings)
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        settings.installEventFilter(self)
        self.fit_width()

    def fit_width(self) -> None:
        """The width limits from the settings' current minimum width."""
        need = self.widget().minimumSizeHint().width() + self.verticalScrollBar().sizeHint().width() + 2
        low, high = max(self._limits[0], need), max(self._limits[1], need)
        if (self.minimumWidth(), self.maximumWidth()) != (low, high):
            self.setMinimumWidth(low)
            self.setMaximumWidth(high)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if watched is self.widget() and event.type() == QEvent.Type.LayoutRequest:
            settle_later(self, self.fit_width)
        return super().eventFilter(watched, event)


def settings_beside_plots(tab: QWidget, settings: QWidget, plots: QWidget, width: tuple[int, int],
                          note: QWidget) -> SettingsScroll:
    """Lay out a tab: its ``settings`` (a :class:`SettingsScroll` of ``width`` = (minimum, maximum)
    px) on the left of its ``plots``, in a splitter, and ``note`` (the citation) below, on the tab's
    :func:`scroll_body`.  Returns the settings' scroll area."""
    scroll = SettingsScroll(settings, *width)
    split = QSplitter(Qt.Orientation.Horizontal)
    split.addWidget(scroll)
    split.addWidget(plots)
    split.setStretchFactor(1, 1)
    split.setChildrenCollapsible(False)
    body = QVBoxLayout(scroll_body(tab))
    body.setContentsMargins(4, 2, 4, 4)
    body.addWidget(split, 1)
    body.addWidget(note)
    return scroll


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
        self._floors: list[DataAreaFloor] = []

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
        for view in self.views():  # a plot's data area never shrinks below a readable height: the tab scrolls
            self._floors.append(DataAreaFloor(view))
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
