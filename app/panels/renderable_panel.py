"""The settings of the Renderable space tab: the profile's ``renderable`` section (schema 6, issue 24).

The rendered environment (M, B, K), the acceleration estimate and its low-pass, the qualities and
their settings (grasp set, band, tolerance, encoder resolution and force-noise limit) and the (M, B)
grid.  Every field edits the section through :class:`~app.widgets.section_binding.SectionBinding`:
one undo command per edit, the first creating the section (undo restores a profile without one).
A refused value (out of its range, or the band above Nyquist) is said below the fields and the
fields show the profile again.  Frequencies are shown in Hz; the profile stores rad/s.
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from analysis.profiles.schema import GRASP_SETS, MAX_GRID_POINTS
from analysis.sampled import ACCELERATION_KINDS, QUALITIES
from analysis.sampled.rendered import LOWPASS_KINDS
from analysis.study import renderable_section

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.widgets.colors import ERROR_STYLE
from app.widgets.sci_spin_box import SciSpinBox
from app.widgets.section_binding import SectionBinding

__all__ = ["RenderablePanel", "NUMBER_FIELDS", "SHORT_TEXTS"]

_HZ = 2.0 * math.pi
#: The section's numbers shown as fields: name -> (group, label, unit shown, stored per shown unit).
NUMBER_FIELDS: dict[str, tuple[str, str, str, float]] = {
    "virtual_mass": ("env", "M", "kg", 1.0),
    "virtual_damping": ("env", "B", "N·s/m", 1.0),
    "virtual_stiffness": ("env", "K", "N/m", 1.0),
    "acceleration_cutoff": ("acc", "Low-pass at", "Hz", _HZ),
    "band_low": ("q", "Band from", "Hz", _HZ),
    "band_high": ("q", "Band to", "Hz", _HZ),
    "tolerance": ("q", "Tolerance ε", "", 1.0),
    "quiet_resolution": ("q", "Encoder q", "m", 1.0),
    "quiet_force_noise": ("q", "Force noise", "N", 1.0),
    "mass_min": ("grid", "M from", "kg", 1.0),
    "mass_max": ("grid", "M to", "kg", 1.0),
    "damping_min": ("grid", "B from", "N·s/m", 1.0),
    "damping_max": ("grid", "B to", "N·s/m", 1.0),
}
_CHOICES = {"acceleration_kind": ("acc", "Estimate", ACCELERATION_KINDS),
            "acceleration_lowpass": ("acc", "Low-pass", LOWPASS_KINDS),
            "grasps": ("q", "Grasps", GRASP_SETS)}
#: The combo boxes' short item texts (the column is ~170 px wide); each item's full description
#: (:data:`~analysis.sampled.ACCELERATION_KINDS`, ...) is its tool tip.
SHORT_TEXTS = {"second_difference": "second difference", "filtered_velocity": "filtered velocity",
               "none": "no low-pass", "lowpass1": "first-order", "butter2": "2nd-order Butterworth",
               "hands_off": "hands-off", "firm": "hands-off, firm", "all": "hands-off, firm, rigid"}
#: The quiet quality's encoder resolution before one is set (m): a 10 µm encoder.
DEFAULT_RESOLUTION = 1e-5


class RenderablePanel(QWidget):
    """Groups: Rendered environment, Acceleration estimate, Qualities, Grid; ``error`` says a refusal."""

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.model = model
        self.section = SectionBinding(model, editor, "renderable", renderable_section, "renderable")
        groups = {"env": QGroupBox("Rendered environment F = M â + B v̂ + K x"),
                  "acc": QGroupBox("Acceleration estimate â"), "q": QGroupBox("Qualities"),
                  "grid": QGroupBox("Grid of (M, B)")}
        forms = {k: QFormLayout(g) for k, g in groups.items()}
        for f in forms.values():
            f.setContentsMargins(6, 4, 6, 4)
            f.setVerticalSpacing(2)
        self.quality_boxes: dict[str, QCheckBox] = {}
        row = QHBoxLayout()
        for q, text in QUALITIES.items():
            box = QCheckBox(q)
            box.setToolTip(text)
            box.toggled.connect(self._on_qualities)
            self.quality_boxes[q] = box
            row.addWidget(box)
        forms["q"].addRow(row)
        self.choices: dict[str, QComboBox] = {}
        for name, (group, label, options) in _CHOICES.items():
            combo = QComboBox()
            combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
            combo.setMinimumContentsLength(14)  # the column's width, not the longest description's
            for key, text in options.items():
                combo.addItem(SHORT_TEXTS.get(key, text), key)
                combo.setItemData(combo.count() - 1, text, Qt.ItemDataRole.ToolTipRole)
            combo.setObjectName(f"renderable_{name}")
            combo.currentIndexChanged.connect(lambda _i, n=name: self._on_choice(n))
            self.choices[name] = combo
            forms[group].addRow(label, combo)
        self._number_fields(forms)
        self.error = QLabel("")
        self.error.setStyleSheet(ERROR_STYLE)
        self.error.setWordWrap(True)
        self.error.setTextFormat(Qt.TextFormat.PlainText)
        self.error.hide()
        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(4)
        for g in groups.values():
            lay.addWidget(g)
        lay.addWidget(self.error)
        lay.addStretch(1)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def _number_fields(self, forms: dict[str, QFormLayout]) -> None:
        """The number fields (:data:`NUMBER_FIELDS`) and the grid's counts, each in its group."""
        self.fields: dict[str, SciSpinBox] = {}
        for name, (group, label, unit, _scale) in NUMBER_FIELDS.items():
            f = SciSpinBox(log_step=name not in ("virtual_mass", "virtual_damping", "mass_min", "mass_max",
                                                 "damping_min", "damping_max"), suffix=unit)
            f.setObjectName(f"renderable_{name}")
            f.setMaximumWidth(140)
            f.editingFinished.connect(lambda n=name: self._on_number(n))
            self.fields[name] = f
            forms[group].addRow(label, f)
        self.points: dict[str, QSpinBox] = {}
        for name, label in (("mass_points", "M values"), ("damping_points", "B values")):
            s = QSpinBox()
            s.setRange(2, MAX_GRID_POINTS)
            s.setKeyboardTracking(False)
            s.setObjectName(f"renderable_{name}")
            s.valueChanged.connect(lambda v, n=name: self.write(n, int(v)))
            self.points[name] = s
            forms["grid"].addRow(label, s)

    # -- edits ---------------------------------------------------------------------------------------
    def write(self, name: str, value: object) -> str | None:
        """Set one field of the section (one undo step); returns the refusal, if any."""
        return self.write_many({name: value}, name.replace("_", " "))

    def write_many(self, changes: dict[str, object], label: str) -> str | None:
        return self.section.write_shown(changes, label, self.error, self.refresh)

    @Slot()
    def _on_qualities(self) -> None:
        names = tuple(q for q, box in self.quality_boxes.items() if box.isChecked())
        changes: dict[str, object] = {"qualities": names}
        if "quiet" in names and self.section.current().quiet_resolution is None:
            changes["quiet_resolution"] = self.fields["quiet_resolution"].value() or DEFAULT_RESOLUTION
        self.write_many(changes, "qualities")

    def _on_choice(self, name: str) -> None:
        value = self.choices[name].currentData()
        if name == "acceleration_lowpass" and value != "none" and not math.isfinite(
                self.section.current().acceleration_cutoff):
            cutoff = self.fields["acceleration_cutoff"].value() * _HZ
            self.write_many({name: value, "acceleration_cutoff": cutoff}, "low-pass")
        elif name == "acceleration_lowpass" and value == "none":
            self.write_many({name: value, "acceleration_cutoff": math.inf}, "low-pass")
        else:
            self.write(name, value)

    def _on_number(self, name: str) -> None:
        scale = NUMBER_FIELDS[name][3]
        value = self.fields[name].value() * scale
        if name == "acceleration_cutoff" and self.section.current().acceleration_lowpass == "none":
            return  # shown for the next low-pass; without one the cut-off is inf
        self.write(name, value)

    # -- from the profile ---------------------------------------------------------------------------
    @Slot(str)
    def _on_field(self, name: str) -> None:
        if name in ("renderable", "sample_time", "device"):
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        sec = self.section.current()
        widgets = [*self.quality_boxes.values(), *self.choices.values(), *self.fields.values(), *self.points.values()]
        for w in widgets:
            w.blockSignals(True)
        for q, box in self.quality_boxes.items():
            box.setChecked(q in sec.qualities)
        for name, combo in self.choices.items():
            combo.setCurrentIndex(max(0, combo.findData(getattr(sec, name))))
            combo.setToolTip(combo.itemData(combo.currentIndex(), Qt.ItemDataRole.ToolTipRole))
        for name, f in self.fields.items():
            value = getattr(sec, name)
            if name == "acceleration_cutoff" and not math.isfinite(value):
                value = f.value() * _HZ or 2 * math.pi * 100.0  # the next low-pass's cut-off: 100 Hz
            if name == "quiet_resolution" and value is None:
                value = f.value() or DEFAULT_RESOLUTION
            f.setValue(value / NUMBER_FIELDS[name][3])
        self.fields["acceleration_cutoff"].setEnabled(sec.acceleration_lowpass != "none")
        self.fields["quiet_resolution"].setEnabled("quiet" in sec.qualities)
        self.fields["quiet_force_noise"].setEnabled("quiet" in sec.qualities)
        for name, s in self.points.items():
            s.setValue(getattr(sec, name))
        for w in widgets:
            w.blockSignals(False)
