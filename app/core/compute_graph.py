"""A lazy computation graph over the model, cached by its inputs.

Each :class:`Node` names the model fields it reads (``inputs``) and a ``key`` function that
reduces the profile to exactly what the result depends on.  A model field change marks the nodes
that read it dirty and emits :attr:`ComputeGraph.invalidated`; nothing is computed until a visible
view *pulls* a node with :meth:`ComputeGraph.get` (synchronous) or :meth:`ComputeGraph.request`
(asynchronous nodes run on the :class:`~app.worker.TaskRunner`).  A pull whose key equals the
cached key returns the cached value, so ``calls`` counts real computations only.

The device nodes (``impedance_display``, ``admittance_display``) build the analysis core's display
objects, which cache the device two-port response per frequency vector; their keys exclude the
coupling gains, so a gain change reuses them.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from PySide6.QtCore import QObject, Signal, Slot

from analysis import AdmittanceDisplay, ImpedanceDisplay, StabilityResult
from analysis.profiles.io import Profile

from app.core.model import ALL_FIELDS, DEVICE_FIELDS, ProfileModel
from app.core.worker import TaskRunner

__all__ = ["Node", "ComputeGraph", "build_graph", "ChartResult"]

_NOTHING = object()

Pull = Callable[[str], Any]


@dataclass(eq=False)
class Node:
    """One cached computation.

    ``func(profile, pull)`` computes the value (``pull(name)`` gets another node's value);
    asynchronous nodes instead have ``func(profile, params, progress, cancelled)`` and run on the
    worker with an immutable snapshot of the profile.
    """

    name: str
    inputs: frozenset[str]
    key: Callable[[Profile, dict], Hashable]
    func: Callable[..., Any]
    asynchronous: bool = False
    params: dict = field(default_factory=dict)
    calls: int = 0
    value: Any = None
    value_key: Any = _NOTHING
    dirty: bool = True
    pending_key: Any = _NOTHING


@dataclass(frozen=True)
class ChartResult:
    """A design chart with the display type it belongs to."""

    display: str
    chart: Any  # StiffnessChart or MassChart


class ComputeGraph(QObject):
    """Nodes cached by input keys, invalidated by model field signals, pulled on demand."""

    invalidated = Signal(object)  # set of node names that became dirty
    ready = Signal(str)  # an asynchronous node has a fresh value
    progress = Signal(str, int, int)
    failed = Signal(str, str)
    started = Signal(str)
    cancelled = Signal(str)

    def __init__(self, model: ProfileModel, runner: TaskRunner, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.model = model
        self.runner = runner
        self._nodes: dict[str, Node] = {}
        self._interactive = False
        model.fieldChanged.connect(self.invalidate)
        model.profileReplaced.connect(self.invalidate_all)
        runner.finished.connect(self._on_finished)
        runner.progress.connect(self._on_progress)
        runner.failed.connect(self._on_failed)
        runner.cancelled.connect(self._on_cancelled)

    # -- structure ---------------------------------------------------------------------------
    def add(self, node: Node) -> Node:
        if node.name in self._nodes:
            raise ValueError(f"node {node.name!r} exists")
        unknown = set(node.inputs) - set(ALL_FIELDS)
        if unknown:
            raise ValueError(f"node {node.name!r} reads unknown fields {sorted(unknown)}")
        self._nodes[node.name] = node
        return node

    def node(self, name: str) -> Node:
        return self._nodes[name]

    def calls(self, name: str) -> int:
        return self._nodes[name].calls

    def names(self) -> list[str]:
        return list(self._nodes)

    # -- interaction ----------------------------------------------------------------------------
    @property
    def stability_name(self) -> str:
        """The stability node views should pull now: the grid-only preview during a slider drag
        (same curves, no refinement of the worst point), the refined result otherwise."""
        return "stability_preview" if self._interactive and "stability_preview" in self._nodes else "stability"

    @property
    def interactive(self) -> bool:
        return self._interactive

    @Slot(bool)
    def set_interactive(self, on: bool) -> None:
        """A slider drag started or ended; at the end the refined results are pulled again."""
        if on == self._interactive:
            return
        self._interactive = on
        if not on and "stability" in self._nodes:
            self.invalidated.emit({"stability"})

    # -- invalidation --------------------------------------------------------------------------
    @Slot(str)
    def invalidate(self, field_name: str) -> None:
        hit = {n.name for n in self._nodes.values() if field_name in n.inputs}
        for name in hit:
            self._nodes[name].dirty = True
        if hit:
            self.invalidated.emit(hit)

    @Slot()
    def invalidate_all(self) -> None:
        for n in self._nodes.values():
            n.dirty = True
        self.invalidated.emit(set(self._nodes))

    # -- pulling ---------------------------------------------------------------------------------
    def key_of(self, name: str) -> Hashable:
        node = self._nodes[name]
        return node.key(self.model.profile, node.params)

    def is_fresh(self, name: str) -> bool:
        node = self._nodes[name]
        if node.value_key is _NOTHING:
            return False
        if not node.dirty:
            return True
        return node.value_key == self.key_of(name)

    def get(self, name: str) -> Any:
        """The value of a synchronous node, computing it only if its key changed."""
        node = self._nodes[name]
        if node.asynchronous:
            raise TypeError(f"{name} is asynchronous: use request()")
        if not node.dirty and node.value_key is not _NOTHING:
            return node.value
        key = node.key(self.model.profile, node.params)
        if key != node.value_key:
            node.calls += 1
            node.value = node.func(self.model.profile, self.get)
            node.value_key = key
        node.dirty = False
        return node.value

    def request(self, name: str) -> Any:
        """The last value of an asynchronous node; starts the worker if that value is stale.

        Returns the cached value (possibly stale, ``None`` before the first result).  When the
        fresh value arrives :attr:`ready` is emitted with the node's name.
        """
        node = self._nodes[name]
        if not node.asynchronous:
            return self.get(name)
        key = node.key(self.model.profile, node.params)
        if key == node.value_key:
            node.dirty = False
            return node.value
        if key != node.pending_key or not self.runner.is_running(name):
            node.calls += 1
            node.pending_key = key
            profile, params = self.model.profile, dict(node.params)

            def job(progress: Callable[[int, int], None], cancelled: Callable[[], bool]) -> Any:
                return key, node.func(profile, params, progress, cancelled)

            self.runner.submit(name, job)
            self.started.emit(name)
        return node.value

    def cancel(self, name: str) -> None:
        node = self._nodes[name]
        node.pending_key = _NOTHING
        self.runner.cancel(name)

    @Slot(str, object)
    def _on_finished(self, name: str, payload: object) -> None:
        node = self._nodes.get(name)
        if node is None or payload is None:
            return
        key, value = payload  # type: ignore[misc]
        if value is None:  # the job stopped early
            return
        node.value, node.value_key, node.pending_key = value, key, _NOTHING
        node.dirty = key != node.key(self.model.profile, node.params)
        self.ready.emit(name)

    @Slot(str, int, int)
    def _on_progress(self, name: str, done: int, total: int) -> None:
        if name in self._nodes:
            self.progress.emit(name, done, total)

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name in self._nodes:
            self._nodes[name].pending_key = _NOTHING
            self.failed.emit(name, message)

    @Slot(str)
    def _on_cancelled(self, name: str) -> None:
        if name in self._nodes:
            self.cancelled.emit(name)


# -- the nodes of the stability analysis ---------------------------------------------------------

GAIN_FIELDS = frozenset({"display", "kc", "bc", "mc", "bc_adm", "kp", "kd"})
_DEVICE = frozenset(DEVICE_FIELDS)


def _impedance_display(profile: Profile, pull: Pull) -> ImpedanceDisplay:
    imp = ImpedanceDisplay(profile.device)
    imp.bound_result(imp.frequencies())  # the device two-port response on the grid
    return imp


def _admittance_display(profile: Profile, pull: Pull) -> AdmittanceDisplay:
    adm = AdmittanceDisplay(profile.device, profile.kp, profile.kd)
    adm.bound_result(adm.frequencies())
    return adm


def _stability_key(p: Profile, params: dict) -> Hashable:
    if p.display == "impedance":
        return ("impedance", p.device.key(), p.kc, p.bc)
    return ("admittance", p.device.key(), p.kp, p.kd, p.mc, p.bc_adm)


def _stability(profile: Profile, pull: Pull) -> StabilityResult:
    if profile.display == "impedance":
        return pull("impedance_display").evaluate(profile.kc, profile.bc)
    return pull("admittance_display").evaluate(profile.mc, profile.bc_adm)


def _stability_preview(profile: Profile, pull: Pull) -> StabilityResult:
    if profile.display == "impedance":
        return pull("impedance_display").evaluate(profile.kc, profile.bc, refine=False)
    return pull("admittance_display").evaluate(profile.mc, profile.bc_adm, refine=False)


def _max_stiffness(profile: Profile, pull: Pull) -> Any:
    return pull("impedance_display").max_stiffness(profile.bc)


def _chart_key(p: Profile, params: dict) -> Hashable:
    grid = (params["bc_range"], params["mc_range"], params["points"])
    if p.display == "impedance":
        return ("impedance", p.device.key(), grid)
    return ("admittance", p.device.key(), p.kp, p.kd, grid)


def _design_chart(profile: Profile, params: dict, progress: Callable[[int, int], None],
                  cancelled: Callable[[], bool]) -> ChartResult | None:
    """The design chart, one grid value at a time so that it can report and stop.

    Builds its own display object: the GUI thread's cached one is never shared across threads.
    """
    n = int(params["points"])
    if profile.display == "impedance":
        imp = ImpedanceDisplay(profile.device)
        bcs = np.geomspace(*params["bc_range"], n)
        kcs, fr = np.full(n, np.nan), np.full(n, np.nan)
        for i, bc in enumerate(bcs):
            if cancelled():
                return None
            d = imp.max_stiffness(float(bc))
            kcs[i] = np.nan if d.kc is None else d.kc
            fr[i] = d.frequency
            progress(i + 1, n)
        from analysis import StiffnessChart

        return ChartResult("impedance", StiffnessChart(bc=bcs, kc=kcs, frequency=fr))
    adm = AdmittanceDisplay(profile.device, profile.kp, profile.kd)
    mcs = np.geomspace(*params["mc_range"], n)
    low, high = np.full(n, np.nan), np.full(n, np.nan)
    for i, mc in enumerate(mcs):
        if cancelled():
            return None
        d = adm.feasible_damping(float(mc))
        if d.feasible:
            low[i], high[i] = d.low, d.high
        progress(i + 1, n)
    from analysis import MassChart

    return ChartResult("admittance", MassChart(mc=mcs, low=low, high=high))


def _min_mass(profile: Profile, params: dict, progress: Callable[[int, int], None],
              cancelled: Callable[[], bool]) -> Any:
    return AdmittanceDisplay(profile.device, profile.kp, profile.kd).min_mass()


def build_graph(model: ProfileModel, runner: TaskRunner, chart_points: int = 40) -> ComputeGraph:
    """The graph of the stability analysis (tabs may add their own nodes)."""
    g = ComputeGraph(model, runner)
    g.add(Node("impedance_display", _DEVICE, lambda p, _: p.device.key(), _impedance_display))
    g.add(Node("admittance_display", _DEVICE | {"kp", "kd"}, lambda p, _: (p.device.key(), p.kp, p.kd),
               _admittance_display))
    g.add(Node("stability", _DEVICE | GAIN_FIELDS, _stability_key, _stability))
    g.add(Node("stability_preview", _DEVICE | GAIN_FIELDS, _stability_key, _stability_preview))
    g.add(Node("max_stiffness", _DEVICE | {"bc"}, lambda p, _: (p.device.key(), p.bc), _max_stiffness))
    g.add(Node("design_chart", _DEVICE | {"display", "kp", "kd"}, _chart_key, _design_chart, asynchronous=True,
               params={"bc_range": (1.0, 1e4), "mc_range": (1e-3, 1e3), "points": chart_points}))
    g.add(Node("min_mass", _DEVICE | {"kp", "kd"}, lambda p, _: (p.device.key(), p.kp, p.kd), _min_mass,
               asynchronous=True))
    return g

