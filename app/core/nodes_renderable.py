"""The node of the Renderable space tab (issue 24).

* ``renderable_space`` -- the renderable (M, B, K) space over the (M, B) grid of the profile's
  ``renderable`` section and the M-width (Colonnese & Chan 2016; Colonnese & Okamura 2012),
  :func:`analysis.study.renderable_study`, about a second of CPU for the HBFD's 41 × 41 grid with the
  stable quality, on the worker with progress and cancel.

* ``renderable_robust`` -- the robust space over the profile's identified parameter box (its
  corners or N seeded samples): :func:`analysis.study.renderable.robust_study`, every device in the
  worker's thread (``workers=1``: no process pool started from the GUI).  Its parameters (the tab's
  choice, not the profile's): ``robust`` (``"off"``, ``"corners"``, ``"samples"``) and ``samples``;
  ``None`` while off or when the profile has no box.

Their requests (:class:`~analysis.study.RenderableRequest`) hold the device, the velocity filter, the
delay, the acceleration estimate, the qualities' settings and the grid (and the robust node's, the
box) -- not the rendered environment, so a click that moves (M, B) recomputes nothing.
Asynchronous and ``live=False`` (held back while a slider drag moves).
"""

from __future__ import annotations

from analysis.profiles.io import Profile
from analysis.progress import Cancelled, Progress
from analysis.sampled import RobustRenderableSpace
from analysis.study import RenderableRequest, RenderableStudy, renderable_study
from analysis.study.renderable import ROBUST_SAMPLES, robust_study

from app.core.compute_graph import ComputeGraph, Node
from app.core.nodes_stability import DEVICE_INPUTS

__all__ = ["RENDERABLE_NODE", "ROBUST_NODE", "ROBUST_PARAMS", "register"]

RENDERABLE_NODE = "renderable_space"
ROBUST_NODE = "renderable_robust"
#: the robust node's parameters: off, and the number of samples when the box is sampled
ROBUST_PARAMS = {"robust": "off", "samples": ROBUST_SAMPLES}
#: the device, the controller section (filter), the delays (simulation section) and the section itself
_INPUTS = DEVICE_INPUTS | {"simulation", "renderable"}


def _space(req: RenderableRequest, progress: Progress, cancelled: Cancelled) -> RenderableStudy | None:
    return renderable_study(req, progress=progress, cancelled=cancelled)


def _request(p: Profile, params: dict) -> RenderableRequest:
    return RenderableRequest.of(p)


def _robust(req: RenderableRequest, progress: Progress, cancelled: Cancelled) -> RobustRenderableSpace | None:
    return None if req.robust is None else robust_study(req, progress=progress, cancelled=cancelled)


def _robust_request(p: Profile, params: dict) -> RenderableRequest:
    return RenderableRequest.of(p, robust=params["robust"], samples=params["samples"])


def register(graph: ComputeGraph) -> None:
    """Add the renderable-space and robust-space nodes to ``graph`` (once)."""
    if RENDERABLE_NODE not in graph:
        graph.add(Node(RENDERABLE_NODE, _INPUTS, _request, _space, asynchronous=True, live=False))
    if ROBUST_NODE not in graph:
        graph.add(Node(ROBUST_NODE, _INPUTS | {"identification"}, _robust_request, _robust, asynchronous=True,
                       live=False, params=dict(ROBUST_PARAMS)))
