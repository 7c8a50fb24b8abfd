"""A lazy computation graph over the model, cached by what each node computes.

Each :class:`Node` names the model fields it reads (``inputs``) and a ``request`` function that
builds, from the profile and the node's parameters, the frozen request of its study computation
(:mod:`analysis.study.requests`: exactly the inputs the computation uses).  The node's function
receives that request, never the profile, so the cache key cannot miss an input.  A model field
change marks the nodes that read it dirty and emits :attr:`ComputeGraph.invalidated`; nothing is
computed until a visible view *pulls* a node with :meth:`ComputeGraph.get` (synchronous) or
:meth:`ComputeGraph.request` (asynchronous nodes run on the :class:`~app.core.worker.TaskRunner`).
A pull whose request equals the cached one returns the cached value, so ``calls`` counts real
computations only.

A slider drag (:meth:`ComputeGraph.set_interactive`, fed by the editor's drag tokens) holds back
the nodes registered with ``live=False`` -- the expensive ones, such as the sampled-data map and
simulation: while the drag moves, a pull returns their last value and starts nothing (a stale job
of theirs is dropped).  When the drag pauses for :data:`SETTLE_MS` or ends, the held nodes are
invalidated again and the next pull runs them on the worker, once.  :meth:`ComputeGraph.waiting`
names the nodes held back, so that views can say they are catching up.

This module is the scheduler only: the nodes themselves are registered by ``app.core.nodes_*``
(:func:`app.core.nodes_stability.build_graph` builds the stability graph).  Callers use the public
methods (:meth:`ComputeGraph.result`, :meth:`ComputeGraph.set_params`, ...), never a node's fields.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any

from PySide6.QtCore import QObject, QTimer, Signal, Slot

from analysis.profiles.io import Profile
from analysis.progress import Cancelled, Progress  # the one protocol (issue 21), re-exported here

from app.core.model import ALL_FIELDS, ProfileModel
from app.core.worker import TaskRunner

__all__ = ["Node", "ComputeGraph", "DragPause", "Pull", "Progress", "Cancelled", "SETTLE_MS", "CONFIRM_MS"]

_NOTHING = object()

Pull = Callable[[str], Any]

#: A drag that has not moved for this long has paused: the held-back nodes catch up (ms).
SETTLE_MS = 200
#: ... and for this long more once the GUI is free again (a slow step is not a pause) (ms).
CONFIRM_MS = 50


@dataclass(eq=False)
class Node:
    """One cached computation.

    ``request(profile, params)`` builds the node's request (its cache key: a hashable, immutable
    value of exactly what it computes from); ``func(request, pull)`` computes the value
    (``pull(name)`` gets another node's value); asynchronous nodes instead have
    ``func(request, progress, cancelled)`` and run on the worker with that immutable request.
    ``live=False`` marks an expensive node that is not recomputed while a slider drag moves
    (see :meth:`ComputeGraph.set_interactive`).
    """

    name: str
    inputs: frozenset[str]
    request: Callable[[Profile, dict], Hashable]
    func: Callable[..., Any]
    asynchronous: bool = False
    params: dict = field(default_factory=dict)
    calls: int = 0
    value: Any = None
    value_key: Any = _NOTHING
    dirty: bool = True
    pending_key: Any = _NOTHING
    live: bool = True
    waiting: bool = False  # held back by a moving drag, to be computed when it pauses or ends

    @property
    def key(self) -> Callable[[Profile, dict], Hashable]:
        """The request function under its former name (deprecated alias, one release)."""
        return self.request


class DragPause(QObject):
    """Whether a slider drag is on, and whether it moves or has paused.

    A drag pauses when no edit came for :data:`SETTLE_MS` and then :data:`CONFIRM_MS` more of
    event loop: an edit whose own work kept the GUI busy past SETTLE_MS is not a pause, the next
    edit of the drag first gets a moment to arrive.  :attr:`paused` is emitted once per pause.
    """

    paused = Signal()

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.active = False
        self._paused = False
        self._settle = QTimer(self)
        self._settle.setSingleShot(True)
        self._settle.setInterval(SETTLE_MS)
        self._confirm = QTimer(self)
        self._confirm.setSingleShot(True)
        self._confirm.setInterval(CONFIRM_MS)
        self._settle.timeout.connect(self._confirm.start)
        self._confirm.timeout.connect(self._on_confirmed)

    @property
    def holding(self) -> bool:
        """A drag is on and moving."""
        return self.active and not self._paused

    @property
    def settle_ms(self) -> int:
        """How long a drag must not move to count as paused (ms; :data:`SETTLE_MS` by default)."""
        return self._settle.interval()

    @settle_ms.setter
    def settle_ms(self, ms: int) -> None:
        self._settle.setInterval(int(ms))

    def set_active(self, on: bool) -> None:
        self.active, self._paused = on, False
        if not on:
            self._settle.stop()
            self._confirm.stop()

    def moved(self) -> None:
        """An edit: the drag moves (again)."""
        if self.active:
            self._paused = False
            self._confirm.stop()
            self._settle.start()

    def held(self) -> None:
        """A view kept a stale value: the pause counts from here, after the edit's own work."""
        if self.active and not self._confirm.isActive():
            self._settle.start()

    @Slot()
    def _on_confirmed(self) -> None:
        if self.active:
            self._paused = True
            self.paused.emit()


class ComputeGraph(QObject):
    """Nodes cached by their requests, invalidated by model field signals, pulled on demand."""

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
        self.drag = DragPause(self)
        self.drag.paused.connect(self._on_paused)
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
        """The node record, for inspection (change it through :meth:`set_params` and friends)."""
        return self._nodes[name]

    def calls(self, name: str) -> int:
        """How often ``name`` was really computed (cache hits are not counted)."""
        return self._nodes[name].calls

    def names(self) -> list[str]:
        return list(self._nodes)

    def __contains__(self, name: object) -> bool:
        return name in self._nodes

    # -- parameters and results (the public face of a node) ----------------------------------------
    def params(self, name: str) -> dict:
        """A copy of the node's parameters (view settings such as a grid, not profile fields)."""
        return dict(self._nodes[name].params)

    def set_params(self, name: str, **changes: Any) -> bool:
        """Change some of the node's parameters; the node is dirty if any value changed.

        Returns whether anything changed.  Nothing is computed: the next pull sees the new request.
        """
        node = self._nodes[name]
        unknown = set(changes) - set(node.params)
        if unknown:
            raise KeyError(f"node {name!r} has no parameter(s) {sorted(unknown)}")
        changed = {k: v for k, v in changes.items() if node.params.get(k) != v}
        if not changed:
            return False
        node.params.update(changed)
        node.dirty = True
        return True

    def set_param(self, name: str, key: str, value: Any) -> bool:
        """One parameter of :meth:`set_params`."""
        return self.set_params(name, **{key: value})

    def result(self, name: str) -> Any:
        """The last computed value of ``name`` (possibly stale; ``None`` before the first) -- no pull."""
        return self._nodes[name].value

    def function(self, name: str) -> Callable[..., Any]:
        """The function computing ``name``."""
        return self._nodes[name].func

    def replace_function(self, name: str, func: Callable[..., Any]) -> Callable[..., Any]:
        """Compute ``name`` with ``func`` from its next computation on (instrumentation, tests).

        ``func`` takes the node's request; the cached value stays until the request changes (returns the old one).
        """
        node = self._nodes[name]
        old, node.func = node.func, func
        return old

    # -- interaction ----------------------------------------------------------------------------
    @property
    def stability_name(self) -> str:
        """The stability node views should pull now: the grid-only preview during a slider drag
        (same curves, no refinement of the worst point), the refined result otherwise."""
        return "stability_preview" if self.drag.active and "stability_preview" in self._nodes else "stability"

    @property
    def interactive(self) -> bool:
        return self.drag.active

    @property
    def holding(self) -> bool:
        """Whether the ``live=False`` nodes are held back now (a drag is moving)."""
        return self.drag.holding

    def waiting(self) -> list[str]:
        """The nodes held back by the moving drag (their views show a stale value, catching up)."""
        return [n.name for n in self._nodes.values() if n.waiting]

    @Slot(bool)
    def set_interactive(self, on: bool) -> None:
        """A slider drag started or ended; at the end the refined results and the nodes held
        back during the drag are pulled again."""
        if on == self.drag.active:
            return
        self.drag.set_active(on)
        if on:
            return
        if names := self._release() | ({"stability"} if "stability" in self._nodes else set()):
            self.invalidated.emit(names)

    @Slot()
    def _on_paused(self) -> None:
        """The drag paused: compute what it held back (a further move holds them again)."""
        if names := self._release():
            self.invalidated.emit(names)

    def _release(self) -> set[str]:
        held = [n for n in self._nodes.values() if n.waiting]
        for n in held:
            n.waiting = False
        return {n.name for n in held}

    def _hold(self, node: Node, key: Hashable) -> Any:
        """Keep ``node``'s last value during the drag; a job of it for an older key is dropped."""
        node.waiting = True
        self.drag.held()
        if node.pending_key is not _NOTHING and node.pending_key != key:
            node.pending_key = _NOTHING
            self.runner.drop(node.name)
        return node.value

    # -- invalidation --------------------------------------------------------------------------
    @Slot(str)
    def invalidate(self, field_name: str) -> None:
        self.drag.moved()
        hit = {n.name for n in self._nodes.values() if field_name in n.inputs}
        for name in hit:
            self._nodes[name].dirty = True
        if hit:
            self.invalidated.emit(hit)

    @Slot()
    def invalidate_all(self) -> None:
        self.drag.moved()
        for n in self._nodes.values():
            n.dirty = True
        self.invalidated.emit(set(self._nodes))

    # -- pulling ---------------------------------------------------------------------------------
    def key_of(self, name: str) -> Hashable:
        """The request ``name`` computes now (its cache key)."""
        node = self._nodes[name]
        return node.request(self.model.profile, node.params)

    def is_fresh(self, name: str) -> bool:
        node = self._nodes[name]
        if node.value_key is _NOTHING:
            return False
        if not node.dirty:
            return True
        return node.value_key == self.key_of(name)

    def get(self, name: str, hold: bool = True) -> Any:
        """A synchronous node's value, computed if its request changed (``live=False``: held in a drag unless not ``hold``)."""
        node = self._nodes[name]
        if node.asynchronous:
            raise TypeError(f"{name} is asynchronous: use request()")
        if not node.dirty and node.value_key is not _NOTHING:
            return node.value
        key = node.request(self.model.profile, node.params)
        if key != node.value_key:
            if hold and not node.live and self.holding and node.value_key is not _NOTHING:
                return self._hold(node, key)  # stays dirty: computed when the drag pauses or ends
            node.calls, node.waiting = node.calls + 1, False
            node.value, node.value_key = node.func(key, self.get), key
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
        key = node.request(self.model.profile, node.params)
        if key == node.value_key:
            node.dirty = False
            node.waiting = False
            return node.value
        if not node.live and self.holding:
            return self._hold(node, key)
        node.waiting = False
        if key != node.pending_key or not self.runner.is_running(name):
            node.calls += 1
            node.pending_key = key

            def job(progress: Progress, cancelled: Cancelled) -> Any:
                return key, node.func(key, progress, cancelled)

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
        if value is None:  # the job stopped early (a cancelled computation returns None)
            return
        node.value, node.value_key, node.pending_key = value, key, _NOTHING
        node.dirty = key != node.request(self.model.profile, node.params)
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


