"""The two-way binding shared by the small labelled fields (choice, integer).

A field shows ``read(model)`` and refreshes when one of its model ``fields`` changes or the
profile is replaced; a user edit calls ``write(value)``, which returns the reason a value was
refused (shown as the editor's tooltip, and the field goes back to the model's value) or None.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QHBoxLayout, QLabel, QWidget

from app.core.model import ProfileModel

__all__ = ["BoundField"]


class BoundField(QWidget):
    """``label [editor]``; subclasses make the editor, call :meth:`_bind` and implement :meth:`_show`."""

    def __init__(self, model: ProfileModel, fields: Iterable[str], read: Callable[[ProfileModel], object],
                 write: Callable[[object], str | None], label: str, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._fields, self._read, self._write = model, frozenset(fields), read, write
        self._syncing = False
        self.label = QLabel(label)
        self.label.setTextFormat(Qt.TextFormat.RichText)
        self._editor: QWidget | None = None

    def _bind(self, editor: QWidget, tooltip: str, stretch: int) -> None:
        """Lay out ``label [editor]`` (with a trailing stretch when ``stretch`` is 0) and connect."""
        self._editor = editor
        if tooltip:
            editor.setToolTip(tooltip)
            self.label.setToolTip(tooltip)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.label)
        lay.addWidget(editor, stretch)
        if not stretch:
            lay.addStretch(1)
        self._model.fieldChanged.connect(self._on_field)
        self._model.profileReplaced.connect(self.refresh)
        self.refresh()

    def _show(self, value: object) -> None:
        raise NotImplementedError

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in self._fields:
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        self._syncing = True
        try:
            self._show(self._read(self._model))
        finally:
            self._syncing = False

    def _send(self, value: object) -> None:
        if self._syncing:
            return
        reason = self._write(value)
        if reason:
            self._editor.setToolTip(reason)
            self.refresh()
