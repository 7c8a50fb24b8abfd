"""Progress bar and Cancel button for the worker's jobs (a permanent status-bar widget).

The widget keeps a fixed size and only swaps its contents, so a job starting or ending repaints
this small area instead of re-laying out (and repainting) the whole window.
"""

from __future__ import annotations

from PySide6.QtCore import Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QProgressBar, QPushButton, QSizePolicy, QWidget

from app.core.compute_graph import ComputeGraph
from app.widgets.progress_value import set_progress

__all__ = ["TaskProgress", "TASK_TITLES"]

TASK_TITLES = {
    "design_chart": "Computing design chart",
    "min_mass": "Minimizing m_c",
    "wall_tradeoff": "Sweeping B_c (transparency / robustness)",
    "sampled_map": "Computing sampled-data stability map",
    "sampled_exact_chart": "Computing exact k_c limits",
    "sampled_limit": "Finding exact k_c limit",
    "sampled_simulation": "Simulating contact",
}


class TaskProgress(QWidget):
    def __init__(self, graph: ComputeGraph, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._graph = graph
        self._name: str | None = None
        self.label = QLabel()
        self.bar = QProgressBar()
        self.bar.setFixedWidth(160)
        self.bar.setTextVisible(True)
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setToolTip("Stop the running computation (the last result stays)")
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addStretch(1)
        lay.addWidget(self.label)
        lay.addWidget(self.bar)
        lay.addWidget(self.cancel_button)
        for w in (self.label, self.bar, self.cancel_button):
            sp = w.sizePolicy()
            sp.setRetainSizeWhenHidden(True)
            w.setSizePolicy(sp)
        self.label.setText(TASK_TITLES["design_chart"] + "…")
        self.setFixedSize(self.sizeHint())
        self.setSizePolicy(QSizePolicy.Policy.Fixed, QSizePolicy.Policy.Fixed)
        self.cancel_button.clicked.connect(self.cancel)
        graph.started.connect(self._on_started)
        graph.progress.connect(self._on_progress)
        graph.ready.connect(self._on_end)
        graph.failed.connect(lambda name, _msg: self._on_end(name))
        graph.cancelled.connect(self._on_end)
        self._set_active(False)

    @property
    def active(self) -> bool:
        """Whether a job is shown (the widget itself always stays in the status bar)."""
        return self._name is not None

    def _set_active(self, on: bool) -> None:
        for w in (self.label, self.bar, self.cancel_button):
            w.setVisible(on)

    @Slot(str)
    def _on_started(self, name: str) -> None:
        self._name = name
        self.label.setText(TASK_TITLES.get(name, name) + "…")
        self.bar.setRange(0, 0)  # busy until the first report
        self._set_active(True)

    @Slot(str, int, int)
    def _on_progress(self, name: str, done: int, total: int) -> None:
        if name == self._name:
            set_progress(self.bar, done, total)

    @Slot(str)
    def _on_end(self, name: str) -> None:
        if name == self._name:
            self._name = None
            self._set_active(False)

    @Slot()
    def cancel(self) -> None:
        if self._name is not None:
            self._graph.cancel(self._name)
