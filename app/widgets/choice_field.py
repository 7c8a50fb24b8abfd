"""A labelled combo box bound to one choice in the model (two-way, like LogSliderField)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

from PySide6.QtCore import Slot
from PySide6.QtWidgets import QComboBox, QWidget

from app.core.model import ProfileModel
from app.widgets.bound_field import BoundField

__all__ = ["ChoiceField"]


class ChoiceField(BoundField):
    """``label [combo]``; ``options`` are ``(value, text)``; ``write(value)`` returns a refusal or None."""

    def __init__(self, model: ProfileModel, fields: Iterable[str], read: Callable[[ProfileModel], object],
                 write: Callable[[object], str | None], label: str, options: Sequence[tuple[object, str]],
                 tooltip: str = "", parent: QWidget | None = None) -> None:
        super().__init__(model, fields, read, write, label, parent)
        self._values = [v for v, _ in options]
        self.combo = QComboBox()
        # long option texts must not widen the whole tab: the popup still shows them in full
        self.combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.combo.setMinimumContentsLength(12)
        for _, text in options:
            self.combo.addItem(text)
        self.combo.currentIndexChanged.connect(self._on_index)
        self._bind(self.combo, tooltip, 1)

    def value(self) -> object:
        return self._values[self.combo.currentIndex()]

    def set_value(self, value: object) -> None:
        """Select ``value`` as the user would (sends the edit)."""
        self.combo.setCurrentIndex(self._values.index(value))

    def _show(self, value: object) -> None:
        if value in self._values:
            self.combo.setCurrentIndex(self._values.index(value))

    @Slot(int)
    def _on_index(self, index: int) -> None:
        if index >= 0:
            self._send(self._values[index])
