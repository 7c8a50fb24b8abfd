"""Adding or removing a mass keeps the lists indexed by mass (the simulator's friction) one value per
mass, in the same undo step, so that what the GUI saves the loader accepts (issue 23)."""

from __future__ import annotations

import pytest
from PySide6.QtGui import QUndoStack

from analysis.profiles.io import bundled_profiles, load_profile, save_profile
from app.core.commands import Editor
from app.core.model import ProfileModel


@pytest.fixture
def editor(qapp):
    return Editor(ProfileModel(load_profile(bundled_profiles()["hbfd"])), QUndoStack())


def test_adding_and_removing_masses_resizes_friction_and_saves_loadably(editor, tmp_path):
    model, stack = editor.model, editor.stack
    assert model.profile.simulation.options.friction == (0.0, 1.0, 0.0, 0.5)
    assert editor.add_mass() is None
    assert model.device.n == 5 and model.profile.simulation.options.friction == (0.0, 1.0, 0.0, 0.5, 0.0)
    assert editor.remove_mass(1) is None
    assert model.device.n == 4 and model.profile.simulation.options.friction == (0.0, 0.0, 0.5, 0.0)
    path = tmp_path / "edited.json"
    save_profile(model.profile, path)
    assert load_profile(path) == model.profile
    stack.undo()
    stack.undo()
    assert stack.count() == 2 and model.profile.simulation.options.friction == (0.0, 1.0, 0.0, 0.5)
