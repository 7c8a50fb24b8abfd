"""Controls of the profile's ``observer`` section (Eom, Suh & Yi, Fig. 1, eqs. 2-5 and 13).

Every field is two-way bound through :class:`~app.widgets.section_binding.SectionBinding`: it shows
the section (its defaults while the profile has none) and edits it through one undo command.
"""

from __future__ import annotations

from PySide6.QtWidgets import QComboBox, QGridLayout, QGroupBox, QWidget

from analysis.study import observer_settings
from analysis.study.labels import OBSERVER_PRESET_LABELS
from analysis.transparency.observer import PRESETS

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.widgets.choice_field import ChoiceField
from app.widgets.int_field import IntField
from app.widgets.log_slider_field import LogSliderField
from app.widgets.section_binding import SectionBinding

__all__ = ["ObserverPanel", "PRESET_LABELS"]

PRESET_LABELS = OBSERVER_PRESET_LABELS  # the one place: analysis.study.labels


class ObserverPanel(QGroupBox):
    """The observer's Q filter, nominal plant, uncertainty and two-axis device; ``fields`` by name."""

    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__("Disturbance observer (Eom, Suh && Yi, Fig. 1, eq. 3–5)", parent)
        self.setToolTip("Stored in the profile's observer section")
        self.section = sec = SectionBinding(model, editor, "observer", observer_settings, "observer")
        self.fields: dict[str, QWidget] = {}
        order = IntField(model, ("observer",), sec.reader("order"), sec.writer("order", "order"), "Q order r", 1, 8,
                         "Q = (ω_Q/(s + ω_Q))^r, binomial low-pass (r ≥ 1 so that Q/P_n is proper)")
        preset = ChoiceField(model, ("observer",), sec.reader("preset"), sec.writer("preset", "preset"),
                             "Two-axis device", [(p, PRESET_LABELS.get(p, p)) for p in PRESETS],
                             "Cartesian inertia and damping of a five-bar linkage (eq. 2)")
        self.fields["order"], self.fields["preset"] = order, preset
        preset.combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToContents)
        preset.combo.setMinimumWidth(preset.combo.sizeHint().width())  # its text is never cut
        rows = [
            [order, self._slider("cutoff", "ω<sub>Q</sub>", "rad/s", 1.0, 1e5, "Cutoff of the Q filter"),
             self._slider("nominal_mass", "M̄", "kg", 1e-4, 10.0, "Nominal mass of P_n = 1/(M̄ s + B̄) (eq. 3)")],
            [preset, self._slider("delta", "δ", "", -1.0, 1.0, "Δ of eq. (13): the real plant's mass is "
                                  "M̄(1 + αδ), its damping B̄(1 + βδ)", log=False),
             self._slider("nominal_damping", "B̄", "N·s/m", 1e-4, 10.0, "Nominal damping of P_n (eq. 3)",
                          zero=True)],
            [self._slider("alpha", "α", "", 0.0, 0.99, "Mass uncertainty of the real plant (eq. 13)", log=False),
             self._slider("beta", "β", "", 0.0, 1.0, "Damping uncertainty of the real plant (eq. 13)", log=False)],
        ]
        g = QGridLayout(self)
        g.setContentsMargins(6, 4, 6, 4)
        g.setHorizontalSpacing(6)  # three columns within the tab's width at 1280 px
        g.setVerticalSpacing(2)
        for r, row in enumerate(rows):
            for c, w in enumerate(row):
                g.addWidget(w, r, c)
        for c in range(3):
            g.setColumnStretch(c, 1)

    def _slider(self, name: str, label: str, unit: str, lo: float, hi: float, tip: str, log: bool = True,
                zero: bool = False) -> LogSliderField:
        self.fields[name] = f = self.section.slider(name, label, unit, lo, hi, tip, log=log, allow_zero=zero)
        return f
