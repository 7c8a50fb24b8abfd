"""The compute graph on its own (no window): laziness, invalidation of dependents only, parameters."""

from __future__ import annotations

import pytest

from analysis import AdmittanceDisplay, ImpedanceDisplay
from analysis.profiles.io import bundled_profiles, load_profile
from app.core.compute_graph import ComputeGraph, Node
from app.core.model import ProfileModel
from app.core.nodes_stability import build_graph
from app.core.worker import TaskRunner


@pytest.fixture
def parts(qapp):
    model = ProfileModel(load_profile(bundled_profiles()["hbfd"]))
    runner = TaskRunner()
    yield model, runner
    runner.shutdown()


@pytest.fixture
def graph(parts):
    model, runner = parts
    return build_graph(model, runner, chart_points=8)


def test_a_node_not_pulled_is_never_computed(graph):
    graph.get("stability")
    assert graph.calls("stability") == 1 and graph.calls("impedance_display") == 1
    for name in ("admittance_display", "stability_preview", "max_stiffness", "design_chart", "min_mass"):
        assert graph.calls(name) == 0, name


def test_moving_a_coupling_gain_does_not_recompute_the_device_node(graph):
    model = graph.model
    res = graph.get("stability")
    for kc in (55000.0, 60000.0, 65000.0):
        model.set("kc", kc)
        res = graph.get("stability")
    assert graph.calls("impedance_display") == 1
    assert graph.calls("stability") == 4
    ref = ImpedanceDisplay(model.device).evaluate(65000.0, model.profile.bc)
    assert res.relative_margin == ref.relative_margin and res.worst_margin == ref.worst_margin
    # a device change does recompute it
    model.set("sample_time", 5e-4)
    graph.get("stability")
    assert graph.calls("impedance_display") == 2


def test_a_pull_with_an_unchanged_key_is_cached(graph):
    first = graph.get("stability")
    assert graph.get("stability") is first
    kc0 = graph.model.profile.kc
    graph.model.set("kc", 60000.0)
    graph.model.set("kc", kc0)
    assert graph.get("stability") is first  # same key as before: no computation
    assert graph.calls("stability") == 1


def test_invalidation_names_only_the_dependents(graph):
    seen: list[set[str]] = []
    graph.invalidated.connect(seen.append)
    graph.get("stability")
    graph.get("max_stiffness")
    graph.model.set("kc", 60000.0)
    assert seen and "stability" in seen[-1]
    assert not {"impedance_display", "admittance_display", "max_stiffness", "design_chart"} & seen[-1]
    assert graph.is_fresh("impedance_display") and graph.is_fresh("max_stiffness")
    assert not graph.is_fresh("stability")
    graph.model.set("bc", 150.0)
    assert "max_stiffness" in seen[-1] and not graph.is_fresh("max_stiffness")
    assert graph.is_fresh("impedance_display")


def test_the_admittance_display_pulls_its_own_device_node(graph):
    model = graph.model
    model.set("display", "admittance")
    res = graph.get("stability")
    assert graph.calls("admittance_display") == 1 and graph.calls("impedance_display") == 0
    ref = AdmittanceDisplay(model.device, model.profile.kp, model.profile.kd).evaluate(model.profile.mc,
                                                                                       model.profile.bc_adm)
    assert res.relative_margin == ref.relative_margin
    model.set("mc", 9.0)
    graph.get("stability")
    assert graph.calls("admittance_display") == 1  # m_c is a coupling gain
    model.set("kd", 120.0)
    graph.get("stability")
    assert graph.calls("admittance_display") == 2  # k_d is part of the device side


def small_graph(model: ProfileModel, runner: TaskRunner) -> ComputeGraph:
    g = ComputeGraph(model, runner)
    g.add(Node("a", frozenset({"kc"}), lambda p, prm: (p.kc, prm["scale"]), lambda req, pull: 2 * req[0],
               params={"scale": 1.0}))
    g.add(Node("b", frozenset({"kc", "bc"}), lambda p, _: (p.kc, p.bc), lambda req, pull: pull("a") + req[1]))
    return g


def test_parameters_are_part_of_the_key(parts):
    model, runner = parts
    g = small_graph(model, runner)
    assert g.get("b") == 2 * 50000.0 + 100.0
    assert g.params("a") == {"scale": 1.0}
    assert g.set_params("a", scale=2.0) is True
    assert g.set_params("a", scale=2.0) is False  # unchanged
    assert not g.is_fresh("a")
    g.get("a")
    assert g.calls("a") == 2
    with pytest.raises(KeyError):
        g.set_params("a", nonsense=1)
    params = g.params("a")
    params["scale"] = 99.0  # a copy: the node is not changed
    assert g.params("a") == {"scale": 2.0}


def test_a_pulled_dependency_recomputes_only_when_its_inputs_change(parts):
    model, runner = parts
    g = small_graph(model, runner)
    g.get("b")
    model.set("bc", 150.0)
    assert g.get("b") == 2 * 50000.0 + 150.0
    assert (g.calls("a"), g.calls("b")) == (1, 2)
    model.set("kc", 1000.0)
    assert g.get("b") == 2150.0
    assert (g.calls("a"), g.calls("b")) == (2, 3)
    assert g.result("a") == 2000.0


def test_nodes_must_read_known_fields(parts):
    model, runner = parts
    g = ComputeGraph(model, runner)
    with pytest.raises(ValueError):
        g.add(Node("x", frozenset({"nonsense"}), lambda p, _: 0, lambda p, pull: 0))
    g.add(Node("x", frozenset({"kc"}), lambda p, _: 0, lambda p, pull: 0))
    with pytest.raises(ValueError):
        g.add(Node("x", frozenset({"kc"}), lambda p, _: 0, lambda p, pull: 0))


def test_an_asynchronous_node_runs_on_the_worker_and_reports_ready(graph, qtbot):
    graph.model.set("display", "admittance")
    assert graph.request("min_mass") is None  # no value yet: the worker starts
    assert graph.calls("min_mass") == 1 and graph.runner.is_running("min_mass")
    with qtbot.waitSignal(graph.ready, timeout=30000) as ready:
        pass
    assert ready.args == ["min_mass"]
    p = graph.model.profile
    expected = AdmittanceDisplay(p.device, p.kp, p.kd).min_mass()
    assert graph.is_fresh("min_mass")
    assert graph.result("min_mass").mc == expected.mc
    assert graph.request("min_mass") is graph.result("min_mass")  # cached: no new job
    assert graph.calls("min_mass") == 1
    with pytest.raises(TypeError):
        graph.get("min_mass")


def test_a_newer_request_supersedes_and_a_cancel_keeps_the_last_result(parts, qtbot):
    import threading

    model, runner = parts
    g = ComputeGraph(model, runner)
    release = {50000.0: threading.Event(), 60000.0: threading.Event(), 70000.0: threading.Event()}
    started: list[float] = []

    def slow(kc, progress, cancelled):
        started.append(kc)
        while not release[kc].is_set():
            if cancelled():
                return None
            release[kc].wait(0.001)
        return 2 * kc

    g.add(Node("slow", frozenset({"kc"}), lambda p, _: p.kc, slow, asynchronous=True))
    ready: list[str] = []
    g.ready.connect(ready.append)
    assert g.request("slow") is None
    qtbot.waitUntil(lambda: started == [50000.0], timeout=30000)
    model.set("kc", 60000.0)  # the running job is now stale: a new one supersedes it
    assert g.request("slow") is None and g.calls("slow") == 2
    release[50000.0].set()
    with qtbot.waitSignal(g.ready, timeout=30000):
        release[60000.0].set()
    assert runner.wait(30000)
    qtbot.waitUntil(lambda: runner.dropped == 1, timeout=30000)
    assert ready == ["slow"] and g.result("slow") == 120000.0 and g.is_fresh("slow")
    # a cancelled computation reports cancelled; the last good value stays
    model.set("kc", 70000.0)
    assert g.request("slow") == 120000.0  # the stale value meanwhile
    with qtbot.waitSignal(g.cancelled, timeout=30000):
        g.cancel("slow")
    assert runner.wait(30000)
    assert ready == ["slow"] and g.result("slow") == 120000.0 and not g.is_fresh("slow")


#: the synchronous nodes of the stability, sampled-data, wall and observer graphs (cheap to pull)
SYNC_NODES = ("impedance_display", "stability", "stability_preview", "max_stiffness", "sampled_point", "wall_design",
              "wall_point", "observer_response")


@pytest.mark.parametrize("field,value", [("kc", 61000.0), ("bc", 140.0), ("mc", 3.0), ("kp", 1234.0),
                                         ("sample_time", 5e-4), ("name", "renamed"), ("notes", "more notes")])
def test_exactly_the_nodes_whose_requests_changed_are_recomputed(graph, field, value):
    """Each node's cache key is its study request: an edit recomputes the nodes whose request it
    changed, and no other (a request that misses an input would fail the first half, one that
    holds an unused input the second)."""
    from app.core import nodes_observer, nodes_sampled, nodes_wall

    for register in (nodes_sampled.register, nodes_wall.register, nodes_observer.register):
        register(graph)
    for name in SYNC_NODES:
        graph.get(name, hold=False)
    before = {n: graph.key_of(n) for n in SYNC_NODES}
    calls = {n: graph.calls(n) for n in SYNC_NODES}
    graph.model.set(field, value)
    for name in SYNC_NODES:
        graph.get(name, hold=False)
    changed = {n for n in SYNC_NODES if graph.key_of(n) != before[n]}
    recomputed = {n for n in SYNC_NODES if graph.calls(n) > calls[n]}
    assert recomputed == changed
    assert all(graph.calls(n) - calls[n] <= 1 for n in SYNC_NODES)
    expected = {"kc": {"stability", "stability_preview", "sampled_point"},
                "bc": {"stability", "stability_preview", "max_stiffness", "sampled_point"},
                "mc": set(), "kp": {"sampled_point"}, "name": set(), "notes": set()}
    if field in expected:
        assert changed == expected[field]
    else:  # a device field: every device-side node (the observer and a rigid-body wall from its mass only)
        assert {"impedance_display", "stability", "max_stiffness", "sampled_point"} <= changed
