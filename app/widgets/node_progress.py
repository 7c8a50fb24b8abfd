"""A compact progress bar with Cancel for one asynchronous graph node (shown while it runs).

After a cancel it says so and offers "Run again" (:attr:`NodeProgress.rerun`); the owner decides
what that means (normally: request the node again).
"""

from __future__ import annotations

from PySide6.QtCore import Signal, Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QPushButton, QWidget

from app.core.compute_graph import ComputeGraph
from app.widgets.progress_value import set_progress

__all__ = ["NodeProgress"]


class NodeProgress(QWidget):
    rerun = Signal(str)

    def __init__(self, graph: ComputeGraph, name: str, title: str, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._graph, self.name, self.title = graph, name, title
        self.running = False
        self.label = QLabel()
        self.bar = QProgressBar()
        self.bar.setMaximumHeight(14)
        self.bar.setFormat("%v/%m")  # the count lives in the bar, so the label's width never changes
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setToolTip("Stop this computation (the last result stays on the plot)")
        self.rerun_button = QPushButton("Run again")
        lay = QHBoxLayout(self)
        lay.setContentsMargins(4, 0, 4, 0)
        lay.addWidget(self.label)
        lay.addWidget(self.bar, 1)
        lay.addWidget(self.cancel_button)
        lay.addWidget(self.rerun_button)
        self.cancel_button.clicked.connect(self.cancel)
        self.rerun_button.clicked.connect(lambda: self.rerun.emit(self.name))
        graph.started.connect(self._on_started)
        graph.progress.connect(self._on_progress)
        graph.ready.connect(self._on_end)
        graph.failed.connect(self._on_failed)
        graph.cancelled.connect(self._on_cancelled)
        self.hide()

    def _show(self, text: str, running: bool) -> None:
        self.running = running
        self.label.setText(text)
        self.bar.setVisible(running)
        self.cancel_button.setVisible(running)
        self.rerun_button.setVisible(not running)
        self.show()

    @Slot(str)
    def _on_started(self, name: str) -> None:
        if name == self.name:
            self.bar.setRange(0, 0)
            self._show(f"{self.title}…", True)

    @Slot(str, int, int)
    def _on_progress(self, name: str, done: int, total: int) -> None:
        if name == self.name and self.running:
            set_progress(self.bar, done, max(total, 1))

    @Slot(str)
    def _on_end(self, name: str) -> None:
        if name == self.name:
            self.running = False
            self.hide()

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name == self.name:
            self._show(f"{self.title} failed: {message}", False)

    @Slot(str)
    def _on_cancelled(self, name: str) -> None:
        if name == self.name:
            self._show(f"{self.title}: cancelled (showing the last result)", False)

    @Slot()
    def cancel(self) -> None:
        if self.running:
            self._graph.cancel(self.name)
