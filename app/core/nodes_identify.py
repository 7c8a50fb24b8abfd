"""The nodes of the Identify tab (issue 14); both run on the worker with progress and cancel.

* ``identify_fit`` -- :func:`analysis.study.identify_chain` of the measurements the tab loaded
  (the tab sets them as node parameters with :func:`fit_params`, with a run number, so the fit
  runs when the user asks for it and never because the profile changed: it reads no model field);
* ``robust_designs`` -- ``(designs,)``, :func:`analysis.study.robust_designs` of the profile: the robust largest
  k_c (impedance) or b_c interval (admittance) over the profile's identification box, and
  whether the current coupling holds for the whole box.  Held back during a slider drag.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from analysis.identify import Measurement
from analysis.study import IdentifyResult, RobustDesigns, RobustRequest, identify_chain, robust_designs
from analysis.progress import Cancelled, Progress

from app.core.compute_graph import ComputeGraph, Node
from app.core.model import DEVICE_FIELDS

__all__ = ["FIT_NODE", "ROBUST_NODE", "NODES", "fit_params", "register"]

FIT_NODE = "identify_fit"
ROBUST_NODE = "robust_designs"
NODES = (FIT_NODE, ROBUST_NODE)
_ROBUST_INPUTS = frozenset(DEVICE_FIELDS) | {"display", "kc", "bc", "mc", "bc_adm", "kp", "kd", "identification"}


def fit_params(run: int, measurements: Sequence[Measurement], n_masses: int, fixed: Mapping[str, float],
               ground: Sequence[int] | None, max_masses: int | None, sample_time: float | None,
               band_min: float) -> dict:
    """The node parameters of one fit request (``run`` makes each request a new computation)."""
    return {"run": run, "measurements": tuple(measurements), "n_masses": int(n_masses), "fixed": dict(fixed),
            "ground": None if ground is None else tuple(ground), "max_masses": max_masses,
            "sample_time": sample_time, "band_min": band_min}


class FitRequest:
    """One fit request: the node parameters, compared by their run number only (each request the
    user makes is a new computation; the measurements are not hashed)."""

    def __init__(self, params: dict) -> None:
        self.params = dict(params)
        self.run = params.get("run", 0)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, FitRequest) and other.run == self.run

    def __hash__(self) -> int:
        return hash(self.run)


def _fit(req: FitRequest, progress: Progress, cancelled: Cancelled) -> IdentifyResult | None:
    params = req.params
    if not params.get("measurements"):
        return None
    return identify_chain(params["measurements"], params["n_masses"], params["fixed"], params["ground"],
                          max_masses=params["max_masses"], sample_time=params["sample_time"],
                          band_min=params["band_min"], progress=progress, cancelled=cancelled)


def _robust(req: RobustRequest, progress: Progress,
            cancelled: Cancelled) -> tuple[RobustDesigns | None] | None:
    """``(designs,)`` -- ``(None,)`` for a profile without intervals -- or ``None`` when cancelled
    (the graph reads a bare ``None`` as "stopped early")."""
    designs = robust_designs(req, progress=progress, cancelled=cancelled)
    return None if cancelled() else (designs,)


def register(graph: ComputeGraph) -> None:
    """Add the Identify tab's nodes to ``graph`` (once)."""
    if FIT_NODE not in graph:
        graph.add(Node(FIT_NODE, frozenset(), lambda p, params: FitRequest(params), _fit, asynchronous=True,
                       params=fit_params(0, (), 4, {}, None, None, None, 1.0)))
    if ROBUST_NODE not in graph:
        graph.add(Node(ROBUST_NODE, _ROBUST_INPUTS, lambda p, _: RobustRequest.of(p), _robust, asynchronous=True,
                       live=False))
