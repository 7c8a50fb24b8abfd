"""The node of the Renderable space tab (issue 24).

* ``renderable_space`` -- the renderable (M, B, K) space over the (M, B) grid of the profile's
  ``renderable`` section and the M-width (Colonnese & Chan 2016; Colonnese & Okamura 2012),
  :func:`analysis.study.renderable_study`, about a second of CPU for the HBFD's 41 × 41 grid with the
  stable quality, on the worker with progress and cancel.

Its request (:class:`~analysis.study.RenderableRequest`) holds the device, the velocity filter, the
delay, the acceleration estimate, the qualities' settings and the grid -- not the rendered
environment, so a click that moves (M, B) recomputes nothing.  Asynchronous and ``live=False``
(held back while a slider drag moves).
"""

from __future__ import annotations

from analysis.profiles.io import Profile
from analysis.progress import Cancelled, Progress
from analysis.study import RenderableRequest, RenderableStudy, renderable_study

from app.core.compute_graph import ComputeGraph, Node
from app.core.nodes_stability import DEVICE_INPUTS

__all__ = ["RENDERABLE_NODE", "register"]

RENDERABLE_NODE = "renderable_space"
#: the device, the controller section (filter), the delays (simulation section) and the section itself
_INPUTS = DEVICE_INPUTS | {"simulation", "renderable"}


def _space(req: RenderableRequest, progress: Progress, cancelled: Cancelled) -> RenderableStudy | None:
    return renderable_study(req, progress=progress, cancelled=cancelled)


def _request(p: Profile, params: dict) -> RenderableRequest:
    return RenderableRequest.of(p)


def register(graph: ComputeGraph) -> None:
    """Add the renderable-space node to ``graph`` (once)."""
    if RENDERABLE_NODE not in graph:
        graph.add(Node(RENDERABLE_NODE, _INPUTS, _request, _space, asynchronous=True, live=False))
