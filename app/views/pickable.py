"""A plot whose left click picks a point in data units (the design chart, the Z-width region)."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal, Slot
from PySide6.QtWidgets import QWidget

from app.views.base import PlotView

__all__ = ["PickablePlotView"]


class PickablePlotView(PlotView):
    """:class:`PlotView` that emits :attr:`pointPicked` ``(x, y)`` in data units (log axes
    undone) for a single left click inside the plot area."""

    pointPicked = Signal(float, float)

    def __init__(self, title: str, parent: QWidget | None = None) -> None:
        super().__init__(title, parent)
        self.plot_widget.scene().sigMouseClicked.connect(self._on_click)

    @Slot(object)
    def _on_click(self, event: object) -> None:
        if event.button() != Qt.MouseButton.LeftButton or event.double():
            return
        vb = self.plot.getViewBox()
        pos = event.scenePos()
        if not vb.sceneBoundingRect().contains(pos):
            return
        x, y = self.data_point(vb.mapSceneToView(pos))
        event.accept()
        self.pointPicked.emit(float(x), float(y))
