"""Controls of the wall controller (Eom, Suh & Yi, section 3, eqs. 7-17) and the current B_c.

The wall fields are two-way bound to the profile's ``wall`` section through
:class:`~app.widgets.section_binding.SectionBinding` (one undo command per edit or drag).  The
current controller damping B_c is not a profile field: the panel holds it (starting at the paper's
B_c = 15 N·s/m) and emits :attr:`WallPanel.bcChanged`; it is not an undo step.
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt, Signal, Slot
from PySide6.QtWidgets import QComboBox, QGridLayout, QGroupBox, QPushButton, QWidget

from analysis.study import default_bc, format_number, wall_settings

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.core.nodes_wall import HOLD_LABELS, PLANT_LABELS
from app.widgets.choice_field import ChoiceField
from app.widgets.int_field import IntField
from app.widgets.log_slider_field import LogSliderField
from app.widgets.section_binding import SectionBinding

__all__ = ["WallPanel", "HOLD_LABELS", "PLANT_LABELS"]



class WallPanel(QGroupBox):
    """The wall section's fields (``fields`` by name), the B_c field and the "robust optimum" button."""

    bcChanged = Signal(float)
    optimumRequested = Signal()

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__("Wall controller (Eom, Suh && Yi, eq. 7–17)", parent)
        self.setToolTip("Stored in the profile's wall section (B_c is a design variable of this tab)")
        self.bc = default_bc(model.profile)  # 15 N·s/m (the paper's), scaled on a wall derived from the device
        self._model = model
        self.section = SectionBinding(model, editor, "wall", wall_settings, "wall")
        self.fields: dict[str, QWidget] = {}
        g = QGridLayout(self)
        g.setContentsMargins(6, 4, 6, 4)
        g.setHorizontalSpacing(10)
        g.setVerticalSpacing(2)
        for r, row in enumerate(self._rows(model)):
            for c, w in enumerate(row):
                g.addWidget(w, r, c)
        self.bc_field = LogSliderField(model, (), lambda _m: self.bc, self._write_bc, editor,
                                       "<b>B<sub>c</sub></b>", "N·s/m", 0.1, 100.0,
                                       tooltip="Controller damping B_c of C(s) = B_c + K_c/s (eq. 12); "
                                               "not stored in the profile")
        self.bc_field.setObjectName("wall_bc")
        self.bc_field.make_compact()
        self.optimum_button = QPushButton("Use robust optimum")
        self.optimum_button.setToolTip("Set B_c to the B_c minimizing J subject to ‖L‖∞ ≤ 1 (section 3)")
        self.optimum_button.clicked.connect(self.optimumRequested)
        self.optimum_button.setEnabled(False)
        g.addWidget(self.bc_field, 3, 2)
        g.addWidget(self.optimum_button, 4, 2, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignTop)
        for c in range(3):
            g.setColumnStretch(c, 1)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self._on_replaced)
        self.update_enabled()

    def _rows(self, model: ProfileModel) -> list[list[QWidget]]:
        sec, s = self.section, self._slider
        plant = ChoiceField(model, ("wall",), sec.reader("plant"), sec.writer("plant", "plant"), "Plant",
                            list(PLANT_LABELS.items()),
                            "P(s) = 1/(m s + b), or the handle admittance of the profile's device chain")
        hold = ChoiceField(model, ("wall",), sec.reader("hold"), sec.writer("hold", "hold model"), "Hold",
                           list(HOLD_LABELS.items()),
                           "Model of the zero-order hold H(s) in eq. (9), (16).  The paper's J and ‖L‖∞ "
                           "depend on it: under the exact sampled loop B_c = 15 is not robustly stable.")
        order = IntField(model, ("wall",), sec.reader("weight_order"), sec.writer("weight_order", "weight order"),
                         "Weight order r", 0, 8, "w₁ = (ω_c/(s + ω_c))^r in eq. (11); r = 0 makes J infinite")
        self.fields.update(plant=plant, hold=hold, weight_order=order)
        for choice in (plant, hold):  # the chosen option's text is never cut
            choice.combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToContents)
            choice.combo.setMinimumWidth(choice.combo.sizeHint().width())
        return [
            [plant, s("mass", "m", "kg", 1e-4, 10.0, "Handle mass (eq. 7)"),
             s("damping", "b", "N·s/m", 1e-4, 10.0, "Handle damping (eq. 7)", zero=True)],
            [hold, s("wall_stiffness", "K", "N/m", 1.0, 1e6, "Virtual wall stiffness (eq. 8)", zero=True),
             s("wall_damping", "B", "N·s/m", 1e-3, 1e3, "Virtual wall damping (eq. 8)", zero=True)],
            [order, s("weight_cutoff", "ω<sub>c</sub>", "rad/s", 1.0, 1e5, "Cutoff of the weight w₁ (eq. 11)"),
             s("sample_time", "T", "s", 1e-5, 1e-1, "Sample period of the wall loop")],
            [s("alpha", "α", "", 0.0, 0.99, "Mass uncertainty of the weight W = α m s + β b (eq. 15)", log=False),
             s("beta", "β", "", 0.0, 1.0, "Damping uncertainty of the weight W = α m s + β b (eq. 15)", log=False)],
        ]

    def _slider(self, name: str, label: str, unit: str, lo: float, hi: float, tip: str, log: bool = True,
                zero: bool = False) -> LogSliderField:
        self.fields[name] = f = self.section.slider(name, label, unit, lo, hi, tip, log=log, allow_zero=zero)
        return f

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "wall":
            self.update_enabled()

    @Slot()
    def _on_replaced(self) -> None:
        """A new profile: its own starting B_c (another device may need a B_c decades away)."""
        self.update_enabled()
        self.set_bc(default_bc(self._model.profile))

    @Slot()
    def update_enabled(self) -> None:
        """m and b are the rigid plant's: disabled for the device chain."""
        rigid = self.section.current().plant == "rigid"
        for name in ("mass", "damping"):
            self.fields[name].setEnabled(rigid)

    def _write_bc(self, value: float, drag: int | None = None) -> str | None:
        if not (math.isfinite(value) and value >= 0):
            return "refused: must be >= 0 and finite (N s/m)"
        self.set_bc(value)
        return None

    def set_bc(self, value: float) -> None:
        """Set the current B_c; emits :attr:`bcChanged` if it changed."""
        value = float(value)
        if value == self.bc:
            return
        self.bc = value
        self.bc_field.refresh()
        self.bcChanged.emit(value)

    def show_optimum(self, bc: float | None, enabled: bool) -> None:
        """The button's text (the robust optimum, or none) and whether it can be used now."""
        self.optimum_button.setEnabled(enabled and bc is not None)
        if bc is not None:
            self.optimum_button.setText(f"Use robust optimum ({format_number(bc, 4, style='text')})")
        else:
            self.optimum_button.setText("Use robust optimum (none)")
