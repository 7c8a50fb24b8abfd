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

from collections.abc import Hashable
from typing import Any

from analysis.profiles.io import Profile
from analysis.study import OBSERVER_W, observer_coupling, observer_response, observer_settings, observer_step

from app.core.compute_graph import Cancelled, ComputeGraph, Node, Progress
from app.core.model import DEVICE_FIELDS

__all__ = ["OBSERVER_W", "NODES", "HELD_NODES", "observer_settings", "register"]

NODES = ("observer_response", "observer_coupling", "observer_step")
#: The nodes held back during a slider drag (asynchronous, ``live=False``).
HELD_NODES = ("observer_coupling", "observer_step")
#: the observer section, and the device (a profile without the section takes P_n from its device)
_INPUTS = frozenset({"observer"}) | frozenset(DEVICE_FIELDS)


def _two_axis_key(p: Profile, params: dict) -> Hashable:
    st = observer_settings(p)
    return st.preset, st.order, st.cutoff


def _step_key(p: Profile, params: dict) -> Hashable:
    st = observer_settings(p)
    return _two_axis_key(p, params), st.step_force, st.step_duration


def _coupling(p: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> Any:
    return observer_coupling(p)


def _step(p: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> Any:
    return observer_step(p)


def register(graph: ComputeGraph) -> None:
    """Add the observer's nodes to ``graph``."""
    graph.add(Node("observer_response", _INPUTS, lambda p, _: observer_settings(p), lambda p, _: observer_response(p)))
    graph.add(Node("observer_coupling", _INPUTS, _two_axis_key, _coupling, asynchronous=True, live=False))
    graph.add(Node("observer_step", _INPUTS, _step_key, _step, asynchronous=True, live=False))
