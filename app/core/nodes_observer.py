"""The nodes of the observer tab: the disturbance observer of Eom, Suh & Yi (Fig. 1, eqs. 2-5, 13).

``observer_response`` (the single axis, eqs. 3-5) is synchronous (< 1 ms) and follows every step
of a slider drag.  The two-axis nodes run on the worker and are ``live=False``: during a drag they
keep their last value and catch up when the drag pauses or ends (:class:`~app.core.compute_graph.DragPause`),
because ``observer_coupling`` (~8 ms, eq. 2 solved at 500 frequencies) and ``observer_step`` (~20 ms,
a 2000-step simulation) would not fit in a 16 ms frame.  All three call :mod:`analysis.study`.
``observer_response`` depends on every observer setting (derived from the device when the profile has
no observer section); the two-axis nodes only on the preset,
the Q order and its cutoff (and the step).
"""

from __future__ import annotations

from typing import Any

from analysis.profiles.io import Profile
from analysis.study import (
    OBSERVER_W,
    TwoAxisRequest,
    TwoAxisStepRequest,
    observer_coupling,
    observer_response,
    observer_settings,
    observer_step,
)
from analysis.progress import Cancelled, Progress

from app.core.compute_graph import ComputeGraph, Node
from app.core.model import DEVICE_FIELDS

__all__ = ["OBSERVER_W", "NODES", "HELD_NODES", "observer_settings", "register"]

NODES = ("observer_response", "observer_coupling", "observer_step")
#: The nodes held back during a slider drag (asynchronous, ``live=False``).
HELD_NODES = ("observer_coupling", "observer_step")
#: the observer section, and the device (a profile without the section takes P_n from its device)
_INPUTS = frozenset({"observer"}) | frozenset(DEVICE_FIELDS)


def _coupling(req: TwoAxisRequest, progress: Progress, cancelled: Cancelled) -> Any:
    return observer_coupling(req)


def _step(req: TwoAxisStepRequest, progress: Progress, cancelled: Cancelled) -> Any:
    return observer_step(req)


def _settings_request(p: Profile, params: dict) -> Any:
    return observer_settings(p)


def register(graph: ComputeGraph) -> None:
    """Add the observer's nodes to ``graph``."""
    graph.add(Node("observer_response", _INPUTS, _settings_request, lambda st, _: observer_response(st)))
    graph.add(Node("observer_coupling", _INPUTS, lambda p, _: TwoAxisRequest.of(p), _coupling, asynchronous=True,
                   live=False))
    graph.add(Node("observer_step", _INPUTS, lambda p, _: TwoAxisStepRequest.of(p), _step, asynchronous=True,
                   live=False))
