"""The settings of the Workspace tab: the profile's ``multidof`` section (schema 7, issue 25).

The handle's position, the wall (isotropic or a plane wall along a normal, given by its angle) and
its damping, and the map's grid.  Every field edits the section through
:class:`~app.widgets.section_binding.SectionBinding`: one undo command per edit, the first creating
the section (undo restores a profile without one).  A refused value is said below the fields, and
the fields show the profile again.  The linkage's own parameters are edited in the profile file.
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QComboBox, QFormLayout, QGroupBox, QLabel, QSpinBox, QVBoxLayout, QWidget

from analysis.profiles.schema import MAX_GRID_POINTS, WALL_KINDS
from analysis.study import multidof_section

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.widgets.colors import ERROR_STYLE
from app.widgets.sci_spin_box import SciSpinBox
from app.widgets.section_binding import SectionBinding

__all__ = ["WorkspacePanel", "NUMBER_FIELDS"]

#: The section's numbers shown as fields: name -> (group, label, unit shown).
NUMBER_FIELDS: dict[str, tuple[str, str, str]] = {
    "handle_x": ("handle", "x", "m"), "handle_y": ("handle", "y", "m"),
    "wall_damping": ("wall", "Damping b", "N·s/m"),
    "x_min": ("grid", "x from", "m"), "x_max": ("grid", "x to", "m"),
    "y_min": ("grid", "y from", "m"), "y_max": ("grid", "y to", "m"),
}


class WorkspacePanel(QWidget):
    """Groups: Handle, Wall, Map grid; ``error`` says a refusal."""

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.model = model
        self.section = SectionBinding(model, editor, "multidof", multidof_section, "workspace")
        groups = {"handle": QGroupBox("Handle position"), "wall": QGroupBox("Wall"), "grid": QGroupBox("Map grid")}
        forms = {k: QFormLayout(g) for k, g in groups.items()}
        self.wall_kind = QComboBox()
        for key, text in WALL_KINDS.items():
            self.wall_kind.addItem(text, key)
        self.wall_kind.setObjectName("multidof_wall_kind")
        self.wall_kind.currentIndexChanged.connect(self._on_kind)
        forms["wall"].addRow("Kind", self.wall_kind)
        self.angle = SciSpinBox(log_step=False, suffix="°")
        self.angle.setObjectName("multidof_wall_angle")
        self.angle.setToolTip("The plane wall's normal, as its angle from the x axis")
        self.angle.editingFinished.connect(self._on_angle)
        forms["wall"].addRow("Normal at", self.angle)
        self.fields: dict[str, SciSpinBox] = {}
        for name, (group, label, unit) in NUMBER_FIELDS.items():
            f = SciSpinBox(log_step=name == "wall_damping", suffix=unit)
            f.setObjectName(f"multidof_{name}")
            f.setMaximumWidth(140)
            f.editingFinished.connect(lambda n=name: self.write(n, self.fields[n].value()))
            self.fields[name] = f
            forms[group].addRow(label, f)
        self.points: dict[str, QSpinBox] = {}
        for name, label in (("x_points", "x points"), ("y_points", "y points")):
            s = QSpinBox()
            s.setRange(2, MAX_GRID_POINTS)
            s.setKeyboardTracking(False)
            s.setObjectName(f"multidof_{name}")
            s.valueChanged.connect(lambda v, n=name: self.write(n, int(v)))
            self.points[name] = s
            forms["grid"].addRow(label, s)
        self.error = QLabel("")
        self.error.setStyleSheet(ERROR_STYLE)
        self.error.setWordWrap(True)
        self.error.setTextFormat(Qt.TextFormat.PlainText)
        self.error.hide()
        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        for g in groups.values():
            lay.addWidget(g)
        lay.addWidget(self.error)
        lay.addStretch(1)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def write(self, name: str, value: object) -> str | None:
        """Set one field of the section (one undo step); returns the refusal, if any."""
        return self.write_many({name: value}, name.replace("_", " "))

    def write_many(self, changes: dict[str, object], label: str) -> str | None:
        return self.section.write_shown(changes, label, self.error, self.refresh)

    @Slot()
    def _on_kind(self) -> None:
        self.write("wall_kind", self.wall_kind.currentData())

    @Slot()
    def _on_angle(self) -> None:
        a = math.radians(self.angle.value())
        self.write_many({"wall_normal": (math.cos(a), math.sin(a))}, "wall normal")

    @Slot(str)
    def _on_field(self, name: str) -> None:
        if name in ("multidof", "sample_time"):
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        sec = self.section.current()
        widgets = [self.wall_kind, self.angle, *self.fields.values(), *self.points.values()]
        for w in widgets:
            w.blockSignals(True)
        self.wall_kind.setCurrentIndex(max(0, self.wall_kind.findData(sec.wall_kind)))
        self.angle.setValue(math.degrees(math.atan2(sec.wall_normal[1], sec.wall_normal[0])))
        self.angle.setEnabled(sec.wall_kind == "normal")
        for name, f in self.fields.items():
            f.setValue(getattr(sec, name))
        for name, s in self.points.items():
            s.setValue(getattr(sec, name))
        for w in widgets:
            w.blockSignals(False)
