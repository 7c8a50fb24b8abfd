"""Read and write one parameter of an optional profile section (``wall``, ``observer``).

A section that is ``None`` reads as its defaults, which ``factory(profile)`` derives from the profile
(:func:`analysis.study.wall_settings`: the profile's own device); the first edit creates it from
them, through the same undo command as any other edit (so undoing it restores ``None``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from analysis import ValidationError
from analysis.profiles.model import Profile
from PySide6.QtWidgets import QLabel

from app.core.commands import Editor, describe_error
from app.core.model import ProfileModel
from app.widgets.log_slider_field import LogSliderField

__all__ = ["SectionBinding"]


class SectionBinding:
    """``section`` is the profile field, ``factory(profile)`` gives its settings (the section, or the
    defaults derived from the profile: e.g. :func:`analysis.study.wall_settings`)."""

    def __init__(self, model: ProfileModel, editor: Editor, section: str, factory: Callable[[Profile], object],
                 title: str) -> None:
        self.model, self.editor, self.section, self.factory, self.title = model, editor, section, factory, title

    def current(self, model: ProfileModel | None = None) -> Any:
        """The section's settings object (its defaults while the profile has none)."""
        model = model or self.model
        value = model.get(self.section)
        return self.factory(model.profile) if value is None else value

    def reader(self, name: str) -> Callable[[ProfileModel], object]:
        return lambda m: getattr(self.current(m), name)

    def write(self, name: str, value: object, label: str, drag: int | None = None) -> str | None:
        return self.write_many({name: value}, label, drag)

    def write_many(self, changes: dict[str, object], label: str, drag: int | None = None) -> str | None:
        """Several fields of the section in one undo step; returns the refusal, if any."""
        try:
            new = self.current().replace(**changes)
        except (ValidationError, TypeError, ValueError) as err:
            reason = describe_error(err)
            self.editor.refused.emit(self.section, reason)
            return reason
        if self.model.get(self.section) is not None and new == self.model.get(self.section):
            return None
        return self.editor.edit_many({self.section: new}, f"Set {self.title} {label}", drag)

    def write_shown(self, changes: dict[str, object], label: str, error: QLabel,
                    refresh: Callable[[], None]) -> str | None:
        """:meth:`write_many`, its refusal shown on the panel's ``error`` label (hidden when
        accepted) and the panel's fields ``refresh``-ed back to the section after a refusal."""
        reason = self.write_many(changes, label)
        error.setText(f"refused: {reason}" if reason else "")
        error.setVisible(bool(reason))
        if reason:
            refresh()
        return reason

    def writer(self, name: str, label: str) -> Callable[..., str | None]:
        """For LogSliderField (``value, drag``) and the choice fields (``value``)."""
        return lambda value, drag=None: self.write(name, value, label, drag)

    def slider(self, name: str, label: str, unit: str, lo: float, hi: float, tooltip: str, log: bool = True,
               allow_zero: bool = False) -> LogSliderField:
        """A compact slider field for one parameter of the section (object name ``section_name``)."""
        f = LogSliderField(self.model, (self.section,), self.reader(name), self.writer(name, label),
                           self.editor, label, unit, lo, hi, log=log, allow_zero=allow_zero,
                           tooltip=tooltip)
        f.setObjectName(f"{self.section}_{name}")
        f.make_compact()
        return f
