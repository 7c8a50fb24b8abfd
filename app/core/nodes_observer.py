"""The nodes of the observer tab: the disturbance observer of Eom, Suh & Yi (Fig. 1, eqs. 2-5, 13).

All three are synchronous (< 50 ms together) and call :mod:`analysis.study`.
``observer_response`` depends on every observer setting (derived from the device when the profile has
no observer section); the two-axis nodes only on the preset,
the Q order and its cutoff (and the step).
"""

from __future__ import annotations

from collections.abc import Hashable

from analysis.profiles.io import Profile
from analysis.study import OBSERVER_W, observer_coupling, observer_response, observer_settings, observer_step

from app.core.compute_graph import ComputeGraph, Node
from app.core.model import DEVICE_FIELDS

__all__ = ["OBSERVER_W", "NODES", "observer_settings", "register"]

NODES = ("observer_response", "observer_coupling", "observer_step")
#: the observer section, and the device (a profile without the section takes P_n from its device)
_INPUTS = frozenset({"observer"}) | frozenset(DEVICE_FIELDS)


def _two_axis_key(p: Profile, params: dict) -> Hashable:
    st = observer_settings(p)
    return st.preset, st.order, st.cutoff


def _step_key(p: Profile, params: dict) -> Hashable:
    st = observer_settings(p)
    return _two_axis_key(p, params), st.step_force, st.step_duration


def register(graph: ComputeGraph) -> None:
    """Add the observer's nodes to ``graph``."""
    graph.add(Node("observer_response", _INPUTS, lambda p, _: observer_settings(p), lambda p, _: observer_response(p)))
    graph.add(Node("observer_coupling", _INPUTS, _two_axis_key, lambda p, _: observer_coupling(p)))
    graph.add(Node("observer_step", _INPUTS, _step_key, lambda p, _: observer_step(p)))
