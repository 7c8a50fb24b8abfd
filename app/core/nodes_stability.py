"""The nodes of the stability analysis (Adams, Moreyra & Hannaford, eqs. 9 and 21) and the graph.

Every node calls the study layer (:mod:`analysis.study`) or the display object it builds; the
display type is a :class:`~analysis.study.DisplayKind`, never a string compare.  The device nodes
(``impedance_display``, ``admittance_display``) build the analysis core's display objects, which
cache the device two-port response per frequency vector; their keys exclude the coupling gains,
so a gain change reuses them.
"""

from __future__ import annotations

from collections.abc import Hashable

from analysis import StabilityResult, StiffnessDesign
from analysis.profiles.io import Profile
from analysis.study import DESIGN_CHART, ChartResult, DisplayKind, design_chart, display_kind, min_mass, profile_filter
from analysis.twoport import DisplayBase, MassDesign

from app.core.compute_graph import Cancelled, ComputeGraph, Node, Progress, Pull
from app.core.model import DEVICE_FIELDS, ProfileModel
from app.core.worker import TaskRunner

__all__ = ["GAIN_FIELDS", "DEVICE_INPUTS", "CHART_PARAMS", "device_node", "build_graph"]

GAIN_FIELDS = frozenset({"display", "kc", "bc", "mc", "bc_adm", "kp", "kd"})
#: The device and the controller section (its velocity filter enters every loop with a damping
#: term; nodes that depend on it have ``profile_filter(p)`` in their keys, the others keep theirs).
DEVICE_INPUTS = frozenset(DEVICE_FIELDS) | {"controller"}
#: The design chart's grid (node parameters): b_c range (impedance), m_c range (admittance).
CHART_PARAMS = {"bc_range": DESIGN_CHART["bc_range"], "mc_range": DESIGN_CHART["mc_range"]}


def device_node(kind: DisplayKind) -> str:
    """The name of the node holding ``kind``'s display object (``impedance_display``, ...)."""
    return f"{kind.name}_display"


def _device_key(kind: DisplayKind, p: Profile) -> Hashable:
    """What a display object depends on: the device (and the PD loop of the admittance display, eq. 30)."""
    vf = profile_filter(p)
    return (kind.name, p.device.key(), vf) if kind.is_impedance else (kind.name, p.device.key(), vf, p.kp, p.kd)


def _display_node(kind: DisplayKind) -> Node:
    def build(profile: Profile, pull: Pull) -> DisplayBase:
        disp = kind.build(profile)
        disp.bound_result(disp.frequencies())  # the device two-port response on the grid
        return disp

    inputs = DEVICE_INPUTS if kind.is_impedance else DEVICE_INPUTS | {"kp", "kd"}
    return Node(device_node(kind), inputs, lambda p, _: _device_key(kind, p), build)


def _stability_key(p: Profile, params: dict) -> Hashable:
    kind = display_kind(p)
    return _device_key(kind, p), kind.coupling(p)


def _stability(profile: Profile, pull: Pull) -> StabilityResult:
    kind = display_kind(profile)
    return kind.evaluate(profile, pull(device_node(kind)))


def _stability_preview(profile: Profile, pull: Pull) -> StabilityResult:
    kind = display_kind(profile)
    return kind.evaluate(profile, pull(device_node(kind)), refine=False)


def _max_stiffness(profile: Profile, pull: Pull) -> StiffnessDesign:
    return pull("impedance_display").max_stiffness(profile.bc)


def _chart_key(p: Profile, params: dict) -> Hashable:
    return _device_key(display_kind(p), p), (params["bc_range"], params["mc_range"], params["points"])


def _design_chart(profile: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> ChartResult | None:
    """:func:`analysis.study.design_chart` on the worker (its own display object, never the GUI's)."""
    return design_chart(profile, bc_range=params["bc_range"], mc_range=params["mc_range"],
                        points=int(params["points"]), progress=progress, cancelled=cancelled)


def _min_mass(profile: Profile, params: dict, progress: Progress, cancelled: Cancelled) -> MassDesign:
    design = min_mass(profile)
    if design is None:
        raise ValueError("no coupling mass satisfies eq. (21) for this device")
    return design


def build_graph(model: ProfileModel, runner: TaskRunner, chart_points: int = DESIGN_CHART["points"]) -> ComputeGraph:
    """The graph of the stability analysis (tabs add their own nodes through ``app.core.nodes_*``)."""
    g = ComputeGraph(model, runner)
    dev = DEVICE_INPUTS
    for kind in (display_kind("impedance"), display_kind("admittance")):
        g.add(_display_node(kind))
    g.add(Node("stability", dev | GAIN_FIELDS, _stability_key, _stability))
    g.add(Node("stability_preview", dev | GAIN_FIELDS, _stability_key, _stability_preview))
    # the refined design at the current b_c (tens of ms): held back while a slider drag moves
    g.add(Node("max_stiffness", dev | {"bc"}, lambda p, _: (p.device.key(), profile_filter(p), p.bc), _max_stiffness,
               live=False))
    g.add(Node("design_chart", dev | {"display", "kp", "kd"}, _chart_key, _design_chart, asynchronous=True,
               params={**CHART_PARAMS, "points": chart_points}))
    g.add(Node("min_mass", dev | {"kp", "kd"}, lambda p, _: (p.device.key(), profile_filter(p), p.kp, p.kd), _min_mass,
               asynchronous=True))
    return g
