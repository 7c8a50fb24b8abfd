"""The nodes of the sampled-data tab: the exact loop behind the two-port bounds.

* ``sampled_map`` -- the spectral radius of the real sampled loop over two parameters;
* ``sampled_exact_chart`` -- the exact stability limit over b_c;
* ``sampled_limit`` -- the exact limit at the current b_c;
* ``sampled_simulation`` -- one run of the nonlinear simulator on the profile's scenario.

All four are asynchronous: they call the study layer (:mod:`analysis.study`) on the worker with
its progress and cancel hooks, and each call builds its own objects.  They are expensive (0.1 to
several seconds), so they are registered ``live=False``: a moving slider drag does not start them,
they catch up when it pauses or ends (:mod:`app.core.compute_graph`).  What follows the drag live
is ``sampled_point``, the exact spectral radius at the current design on the map's axes
(:func:`analysis.study.design_radius`, one point of the map, about a millisecond).  The delays, the scenario and
the simulator options are the profile's ``simulation`` section; the map's axes and ranges are node
parameters (the display object's map definition by default).  Each node is keyed on its study
request (:mod:`analysis.study.requests`), built from the profile and those parameters.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from analysis.profiles.io import Profile
from analysis.profiles.sections import SimulationSection
from analysis.sampled import CriticalChart, CriticalMassChart, SimulationResult, StabilityMap
from analysis.study import (
    DISPLAY_KINDS,
    EXACT_CHART,
    MAP_POINTS,
    ExactChartRequest,
    ExactLimitRequest,
    MapRequest,
    PointRequest,
    SimulationRequest,
    delays,
    design_radius,
    display_kind,
    exact_chart,
    exact_limit,
    map_arguments,
    simulation,
    simulation_section,
    stability_map_result,
)

from analysis.study.labels import PARAMETER_LABELS
from analysis.progress import Cancelled, Progress
from app.core.compute_graph import ComputeGraph, Node
from app.core.nodes_stability import DEVICE_INPUTS, GAIN_FIELDS

__all__ = ["MAP_NODE", "EXACT_NODE", "LIMIT_NODE", "SIM_NODE", "POINT_NODE", "ASYNC_NODES", "MAP_AXES", "DEFAULT_RANGES",
           "MAP_POINTS", "PARAMETER_LABELS", "EXACT_BC_RANGE", "EXACT_POINTS", "current_section", "delays",
           "map_arguments", "default_map_settings", "exact_grid", "register"]

MAP_NODE, EXACT_NODE, LIMIT_NODE, SIM_NODE = "sampled_map", "sampled_exact_chart", "sampled_limit", "sampled_simulation"
ASYNC_NODES = (MAP_NODE, EXACT_NODE, LIMIT_NODE, SIM_NODE)
POINT_NODE = "sampled_point"

#: The map axes offered for each display type (x, y) -- the display objects' map definitions.
MAP_AXES: dict[str, list[tuple[str, str]]] = {name: list(k.map_axes) for name, k in DISPLAY_KINDS.items()}
DEFAULT_RANGES: dict[tuple[str, str], tuple[float, float]] = {
    (name, p): r for name, k in DISPLAY_KINDS.items() for p, r in k.map_ranges.items()}
EXACT_BC_RANGE, EXACT_POINTS = EXACT_CHART["bc_range"], EXACT_CHART["points"]


def current_section(profile: Profile) -> SimulationSection:
    """The profile's simulation section, or the paper's worst case for its display (ideal sensors)."""
    return simulation_section(profile)


def default_map_settings(display: str) -> dict[str, Any]:
    """The map parameters a display starts with: its first axes, their default ranges."""
    kind = display_kind(display)
    x, y = kind.map_axes[0]
    return {"x": x, "x_range": kind.map_ranges[x], "y": y, "y_range": kind.map_ranges[y], "points": MAP_POINTS}


def _map(req: MapRequest, progress: Progress, cancelled: Cancelled) -> StabilityMap | None:
    return stability_map_result(req, progress=progress, cancelled=cancelled)


def exact_grid(params: dict) -> np.ndarray:
    """The b_c grid of the exact limit chart (node parameters ``bc_range`` and ``points``)."""
    return np.geomspace(*params["bc_range"], int(params["points"]))


def _exact_chart(req: ExactChartRequest, progress: Progress, cancelled: Cancelled
                 ) -> CriticalChart | CriticalMassChart | None:
    return exact_chart(req, progress=progress, cancelled=cancelled)


def _limit(req: ExactLimitRequest, progress: Progress, cancelled: Cancelled) -> float:
    """The exact limit at the current b_c: largest stable k_c or smallest stable m_c."""
    progress(0, 1)
    v = exact_limit(req)
    progress(1, 1)
    return v


def _simulation(req: SimulationRequest, progress: Progress, cancelled: Cancelled) -> SimulationResult | None:
    return simulation(req, progress=progress, cancelled=cancelled)


def register(graph: ComputeGraph) -> None:
    """Add the four sampled-data nodes (held back during a drag) and the live design point to ``graph``."""
    sim_inputs = DEVICE_INPUTS | GAIN_FIELDS | {"simulation"}
    graph.add(Node(MAP_NODE, sim_inputs, MapRequest.of, _map, asynchronous=True, live=False,
                   params=default_map_settings("impedance")))
    graph.add(Node(EXACT_NODE, DEVICE_INPUTS | {"display", "kp", "kd", "simulation"},
                   lambda p, prm: ExactChartRequest.of(p, prm["bc_range"], prm["points"]), _exact_chart,
                   asynchronous=True, live=False, params={"bc_range": EXACT_BC_RANGE, "points": EXACT_POINTS}))
    graph.add(Node(LIMIT_NODE, DEVICE_INPUTS | GAIN_FIELDS | {"simulation"}, lambda p, _: ExactLimitRequest.of(p),
                   _limit, asynchronous=True, live=False))
    graph.add(Node(SIM_NODE, sim_inputs, lambda p, _: SimulationRequest.of(p), _simulation, asynchronous=True,
                   live=False))
    axes = {k: v for k, v in default_map_settings("impedance").items() if k in ("x", "y")}
    graph.add(Node(POINT_NODE, sim_inputs, lambda p, prm: PointRequest.of(p, prm["x"], prm["y"]),
                   lambda req, _pull: design_radius(req), params=axes))
