"""What zwidth computes for a profile: the stability result, the designs, the design chart,
the exact sampled-data limits, the stability map and the scenario simulation.

The GUI's compute graph, ``zwidth`` and the report all call these functions; none of them
has a copy.  Long computations take ``progress(done, total)`` and ``cancelled() -> bool``
and return ``None`` once cancelled.  Each call builds its own analysis objects, so a call on a
worker thread never shares a cache with the GUI thread.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from analysis.chain.limits import MAX_CHART_POINTS, MAX_MAP_POINTS, check_count
from analysis.profiles.model import Profile
from analysis.profiles.sections import SimulationSection
from analysis.sampled import (
    HANDS_OFF,
    RIGID_GRASP,
    SCENARIOS,
    CriticalChart,
    CriticalMassChart,
    SimulationOptions,
    Scenario,
    SimulationResult,
    StabilityMap,
    critical_mass,
    critical_mass_chart,
    critical_stiffness,
    critical_stiffness_chart,
    scenario,
    simulate,
)
from analysis.sampled import stability_map as sampled_stability_map
from analysis.sampled.terminations import PAPER_WALL_STIFFNESS
from analysis.study.displays import DisplayKind, display_kind, profile_filter
from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.twoport.results import (
    Cancelled,
    DampingInterval,
    MassChart,
    MassDesign,
    Progress,
    StabilityResult,
    StiffnessChart,
    StiffnessDesign,
)

__all__ = ["ChartResult", "DESIGN_CHART", "EXACT_CHART", "MAP_POINTS", "stability", "max_stiffness",
           "feasible_damping", "min_mass", "design_chart", "exact_chart", "exact_limit", "simulation_section",
           "scenario_matches",
           "delays", "map_params", "map_arguments", "stability_map", "map_point", "design_radius", "simulation"]

#: the design chart's grid: b_c (impedance) or m_c (admittance) ranges and points per chart
DESIGN_CHART = {"bc_range": (1.0, 1e4), "mc_range": (1e-3, 1e3), "points": 40}
#: the exact sampled-data limit chart's b_c grid
EXACT_CHART = {"bc_range": (1.0, 1e4), "points": 24}
#: grid points per axis of the sampled-data stability map
MAP_POINTS = 48


@dataclass(frozen=True)
class ChartResult:
    """A design chart with the display type it belongs to."""

    display: str
    chart: StiffnessChart | MassChart


def stability(profile: Profile, refine: bool = True) -> StabilityResult:
    """Eq. (9) or (21) at the profile's coupling, for the profile's display."""
    return display_kind(profile).evaluate(profile, refine=refine)


def max_stiffness(profile: Profile) -> StiffnessDesign:
    """The largest k_c satisfying eq. (9) at the profile's b_c."""
    return ImpedanceDisplay(profile.device, velocity_filter=profile_filter(profile)).max_stiffness(profile.bc)


def feasible_damping(profile: Profile) -> DampingInterval:
    """The b_c interval satisfying eq. (21) at the profile's m_c."""
    return AdmittanceDisplay(profile.device, profile.kp, profile.kd, velocity_filter=profile_filter(profile)).feasible_damping(profile.mc)


def min_mass(profile: Profile) -> MassDesign | None:
    """The smallest m_c for which some b_c satisfies eq. (21); ``None`` when none is found."""
    try:
        return AdmittanceDisplay(profile.device, profile.kp, profile.kd, velocity_filter=profile_filter(profile)).min_mass()
    except ValueError:
        return None


def design_chart(profile: Profile, kind: DisplayKind | str | None = None, *, bc_range: tuple[float, float] = DESIGN_CHART["bc_range"],
                 mc_range: tuple[float, float] = DESIGN_CHART["mc_range"], points: int = DESIGN_CHART["points"],
                 progress: Progress | None = None, cancelled: Cancelled | None = None) -> ChartResult | None:
    """The design chart of the profile's display (or ``kind``): the largest k_c over b_c
    (eq. 9), or the feasible b_c interval over m_c (eq. 21), on a geometric grid."""
    kind = display_kind(profile if kind is None else kind)
    check_count("chart points", int(points), MAX_CHART_POINTS)
    disp = kind.build(profile)
    if isinstance(disp, ImpedanceDisplay):
        chart: Any = disp.stiffness_chart(np.geomspace(*bc_range, int(points)), progress=progress,
                                          cancelled=cancelled)
    else:
        assert isinstance(disp, AdmittanceDisplay)
        chart = disp.mass_chart(np.geomspace(*mc_range, int(points)), progress=progress, cancelled=cancelled)
    return None if chart is None else ChartResult(kind.name, chart)


def scenario_matches(profile: Profile, sc: Scenario) -> bool:
    """False for the paper's worst case of the *other* display (e.g. ``impedance_worst_case``, a
    penalty wall, on an admittance display); any other scenario is the user's choice and matches."""
    own = f"{display_kind(profile).name}_worst_case"
    return not (sc.name.endswith("_worst_case") and sc.name in SCENARIOS and sc.name != own)


def simulation_section(profile: Profile) -> SimulationSection:
    """What the Sampled-data tab simulates: the profile's simulation section, its scenario following
    the display (:func:`scenario_matches`: the other display's worst case becomes this display's,
    the options kept), or, without a section, ideal sensors and the paper's worst case for its display."""
    own = scenario(f"{display_kind(profile).name}_worst_case")
    if profile.simulation is None:
        return SimulationSection(options=SimulationOptions(), scenario=own)
    if scenario_matches(profile, profile.simulation.scenario):
        return profile.simulation
    return SimulationSection(options=profile.simulation.options, scenario=own)


def delays(profile: Profile) -> tuple[int, bool]:
    """``(delay_samples, implementation_delay)`` of the profile's simulation section."""
    o = simulation_section(profile).options
    return o.delay_samples, o.implementation_delay


def exact_chart(profile: Profile, *, bc_range: tuple[float, float] = EXACT_CHART["bc_range"],
                points: int = EXACT_CHART["points"], progress: Progress | None = None,
                cancelled: Cancelled | None = None) -> CriticalChart | CriticalMassChart | None:
    """The exact sampled-data limit over b_c: the largest stable k_c (impedance) or the
    smallest stable m_c (admittance) of the real loop, with the profile's delays."""
    bcs = np.geomspace(*bc_range, check_count("chart points", int(points), MAX_CHART_POINTS))
    d, impl = delays(profile)
    if display_kind(profile).is_impedance:
        return critical_stiffness_chart(profile.device, bcs, d, implementation_delay=impl, progress=progress,
                                        cancelled=cancelled, velocity_filter=profile_filter(profile))
    return critical_mass_chart(profile.device, bcs, (profile.kp, profile.kd), d, implementation_delay=impl,
                               progress=progress, cancelled=cancelled, velocity_filter=profile_filter(profile))


def exact_limit(profile: Profile) -> float:
    """The exact limit at the profile's b_c: the largest stable k_c or the smallest stable m_c."""
    d, impl = delays(profile)
    if display_kind(profile).is_impedance:
        return critical_stiffness(profile.device, float(profile.bc), d, implementation_delay=impl,
                                  velocity_filter=profile_filter(profile))
    return critical_mass(profile.device, float(profile.bc_adm), (profile.kp, profile.kd), d, implementation_delay=impl,
                         velocity_filter=profile_filter(profile))


def map_params(profile: Profile, axes: tuple[str, str] | None = None) -> dict[str, Any]:
    """The map's default parameters for the profile's display (its first axes pair unless ``axes``)."""
    kind = display_kind(profile)
    x, y = kind.map_axes[0] if axes is None else axes
    return {"x": x, "x_range": kind.map_ranges[x], "y": y, "y_range": kind.map_ranges[y], "points": MAP_POINTS}


def map_arguments(profile: Profile, params: dict[str, Any]) -> dict[str, Any]:
    """The keyword arguments of :func:`analysis.sampled.stability_map` for the map ``params``.

    The termination is the analysis default (impedance: hands-off against the paper's
    500 kN/m penalty wall; admittance: rigid grasp in free motion).
    """
    n = int(params["points"])
    check_count("map points", n * n, MAX_MAP_POINTS, f"{n} × {n}; at most 400 per axis")
    d, impl = delays(profile)
    kind = display_kind(profile)
    return dict(x=(params["x"], np.geomspace(*params["x_range"], n)),
                y=(params["y"], np.geomspace(*params["y_range"], n)),
                display=kind.name, coupling=kind.coupling(profile), pd=(profile.kp, profile.kd), delay_samples=d,
                implementation_delay=impl, velocity_filter=profile_filter(profile))


def stability_map(profile: Profile, params: dict[str, Any] | None = None, *, progress: Progress | None = None,
                  cancelled: Cancelled | None = None) -> StabilityMap | None:
    """The spectral radius of the exact sampled loop over two parameters (``params``: see
    :func:`map_params`), in row blocks (one batched sweep each) so that it can report and stop."""
    args = map_arguments(profile, map_params(profile) if params is None else params)
    yn, yv = args.pop("y")
    blocks = np.array_split(np.arange(yv.size), min(8, yv.size))
    rows, x_name, x = [], args["x"][0], args["x"][1]
    for i, idx in enumerate(blocks):
        if cancelled is not None and cancelled():
            return None
        rows.append(sampled_stability_map(profile.device, y=(yn, yv[idx]), **args).spectral_radius)
        if progress is not None:
            progress(i + 1, len(blocks))
    return StabilityMap(x_name=x_name, x=x, y_name=yn, y=yv, spectral_radius=np.vstack(rows))


def map_point(profile: Profile, x_name: str, y_name: str) -> tuple[float, float | None]:
    """Where the profile's design sits on a map of ``x_name`` (the coupling's first gain) and
    ``y_name`` (``None`` when the profile does not fix it)."""
    kind = display_kind(profile)
    first, second = kind.coupling(profile)
    grasp = HANDS_OFF if kind.is_impedance else RIGID_GRASP
    y = {"kobj": PAPER_WALL_STIFFNESS, "bc": second, "kd": profile.kd, "grasp_mass": grasp.mass,
         "grasp_stiffness": grasp.stiffness}.get(y_name)
    return float(first), (None if y is None else float(y))


def design_radius(profile: Profile, x_name: str, y_name: str) -> float | None:
    """The exact spectral radius of the sampled loop at the current design, on a map of ``x_name``
    and ``y_name`` (the same loop and termination as :func:`stability_map`, one point: cheap
    enough to follow a slider drag).  ``None`` when the design is not a point of that map."""
    x, y = map_point(profile, x_name, y_name)
    if y is None or not (x > 0 and y > 0):
        return None
    args = map_arguments(profile, {"x": x_name, "x_range": (x, x), "y": y_name, "y_range": (y, y), "points": 1})
    return float(sampled_stability_map(profile.device, **args).spectral_radius[0, 0])


def simulation(profile: Profile, *, progress: Progress | None = None, cancelled: Cancelled | None = None
               ) -> SimulationResult | None:
    """One run of the nonlinear simulator on the profile's scenario.  It has no progress hook of
    its own: reports 0/1 and 1/1, and a cancel drops the result."""
    sec = simulation_section(profile)
    if progress is not None:
        progress(0, 1)
    if cancelled is not None and cancelled():
        return None
    res = simulate(profile, sec.scenario, options=sec.options, velocity_filter=profile_filter(profile))
    if progress is not None:
        progress(1, 1)
    return None if cancelled is not None and cancelled() else res
