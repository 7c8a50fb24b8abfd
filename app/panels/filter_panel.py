"""The controller's velocity estimate: the profile's ``controller`` section (schema 5, issue 15).

A kind (backward difference, + first-order low-pass, + second-order Butterworth; see
:class:`~analysis.chain.velocity_filter.VelocityFilter` and Chawda, Celik & O'Malley 2015) and
a cut-off on a log slider in Hz (the profile stores rad/s).  Both edit the section through
:class:`~app.widgets.section_binding.SectionBinding`, one undo command each (the first edit
creates the section; undoing it restores a profile without one).  The filter enters eq. (9)/(21),
the exact sampled loop, the passivity test and the simulator, so every view that depends on it
updates.
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QGroupBox, QLabel, QVBoxLayout, QWidget

from analysis.chain.velocity_filter import VelocityFilter, highest_cutoff
from analysis.profiles.model import Profile
from analysis.study import controller_section, format_number

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.widgets.choice_field import ChoiceField
from app.widgets.log_slider_field import LogSliderField
from app.widgets.section_binding import SectionBinding

__all__ = ["FilterPanel", "DEFAULT_CUTOFF_HZ", "KIND_LABELS"]

#: The cut-off a filter starts with when the backward difference had none (Hz).
DEFAULT_CUTOFF_HZ = 30.0
KIND_LABELS = {"backward": "backward difference (no filter)", "lowpass1": "+ 1st-order low-pass",
               "butter2": "+ 2nd-order Butterworth"}
_TWO_PI = 2.0 * math.pi


def _cutoff_hz(p: Profile) -> float:
    """The shown cut-off (Hz): the filter's, or the default while it is the backward difference."""
    vf = controller_section(p).velocity_filter
    return DEFAULT_CUTOFF_HZ if vf.is_backward else vf.cutoff / _TWO_PI


class FilterPanel(QGroupBox):
    """``Velocity estimate [kind]`` and ``f_c [slider] Hz``; ``kind`` and ``cutoff`` are the fields."""

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__("Velocity filter (controller as built)", parent)
        self.setToolTip("Stored in the profile's controller section; used by eq. 9/21, the exact sampled loop, "
                        "the passivity test and the simulator")
        self._model = model
        self.section = SectionBinding(model, editor, "controller", controller_section, "velocity filter")
        self.kind = ChoiceField(model, ("controller",), lambda m: controller_section(m.profile).velocity_filter.kind,
                                self.set_kind, "Velocity estimate", list(KIND_LABELS.items()),
                                "v = H_f(z)·(1 − z⁻¹)/T: the backward difference, optionally low-pass filtered")
        self.kind.setObjectName("controller_kind")
        self.cutoff = LogSliderField(model, ("controller",), lambda m: _cutoff_hz(m.profile), self.set_cutoff_hz,
                                     editor, "f<sub>c</sub>", "Hz", 1.0, 5000.0,
                                     tooltip="Filter cut-off in Hz (ω_f = 2π f_c rad/s), below Nyquist 1/(2T)")
        self.cutoff.setObjectName("controller_cutoff")
        self.cutoff.make_compact()
        self.note = QLabel("")
        self.note.setWordWrap(True)
        self.note.setTextFormat(Qt.TextFormat.PlainText)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(6, 4, 6, 4)
        lay.setSpacing(2)
        lay.addWidget(self.kind)
        lay.addWidget(self.cutoff)
        lay.addWidget(self.note)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def filter(self) -> VelocityFilter:
        """The profile's velocity filter (the backward difference without a section)."""
        return controller_section(self._model.profile).velocity_filter

    def set_kind(self, kind: object, drag: int | None = None) -> str | None:
        """Change the filter kind (keeping the shown cut-off); one undo step.  Returns a refusal."""
        kind = str(kind)
        cutoff = math.inf if kind == "backward" else _cutoff_hz(self._model.profile) * _TWO_PI
        if kind != "backward":  # a filter must stay below Nyquist: clamp the default cut-off
            cutoff = min(cutoff, highest_cutoff(self._model.device.sample_time))
        return self._write(VelocityFilter(kind, cutoff), f"kind to {KIND_LABELS.get(kind, kind)}", drag)

    def set_cutoff_hz(self, hz: float, drag: int | None = None) -> str | None:
        """Change the cut-off (Hz); with the backward difference it selects the first-order low-pass."""
        vf = self.filter()
        kind = "lowpass1" if vf.is_backward else vf.kind
        try:
            new = VelocityFilter(kind, float(hz) * _TWO_PI)
        except ValueError as err:
            return str(err)
        return self._write(new, "cut-off", drag)

    def _write(self, vf: VelocityFilter, label: str, drag: int | None) -> str | None:
        return self.section.write("velocity_filter", vf, label, drag)

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in ("controller", "sample_time"):
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        vf = self.filter()
        self.cutoff.setEnabled(not vf.is_backward)
        nyq = 0.5 / self._model.device.sample_time
        nyquist = f"Nyquist {format_number(nyq, 4, style='text')} Hz"
        self.note.setText(f"{vf.label()}  (ω_f = {format_number(vf.cutoff, 4, style='text')} rad/s; {nyquist})"
                          if not vf.is_backward else f"{vf.label()}  ({nyquist})")
