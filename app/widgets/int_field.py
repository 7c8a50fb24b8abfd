"""A labelled integer spin box bound to one integer in the model (two-way)."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QSpinBox, QWidget

from ..model import ProfileModel

__all__ = ["IntField"]


class IntField(QWidget):
    """``label [spin]``; ``write(value)`` returns the reason a value was refused, or None."""

    def __init__(self, model: ProfileModel, fields: Iterable[str], read: Callable[[ProfileModel], int],
                 write: Callable[[int], str | None], label: str, lo: int, hi: int, tooltip: str = "",
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._fields, self._read, self._write = model, frozenset(fields), read, write
        self._syncing = False
        self.label = QLabel(label)
        self.label.setTextFormat(Qt.TextFormat.RichText)
        self.spin = QSpinBox()
        self.spin.setRange(lo, hi)
        self.spin.setKeyboardTracking(False)
        if tooltip:
            self.spin.setToolTip(tooltip)
            self.label.setToolTip(tooltip)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.label)
        lay.addWidget(self.spin)
        lay.addStretch(1)
        self.spin.valueChanged.connect(self._on_value)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in self._fields:
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        self._syncing = True
        try:
            self.spin.setValue(int(self._read(self._model)))
        finally:
            self._syncing = False

    @Slot(int)
    def _on_value(self, value: int) -> None:
        if self._syncing:
            return
        reason = self._write(value)
        if reason:
            self.spin.setToolTip(reason)
            self.refresh()
