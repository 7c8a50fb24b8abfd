"""What zwidth computes for a profile: the stability result, the designs, the design chart,
the exact sampled-data limits, the stability map and the scenario simulation.

The GUI's compute graph, ``zwidth`` and the report all call these functions; none of them
has a copy.  Long computations take ``progress(done, total)`` and ``cancelled() -> bool``
and return ``None`` once cancelled (the one protocol of :mod:`analysis.progress`).  Each call builds its own analysis objects, so a call on a
worker thread never shares a cache with the GUI thread.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from analysis.chain.limits import MAX_CHART_POINTS, MAX_MAP_POINTS, check_count
from analysis.profiles.model import Profile
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled import (
    HANDS_OFF,
    RIGID_GRASP,
    CriticalChart,
    CriticalMassChart,
    SimulationResult,
    StabilityMap,
    critical_mass,
    critical_mass_chart,
    critical_stiffness,
    critical_stiffness_chart,
    simulate,
)
from analysis.sampled import stability_map as sampled_stability_map
from analysis.sampled.terminations import PAPER_WALL_STIFFNESS
from analysis.study.displays import DeviceRequest, DisplayKind, display_kind
from analysis.study.requests import (
    ChartRequest,
    ExactChartRequest,
    ExactLimitRequest,
    LoopRequest,
    MapRequest,
    PointRequest,
    SimulationRequest,
    StabilityRequest,
    delays,
    scenario_matches,
    simulation_section,
)
from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.display_base import DisplayBase
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.twoport.results import (
    DampingInterval,
    MassChart,
    MassDesign,
    StabilityResult,
    StiffnessChart,
    StiffnessDesign,
)

__all__ = ["ChartResult", "DESIGN_CHART", "EXACT_CHART", "MAP_POINTS", "stability", "max_stiffness",
           "feasible_damping", "min_mass", "design_chart", "exact_chart", "exact_limit", "simulation_section",
           "scenario_matches",
           "delays", "map_params", "map_arguments", "stability_map_result", "stability_map", "map_point", "design_radius",
           "simulation"]

#: the design chart's grid: b_c (impedance) or m_c (admittance) ranges and points per chart
DESIGN_CHART = {"bc_range": (1.0, 1e4), "mc_range": (1e-3, 1e3), "points": 40}
#: the exact sampled-data limit chart's b_c grid
EXACT_CHART = {"bc_range": (1.0, 1e4), "points": 24}
#: grid points per axis of the sampled-data stability map
MAP_POINTS = 48


@dataclass(frozen=True)
class ChartResult:
    """A design chart with the display type it belongs to.

    Attributes
    ----------
    display : str
        The display type: ``"impedance"`` or ``"admittance"``.
    chart : StiffnessChart or MassChart
        The largest k_c over b_c (impedance, eq. 9) or the feasible b_c interval over m_c
        (admittance, eq. 21).
    """

    display: str
    chart: StiffnessChart | MassChart


def stability(request: StabilityRequest | Profile, refine: bool = True, display: DisplayBase | None = None
              ) -> StabilityResult:
    """Eq. (9) or (21) at the coupling.

    Parameters
    ----------
    request : StabilityRequest or Profile
        The request, or a profile to build it from.
    refine : bool, optional
        Refine the worst margin between grid points (default ``True``).
    display : DisplayBase or None, optional
        The request's built display object, to reuse its cache; ``None`` builds a fresh one.

    Returns
    -------
    StabilityResult
        The bound, the coupling term and their margins over the frequency grid.
    """
    req = StabilityRequest.of(request) if isinstance(request, Profile) else request
    disp = req.model.build() if display is None else display
    return disp.evaluate(*req.coupling, refine=refine)


def max_stiffness(request: DeviceRequest | Profile, bc: float | None = None) -> StiffnessDesign:
    """The largest k_c satisfying eq. (9) at ``bc``.

    Parameters
    ----------
    request : DeviceRequest or Profile
        The impedance device model, or a profile (its impedance device model).
    bc : float or None, optional
        The coupling damping b_c [N·s/m]; ``None`` takes the profile's (required with a
        :class:`DeviceRequest`).

    Returns
    -------
    StiffnessDesign
        The largest k_c [N/m] (``None`` when none is stable), its binding frequency and margin.
    """
    if isinstance(request, Profile):
        request, bc = DeviceRequest.of(request, "impedance"), request.bc if bc is None else bc
    disp = request.build()
    assert isinstance(disp, ImpedanceDisplay)
    return disp.max_stiffness(float(bc))  # type: ignore[arg-type]


def feasible_damping(profile: Profile) -> DampingInterval:
    """The b_c interval satisfying eq. (21) at the profile's m_c.

    Parameters
    ----------
    profile : Profile
        The device profile (its admittance device model and m_c).

    Returns
    -------
    DampingInterval
        The feasible b_c interval [N·s/m] and the frequencies where its edges bind.
    """
    disp = DeviceRequest.of(profile, "admittance").build()
    assert isinstance(disp, AdmittanceDisplay)
    return disp.feasible_damping(profile.mc)


def min_mass(request: DeviceRequest | Profile) -> MassDesign | None:
    """The smallest m_c for which some b_c satisfies eq. (21) (the admittance device model).

    Parameters
    ----------
    request : DeviceRequest or Profile
        The admittance device model, or a profile (its admittance device model).

    Returns
    -------
    MassDesign or None
        The smallest m_c [kg] with its b_c and binding frequency; ``None`` when none is found.
    """
    req = DeviceRequest.of(request, "admittance") if isinstance(request, Profile) else request
    disp = req.build()
    assert isinstance(disp, AdmittanceDisplay)
    try:
        return disp.min_mass()
    except ValueError:
        return None


def design_chart(request: ChartRequest | Profile, kind: DisplayKind | str | None = None, *,
                 bc_range: tuple[float, float] = DESIGN_CHART["bc_range"],
                 mc_range: tuple[float, float] = DESIGN_CHART["mc_range"], points: int = DESIGN_CHART["points"],
                 progress: Progress | None = None, cancelled: Cancelled | None = None) -> ChartResult | None:
    """The design chart of the display, on a geometric grid.

    The largest k_c over b_c (eq. 9), or the feasible b_c interval over m_c (eq. 21).

    Parameters
    ----------
    request : ChartRequest or Profile
        The request, or a profile: its display (or ``kind``) on the grid given below.
    kind : DisplayKind or str or None, optional
        With a profile, the display type; ``None`` takes the profile's.
    bc_range : tuple of (float, float), optional
        With a profile, the b_c range [N·s/m] of the impedance chart.
    mc_range : tuple of (float, float), optional
        With a profile, the m_c range [kg] of the admittance chart.
    points : int, optional
        With a profile, the number of grid points.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    ChartResult or None
        The chart, or ``None`` once cancelled.

    Raises
    ------
    ValidationError
        When the chart has more than ``MAX_CHART_POINTS`` points.
    """
    req = (ChartRequest.of(request, kind, bc_range=bc_range, mc_range=mc_range, points=points)
           if isinstance(request, Profile) else request)
    check_count("chart points", req.points, MAX_CHART_POINTS)
    disp = req.model.build()
    grid = np.geomspace(*req.grid, req.points)
    if isinstance(disp, ImpedanceDisplay):
        chart: Any = disp.stiffness_chart(grid, progress=progress, cancelled=cancelled)
    else:
        assert isinstance(disp, AdmittanceDisplay)
        chart = disp.mass_chart(grid, progress=progress, cancelled=cancelled)
    return None if chart is None else ChartResult(req.model.display, chart)


def exact_chart(request: ExactChartRequest | Profile, *, bc_range: tuple[float, float] = EXACT_CHART["bc_range"],
                points: int = EXACT_CHART["points"], progress: Progress | None = None,
                cancelled: Cancelled | None = None) -> CriticalChart | CriticalMassChart | None:
    """The exact sampled-data limit over b_c.

    The largest stable k_c (impedance) or the smallest stable m_c (admittance) of the real loop,
    with its delays.

    Parameters
    ----------
    request : ExactChartRequest or Profile
        The request, or a profile on the grid given below.
    bc_range : tuple of (float, float), optional
        With a profile, the range of the geometric b_c grid [N·s/m].
    points : int, optional
        With a profile, the number of b_c grid points.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    CriticalChart or CriticalMassChart or None
        The limit at each b_c, or ``None`` once cancelled.

    Raises
    ------
    ValidationError
        When the chart has more than ``MAX_CHART_POINTS`` points.
    """
    req = ExactChartRequest.of(request, bc_range, points) if isinstance(request, Profile) else request
    bcs = np.geomspace(*req.bc_range, check_count("chart points", req.points, MAX_CHART_POINTS))
    lp = req.loop
    if lp.pd is None:
        return critical_stiffness_chart(lp.device, bcs, lp.delay_samples, implementation_delay=lp.implementation_delay,
                                        progress=progress, cancelled=cancelled, velocity_filter=lp.velocity_filter)
    return critical_mass_chart(lp.device, bcs, lp.pd, lp.delay_samples, implementation_delay=lp.implementation_delay,
                               progress=progress, cancelled=cancelled, velocity_filter=lp.velocity_filter)


def exact_limit(request: ExactLimitRequest | Profile) -> float:
    """The exact limit at b_c: the largest stable k_c or the smallest stable m_c.

    Parameters
    ----------
    request : ExactLimitRequest or Profile
        The request, or a profile (at its b_c).

    Returns
    -------
    float
        The largest stable k_c [N/m] (impedance) or the smallest stable m_c [kg] (admittance).
    """
    req = ExactLimitRequest.of(request) if isinstance(request, Profile) else request
    lp = req.loop
    if lp.pd is None:
        return critical_stiffness(lp.device, req.bc, lp.delay_samples, implementation_delay=lp.implementation_delay,
                                  velocity_filter=lp.velocity_filter)
    return critical_mass(lp.device, req.bc, lp.pd, lp.delay_samples, implementation_delay=lp.implementation_delay,
                         velocity_filter=lp.velocity_filter)


def map_params(profile: Profile, axes: tuple[str, str] | None = None) -> dict[str, Any]:
    """The map's default parameters for the profile's display (its first axes pair unless ``axes``).

    Parameters
    ----------
    profile : Profile
        The device profile (its display).
    axes : tuple of (str, str) or None, optional
        The map's (x, y) parameters; ``None`` takes the display's first pair of
        :attr:`DisplayKind.map_axes`.

    Returns
    -------
    dict of str to Any
        ``x``, ``x_range``, ``y``, ``y_range`` (the display's default ranges) and ``points``
        (:data:`MAP_POINTS`).

    Raises
    ------
    KeyError
        When an axis has no default range on this display.
    """
    kind = display_kind(profile)
    x, y = kind.map_axes[0] if axes is None else axes
    return {"x": x, "x_range": kind.map_ranges[x], "y": y, "y_range": kind.map_ranges[y], "points": MAP_POINTS}


def map_arguments(request: MapRequest | Profile, params: dict[str, Any] | None = None) -> dict[str, Any]:
    """The keyword arguments of :func:`analysis.sampled.stability_map` for the map (a profile: with
    the map ``params``).

    The termination is the analysis default (impedance: hands-off against the paper's
    500 kN/m penalty wall; admittance: rigid grasp in free motion).

    Parameters
    ----------
    request : MapRequest or Profile
        The request, or a profile with the map ``params``.
    params : dict of str to Any or None, optional
        With a profile, the map parameters (:func:`map_params`); ``None`` takes the defaults.

    Returns
    -------
    dict of str to Any
        ``x`` and ``y`` as ``(name, grid)`` with geometric grids of shape (points,), and the
        loop's ``display``, ``coupling``, ``pd``, ``delay_samples``, ``implementation_delay`` and
        ``velocity_filter``.

    Raises
    ------
    ValidationError
        When the map has more than ``MAX_MAP_POINTS`` points.
    """
    req = MapRequest.of(request, params or map_params(request)) if isinstance(request, Profile) else request
    n, lp = req.points, req.loop
    check_count("map points", n * n, MAX_MAP_POINTS, f"{n} × {n}; at most 400 per axis")
    return dict(x=(req.x, np.geomspace(*req.x_range, n)), y=(req.y, np.geomspace(*req.y_range, n)),
                display=lp.display, coupling=lp.coupling, pd=lp.pd, delay_samples=lp.delay_samples,
                implementation_delay=lp.implementation_delay, velocity_filter=lp.velocity_filter)


@none_if_cancelled
def stability_map_result(request: MapRequest | Profile, params: dict[str, Any] | None = None, *,
                         progress: Progress | None = None, cancelled: Cancelled | None = None) -> StabilityMap | None:
    """The spectral radius of the exact sampled loop over two parameters.

    Computed in row blocks (one batched sweep each) so that it can report and stop.
    (:func:`analysis.sampled.stability_map` is the one batched sweep.)

    Parameters
    ----------
    request : MapRequest or Profile
        The request, or a profile with the map ``params``.
    params : dict of str to Any or None, optional
        With a profile, the map parameters (see :func:`map_params`); ``None`` takes the defaults.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    StabilityMap or None
        The spectral radius, shape (points, points) (``[j, i]`` at ``(x[i], y[j])``), or ``None``
        once cancelled.
    """
    req = MapRequest.of(request, params or map_params(request)) if isinstance(request, Profile) else request
    args = map_arguments(req)
    yn, yv = args.pop("y")
    blocks = np.array_split(np.arange(yv.size), min(8, yv.size))
    rows, x_name, x = [], args["x"][0], args["x"][1]
    for i, idx in enumerate(blocks):
        check_cancelled(cancelled)
        rows.append(sampled_stability_map(req.loop.device, y=(yn, yv[idx]), **args).spectral_radius)
        report_progress(progress, i + 1, len(blocks))
    return StabilityMap(x_name=x_name, x=x, y_name=yn, y=yv, spectral_radius=np.vstack(rows))


def map_point(request: LoopRequest | Profile, x_name: str, y_name: str) -> tuple[float, float | None]:
    """Where the design sits on a map of ``x_name`` (the coupling's first gain) and ``y_name``.

    Parameters
    ----------
    request : LoopRequest or Profile
        The loop with its coupling and PD gains, or a profile.
    x_name : str
        The map's x parameter (the coupling's first gain).
    y_name : str
        The map's y parameter.

    Returns
    -------
    tuple of (float, float or None)
        The coupling's first gain and the design's value of ``y_name``, in their units; the
        second is ``None`` when the design does not fix it.
    """
    lp = LoopRequest.of(request) if isinstance(request, Profile) else request
    assert lp.coupling is not None and lp.pd is not None
    first, second = lp.coupling
    grasp = HANDS_OFF if lp.kind.is_impedance else RIGID_GRASP
    y = {"kobj": PAPER_WALL_STIFFNESS, "bc": second, "kd": lp.pd[1], "grasp_mass": grasp.mass,
         "grasp_stiffness": grasp.stiffness}.get(y_name)
    return float(first), (None if y is None else float(y))


def design_radius(request: PointRequest | Profile, x_name: str | None = None, y_name: str | None = None
                  ) -> float | None:
    """The exact spectral radius of the sampled loop at the current design, on a map of ``x`` and
    ``y`` (the same loop and termination as :func:`stability_map_result`, one point: cheap enough
    to follow a slider drag).  ``None`` when the design is not a point of that map.

    Parameters
    ----------
    request : PointRequest or Profile
        The request, or a profile with the map's parameter names below.
    x_name : str or None, optional
        With a profile, the map's x parameter.
    y_name : str or None, optional
        With a profile, the map's y parameter.

    Returns
    -------
    float or None
        The spectral radius (below 1: stable), or ``None`` when the design is not a point of the
        map.
    """
    req = PointRequest.of(request, str(x_name), str(y_name)) if isinstance(request, Profile) else request
    x, y = map_point(req.loop, req.x, req.y)
    if y is None or not (x > 0 and y > 0):
        return None
    args = map_arguments(MapRequest(req.loop, req.x, (x, x), req.y, (y, y), 1))
    return float(sampled_stability_map(req.loop.device, **args).spectral_radius[0, 0])


@none_if_cancelled
def simulation(request: SimulationRequest | Profile, *, progress: Progress | None = None,
               cancelled: Cancelled | None = None) -> SimulationResult | None:
    """One run of the nonlinear simulator on the scenario.

    It has no progress hook of its own: it reports 0/1 and 1/1, and a cancel drops the result.

    Parameters
    ----------
    request : SimulationRequest or Profile
        The request, or a profile.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    SimulationResult or None
        The simulated traces, or ``None`` once cancelled.
    """
    req = SimulationRequest.of(request) if isinstance(request, Profile) else request
    report_progress(progress, 0, 1)
    check_cancelled(cancelled)
    lp, sec = req.loop, req.section
    res = simulate(lp.device, sec.scenario, display=lp.display, coupling=lp.coupling, pd=lp.pd, options=sec.options,
                   velocity_filter=lp.velocity_filter)
    report_progress(progress, 1, 1)
    check_cancelled(cancelled)
    return res


#: deprecated alias of :func:`stability_map_result` (one release): :func:`analysis.sampled.stability_map`
#: is the batched sweep of the same name
stability_map = stability_map_result
