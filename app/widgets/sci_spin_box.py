"""A spin box for SI values spanning decades: %g text, no silent clamping, log stepping."""

from __future__ import annotations

import math

from PySide6.QtGui import QValidator
from PySide6.QtWidgets import QDoubleSpinBox, QWidget

__all__ = ["SciSpinBox"]

_HUGE = 1e300


class SciSpinBox(QDoubleSpinBox):
    """Shows values with 6 significant digits and accepts any number (``1e5``, ``-3``, ``0.002``).

    The range is unbounded on purpose: values the analysis core refuses are refused by the model,
    with a reason, instead of being clamped here.  Arrow keys step by 1/20 decade when
    ``log_step`` is set, else by ``singleStep``.
    """

    def __init__(self, parent: QWidget | None = None, log_step: bool = True, suffix: str = "") -> None:
        super().__init__(parent)
        self._log_step = log_step
        self.setDecimals(323)
        self.setRange(-_HUGE, _HUGE)
        self.setKeyboardTracking(False)
        self.setAccelerated(True)
        if suffix:
            self.setSuffix(" " + suffix)

    def textFromValue(self, value: float) -> str:  # noqa: N802 - Qt API
        return f"{value:.6g}"

    def valueFromText(self, text: str) -> float:  # noqa: N802 - Qt API
        try:
            return float(self._strip(text))
        except ValueError:
            return self.value()

    def validate(self, text: str, pos: int) -> object:
        body = self._strip(text)
        if body in ("", "-", "+", ".", "-.", "+.") or body.lower().endswith(("e", "e-", "e+")):
            return (QValidator.State.Intermediate, text, pos)
        try:
            value = float(body)
        except ValueError:
            return (QValidator.State.Invalid, text, pos)
        if not math.isfinite(value):
            return (QValidator.State.Intermediate, text, pos)
        return (QValidator.State.Acceptable, text, pos)

    def fixup(self, text: str) -> str:
        return self.textFromValue(self.value())

    def stepBy(self, steps: int) -> None:  # noqa: N802 - Qt API
        v = self.value()
        if self._log_step and v > 0:
            self.setValue(v * 10.0 ** (steps / 20.0))
        else:
            self.setValue(v + steps * self.singleStep())

    def _strip(self, text: str) -> str:
        body = text.strip()
        suffix = self.suffix().strip()
        if suffix and body.endswith(suffix):
            body = body[: -len(suffix)].strip()
        return body
