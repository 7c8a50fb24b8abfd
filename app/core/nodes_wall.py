"""The nodes of the transparency tab: the wall controller of Eom, Suh & Yi (section 3, Figs. 7-10).

``wall_design`` is the :class:`WallDesign` of the profile's wall section; ``wall_tradeoff`` (J and
‖L‖∞ over B_c, eqs. 11 and 16-17, and the robust optimum) runs on the worker.  ``wall_point``
(J and ‖L‖∞ at the current B_c: the markers and the summary), ``wall_admittance`` and ``wall_step``
are evaluated at the node parameter ``bc`` (the tab's current B_c, which is not a profile field).
Every node calls :mod:`analysis.study`.

During a slider drag (:class:`~app.core.compute_graph.DragPause`) the cheap nodes follow every step
(``wall_point`` ~5 ms, ``wall_admittance`` < 1 ms), while the two ``live=False`` nodes are held
and catch up on the worker when the drag pauses or ends: the curves over B_c (up to ~0.2 s) and
the step response (a 4000-step simulation of the sampled loop, ~6 ms: together with the point it
would not fit in a 16 ms frame).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from analysis.profiles.io import Profile
from analysis.study import (
    DEFAULT_BC,
    WallAdmittances,
    WallAtRequest,
    WallPoint,
    WallRequest,
    WallTradeoff,
    admittance_grid,
    wall_admittances,
    wall_design,
    wall_point,
    wall_settings,
    wall_step,
    wall_tradeoff,
)

from analysis.study.labels import HOLD_LABELS, PLANT_LABELS
from analysis.progress import Cancelled, Progress
from app.core.compute_graph import ComputeGraph, Node, Pull
from app.core.model import DEVICE_FIELDS

__all__ = ["DEFAULT_BC", "NODES", "AT_BC_NODES", "HOLD_LABELS", "PLANT_LABELS", "wall_settings", "wall_design",
           "WallTradeoff", "WallPoint", "WallAdmittances", "admittance_grid", "register"]

NODES = ("wall_design", "wall_tradeoff", "wall_point", "wall_step", "wall_admittance")
#: The nodes evaluated at the current B_c (node parameter ``bc``); ``wall_step`` is asynchronous.
AT_BC_NODES = ("wall_point", "wall_step", "wall_admittance")
_INPUTS = frozenset({"wall"}) | frozenset(DEVICE_FIELDS)


def _wall_request(p: Profile, params: dict) -> WallRequest:
    return WallRequest.of(p)


def _at_bc_request(p: Profile, params: dict) -> WallAtRequest:
    return WallAtRequest(WallRequest.of(p), float(params["bc"]))


def _tradeoff(req: WallRequest, progress: Progress, cancelled: Cancelled) -> WallTradeoff | None:
    return wall_tradeoff(req, progress=progress, cancelled=cancelled)  # its own WallDesign, never shared


def _step(req: WallAtRequest, progress: Progress, cancelled: Cancelled) -> Any:
    """The step response at the current B_c (Figs. 7, 10), on the worker: its own WallDesign."""
    return wall_step(wall_design(req.wall), req.bc)


def _at_bc_node(name: str, func: Callable[[Any, float], Any]) -> Node:
    """A synchronous node: ``func(design, bc)`` at its parameter ``bc`` (the tab's current B_c)."""

    def compute(req: WallAtRequest, pull: Pull) -> Any:
        return func(pull("wall_design"), req.bc)

    return Node(name, _INPUTS, _at_bc_request, compute, params={"bc": DEFAULT_BC})


def register(graph: ComputeGraph) -> None:
    """Add the wall controller's nodes to ``graph``."""
    graph.add(Node("wall_design", _INPUTS, _wall_request, lambda req, _: wall_design(req)))
    graph.add(Node("wall_tradeoff", _INPUTS, _wall_request, _tradeoff, asynchronous=True, live=False))
    graph.add(_at_bc_node("wall_point", wall_point))
    graph.add(Node("wall_step", _INPUTS, _at_bc_request, _step, params={"bc": DEFAULT_BC}, asynchronous=True,
                   live=False))
    graph.add(_at_bc_node("wall_admittance", wall_admittances))
