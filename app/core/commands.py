"""Undo commands, and the :class:`Editor` through which every widget edits the model.

A slider drag is one undo step: while the slider is down every change carries the same *drag
token*, and :meth:`SetFields.mergeWith` folds commands with equal tokens into one.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping

import numpy as np
from PySide6.QtCore import QObject, Signal
from PySide6.QtGui import QUndoCommand, QUndoStack

from analysis import Device, ValidationError, damping_from_ratio
from analysis.chain.limits import DAMPING_RATIO
from analysis.profiles import per_mass_changes

from app.core.model import ProfileModel

__all__ = ["SetFields", "Editor", "FIELD_LABELS", "describe_error", "UNDO_LIMIT"]

FIELD_LABELS: dict[str, str] = {
    "masses": "mass",
    "stiffnesses": "stiffness",
    "dampings": "damping",
    "ground_dampings": "ground damping",
    "sensor_element": "sensor element",
    "sample_time": "sample period T",
    "band_min": "band minimum",
    "device": "device chain",
    "display": "display type",
    "kc": "k_c",
    "bc": "b_c",
    "mc": "m_c",
    "bc_adm": "b_c",
    "kp": "k_p",
    "kd": "k_d",
    "name": "name",
    "notes": "notes",
}

_MERGE_ID = 0x2A1D

#: The undo history keeps the last this many steps (a whole drag is one step): each holds the
#: old and new values of its fields (up to ~5 kB with a device), so an unbounded history would
#: grow for as long as the window stays open.  Older steps are dropped, oldest first.
UNDO_LIMIT = 1000


def describe_error(err: Exception) -> str:
    """The reason shown next to a field for a refused value."""
    if isinstance(err, ValidationError):
        return f"refused: must be {err.allowed}"
    return f"refused: {err}"


class SetFields(QUndoCommand):
    """Set one or more model fields; commands with the same drag token merge."""

    def __init__(self, model: ProfileModel, changes: Mapping[str, object], text: str,
                 drag: int | None = None) -> None:
        super().__init__(text)
        self._model = model
        self._new = dict(changes)
        self._old = {f: model.get(f) for f in changes}
        self.drag = drag

    def redo(self) -> None:
        self._model.set_many(self._new)

    def undo(self) -> None:
        self._model.set_many(self._old)

    def id(self) -> int:  # noqa: A003 - Qt API
        return _MERGE_ID if self.drag is not None else -1

    def mergeWith(self, other: QUndoCommand) -> bool:  # noqa: N802 - Qt API
        if not isinstance(other, SetFields) or other.drag is None or other.drag != self.drag:
            return False
        if set(other._new) != set(self._new):
            return False
        self._new = dict(other._new)
        return True


class Editor(QObject):
    """Turns widget edits into validated undo commands.

    Every ``edit*`` method returns ``None`` on success or the reason the value was refused; a
    refused value changes nothing (it is never clamped).
    """

    refused = Signal(str, str)  # field, reason
    dragChanged = Signal(bool)  # a slider drag started (True) or the last one ended (False)

    def __init__(self, model: ProfileModel, stack: QUndoStack, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.model = model
        self.stack = stack
        self._drags = itertools.count(1)
        self._active: set[int] = set()

    def new_drag(self) -> int:
        """A fresh token for one slider drag (call :meth:`end_drag` with it on release)."""
        token = next(self._drags)
        self._active.add(token)
        if len(self._active) == 1:
            self.dragChanged.emit(True)
        return token

    def end_drag(self, token: int) -> None:
        if token in self._active:
            self._active.discard(token)
            if not self._active:
                self.dragChanged.emit(False)

    @property
    def dragging(self) -> bool:
        return bool(self._active)

    def edit_many(self, changes: Mapping[str, object], text: str, drag: int | None = None) -> str | None:
        try:
            self.model.validated(changes)
        except (ValidationError, TypeError, ValueError) as err:
            reason = describe_error(err)
            for f in changes:
                self.refused.emit(f, reason)
            return reason
        if all(_equal(self.model.get(f), v) for f, v in changes.items()):
            return None
        self.stack.push(SetFields(self.model, changes, text, drag))
        return None

    def edit(self, field: str, value: object, drag: int | None = None) -> str | None:
        label = FIELD_LABELS.get(field, field)
        return self.edit_many({field: value}, f"Set {label}", drag)

    def edit_element(self, field: str, index: int, value: float, drag: int | None = None) -> str | None:
        values = np.array(self.model.get(field), dtype=float)
        values[index] = value
        label = FIELD_LABELS.get(field, field)
        return self.edit_many({field: values}, f"Set {label} {index + 1}", drag)

    def edit_damping_ratio(self, index: int, ratio: float, drag: int | None = None) -> str | None:
        """Element damping given by its damping ratio, eq. (28) with the reduced mass."""
        dev = self.model.device
        if not DAMPING_RATIO.contains(ratio):
            reason = f"refused: must be {DAMPING_RATIO.text}"
            self.refused.emit("dampings", reason)
            return reason
        b = damping_from_ratio(float(dev.stiffnesses[index]), float(dev.masses[index]),
                               float(dev.masses[index + 1]), float(ratio))
        return self.edit_element("dampings", index, b, drag)

    def add_mass(self) -> str | None:
        """Append a mass at the actuator end (a copy of the last mass, joined by a stiff element)."""
        dev = self.model.device
        m = np.append(dev.masses, dev.masses[-1])
        k = np.append(dev.stiffnesses, dev.stiffnesses[-1] if dev.n > 1 else 1e5)
        b = np.append(dev.dampings, damping_from_ratio(float(k[-1]), float(m[-2]), float(m[-1]), 0.1))  # eq. (28)
        g = np.append(dev.ground_dampings, 0.0)
        try:
            new = dev.replace(masses=m, stiffnesses=k, dampings=b, ground_dampings=g)
        except ValidationError as err:
            return describe_error(err)
        return self.edit_many({"device": new, **per_mass_changes(self.model.profile, new.n)}, "Add mass")

    def remove_mass(self, index: int | None = None) -> str | None:
        """Remove a mass (the last one by default) and the element that joined it."""
        dev = self.model.device
        if dev.n <= 1:
            return "refused: the chain needs at least one mass"
        i = dev.n - 1 if index is None else int(index)
        e = min(i, dev.n - 2)  # element removed with the mass
        m = np.delete(dev.masses, i)
        k = np.delete(dev.stiffnesses, e)
        b = np.delete(dev.dampings, e)
        g = np.delete(dev.ground_dampings, i)
        sensor = min(dev.sensor_element, max(m.size - 2, 0))
        try:
            new = Device(masses=m, stiffnesses=k, dampings=b, ground_dampings=g, sensor_element=sensor,
                         sample_time=dev.sample_time, band_min=dev.band_min)
        except ValidationError as err:
            return describe_error(err)
        return self.edit_many({"device": new, **per_mass_changes(self.model.profile, new.n, removed=i)},
                              f"Remove mass {i + 1}")


def _equal(a: object, b: object) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    if isinstance(a, Device) or isinstance(b, Device):
        return a == b
    return a == b
