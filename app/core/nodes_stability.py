"""The nodes of the stability analysis (Adams, Moreyra & Hannaford, eqs. 9 and 21) and the graph.

Every node calls the study layer (:mod:`analysis.study`) or the display object it builds; the
display type is a :class:`~analysis.study.DisplayKind`, never a string compare.  Each node is
keyed on its study request (:mod:`analysis.study.requests`).  The device nodes
(``impedance_display``, ``admittance_display``) build the analysis core's display objects, which
cache the device two-port response per frequency vector; their request
(:class:`~analysis.study.DeviceRequest`) holds no coupling gain, so a gain change reuses them.
"""

from __future__ import annotations

from analysis import StabilityResult, StiffnessDesign
from analysis.profiles.io import Profile
from analysis.study import (
    DESIGN_CHART,
    ChartRequest,
    ChartResult,
    DeviceRequest,
    DisplayKind,
    StabilityRequest,
    design_chart,
    display_kind,
    min_mass,
    stability,
)
from analysis.twoport import DisplayBase, MassDesign
from analysis.progress import Cancelled, Progress

from app.core.compute_graph import ComputeGraph, Node, Pull
from app.core.model import DEVICE_FIELDS, ProfileModel
from app.core.worker import TaskRunner

__all__ = ["GAIN_FIELDS", "DEVICE_INPUTS", "CHART_PARAMS", "device_node", "build_graph"]

GAIN_FIELDS = frozenset({"display", "kc", "bc", "mc", "bc_adm", "kp", "kd"})
#: The device and the controller section (its velocity filter enters every loop with a damping
#: term; the requests of the nodes that depend on it hold the filter).
DEVICE_INPUTS = frozenset(DEVICE_FIELDS) | {"controller"}
#: The design chart's grid (node parameters): b_c range (impedance), m_c range (admittance).
CHART_PARAMS = {"bc_range": DESIGN_CHART["bc_range"], "mc_range": DESIGN_CHART["mc_range"]}


def device_node(kind: DisplayKind) -> str:
    """The name of the node holding ``kind``'s display object (``impedance_display``, ...)."""
    return f"{kind.name}_display"


def _display_node(kind: DisplayKind) -> Node:
    def build(req: DeviceRequest, pull: Pull) -> DisplayBase:
        disp = req.build()
        disp.bound_result(disp.frequencies())  # the device two-port response on the grid
        return disp

    inputs = DEVICE_INPUTS if kind.is_impedance else DEVICE_INPUTS | {"kp", "kd"}
    return Node(device_node(kind), inputs, lambda p, _: DeviceRequest.of(p, kind), build)


def _stability_request(p: Profile, params: dict) -> StabilityRequest:
    return StabilityRequest.of(p)


def _stability(req: StabilityRequest, pull: Pull) -> StabilityResult:
    return stability(req, display=pull(device_node(req.model.kind)))


def _stability_preview(req: StabilityRequest, pull: Pull) -> StabilityResult:
    return stability(req, refine=False, display=pull(device_node(req.model.kind)))


def _stiffness_request(p: Profile, params: dict) -> tuple[DeviceRequest, float]:
    return DeviceRequest.of(p, "impedance"), float(p.bc)


def _max_stiffness(req: tuple[DeviceRequest, float], pull: Pull) -> StiffnessDesign:
    return pull("impedance_display").max_stiffness(req[1])


def _chart_request(p: Profile, params: dict) -> ChartRequest:
    return ChartRequest.of(p, bc_range=params["bc_range"], mc_range=params["mc_range"], points=params["points"])


def _design_chart(req: ChartRequest, progress: Progress, cancelled: Cancelled) -> ChartResult | None:
    """:func:`analysis.study.design_chart` on the worker (its own display object, never the GUI's)."""
    return design_chart(req, progress=progress, cancelled=cancelled)


def _min_mass(req: DeviceRequest, progress: Progress, cancelled: Cancelled) -> MassDesign:
    design = min_mass(req)
    if design is None:
        raise ValueError("no coupling mass satisfies eq. (21) for this device")
    return design


def build_graph(model: ProfileModel, runner: TaskRunner, chart_points: int = DESIGN_CHART["points"]) -> ComputeGraph:
    """The graph of the stability analysis (tabs add their own nodes through ``app.core.nodes_*``)."""
    g = ComputeGraph(model, runner)
    dev = DEVICE_INPUTS
    for kind in (display_kind("impedance"), display_kind("admittance")):
        g.add(_display_node(kind))
    g.add(Node("stability", dev | GAIN_FIELDS, _stability_request, _stability))
    g.add(Node("stability_preview", dev | GAIN_FIELDS, _stability_request, _stability_preview))
    # the refined design at the current b_c (tens of ms): held back while a slider drag moves
    g.add(Node("max_stiffness", dev | {"bc"}, _stiffness_request, _max_stiffness, live=False))
    g.add(Node("design_chart", dev | {"display", "kp", "kd"}, _chart_request, _design_chart, asynchronous=True,
               params={**CHART_PARAMS, "points": chart_points}))
    g.add(Node("min_mass", dev | {"kp", "kd"}, lambda p, _: DeviceRequest.of(p, "admittance"), _min_mass,
               asynchronous=True))
    return g
