"""Undo commands and the Editor on their own (no window): merging drags, exact undo, refusals."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtGui import QUndoStack

from analysis.chain import ratio_from_damping
from analysis.profiles.io import bundled_profiles, load_profile
from app.core.commands import Editor
from app.core.model import ProfileModel


@pytest.fixture
def editor(qapp):
    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    stack = QUndoStack()
    ed = Editor(model, stack)
    return ed


def test_an_edit_is_one_undo_step_with_exact_values(editor):
    model, stack = editor.model, editor.stack
    kc0 = model.profile.kc
    assert editor.edit("kc", 61234.5678) is None
    assert stack.count() == 1 and stack.undoText() == "Set k_c"
    stack.undo()
    assert model.profile.kc == kc0
    stack.redo()
    assert model.profile.kc == 61234.5678


def test_a_slider_drag_merges_into_one_step(editor):
    model, stack = editor.model, editor.stack
    kc0 = model.profile.kc
    dragging: list[bool] = []
    editor.dragChanged.connect(dragging.append)
    token = editor.new_drag()
    values = [51000.0, 52500.0, 54321.0, 60000.0]
    for v in values:
        assert editor.edit("kc", v, token) is None
    editor.end_drag(token)
    assert dragging == [True, False]
    assert stack.count() == 1
    assert model.profile.kc == values[-1]
    stack.undo()
    assert model.profile.kc == kc0  # the value before the drag, not an intermediate one
    stack.redo()
    assert model.profile.kc == values[-1]
    # a second drag is a second step
    token = editor.new_drag()
    editor.edit("kc", 70000.0, token)
    editor.edit("kc", 71000.0, token)
    editor.end_drag(token)
    assert stack.count() == 2
    stack.undo()
    assert model.profile.kc == values[-1]


def test_edits_of_different_fields_or_without_token_do_not_merge(editor):
    stack = editor.stack
    token = editor.new_drag()
    editor.edit("kc", 51000.0, token)
    editor.edit("bc", 120.0, token)  # another field: its own step
    editor.end_drag(token)
    editor.edit("kc", 52000.0)
    editor.edit("kc", 53000.0)
    assert stack.count() == 4


def test_a_refused_value_is_not_pushed(editor):
    model, stack = editor.model, editor.stack
    refused: list[tuple[str, str]] = []
    editor.refused.connect(lambda f, r: refused.append((f, r)))
    before = model.profile
    reason = editor.edit("kc", -5.0)
    assert reason is not None and reason.startswith("refused: must be")
    assert stack.count() == 0 and model.profile is before
    assert refused == [("kc", reason)]
    # the same during a drag: the drag's earlier value stays, nothing is merged
    token = editor.new_drag()
    editor.edit("kc", 55000.0, token)
    assert editor.edit("kc", float("inf"), token) is not None
    editor.end_drag(token)
    assert stack.count() == 1 and model.profile.kc == 55000.0


def test_an_unchanged_value_is_not_pushed(editor):
    assert editor.edit("kc", editor.model.profile.kc) is None
    assert editor.stack.count() == 0


def test_element_edit_and_undo_restore_the_vector(editor):
    model, stack = editor.model, editor.stack
    masses0 = np.array(model.device.masses)
    assert editor.edit_element("masses", 1, 2.5) is None
    assert model.device.masses[1] == 2.5 and stack.undoText() == "Set mass 2"
    stack.undo()
    np.testing.assert_array_equal(model.device.masses, masses0)


def test_add_and_remove_mass_are_single_steps(editor):
    model, stack = editor.model, editor.stack
    n = model.device.n
    assert editor.add_mass() is None
    assert model.device.n == n + 1 and stack.count() == 1
    # the new element: a copy of the last mass, damped at ratio 0.1 (eq. 28 with the reduced mass)
    dev = model.device
    m_a, m_b, k = dev.masses[-2], dev.masses[-1], dev.stiffnesses[-1]
    assert m_b == m_a
    assert dev.dampings[-1] == pytest.approx(0.2 * np.sqrt(k * m_a * m_b / (m_a + m_b)), rel=1e-12)
    assert ratio_from_damping(k, m_a, m_b, dev.dampings[-1]) == pytest.approx(0.1, rel=1e-12)
    assert editor.remove_mass() is None
    assert model.device.n == n
    stack.undo()
    stack.undo()
    assert model.device.n == n and stack.count() == 2 and stack.index() == 0
