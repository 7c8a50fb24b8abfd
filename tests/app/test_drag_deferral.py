"""A slider drag holds back the expensive sampled-data nodes; the cheap parts follow it live.

Structural, not timed (the latency figures are in tests/benchmarks/bench_gui.py): graph call
counters show that during a drag (edits carrying one drag token) the stability map and the
simulation are not computed, that the exact spectral radius at the current gains is computed on
every edit, and that after the drag ends -- or pauses for SETTLE_MS -- each held-back node is
computed exactly once, for the final values.  A pause is SETTLE_MS without an edit plus
CONFIRM_MS of free event loop (a step that kept the GUI busy is not a pause).
"""

from __future__ import annotations

import pytest
from PySide6.QtGui import QUndoStack

from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import design_radius
from app.core import nodes_sampled
from app.core.commands import Editor
from app.core.compute_graph import CONFIRM_MS, SETTLE_MS
from app.core.model import ProfileModel
from app.core.nodes_sampled import EXACT_NODE, LIMIT_NODE, MAP_NODE, POINT_NODE, SIM_NODE
from app.core.nodes_stability import build_graph
from app.core.worker import TaskRunner
from app.tabs.sampled_tab import SampledTab

HELD = (MAP_NODE, SIM_NODE, LIMIT_NODE)
KC = (52e3, 54e3, 56e3, 58e3, 60e3)


@pytest.fixture
def setup(qapp):
    """Model, editor (drag tokens), graph with the sampled nodes; the held nodes return their
    request's coupling ``(k_c, b_c)`` (the request itself when it holds none)."""
    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    stack = QUndoStack()
    editor = Editor(model, stack)
    runner = TaskRunner()
    graph = build_graph(model, runner, chart_points=8)
    nodes_sampled.register(graph)
    editor.dragChanged.connect(graph.set_interactive)
    for name in (MAP_NODE, SIM_NODE, LIMIT_NODE, EXACT_NODE):
        graph.replace_function(name, lambda req, progress, cancelled: req.loop.coupling or req)
    yield model, editor, graph, stack
    runner.shutdown()


def pull_all(graph) -> None:
    for name in HELD:
        graph.request(name)
    graph.get(POINT_NODE)


def settle(qtbot, graph) -> None:
    qtbot.waitUntil(lambda: all(graph.is_fresh(n) for n in HELD), timeout=10000)


def test_a_drag_holds_back_the_map_and_the_simulation(setup, qtbot):
    model, editor, graph, stack = setup
    graph.drag.settle_ms = 600_000  # only the release ends the hold here (not timed: a loaded machine may pause)
    pull_all(graph)
    settle(qtbot, graph)
    calls = {n: graph.calls(n) for n in (*HELD, POINT_NODE)}
    assert calls == {MAP_NODE: 1, SIM_NODE: 1, LIMIT_NODE: 1, POINT_NODE: 1}
    token = editor.new_drag()
    for kc in KC:
        assert editor.edit("kc", kc, token) is None
        pull_all(graph)
        # the cheap part follows every edit, the expensive ones keep their last value
        assert graph.result(POINT_NODE) == design_radius(model.profile, "kc", "kobj")
        assert graph.result(MAP_NODE) == (50e3, model.profile.bc)
    assert graph.calls(POINT_NODE) == 1 + len(KC)
    assert {n: graph.calls(n) for n in HELD} == {MAP_NODE: 1, SIM_NODE: 1, LIMIT_NODE: 1}
    # k_c does not change the exact limit at the current b_c: not stale, so not waiting either
    assert set(graph.waiting()) == {MAP_NODE, SIM_NODE}
    assert graph.holding and not graph.runner.is_running()
    seen: list[set] = []
    graph.invalidated.connect(lambda names: seen.append(set(names)))
    editor.end_drag(token)
    assert not graph.holding and graph.waiting() == []
    assert seen and {MAP_NODE, SIM_NODE} <= seen[-1]
    pull_all(graph)
    settle(qtbot, graph)
    assert {n: graph.calls(n) for n in HELD} == {MAP_NODE: 2, SIM_NODE: 2, LIMIT_NODE: 1}
    assert graph.result(MAP_NODE) == graph.result(SIM_NODE) == (KC[-1], model.profile.bc)
    assert stack.count() == 1  # one drag, one undo step


def test_a_pause_in_the_drag_catches_up_once(setup, qtbot):
    model, editor, graph, _stack = setup
    pull_all(graph)
    settle(qtbot, graph)
    graph.drag.settle_ms = SETTLE_MS
    token = editor.new_drag()
    editor.edit("bc", 120.0, token)
    pull_all(graph)
    assert set(graph.waiting()) == set(HELD)
    with qtbot.waitSignal(graph.invalidated, timeout=(SETTLE_MS + CONFIRM_MS) * 20):
        pass  # the drag has not moved for SETTLE_MS
    assert not graph.holding and graph.waiting() == []
    pull_all(graph)
    settle(qtbot, graph)
    assert {n: graph.calls(n) for n in HELD} == {MAP_NODE: 2, SIM_NODE: 2, LIMIT_NODE: 2}
    # the drag moves again: held back again; the release computes the last value once more
    editor.edit("bc", 140.0, token)
    pull_all(graph)
    assert graph.holding and set(graph.waiting()) == set(HELD)
    editor.end_drag(token)
    pull_all(graph)
    settle(qtbot, graph)
    assert {n: graph.calls(n) for n in HELD} == {MAP_NODE: 3, SIM_NODE: 3, LIMIT_NODE: 3}
    assert graph.result(MAP_NODE) == (model.profile.kc, 140.0)


def test_typed_values_are_not_held_back(setup, qtbot):
    _model, editor, graph, _stack = setup
    pull_all(graph)
    settle(qtbot, graph)
    editor.edit("kc", 70e3)  # no drag token: computed at once
    pull_all(graph)
    assert graph.waiting() == []
    settle(qtbot, graph)
    assert graph.calls(MAP_NODE) == 2 and graph.calls(SIM_NODE) == 2


@pytest.fixture
def window(win):
    win.maybe_save = lambda: True
    return win


def test_the_sampled_tab_during_a_slider_drag(window, qtbot):
    g = window.graph
    tab = window.tab(SampledTab)
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: all(g.is_fresh(n) for n in (*HELD, EXACT_NODE)), timeout=120000)
    calls = {n: g.calls(n) for n in (*HELD, EXACT_NODE)}
    point_calls = g.calls(POINT_NODE)
    g.drag.settle_ms = 600_000  # only the release ends the hold here (a loaded machine may pause between steps)
    slider = window.panel.fields["kc"].slider
    slider.setSliderDown(True)  # a drag through the real widget: one token for all steps
    for step in range(1, 6):
        slider.setValue(slider.value() + 3)
        qtbot.waitUntil(lambda: not tab.stale, timeout=5000)
        assert g.calls(POINT_NODE) == point_calls + step  # live: the exact radius at the new k_c
        assert {n: g.calls(n) for n in calls} == calls  # held back
        assert "updating after the drag" in tab.map_view.header.text()
        assert "updating after the drag" in tab.time_view.plot_views()[0].header.text()
    assert g.result(POINT_NODE) == design_radius(window.model.profile, "kc", "kobj")
    slider.setSliderDown(False)
    qtbot.waitUntil(lambda: all(g.is_fresh(n) for n in calls), timeout=120000)
    assert g.calls(MAP_NODE) == calls[MAP_NODE] + 1 and g.calls(SIM_NODE) == calls[SIM_NODE] + 1
    assert g.calls(EXACT_NODE) == calls[EXACT_NODE] and g.calls(LIMIT_NODE) == calls[LIMIT_NODE]
    qtbot.waitUntil(lambda: "updating" not in tab.map_view.header.text(), timeout=5000)
    assert window.undo_stack.count() == 1
