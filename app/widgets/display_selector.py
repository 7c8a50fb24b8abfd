"""Impedance or admittance display (the profile's ``display`` field)."""

from __future__ import annotations

from PySide6.QtCore import Slot
from PySide6.QtWidgets import QButtonGroup, QHBoxLayout, QRadioButton, QWidget

from app.core.commands import Editor
from app.core.model import ProfileModel

__all__ = ["DisplaySelector"]


class DisplaySelector(QWidget):
    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._editor = model, editor
        self.impedance = QRadioButton("Impedance display")
        self.impedance.setToolTip("Spring-damper virtual coupling, section III (eq. 4, 9)")
        self.admittance = QRadioButton("Admittance display")
        self.admittance.setToolTip("Mass-damper virtual coupling with a PD position loop, section IV (eq. 16, 21)")
        self._group = QButtonGroup(self)
        self._group.addButton(self.impedance)
        self._group.addButton(self.admittance)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.impedance)
        lay.addWidget(self.admittance)
        lay.addStretch(1)
        self.impedance.clicked.connect(lambda: self._editor.edit("display", "impedance"))
        self.admittance.clicked.connect(lambda: self._editor.edit("display", "admittance"))
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "display":
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        button = self.impedance if self._model.profile.display == "impedance" else self.admittance
        button.setChecked(True)
