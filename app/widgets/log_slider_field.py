"""A slider (logarithmic where the range spans decades) paired with an SI spin box and an error label.

Two-way binding: the field reads its value from the model whenever one of its ``fields`` changes,
and sends user edits through ``write`` (an :class:`~app.commands.Editor` call) which returns the
reason a value was refused, shown next to the field while the field goes back to the model's value.
The slider's range is a soft display range: a value typed beyond it is accepted when the model
accepts it (the physical ranges of :mod:`analysis.chain.limits`), and refused with that range
named otherwise.  One slider drag carries one drag token, so
the whole drag is one undo step.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Protocol

from PySide6.QtCore import Qt, Signal, Slot
from PySide6.QtWidgets import QGridLayout, QLabel, QSizePolicy, QSlider, QWidget

from analysis.chain import LIMITS
from analysis.study import format_number

from app.core.model import ProfileModel
from app.widgets.sci_spin_box import SciSpinBox

__all__ = ["LogSliderField", "SLIDER_STEPS", "with_range"]

SLIDER_STEPS = 1000


def with_range(tooltip: str, field: str) -> str:
    """``tooltip`` plus the field's physical range (:data:`analysis.chain.LIMITS`), which typed values
    must respect (the slider only shows a part of it)."""
    limit = LIMITS.get({"ratios": "damping_ratios"}.get(field, field))
    if limit is None:
        return tooltip
    unit = f" {limit.unit}" if limit.unit else ""
    return (f"{tooltip}\nTyped values: {format_number(limit.lo, style='text')} to "
            f"{format_number(limit.hi, style='text')}{unit} (the slider shows part of this range)")

Reader = Callable[[ProfileModel], float]
Writer = Callable[[float, "int | None"], "str | None"]


class Drags(Protocol):
    """Hands out one token per slider drag (the Editor: edits with one token merge into one undo step)."""

    def new_drag(self) -> int: ...

    def end_drag(self, token: int) -> None: ...


class LogSliderField(QWidget):
    """``label  [slider]  [spin box] unit`` with a refusal message underneath."""

    edited = Signal(float)  # a value was accepted from the user

    def __init__(
        self,
        model: ProfileModel,
        fields: Iterable[str],
        read: Reader,
        write: Writer,
        drags: Drags,
        label: str,
        unit: str,
        lo: float,
        hi: float,
        log: bool = True,
        allow_zero: bool = False,
        tooltip: str = "",
        parent: QWidget | None = None,
    ) -> None:
        super().__init__(parent)
        self._model, self._fields = model, frozenset(fields)
        self._read, self._write, self._drags = read, write, drags
        self._lo, self._hi, self._log, self._zero = lo, hi, log, allow_zero
        self._drag: int | None = None
        self._syncing = False

        self._build(label, unit, log, tooltip)
        self.slider.valueChanged.connect(self._on_slider)
        self.slider.sliderPressed.connect(self._on_pressed)
        self.slider.sliderReleased.connect(self._on_released)
        self.spin.valueChanged.connect(self._on_spin)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def _build(self, label: str, unit: str, log: bool, tooltip: str) -> None:
        """``label  [slider]  [spin box] unit`` over the error label."""
        self.label = QLabel(label)
        self.label.setTextFormat(Qt.TextFormat.RichText)
        self.label.setMinimumWidth(34)
        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider.setRange(0, SLIDER_STEPS)
        self.slider.setPageStep(SLIDER_STEPS // 20)
        self.slider.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
        self.slider.setMinimumWidth(90)
        self.spin = SciSpinBox(log_step=log)
        self.spin.setFixedWidth(96)
        self.spin.setAlignment(Qt.AlignmentFlag.AlignRight)
        self.unit = QLabel(unit)
        self.unit.setMinimumWidth(52)
        self.error = QLabel()
        self.error.setObjectName("fieldError")
        self.error.setWordWrap(True)
        self.error.setStyleSheet("color: #d0312d; font-size: 11px;")
        self.error.hide()
        if tooltip:
            for w in (self.label, self.slider, self.spin):
                w.setToolTip(tooltip)

        grid = QGridLayout(self)
        grid.setContentsMargins(0, 0, 0, 0)
        grid.setHorizontalSpacing(6)
        grid.setVerticalSpacing(1)
        grid.addWidget(self.label, 0, 0)
        grid.addWidget(self.slider, 0, 1)
        grid.addWidget(self.spin, 0, 2)
        grid.addWidget(self.unit, 0, 3)
        grid.addWidget(self.error, 1, 1, 1, 3)
        grid.setColumnStretch(1, 1)

    # -- mapping ------------------------------------------------------------------------------------
    def make_compact(self) -> None:
        """Narrow minimum widths, for several fields side by side next to the parameter panel."""
        self.slider.setMinimumWidth(60)
        self.unit.setMinimumWidth(40)

    def value_to_position(self, value: float) -> int:
        if not math.isfinite(value):
            return 0
        z = 1 if (self._zero and self._log) else 0
        if self._log:
            if value <= 0:
                return 0
            t = (math.log10(value) - math.log10(self._lo)) / (math.log10(self._hi) - math.log10(self._lo))
        else:
            t = (value - self._lo) / (self._hi - self._lo)
        return int(round(z + min(max(t, 0.0), 1.0) * (SLIDER_STEPS - z)))

    def position_to_value(self, pos: int) -> float:
        z = 1 if (self._zero and self._log) else 0
        if z and pos <= 0:
            return 0.0
        t = (pos - z) / (SLIDER_STEPS - z)
        if self._log:
            value = 10.0 ** (math.log10(self._lo) + t * (math.log10(self._hi) - math.log10(self._lo)))
            return float(f"{value:.4g}")  # tidy numbers from a drag
        return self._lo + t * (self._hi - self._lo)

    # -- model -> widget ------------------------------------------------------------------------
    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in self._fields:
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        """Show the model's value and clear any refusal message (the model changed: a new edit)."""
        if self.show_model_value():
            self.set_error(None)

    def show_model_value(self) -> bool:
        """Put the model's value in the slider and the spin box (the message is left as it is);
        False when the model has no such value (an element index gone)."""
        try:
            value = float(self._read(self._model))
        except (IndexError, ValueError):
            return False
        self._syncing = True
        try:
            if not self.slider.isSliderDown():
                self.slider.setValue(self.value_to_position(value))
            self.spin.setValue(value)
        finally:
            self._syncing = False
        return True

    def set_error(self, reason: str | None) -> None:
        self.error.setText(reason or "")
        self.error.setVisible(bool(reason))
        style = "QDoubleSpinBox { border: 1px solid #d0312d; }" if reason else ""
        if style != self.spin.styleSheet():  # (setting it re-polishes and repaints: every field, every drag step)
            self.spin.setStyleSheet(style)

    # -- widget -> editor -------------------------------------------------------------------------
    def write(self, value: float, drag: int | None = None) -> str | None:
        """Send ``value`` as a user edit (``drag``: the token of a slider drag); returns the refusal reason.

        A refused value changes nothing: the field shows the model's value again at once, and the
        reason (which names the allowed range) stays underneath until the next accepted edit.
        """
        reason = self._write(value, drag)
        if reason:
            self.show_model_value()
            self.set_error(reason)
        else:
            self.set_error(None)
            self.edited.emit(value)
        return reason

    def _send(self, value: float, drag: int | None) -> None:
        self.write(value, drag)

    @Slot()
    def _on_pressed(self) -> None:
        self._drag = self._drags.new_drag()

    @Slot()
    def _on_released(self) -> None:
        token, self._drag = self._drag, None
        if token is not None:
            self._drags.end_drag(token)

    @Slot(int)
    def _on_slider(self, pos: int) -> None:
        if self._syncing:
            return
        self._send(self.position_to_value(pos), self._drag if self.slider.isSliderDown() else None)

    @Slot(float)
    def _on_spin(self, value: float) -> None:
        if self._syncing:
            return
        self._send(value, None)
