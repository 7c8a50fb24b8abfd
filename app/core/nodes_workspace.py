"""The nodes of the Workspace tab (issue 25).

* ``workspace_map`` -- the workspace map of the profile's multi-DOF linkage over its grid
  (:func:`analysis.study.workspace_study`: :func:`analysis.multidof.workspace_map` in bands of grid
  rows), seconds of CPU, on the worker with progress and cancel; asynchronous and ``live=False``.
  Its request (:class:`~analysis.study.WorkspaceRequest`) holds the linkage, the grid, the wall's
  damping and the loop -- not the handle, so a click that moves the handle recomputes no map.
* ``workspace_point`` -- the limits at the handle (:func:`analysis.study.workspace_point`: the
  inertia ellipse, the per-direction limits, the worst normal, the linkage's joints), a fifth of a
  second, synchronous; a handle the study refuses (a singular configuration) gives the refusal's text.
"""

from __future__ import annotations

from analysis.errors import ValidationError
from analysis.multidof import WorkspaceMap
from analysis.progress import Cancelled, Progress
from analysis.study import HandleRequest, WorkspacePoint, WorkspaceRequest, workspace_point, workspace_study

from app.core.compute_graph import ComputeGraph, Node, Pull
from app.core.nodes_stability import DEVICE_INPUTS

__all__ = ["WORKSPACE_MAP_NODE", "WORKSPACE_POINT_NODE", "register"]

WORKSPACE_MAP_NODE = "workspace_map"
WORKSPACE_POINT_NODE = "workspace_point"
#: the device (sample period), the controller section (filter), the delays (simulation section), the section
_INPUTS = DEVICE_INPUTS | {"simulation", "multidof"}


def _map(req: WorkspaceRequest, progress: Progress, cancelled: Cancelled) -> WorkspaceMap | None:
    return workspace_study(req, progress=progress, cancelled=cancelled)


def _point(req: HandleRequest, pull: Pull) -> WorkspacePoint | str:
    try:
        return workspace_point(req)
    except ValidationError as err:
        return str(err)


def register(graph: ComputeGraph) -> None:
    """Add the workspace nodes to ``graph`` (once)."""
    if WORKSPACE_MAP_NODE not in graph:
        graph.add(Node(WORKSPACE_MAP_NODE, _INPUTS, lambda p, _params: WorkspaceRequest.of(p), _map,
                       asynchronous=True, live=False))
    if WORKSPACE_POINT_NODE not in graph:
        graph.add(Node(WORKSPACE_POINT_NODE, _INPUTS, lambda p, _params: HandleRequest.of(p), _point))
