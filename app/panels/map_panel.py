"""The stability map's settings: axes, ranges and resolution (view state, not the profile).

Each display type keeps its own settings.  :meth:`MapPanel.set_map` validates a change (log axes
need 0 < low < high), shows the reason when it refuses one, and emits :attr:`MapPanel.changed`
when it accepts one; the tab passes :meth:`MapPanel.settings` to the map node as its parameters.
"""

from __future__ import annotations

import math
from typing import Any

from PySide6.QtCore import Signal, Slot
from PySide6.QtWidgets import QComboBox, QFormLayout, QGroupBox, QHBoxLayout, QLabel, QSpinBox, QWidget

from app.widgets.colors import ERROR_STYLE
from app.core.nodes_sampled import DEFAULT_RANGES, MAP_AXES, PARAMETER_LABELS, default_map_settings
from app.widgets.sci_spin_box import SciSpinBox

__all__ = ["MapPanel"]


class MapPanel(QGroupBox):
    """``Axes (x × y)``, the two ranges and the points per axis of the sampled-data stability map."""

    changed = Signal()

    def __init__(self, display: str, parent: QWidget | None = None) -> None:
        super().__init__("Stability map", parent)
        self.display = display
        self.all_settings = {d: default_map_settings(d) for d in MAP_AXES}
        self.axes_box = QComboBox()
        self.axes_box.activated.connect(self._on_axes)
        self.range_fields = {k: SciSpinBox() for k in ("x_lo", "x_hi", "y_lo", "y_hi")}
        for f in self.range_fields.values():
            f.setMaximumWidth(100)
            f.editingFinished.connect(self._on_range)
        self.points = QSpinBox()
        self.points.setRange(4, 400)
        self.points.setKeyboardTracking(False)
        self.points.setToolTip("Grid points per axis (the map costs points² eigenvalue problems)")
        self.points.valueChanged.connect(self._on_points)
        self.error = QLabel("")
        self.error.setStyleSheet(ERROR_STYLE)
        self.error.hide()
        form = QFormLayout(self)
        form.addRow("Axes (x × y)", self.axes_box)
        self.x_label, self.y_label = QLabel("x range"), QLabel("y range")
        for label, lo, hi in ((self.x_label, "x_lo", "x_hi"), (self.y_label, "y_lo", "y_hi")):
            row = QHBoxLayout()
            row.addWidget(self.range_fields[lo])
            row.addWidget(QLabel("to"))
            row.addWidget(self.range_fields[hi])
            form.addRow(label, row)
        form.addRow("Points per axis", self.points)
        form.addRow(self.error)
        self.show_display(display)

    def settings(self, display: str | None = None) -> dict[str, Any]:
        """A copy of the map settings of ``display`` (the shown one by default)."""
        return dict(self.all_settings[display or self.display])

    def show_display(self, display: str) -> None:
        """Show (and from now on edit) the settings of ``display``."""
        self.display = display
        s = self.all_settings[display]
        self.axes_box.blockSignals(True)
        self.axes_box.clear()
        for x, y in MAP_AXES[display]:
            self.axes_box.addItem(f"{PARAMETER_LABELS[x][0]} × {PARAMETER_LABELS[y][0]}", (x, y))
        self.axes_box.setCurrentIndex(MAP_AXES[display].index((s["x"], s["y"])))
        self.axes_box.blockSignals(False)
        for key, (lo, hi) in (("x", s["x_range"]), ("y", s["y_range"])):
            self.range_fields[f"{key}_lo"].setValue(lo)
            self.range_fields[f"{key}_hi"].setValue(hi)
            name, unit = PARAMETER_LABELS[s[key]]
            for k in ("lo", "hi"):
                self.range_fields[f"{key}_{k}"].setSuffix(f" {unit}")
            (self.x_label if key == "x" else self.y_label).setText(f"{name} range")
        self.points.blockSignals(True)
        self.points.setValue(int(s["points"]))
        self.points.blockSignals(False)

    def set_map(self, x: str | None = None, y: str | None = None, x_range: tuple[float, float] | None = None,
                y_range: tuple[float, float] | None = None, points: int | None = None) -> str | None:
        """Change the shown display's axes, ranges or resolution; returns the reason if refused."""
        display = self.display
        s = dict(self.all_settings[display])
        if x is not None or y is not None:
            x, y = x or s["x"], y or s["y"]
            if (x, y) not in MAP_AXES[display]:
                return self._refused(f"axes {x} × {y} are not offered for the {display} display")
            if x != s["x"]:
                s["x_range"] = DEFAULT_RANGES[(display, x)]
            if y != s["y"]:
                s["y_range"] = DEFAULT_RANGES[(display, y)]
            s["x"], s["y"] = x, y
        for key, rng in (("x_range", x_range), ("y_range", y_range)):
            if rng is not None:
                lo, hi = float(rng[0]), float(rng[1])
                if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
                    return self._refused(f"{key.replace('_', ' ')}: must satisfy 0 < low < high (log axis)")
                s[key] = (lo, hi)
        if points is not None:
            s["points"] = int(points)
        self.error.hide()
        self.all_settings[display] = s
        self.show_display(display)
        self.changed.emit()
        return None

    def _refused(self, reason: str) -> str:
        self.error.setText(f"refused: {reason}")
        self.error.show()
        self.show_display(self.display)
        return reason

    @Slot(int)
    def _on_axes(self, _i: int) -> None:
        x, y = self.axes_box.currentData()
        self.set_map(x=x, y=y)

    @Slot()
    def _on_range(self) -> None:
        f = self.range_fields
        self.set_map(x_range=(f["x_lo"].value(), f["x_hi"].value()), y_range=(f["y_lo"].value(), f["y_hi"].value()))

    @Slot(int)
    def _on_points(self, n: int) -> None:
        self.set_map(points=n)
