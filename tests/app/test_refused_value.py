"""Typed values: accepted within the physical range (beyond the slider's soft range), refused
beyond it with the range named; a refused value never stays in its field (issue 13)."""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QUndoStack

from analysis.chain.limits import MASS, SAMPLE_TIME
from analysis.profiles.io import bundled_profiles, load_profile
from app.core.commands import Editor
from app.core.model import ProfileModel
from app.panels.parameter_panel import ParameterPanel

pytestmark = pytest.mark.gui


@pytest.fixture
def panel(qtbot):
    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    editor = Editor(model, QUndoStack())
    panel = ParameterPanel(model, editor, QAction("max k_c"), QAction("min m_c"))
    qtbot.addWidget(panel)
    panel.show()
    panel.model = model  # the test's handle on the model behind the panel
    return panel


def type_into(qtbot, field, text: str) -> None:
    """Select the spin box's text, type ``text`` and press Enter, as a user does."""
    line = field.spin.lineEdit()
    field.spin.setFocus()
    line.selectAll()
    qtbot.keyClicks(line, text)
    qtbot.keyClick(line, Qt.Key.Key_Return)


def test_a_refused_mass_shows_the_model_value_and_the_range(qtbot, panel):
    model, m1 = panel.model, panel.chain.fields[("masses", 0)]
    assert model.device.masses[0] == 0.2 and m1.spin.value() == 0.2
    type_into(qtbot, m1, "0")
    assert model.device.masses[0] == 0.2
    assert m1.spin.value() == 0.2 and m1.spin.text() == "0.2"  # not the refused "0"
    assert not m1.error.isHidden()
    assert m1.error.text() == f"refused: must be {MASS.text}"
    assert "[1e-06, 1000] (kg)" in m1.error.text()
    # a later edit of another field does not bring the refused value back, nor hide the reason
    type_into(qtbot, panel.fields["kc"], "60000")
    assert model.profile.kc == 60000.0
    assert m1.spin.text() == "0.2" and not m1.error.isHidden()
    # the next accepted edit of the field clears its message
    type_into(qtbot, m1, "0.3")
    assert model.device.masses[0] == 0.3 and m1.spin.value() == 0.3 and m1.error.isHidden()


def test_typed_values_beyond_the_slider_but_inside_the_physical_range_are_accepted(qtbot, panel):
    model, T, kc = panel.model, panel.fields["sample_time"], panel.fields["kc"]
    type_into(qtbot, kc, "2e7")  # the slider ends at 1e7; the physical range at 1e9 N/m
    assert model.profile.kc == 2e7 and kc.error.isHidden()
    assert kc.slider.value() == kc.slider.maximum()  # the slider is pinned at its end
    type_into(qtbot, T, "5e-6")  # the slider starts at 1e-5 s; the physical range at 1e-6 s
    assert model.device.sample_time == 5e-6 and T.error.isHidden()


@pytest.mark.parametrize("field, text, model_value, range_text", [
    ("sample_time", "1e-7", 1e-3, "[1e-06, 1] (s)"),
    ("sample_time", "2", 1e-3, "[1e-06, 1] (s)"),
    ("kc", "2e9", 50000.0, "[0, 1e+09] (N/m)"),
    ("mc", "5000", 8.0, "[1e-06, 1000] (kg)"),
])
def test_typed_values_beyond_the_physical_range_are_refused(qtbot, panel, field, text, model_value, range_text):
    f = panel.fields[field]
    type_into(qtbot, f, text)
    value = panel.model.get(field)
    assert value == model_value and f.spin.value() == model_value
    assert range_text in f.error.text() and not f.error.isHidden()
    if field == "sample_time":
        assert f.error.text() == f"refused: must be {SAMPLE_TIME.text}"
