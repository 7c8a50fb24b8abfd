"""The control panels on their own (no window): two-way binding, refusals, undo steps."""

from __future__ import annotations

import pytest
from PySide6.QtGui import QUndoStack

from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import ADMITTANCE, IMPEDANCE
from analysis.transparency.observer import ObserverSettings
from app.core.commands import Editor
from app.core.model import ProfileModel
from app.panels.map_panel import MapPanel
from app.panels.observer_panel import ObserverPanel
from app.panels.wall_panel import WallPanel


@pytest.fixture
def editor(qapp):
    model = ProfileModel(load_profile(bundled_profiles()["eom"]))
    ed = Editor(model, QUndoStack())
    return ed


def test_map_panel_validates_and_keeps_one_setting_per_display(qapp):
    panel = MapPanel("impedance")
    changed: list[bool] = []
    panel.changed.connect(lambda: changed.append(True))
    assert (panel.settings()["x"], panel.settings()["y"]) == IMPEDANCE.map_axes[0]
    assert panel.set_map(x_range=(2e4, 2e5), points=12) is None
    assert panel.settings()["x_range"] == (2e4, 2e5) and panel.points.value() == 12
    assert changed == [True]
    reason = panel.set_map(x_range=(5.0, 1.0))
    assert reason is not None and "0 < low < high" in reason
    assert not panel.error.isHidden() and panel.settings()["x_range"] == (2e4, 2e5)
    assert panel.set_map(x="mc", y="bc") is not None  # an admittance axis pair: refused here
    assert changed == [True]
    # the axes choice resets the ranges to the display object's defaults
    assert panel.set_map(y="grasp_mass") is None
    assert panel.settings()["y_range"] == IMPEDANCE.map_ranges["grasp_mass"]
    panel.show_display("admittance")
    assert (panel.settings()["x"], panel.settings()["y"]) == ADMITTANCE.map_axes[0]
    assert panel.settings("impedance")["x_range"] == (2e4, 2e5)  # kept for when it comes back
    assert panel.axes_box.count() == len(ADMITTANCE.map_axes)


def test_wall_panel_holds_bc_outside_the_undo_stack(editor):
    panel = WallPanel(editor.model, editor)
    seen: list[float] = []
    panel.bcChanged.connect(seen.append)
    assert panel.bc == 15.0 and panel.bc_field.spin.value() == 15.0
    assert panel.bc_field.write(6.5) is None
    assert panel.bc == 6.5 and seen == [6.5]
    assert panel.bc_field.write(-1.0) is not None  # refused, shown, nothing changes
    assert panel.bc == 6.5 and not panel.bc_field.error.isHidden()
    assert editor.stack.count() == 0
    panel.show_optimum(6.47, True)
    assert panel.optimum_button.isEnabled() and "6.47" in panel.optimum_button.text()
    panel.show_optimum(None, True)
    assert not panel.optimum_button.isEnabled() and "none" in panel.optimum_button.text()


def test_wall_panel_fields_edit_the_wall_section(editor):
    panel = WallPanel(editor.model, editor)
    stiffness = panel.fields["wall_stiffness"]
    token = editor.new_drag()
    assert stiffness.write(2000.0, token) is None and stiffness.write(3000.0, token) is None
    editor.end_drag(token)
    assert editor.model.profile.wall.wall_stiffness == 3000.0 and editor.stack.count() == 1
    editor.stack.undo()
    assert stiffness.spin.value() == editor.model.profile.wall.wall_stiffness  # the field follows the model
    panel.fields["plant"].set_value("chain")
    assert not panel.fields["mass"].isEnabled()  # m and b belong to the rigid plant


def test_observer_panel_creates_a_missing_section(editor):
    editor.model.set("observer", None)
    panel = ObserverPanel(editor.model, editor)
    assert panel.fields["order"].spin.value() == ObserverSettings().order
    panel.fields["order"].spin.setValue(4)
    assert editor.model.profile.observer == ObserverSettings(order=4)
    editor.stack.undo()
    assert editor.model.profile.observer is None


def test_filter_panel_clamps_a_new_filter_below_nyquist(qapp):
    """Choosing a filter while the shown cut-off is above 0.9 Nyquist starts it at 0.9 Nyquist."""
    import math

    from analysis.chain.velocity_filter import highest_cutoff
    from analysis.study import controller_section
    from app.panels.filter_panel import DEFAULT_CUTOFF_HZ, FilterPanel

    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    stack = QUndoStack()
    panel = FilterPanel(model, Editor(model, stack))
    T = model.device.sample_time
    assert highest_cutoff(T) == pytest.approx(0.9 * math.pi / T, rel=1e-15)
    assert panel.set_kind("lowpass1") is None  # the default 30 Hz, well below Nyquist here
    assert controller_section(model.profile).velocity_filter.cutoff == pytest.approx(2 * math.pi * DEFAULT_CUTOFF_HZ)
    stack.undo()
    model.set("sample_time", 1.0 / (2 * 30.0))  # Nyquist 30 Hz: the shown 30 Hz is too high for a filter
    T = model.device.sample_time
    assert panel.set_kind("butter2") is None
    vf = controller_section(model.profile).velocity_filter
    assert vf.kind == "butter2" and vf.cutoff == highest_cutoff(T) < math.pi / T
