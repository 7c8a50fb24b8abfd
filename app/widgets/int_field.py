"""A labelled integer spin box bound to one integer in the model (two-way)."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from PySide6.QtWidgets import QSpinBox, QWidget

from app.core.model import ProfileModel
from app.widgets.bound_field import BoundField

__all__ = ["IntField"]


class IntField(BoundField):
    """``label [spin]``; ``write(value)`` returns the reason a value was refused, or None."""

    def __init__(self, model: ProfileModel, fields: Iterable[str], read: Callable[[ProfileModel], int],
                 write: Callable[[int], str | None], label: str, lo: int, hi: int, tooltip: str = "",
                 parent: QWidget | None = None) -> None:
        super().__init__(model, fields, read, write, label, parent)
        self.spin = QSpinBox()
        self.spin.setRange(lo, hi)
        self.spin.setKeyboardTracking(False)
        self.spin.valueChanged.connect(self._send)
        self._bind(self.spin, tooltip, 0)

    def _show(self, value: object) -> None:
        self.spin.setValue(int(value))
