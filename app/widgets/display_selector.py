"""Impedance or admittance display (the profile's ``display`` field): one radio button per display object."""

from __future__ import annotations

from PySide6.QtCore import Slot
from PySide6.QtWidgets import QButtonGroup, QHBoxLayout, QRadioButton, QWidget

from analysis.study import ADMITTANCE, DISPLAY_KINDS, IMPEDANCE, display_kind

from app.core.commands import Editor
from app.core.model import ProfileModel

__all__ = ["DisplaySelector"]

_TIPS = {IMPEDANCE.name: "Spring-damper virtual coupling, section III (eq. 4, 9)",
         ADMITTANCE.name: "Mass-damper virtual coupling with a PD position loop, section IV (eq. 16, 21)"}


class DisplaySelector(QWidget):
    """``buttons`` by display name; ``impedance`` and ``admittance`` are the two buttons."""

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._editor = model, editor
        self._group = QButtonGroup(self)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        self.buttons: dict[str, QRadioButton] = {}
        for name, kind in DISPLAY_KINDS.items():
            button = QRadioButton(kind.title)
            button.setToolTip(_TIPS.get(name, kind.title))
            button.clicked.connect(lambda _=False, n=name: self._editor.edit("display", n))
            self._group.addButton(button)
            lay.addWidget(button)
            self.buttons[name] = button
        lay.addStretch(1)
        self.impedance, self.admittance = self.buttons[IMPEDANCE.name], self.buttons[ADMITTANCE.name]
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "display":
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        self.buttons[display_kind(self._model.profile).name].setChecked(True)
