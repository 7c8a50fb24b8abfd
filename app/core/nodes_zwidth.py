"""The nodes of the Z-width tab: the controller as built (issue 15).

* ``zwidth_region`` -- the exact (B, K) region of the virtual wall with the profile's velocity
  filter and delays, the passive region and eq. (9)'s limit (Colgate & Brown, ICRA 1994),
  :func:`analysis.study.zwidth_region_result`, about a second for the HBFD at 100 values of B;
* ``zwidth_optimum`` -- the area against the filter cut-off and its maximum (Chawda, Celik &
  O'Malley 2015), :func:`analysis.study.filter_optimum`, several seconds, with progress;
* ``zwidth_trials`` -- the hardware trials of the profile's trials file (synchronous, cheap).  Its
  request (:class:`~analysis.study.TrialsRequest`) holds the file's absolute path: a relative
  ``trials`` path is resolved against the document's folder, the node's ``folder`` parameter
  (:func:`set_trials_folder`, set by :class:`~app.window.documents.Documents`), as the command line
  resolves it against the profile's folder -- so opening the profile from another folder reads
  the file beside it, whatever the working directory.

The two computations are asynchronous and ``live=False`` (held back while a slider drag moves).
Their requests (:class:`~analysis.study.ZWidthRequest`, :class:`~analysis.study.OptimumRequest`) hold
only what they depend on: the device, the filter (the optimum: only its kind), the region's B
values and the delays -- so moving the wall (``kc``, ``bc``) recomputes nothing.
"""

from __future__ import annotations

from analysis.profiles.io import Profile
from analysis.sampled import FilterOptimum, MeasuredTrials, ZWidthRegion
from analysis.study import (
    OptimumRequest,
    TrialsRequest,
    ZWidthRequest,
    filter_optimum,
    profile_trials,
    zwidth_region_result,
)
from analysis.progress import Cancelled, Progress

from app.core.compute_graph import ComputeGraph, Node
from app.core.nodes_stability import DEVICE_INPUTS

__all__ = ["REGION_NODE", "OPTIMUM_NODE", "TRIALS_NODE", "ZWIDTH_NODES", "register", "set_trials_folder"]

REGION_NODE, OPTIMUM_NODE, TRIALS_NODE = "zwidth_region", "zwidth_optimum", "zwidth_trials"
ZWIDTH_NODES = (REGION_NODE, OPTIMUM_NODE)
_INPUTS = DEVICE_INPUTS | {"simulation"}  # the device, the controller section and the delays


def _region(req: ZWidthRequest, progress: Progress, cancelled: Cancelled) -> ZWidthRegion | None:
    return zwidth_region_result(req, progress=progress, cancelled=cancelled)


def _optimum(req: OptimumRequest, progress: Progress, cancelled: Cancelled) -> FilterOptimum | None:
    return filter_optimum(req, progress=progress, cancelled=cancelled)


def _trials(req: TrialsRequest, _pull: object) -> MeasuredTrials | None:
    return profile_trials(req)


def _trials_request(p: Profile, params: dict) -> TrialsRequest:
    return TrialsRequest.of(p, params["folder"])


def set_trials_folder(graph: ComputeGraph, folder: str | None) -> bool:
    """Resolve a relative trials path against ``folder`` (the document's folder; ``None``: the
    working directory) from now on; returns whether that changed (the trials node is then
    invalidated, so the views showing it refresh).  Nothing happens before the node is registered."""
    if TRIALS_NODE not in graph or not graph.set_params(TRIALS_NODE, folder=folder):
        return False
    graph.invalidated.emit({TRIALS_NODE})
    return True


def _request_of(cls: type) -> object:
    def request(p: Profile, params: dict) -> object:
        return cls.of(p)

    return request


def register(graph: ComputeGraph) -> None:
    """Add the Z-width nodes to ``graph``."""
    graph.add(Node(REGION_NODE, _INPUTS, _request_of(ZWidthRequest), _region, asynchronous=True, live=False))
    graph.add(Node(OPTIMUM_NODE, _INPUTS, _request_of(OptimumRequest), _optimum, asynchronous=True, live=False))
    graph.add(Node(TRIALS_NODE, frozenset({"controller"}), _trials_request, _trials, params={"folder": None}))
