"""What zwidth computes for a profile: one definition shared by the GUI, the CLI and the report.

* :mod:`.displays` -- the two display types as objects (the only place that reads the
  profile's display string);
* :mod:`.quantities` -- names, units and the one rule that prints a number;
* :mod:`.headline` -- the verdict, the impedance range and the designs (eq. 9/21, 11-12/23-24);
* :mod:`.design_limits` -- designs beyond the physical range of the field they would set (the
  loader's own limits), reported as "beyond the physical range" and never applied (issue 22);
* :mod:`.compute` -- stability, designs, design chart, exact sampled-data limits, stability
  map and simulation, with progress and cancel hooks;
* :mod:`.wall` -- the wall controller and the disturbance observer of Eom, Suh & Yi;
* :mod:`.summary` -- the plain-data summaries of ``zwidth analyze`` and ``zwidth design``;
* :mod:`.zwidth` -- the controller as built: the (B, K) Z-width region with its velocity
  filter, the optimum cut-off and the hardware trials (issue 15);
* :mod:`.identify` -- identification fits, the profile's identification section and the
  robust designs over its parameter box (issue 14);
* :mod:`.labels` -- names and units of swept parameters, hold models and plants, for people.
* :mod:`.requests` -- what each computation depends on: frozen requests built from a profile
  (each computation takes its request, or a profile from which it builds it);
* :mod:`.citations` -- the full references of the papers whose equation numbers zwidth shows;
* :mod:`.renderable` -- the renderable (M, B, K) space and the M-width of a profile (issue 24);
* :mod:`.workspace` -- the workspace map of a multi-DOF linkage and the limits at its handle (issue 25).
"""

from __future__ import annotations

from .displays import ADMITTANCE, DISPLAY_KINDS, IMPEDANCE, DeviceRequest, DisplayKind, Gain, display_kind, profile_filter
from .requests import (
    ChartRequest,
    ExactChartRequest,
    ExactLimitRequest,
    LoopRequest,
    MapRequest,
    PointRequest,
    SimulationRequest,
    StabilityRequest,
)
from .quantities import DIGITS, QUANTITIES, Quantity, format_number, quantity, rich_numbers, superscript_numbers
from .design_limits import (
    BEYOND,
    DESIGN_FIELDS,
    BeyondLimit,
    beyond_limit,
    design_beyond_limits,
    edits_beyond_limits,
    field_limit,
)
from .headline import DESIGN_KEYS, HEADLINE_KEYS, Headline, designs, headline
from .compute import (
    DESIGN_CHART,
    EXACT_CHART,
    MAP_POINTS,
    ChartResult,
    delays,
    design_chart,
    design_radius,
    exact_chart,
    exact_limit,
    feasible_damping,
    map_arguments,
    map_params,
    map_point,
    max_stiffness,
    min_mass,
    simulation,
    scenario_matches,
    simulation_section,
    stability,
    stability_map,
    stability_map_result,
)
from .wall import (
    DEFAULT_BC,
    OBSERVER_W,
    PAPER_MASS,
    default_bc,
    derived_wall_settings,
    mass_scale,
    observer_device_label,
    wall_device_label,
    TwoAxisRequest,
    TwoAxisStepRequest,
    WallAdmittances,
    WallAtRequest,
    WallPoint,
    WallRequest,
    WallTradeoff,
    admittance_grid,
    observer_coupling,
    observer_response,
    observer_settings,
    observer_step,
    wall_admittances,
    wall_design,
    wall_point,
    wall_settings,
    wall_step,
    wall_tradeoff,
)
from .citations import REFERENCES, Reference, citation_text
from .labels import HOLD_LABELS, PARAMETER_LABELS, PLANT_LABELS, SCENARIO_TIPS, SCENARIO_TITLES, scenario_title
from .summary import SUMMARY_VERSION, design_summary, format_design, format_summary, summarize
from .zwidth import (
    TrialsRequest,
    ZWidthRequest,
    ZWidthStudy,
    controller_section,
    noise_options,
    profile_trials,
    region_b,
    resolve_trials,
    trial_score,
    trials_path,
    twoport_limit,
    region_wall,
    wall_edits,
    with_filter,
    zwidth_region,
    zwidth_region_result,
)
from .renderable import (
    GRASPS,
    QUALITY_LABELS,
    ROBUST_KINDS,
    ROBUST_SAMPLES,
    RenderableRequest,
    RenderableStudy,
    RobustBox,
    damping_axis,
    damping_from_axis,
    environment_edits,
    k_max_at,
    renderable_section,
    renderable_study,
    robust_box_reason,
    robust_study,
)
from .optimum import OPTIMUM_CUTOFFS, OptimumRequest, filter_optimum, optimum_kind, optimum_verdict
from .workspace import (
    HandleRequest,
    WorkspacePoint,
    WorkspaceRequest,
    handle_edits,
    inertia_ellipse,
    multidof_section,
    polar_curve,
    workspace_point,
    workspace_study,
)
from .identify import (
    UNUSED_BINS_LABEL,
    BodeData,
    IdentifyResult,
    RobustDesigns,
    RobustRequest,
    bins_summary,
    bode_data,
    curves_goodness,
    fit_curves,
    identify_chain,
    load_measurements,
    parameter_rows,
    parse_fixed,
    profile_with_fit,
    robust_designs,
    section_measurements,
)

__all__ = [
    "HOLD_LABELS", "PARAMETER_LABELS", "PLANT_LABELS", "SCENARIO_TIPS", "SCENARIO_TITLES", "scenario_title",
    "ADMITTANCE", "DISPLAY_KINDS", "IMPEDANCE", "DisplayKind", "Gain", "display_kind",
    "DIGITS", "QUANTITIES", "Quantity", "format_number", "quantity", "rich_numbers", "superscript_numbers",
    "DESIGN_KEYS", "HEADLINE_KEYS", "Headline", "designs", "headline",
    "BEYOND", "DESIGN_FIELDS", "BeyondLimit", "beyond_limit", "design_beyond_limits", "edits_beyond_limits",
    "field_limit",
    "DESIGN_CHART", "EXACT_CHART", "MAP_POINTS", "ChartResult", "delays", "design_chart", "design_radius", "exact_chart",
    "exact_limit", "feasible_damping", "map_arguments", "map_params", "map_point", "max_stiffness", "min_mass",
    "scenario_matches", "simulation", "simulation_section", "stability", "stability_map_result",
    "DEFAULT_BC", "OBSERVER_W", "WallAdmittances", "WallPoint", "WallTradeoff", "admittance_grid",
    "observer_coupling", "observer_response", "observer_settings", "observer_step", "wall_admittances",
    "wall_design", "wall_point", "wall_settings", "wall_step", "wall_tradeoff",
    "PAPER_MASS", "default_bc", "derived_wall_settings", "mass_scale", "observer_device_label", "wall_device_label",
    "SUMMARY_VERSION", "design_summary", "format_design", "format_summary", "summarize",
    "BodeData", "IdentifyResult", "RobustDesigns", "bode_data", "fit_curves", "identify_chain", "load_measurements", "parameter_rows",
    "parse_fixed", "profile_with_fit", "robust_designs", "section_measurements", "UNUSED_BINS_LABEL", "bins_summary", "curves_goodness",
    "OPTIMUM_CUTOFFS", "ZWidthStudy", "controller_section", "filter_optimum", "noise_options", "optimum_kind",
    "optimum_verdict", "profile_trials", "resolve_trials", "trials_path",
    "region_b", "trial_score", "twoport_limit", "wall_edits", "region_wall", "with_filter", "zwidth_region_result",
    "profile_filter",
    "REFERENCES", "Reference", "citation_text",
    # the requests: what each computation depends on (the compute graph's cache keys)
    "DeviceRequest", "StabilityRequest", "ChartRequest", "LoopRequest", "MapRequest", "PointRequest",
    "ExactChartRequest", "ExactLimitRequest", "SimulationRequest", "WallRequest", "WallAtRequest",
    "TwoAxisRequest", "TwoAxisStepRequest", "ZWidthRequest", "OptimumRequest", "TrialsRequest", "RobustRequest",
    "GRASPS", "QUALITY_LABELS", "RenderableRequest", "RenderableStudy", "damping_axis", "damping_from_axis",
    "environment_edits", "k_max_at", "renderable_section", "renderable_study", "ROBUST_KINDS", "ROBUST_SAMPLES", "RobustBox",
    "robust_box_reason", "robust_study",
    "HandleRequest", "WorkspacePoint", "WorkspaceRequest", "handle_edits", "inertia_ellipse", "multidof_section",
    "polar_curve", "workspace_point", "workspace_study",
    # deprecated aliases, for one release: analysis.sampled's functions of these names are other things
    "stability_map", "zwidth_region",
]
