"""The Identify tab's controls (issue 14): measurement files, how they were taken, the model order
and the fixed parameters.

Files are loaded when added (:meth:`IdentifyPanel.load_files`, which the Add button calls after a
file dialog and tests call directly), each with the quantity, boundary and timing chosen at that
moment, so that an actuator test with the handle free and a gauge test with the handle clamped can
be fitted together.  Each file keeps its own kind: a path may name it as the command line does
(``g.csv:gauge``, ``c.csv:actuator:clamped``, :func:`analysis.study.measurement_files.parse_measurement_spec`),
and Apply gives the selected file the quantity, handle and timing shown (:meth:`IdentifyPanel.set_kind`).
A time series is sampled: unless "sampled, T" is ticked it takes its own time step as the sample
time, as ``zwidth identify`` does, and its row says so.  A bad file is refused with the file, row
and column named.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QFileDialog,
    QFormLayout,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QListWidget,
    QPushButton,
    QSpinBox,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from analysis.identify import (BOUNDARIES, MEASURED_QUANTITIES, Measurement, MeasurementError, parameter_keys,
                               parameter_symbol)
from analysis.study.measurement_files import (SAMPLE_TIME_STEP, LoadedMeasurement, MeasurementSpec,
                                              parse_measurement_spec, read_measurement_files)
from analysis.study.quantities import format_number

from app.widgets.sci_spin_box import SciSpinBox

__all__ = ["IdentifyPanel", "MAX_MASSES", "FIXED_COLUMNS", "NumberBox"]

#: Largest chain the panel offers.
MAX_MASSES = 8
#: The fixed-parameters table: symbol (m₁ ...), tick, value, unit.
FIXED_COLUMNS = ("parameter", "fix", "value", "unit")


#: The Apply button's tool tip: each file keeps its own kind.
APPLY_TIP = ("Give the selected file the quantity, handle and timing above (each file keeps its own: e.g. "
             "an actuator test and a gauge test fitted together)")

class NumberBox(SciSpinBox):
    """A :class:`~app.widgets.sci_spin_box.SciSpinBox` that prints its value by the study's one rule
    (:func:`~analysis.study.quantities.format_number`, plain text: it reads back)."""

    def textFromValue(self, value: float) -> str:  # noqa: N802 - Qt API
        return format_number(value)


class IdentifyPanel(QWidget):
    """Measurement list, settings, fixed parameters and the Fit / Use buttons."""

    fitRequested = Signal()
    useRequested = Signal()

    def __init__(self, sample_time: float, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.measurements: list[Measurement] = []
        self.paths: list[str] = []  # each measurement's file
        self.files = QListWidget()
        self.files.setMaximumHeight(80)
        self.add_button = QPushButton("Add files…")
        self.remove_button = QPushButton("Remove")
        self.apply_button = QPushButton("Apply")
        self.apply_button.setToolTip(APPLY_TIP)
        self.error = QLabel()
        self.error.setObjectName("identifyError")
        self.error.setWordWrap(True)
        self.error.setStyleSheet("color: #c92a2a")
        self.quantity = QComboBox()
        self.quantity.addItems(list(MEASURED_QUANTITIES))
        self.boundary = QComboBox()
        self.boundary.addItems(list(BOUNDARIES))
        self.sampled = QCheckBox("sampled, T")
        self.sampled.setToolTip("Measured through the controller: force through a zero-order hold, sampled "
                                "encoder, a delay of d samples (exact ZOH model); unticked: an FRF is "
                                "continuous-time (an analyser) and a time series is sampled at its own time step")
        self.sample_time = QDoubleSpinBox()
        self.sample_time.setDecimals(4)
        self.sample_time.setRange(0.001, 1000.0)
        self.sample_time.setSuffix(" ms")
        self.sample_time.setValue(sample_time * 1e3)
        self.delay = QSpinBox()
        self.delay.setRange(0, 10)
        self.delay.setSuffix(" samples")
        self.masses = QSpinBox()
        self.masses.setRange(1, MAX_MASSES)
        self.masses.setValue(4)
        self.max_order = QSpinBox()
        self.max_order.setRange(0, MAX_MASSES)
        self.max_order.setValue(4)
        self.max_order.setSpecialValueText("off")
        self.fixed_table = QTableWidget(0, len(FIXED_COLUMNS))
        self.fixed_table.setHorizontalHeaderLabels(list(FIXED_COLUMNS))
        self.fixed_table.verticalHeader().hide()
        header = self.fixed_table.horizontalHeader()
        header.setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        header.setSectionResizeMode(2, QHeaderView.ResizeMode.Stretch)  # the value: the rest of the width
        header.setStretchLastSection(False)
        self.fixed_table.setMinimumHeight(120)
        self.fit_button = QPushButton("Fit")
        self.fit_button.setDefault(True)
        self.use_button = QPushButton("Use this device")
        self.use_button.setToolTip("Set the profile's device to the fitted one and store the intervals and "
                                   "measurements in the profile (one undo step)")
        self.use_button.setEnabled(False)
        self._layout()
        self.add_button.clicked.connect(self.choose_files)
        self.remove_button.clicked.connect(self.remove_selected)
        self.apply_button.clicked.connect(self.apply_selected)
        self.masses.valueChanged.connect(self._fill_fixed)
        self.fit_button.clicked.connect(self.fitRequested)
        self.use_button.clicked.connect(self.useRequested)
        self._fill_fixed()
        self._update_buttons()

    def _layout(self) -> None:
        buttons = QHBoxLayout()
        buttons.addWidget(self.add_button)
        buttons.addWidget(self.remove_button)
        buttons.addWidget(self.apply_button)
        form = QFormLayout()
        form.addRow("Quantity", self.quantity)
        form.addRow("Handle", self.boundary)
        form.addRow(self.sampled, self.sample_time)
        form.addRow("Delay d", self.delay)
        form.addRow("Masses n", self.masses)
        form.addRow("Order table n = 1 …", self.max_order)
        run = QHBoxLayout()
        run.addWidget(self.fit_button)
        run.addWidget(self.use_button)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        title = QLabel("<b>Measurements</b> (FRF or time-series CSV; settings apply to files added next, "
                       "or to the selected file by Apply)")
        title.setWordWrap(True)
        lay.addWidget(title)
        lay.addLayout(form)
        lay.addLayout(buttons)
        lay.addWidget(self.files)
        lay.addWidget(self.error)
        fixed = QLabel("<b>Fixed parameters</b> (known values, e.g. a handle mass from CAD)")
        fixed.setWordWrap(True)
        lay.addWidget(fixed)
        lay.addWidget(self.fixed_table, 1)
        lay.addLayout(run)

    # -- measurements --------------------------------------------------------------------------
    def timing(self) -> tuple[float | None, int]:
        """(sample time in s or ``None`` for continuous, delay in samples) for the next files."""
        if not self.sampled.isChecked():
            return None, 0
        return self.sample_time.value() * 1e-3, self.delay.value()

    def _read(self, spec: MeasurementSpec) -> LoadedMeasurement:
        T, d = self.timing()
        (loaded,) = read_measurement_files([spec], self.quantity.currentText(), self.boundary.currentText(), T, d,
                                           step_as_sample_time=True)
        return loaded

    @staticmethod
    def _row_text(path: str, loaded: LoadedMeasurement) -> str:
        m = loaded.measurement
        timing = ("continuous" if m.sample_time is None else
                  f"T = {format_number(m.sample_time * 1e3, style='text')} ms, d = {m.delay_samples}")
        if loaded.sample_time_source == SAMPLE_TIME_STEP:
            timing += " (the time series' own step)"
        return f"{os.path.basename(path)} — {m.quantity}, {m.boundary}, {timing}, {m.size} points"

    def load_files(self, paths: Sequence[str | os.PathLike]) -> list[str]:
        """Load ``paths`` with the current settings; returns the error messages (file, row, column).

        A path may carry its own kind as on the command line, ``FILE:QUANTITY[:BOUNDARY]``; a time
        series without a ticked sample time is sampled at its own step."""
        errors = []
        for path in paths:
            try:
                spec = parse_measurement_spec(path)
                loaded = self._read(spec)
            except (MeasurementError, ValueError, OSError) as err:
                errors.append(str(err))
                continue
            self.measurements.append(loaded.measurement)
            self.paths.append(spec.path)
            self.files.addItem(self._row_text(spec.path, loaded))
        self.error.setText("\n".join(errors))
        self._update_buttons()
        return errors

    def set_kind(self, row: int) -> str | None:
        """Read file ``row`` again with the quantity, handle and timing shown; the error message, or
        ``None`` when done (the file keeps its place)."""
        if not 0 <= row < len(self.measurements):
            return "no file selected"
        try:
            loaded = self._read(MeasurementSpec(self.paths[row]))
        except (MeasurementError, ValueError, OSError) as err:
            self.error.setText(str(err))
            return str(err)
        self.measurements[row] = loaded.measurement
        self.files.item(row).setText(self._row_text(self.paths[row], loaded))
        self.error.setText("")
        return None

    def apply_selected(self) -> None:
        self.set_kind(self.files.currentRow())

    def choose_files(self) -> None:
        paths, _ = QFileDialog.getOpenFileNames(self, "Add measurements", "", "CSV files (*.csv);;All files (*)")
        if paths:
            self.load_files(paths)

    def remove_selected(self) -> None:
        row = self.files.currentRow()
        if 0 <= row < len(self.measurements):
            self.files.takeItem(row)
            del self.measurements[row]
            del self.paths[row]
        self._update_buttons()

    def _update_buttons(self) -> None:
        self.fit_button.setEnabled(bool(self.measurements))
        self.remove_button.setEnabled(bool(self.measurements))
        self.apply_button.setEnabled(bool(self.measurements))

    # -- order and fixed parameters ---------------------------------------------------------------
    def _fill_fixed(self) -> None:
        keys = parameter_keys(self.masses.value(), None)
        old = self.fixed()
        self.fixed_table.setRowCount(len(keys))
        for r, key in enumerate(keys):
            symbol, unit = parameter_symbol(key)  # m₁ as the device editor names it; the key stays 0-based
            name = QTableWidgetItem(symbol)
            name.setFlags(name.flags() & ~Qt.ItemFlag.ItemIsEditable)
            name.setData(Qt.ItemDataRole.UserRole, key)
            name.setToolTip(f"{key} in profiles and on the command line")
            self.fixed_table.setItem(r, 0, name)
            check = QCheckBox()
            check.setChecked(key in old)
            self.fixed_table.setCellWidget(r, 1, check)
            value = NumberBox(log_step=True)
            value.setRange(1e-6, 1e9)
            value.setValue(old.get(key, 1.0))
            self.fixed_table.setCellWidget(r, 2, value)
            unit_item = QTableWidgetItem(unit)
            unit_item.setFlags(unit_item.flags() & ~Qt.ItemFlag.ItemIsEditable)
            self.fixed_table.setItem(r, 3, unit_item)
        self.fixed_table.resizeRowsToContents()

    def set_fixed(self, key: str, value: float) -> None:
        """Tick ``key``'s fix box and set its value."""
        for r in range(self.fixed_table.rowCount()):
            if self.fixed_table.item(r, 0).data(Qt.ItemDataRole.UserRole) == key:
                self.fixed_table.cellWidget(r, 1).setChecked(True)
                self.fixed_table.cellWidget(r, 2).setValue(value)
                return
        raise KeyError(key)

    def fixed(self) -> dict[str, float]:
        """The ticked parameters and their values."""
        out = {}
        for r in range(self.fixed_table.rowCount()):
            check, value = self.fixed_table.cellWidget(r, 1), self.fixed_table.cellWidget(r, 2)
            if check is not None and check.isChecked():
                out[self.fixed_table.item(r, 0).data(Qt.ItemDataRole.UserRole)] = value.value()
        return out
