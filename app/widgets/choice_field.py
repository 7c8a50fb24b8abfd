"""A labelled combo box bound to one choice in the model (two-way, like LogSliderField)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QComboBox, QHBoxLayout, QLabel, QWidget

from ..model import ProfileModel

__all__ = ["ChoiceField"]


class ChoiceField(QWidget):
    """``label [combo]``; ``options`` are ``(value, text)``; ``write(value)`` returns a refusal or None."""

    def __init__(self, model: ProfileModel, fields: Iterable[str], read: Callable[[ProfileModel], object],
                 write: Callable[[object], str | None], label: str, options: Sequence[tuple[object, str]],
                 tooltip: str = "", parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._fields, self._read, self._write = model, frozenset(fields), read, write
        self._values = [v for v, _ in options]
        self._syncing = False
        self.label = QLabel(label)
        self.label.setTextFormat(Qt.TextFormat.RichText)
        self.combo = QComboBox()
        # long option texts must not widen the whole tab: the popup still shows them in full
        self.combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.combo.setMinimumContentsLength(12)
        for _, text in options:
            self.combo.addItem(text)
        if tooltip:
            self.combo.setToolTip(tooltip)
            self.label.setToolTip(tooltip)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.label)
        lay.addWidget(self.combo, 1)
        self.combo.currentIndexChanged.connect(self._on_index)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def value(self) -> object:
        return self._values[self.combo.currentIndex()]

    def set_value(self, value: object) -> None:
        """Select ``value`` as the user would (sends the edit)."""
        self.combo.setCurrentIndex(self._values.index(value))

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in self._fields:
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        value = self._read(self._model)
        if value not in self._values:
            return
        self._syncing = True
        try:
            self.combo.setCurrentIndex(self._values.index(value))
        finally:
            self._syncing = False

    @Slot(int)
    def _on_index(self, index: int) -> None:
        if self._syncing or index < 0:
            return
        reason = self._write(self._values[index])
        if reason:
            self.combo.setToolTip(reason)
            self.refresh()
