"""The nodes of the Z-width tab: the controller as built (issue 15).

* ``zwidth_region`` -- the exact (B, K) region of the virtual wall with the profile's velocity
  filter and delays, the passive region and eq. (9)'s limit (Colgate & Brown, ICRA 1994),
  :func:`analysis.study.zwidth_region`, about a second for the HBFD at 100 values of B;
* ``zwidth_optimum`` -- the area against the filter cut-off and its maximum (Chawda, Celik &
  O'Malley 2015), :func:`analysis.study.filter_optimum`, several seconds, with progress;
* ``zwidth_trials`` -- the hardware trials of the profile's trials file (synchronous, cheap).

The two computations are asynchronous and ``live=False`` (held back while a slider drag moves).
Their keys hold only what they depend on: the device, the filter (the optimum: only its kind),
the region's B values and the delays -- so moving the wall (``kc``, ``bc``) recomputes nothing.
"""

from __future__ import annotations

import os
from collections.abc import Hashable

from analysis.profiles.io import Profile
from analysis.sampled import FilterOptimum, MeasuredTrials, ZWidthRegion
from analysis.study import (
    controller_section,
    delays,
    filter_optimum,
    optimum_kind,
    profile_filter,
    profile_trials,
    zwidth_region,
)

from app.core.compute_graph import Cancelled, ComputeGraph, Node, Progress
from app.core.nodes_stability import DEVICE_INPUTS

__all__ = ["REGION_NODE", "OPTIMUM_NODE", "TRIALS_NODE", "ZWIDTH_NODES", "register"]

REGION_NODE, OPTIMUM_NODE, TRIALS_NODE = "zwidth_region", "zwidth_optimum", "zwidth_trials"
ZWIDTH_NODES = (REGION_NODE, OPTIMUM_NODE)
_INPUTS = DEVICE_INPUTS | {"simulation"}  # the device, the controller section and the delays


def _b_key(p: Profile) -> Hashable:
    """The region's B grid and its encoder-noise criterion (both change the region and the optimum)."""
    sec = controller_section(p)
    return sec.b_range, sec.b_points, sec.encoder_resolution, sec.force_noise


def _region_key(p: Profile, params: dict) -> Hashable:
    return p.device.key(), profile_filter(p), _b_key(p), delays(p)


def _region(p: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> ZWidthRegion | None:
    return zwidth_region(p, progress=progress, cancelled=cancelled)


def _optimum_key(p: Profile, params: dict) -> Hashable:
    return p.device.key(), optimum_kind(p), _b_key(p), delays(p)


def _optimum(p: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> FilterOptimum | None:
    return filter_optimum(p, progress=progress, cancelled=cancelled)


def _trials_key(p: Profile, params: dict) -> Hashable:
    path = controller_section(p).trials
    if path is None:
        return None
    try:
        return path, os.stat(path).st_mtime_ns  # a rewritten file is read again
    except OSError:
        return path, None


def _trials(p: Profile, _pull: object) -> MeasuredTrials | None:
    return profile_trials(p)


def register(graph: ComputeGraph) -> None:
    """Add the Z-width nodes to ``graph``."""
    graph.add(Node(REGION_NODE, _INPUTS, _region_key, _region, asynchronous=True, live=False))
    graph.add(Node(OPTIMUM_NODE, _INPUTS, _optimum_key, _optimum, asynchronous=True, live=False))
    graph.add(Node(TRIALS_NODE, frozenset({"controller"}), _trials_key, _trials))
