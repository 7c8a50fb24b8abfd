"""The device chain edited in place: masses, element springs and dampers, dampers to ground.

Dampings can be given directly (N·s/m) or by damping ratio (eq. 28, reduced mass).  Rows are
rebuilt when the number of masses changes.
"""

from __future__ import annotations

from PySide6.QtCore import Slot
from PySide6.QtWidgets import (
    QButtonGroup,
    QComboBox,
    QHBoxLayout,
    QLabel,
    QPushButton,
    QRadioButton,
    QVBoxLayout,
    QWidget,
)

from app.widgets.colors import ERROR_STYLE
from app.core.commands import Editor
from app.core.model import ProfileModel
from app.widgets.log_slider_field import LogSliderField, with_range

__all__ = ["ChainEditor"]

_DEV = ("device",)


class ChainEditor(QWidget):
    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model, self._editor = model, editor
        self._n = -1
        self._ratio_mode = False
        self.fields: dict[tuple[str, int], LogSliderField] = {}

        top = QHBoxLayout()
        self.add_button = QPushButton("+ Add mass")
        self.add_button.setToolTip("Append a mass at the actuator end")
        self.remove_button = QPushButton("− Remove mass")
        self.remove_button.setToolTip("Remove the mass at the actuator end")
        top.addWidget(self.add_button)
        top.addWidget(self.remove_button)
        top.addStretch(1)

        mode = QHBoxLayout()
        mode.addWidget(QLabel("Element damping:"))
        self.by_value = QRadioButton("b (N·s/m)")
        self.by_ratio = QRadioButton("ratio ζ (eq. 28)")
        self.by_value.setChecked(True)
        group = QButtonGroup(self)
        group.addButton(self.by_value)
        group.addButton(self.by_ratio)
        mode.addWidget(self.by_value)
        mode.addWidget(self.by_ratio)
        mode.addStretch(1)

        sensor = QHBoxLayout()
        sensor.addWidget(QLabel("Force sensor on:"))
        self.sensor = QComboBox()
        self.sensor.setToolTip("Element carrying the force gauge (eq. 27)")
        sensor.addWidget(self.sensor, 1)
        self.sensor_error = QLabel()
        self.sensor_error.setStyleSheet(ERROR_STYLE + " font-size: 11px;")
        self.sensor_error.hide()

        self.rows = QVBoxLayout()
        self.rows.setSpacing(3)
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.addLayout(top)
        outer.addLayout(mode)
        outer.addLayout(self.rows)
        outer.addLayout(sensor)
        outer.addWidget(self.sensor_error)

        self.add_button.clicked.connect(lambda: self._editor.add_mass())
        self.remove_button.clicked.connect(lambda: self._editor.remove_mass())
        self.by_ratio.toggled.connect(self._set_ratio_mode)
        self.sensor.activated.connect(self._on_sensor)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self._sync)
        self._sync()

    # -- building ---------------------------------------------------------------------------------
    def _clear(self) -> None:
        while self.rows.count():
            item = self.rows.takeAt(0)
            w = item.widget()
            if w is not None:
                w.setParent(None)
                w.deleteLater()
        self.fields.clear()

    def _field(self, key: tuple[str, int], label: str, unit: str, lo: float, hi: float, zero: bool,
               tip: str, ratio: bool = False) -> LogSliderField:
        name, i = key
        model, ed = self._model, self._editor
        tip = with_range(tip, name)
        if ratio:
            f = LogSliderField(model, ("dampings", "masses", "stiffnesses", *_DEV),
                               lambda m: float(m.device.damping_ratios[i]),
                               lambda v, d: ed.edit_damping_ratio(i, v, d), ed,
                               label, unit, lo, hi, allow_zero=zero, tooltip=tip)
        else:
            f = LogSliderField(model, (name, *_DEV), lambda m: float(m.get(name)[i]),
                               lambda v, d: ed.edit_element(name, i, v, d), ed,
                               label, unit, lo, hi, allow_zero=zero, tooltip=tip)
        f.setObjectName(f"{name}_{i}")
        self.fields[key] = f
        self.rows.addWidget(f)
        return f

    def _rebuild(self) -> None:
        self._clear()
        n = self._model.device.n
        for i in range(n):
            role = " (handle)" if i == 0 else (" (actuator)" if i == n - 1 else "")
            title = QLabel(f"<b>Mass {i + 1}</b>{role}")
            title.setContentsMargins(0, 4, 0, 0)
            self.rows.addWidget(title)
            self._field(("masses", i), f"m<sub>{i + 1}</sub>", "kg", 1e-3, 1e2, False, f"Mass {i + 1}")
            self._field(("ground_dampings", i), f"g<sub>{i + 1}</sub>", "N·s/m", 1e-3, 1e3, True,
                        f"Damping from mass {i + 1} to ground")
            if i < n - 1:
                title = QLabel(f"<i>Element {i + 1}: mass {i + 1} ↔ mass {i + 2}</i>")
                title.setContentsMargins(0, 4, 0, 0)
                self.rows.addWidget(title)
                self._field(("stiffnesses", i), f"k<sub>{i + 1}</sub>", "N/m", 1e2, 1e8, False,
                            f"Stiffness of element {i + 1}")
                if self._ratio_mode:
                    self._field(("ratios", i), f"ζ<sub>{i + 1}</sub>", "", 1e-4, 10.0, True,
                                f"Damping ratio of element {i + 1}, eq. (28) with the reduced mass", ratio=True)
                else:
                    self._field(("dampings", i), f"b<sub>{i + 1}</sub>", "N·s/m", 1e-2, 1e4, True,
                                f"Damping of element {i + 1}")
        self._n = n
        self.remove_button.setEnabled(n > 1)
        self.by_ratio.setEnabled(n > 1)

    # -- sync -------------------------------------------------------------------------------------
    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in ("device", "sensor_element", "masses") and self._model.device.n != self._n:
            self._sync()
        elif field in ("device", "sensor_element"):
            self._sync_sensor()

    @Slot()
    def _sync(self) -> None:
        if self._model.device.n != self._n:
            self._rebuild()
        self._sync_sensor()

    def _sync_sensor(self) -> None:
        dev = self._model.device
        self.sensor.blockSignals(True)
        self.sensor.clear()
        if dev.n < 2:
            self.sensor.addItem("the handle (single mass)")
        for i in range(dev.n - 1):
            self.sensor.addItem(f"element {i + 1} (mass {i + 1} ↔ mass {i + 2})")
        self.sensor.setCurrentIndex(dev.sensor_element)
        self.sensor.setEnabled(dev.n > 2)
        self.sensor.blockSignals(False)
        self.sensor_error.hide()

    @Slot(bool)
    def _set_ratio_mode(self, on: bool) -> None:
        self._ratio_mode = on
        self._n = -1
        self._sync()

    @Slot(int)
    def _on_sensor(self, index: int) -> None:
        reason = self._editor.edit("sensor_element", int(index))
        self.sensor_error.setText(reason or "")
        self.sensor_error.setVisible(bool(reason))
        if reason:
            self._sync_sensor()
            self.sensor_error.setText(reason)
            self.sensor_error.show()

