"""Sampled-data truth: exact closed-loop stability and time-domain simulation (public facade).

The two-port bounds of Adams, Moreyra & Hannaford rest on Tustin's method for the plant, a
half-sample model of the hold and passive terminations.  This module gives the ground truth
for the real sampled loop:

* :func:`critical_stiffness` -- exact largest stable k_c of an impedance display (rigid wall,
  hands-off), and :func:`critical_stiffness_chart` to overlay on the two-port design chart;
  :func:`critical_mass` / :func:`critical_mass_chart` for the admittance display's m_c;
* :func:`worst_case` -- worst spectral radius over human grasps x environments;
* :func:`stability_map` -- spectral radius over two parameters in one batched sweep;
* :func:`is_stable` / :data:`STABILITY_TOLERANCE` -- the one stability rule (spectral radius at
  most ``1 + 1e-12``); :func:`discrete_plants` -- the exact ZOH plant, computed once per device
  and grasps (cached by value) and shared by every sweep over gains;
* :func:`passivity_limit` -- Colgate & Schenkel's exact passivity limit of a rigid device;
* :class:`VelocityFilter` -- the controller's velocity estimate (backward difference, optionally
  low-pass filtered), accepted by every analysis with a damping term;
* :func:`zwidth_region` / :func:`optimal_filter` -- Colgate & Brown's (B, K) Z-width region,
  its area and the velocity-filter cut-off that maximizes it (Chawda et al.);
  :func:`load_trials` / :func:`score_trials` -- hardware trials against the region;
  :func:`estimate_noise` / :func:`noise_gain` -- the encoder-quantization noise of the velocity
  estimate and the damping it limits (the noise side of Chawda et al.'s trade-off);
* :func:`passivity_comparison` -- a too-stiff wall with and without Hannaford & Ryu's passivity
  controller (``SimulationOptions.passivity_control``) and behind an eq. (9) coupling;
* :func:`simulate` -- the nonlinear time-domain simulator with scenario presets;
* :func:`renderable_space` / :func:`m_width` -- the (M, B, K) space an impedance display renders
  with chosen qualities (:data:`QUALITIES`: stable, passive, accurate, quiet) and the M-width
  of Colonnese & Okamura; the rendered environment ``F = M a^ + B v^ + K x`` and its
  acceleration estimate (:class:`AccelerationEstimate`) in :mod:`analysis.sampled.rendered`,
  the impedance felt at the handle (:func:`handle_transmission`, :func:`handle_force_response`)
  and the space's volume (:func:`space_volume`);
* :func:`robust_renderable_space` -- the space every device of a batch has (the corners or
  samples of an identified parameter box: :func:`box_corners`, :func:`box_samples`), on a
  process pool or a Dask cluster; :func:`map_devices` / :func:`intersect_devices` for any
  per-device computation (:mod:`analysis.sampled.batch`).

The loop model is documented in :mod:`analysis.sampled.loop`, the controllers of the two
displays in :mod:`analysis.sampled.controllers`, the terminations in
:mod:`analysis.sampled.terminations`, passivity in :mod:`analysis.sampled.passivity`, the
simulator and its verdict detector in :mod:`analysis.sampled.simulator`, options and scenarios in
:mod:`analysis.sampled.scenarios`.  Numpy and scipy only.

A display and an environment causality are objects here: :func:`display_loop` maps a display
name (``"impedance"``/``"admittance"``) to :data:`IMPEDANCE_LOOP`/:data:`ADMITTANCE_LOOP`
(:data:`DISPLAY_LOOPS`), :func:`causality_kind` maps an environment causality to
:data:`PENALTY`/:data:`CONSTRAINT` (:data:`CAUSALITY_KINDS`); nothing else reads the names.

Loading is layered: the settings records (options, scenarios, terminations) and the display
loop objects are light and imported with the package; the loop, sweeps, passivity, results and
simulator are imported on first use of one of their names (a PEP 562 module ``__getattr__``),
so that the profile record
can hold a scenario without loading the simulator.  ``from analysis.sampled import simulate``,
``__all__`` and ``dir()`` work as before.
"""

from __future__ import annotations

import importlib

from analysis.sampled.controllers import (
    ADMITTANCE_LOOP,
    DISPLAY_LOOPS,
    IMPEDANCE_LOOP,
    AdmittanceLoop,
    DisplayLoop,
    ImpedanceLoop,
    display_loop,
)
from analysis.chain.velocity_filter import FILTER_KINDS, VelocityFilter
from analysis.sampled.scenarios import SCENARIOS, Scenario, SimulationOptions, hbfd_options, scenario
from analysis.sampled.terminations import (
    CAUSALITIES,
    CAUSALITY_KINDS,
    CLAMPED,
    CONSTRAINT,
    FIRM_GRASP,
    HANDS_OFF,
    PENALTY,
    RIGID_GRASP,
    ConstraintCausality,
    Environment,
    EnvironmentCausality,
    Grasp,
    PenaltyCausality,
    Termination,
    causality_kind,
    default_environments,
    default_grasps,
    default_terminations,
    free_motion,
    god_object_wall,
    penalty_wall,
)

__all__ = [
    "ACCELERATION_KINDS",
    "ADMITTANCE_LOOP",
    "AccelerationEstimate",
    "EffectiveEnvironment",
    "MWidth",
    "QUALITIES",
    "QualitySettings",
    "RenderableSpace",
    "RenderedEnvironment",
    "RenderingController",
    "effective_environment",
    "handle_force_response",
    "handle_transmission",
    "m_width",
    "renderable_space",
    "rendered_force_response",
    "space_volume",
    "DeviceFailed",
    "RobustRenderableSpace",
    "RobustSpace",
    "box_corners",
    "box_samples",
    "intersect_devices",
    "map_devices",
    "robust_renderable_space",
    "renders_accurately",
    "renders_passively",
    "renders_quietly",
    "renders_stably",
    "AdmittanceLoop",
    "CAUSALITIES",
    "CAUSALITY_KINDS",
    "CLAMPED",
    "CONSTRAINT",
    "ComparisonRun",
    "ConstraintCausality",
    "CROSSING_RTOL",
    "CriticalChart",
    "CriticalMassChart",
    "DISPLAY_LOOPS",
    "DisplayLoop",
    "Environment",
    "EnvironmentCausality",
    "FILTER_KINDS",
    "FIRM_GRASP",
    "FilterOptimum",
    "Grasp",
    "HANDS_OFF",
    "IMPEDANCE_LOOP",
    "ImpedanceLoop",
    "LoopSpec",
    "MAP_PARAMETERS",
    "MeasuredTrials",
    "DEFAULT_FORCE_NOISE",
    "OPTIMIZER_AREA",
    "PENALTY",
    "PassivityComparison",
    "PenaltyCausality",
    "RIGID_GRASP",
    "SCENARIOS",
    "STABILITY_TOLERANCE",
    "STABLE_VALUES",
    "Scenario",
    "SimulationOptions",
    "SimulationResult",
    "Simulator",
    "StabilityMap",
    "TRIAL_COLUMNS",
    "Termination",
    "TrialScore",
    "TrialsError",
    "VelocityFilter",
    "VelocityNoise",
    "Verdict",
    "WorstCase",
    "ZWidthRegion",
    "causality_kind",
    "closed_loop_matrices",
    "critical_mass",
    "critical_mass_chart",
    "critical_stiffness",
    "critical_stiffness_chart",
    "default_environments",
    "default_grasps",
    "default_terminations",
    "estimate_noise",
    "detect",
    "discrete_plants",
    "discretize_zoh",
    "display_loop",
    "free_motion",
    "god_object_wall",
    "hbfd_options",
    "is_stable",
    "linear_stability_limit",
    "load_trials",
    "noise_gain",
    "noise_limited_damping",
    "filter_area",
    "optimal_filter",
    "passivity_closed_form",
    "passivity_comparison",
    "passivity_limit",
    "passivity_limits",
    "penalty_wall",
    "plant_matrices",
    "radii",
    "required_damping",
    "rigid_stability_polynomial",
    "scenario",
    "score_trials",
    "simulate",
    "spectral_radius",
    "stability_map",
    "stable_end",
    "virtual_wall",
    "worst_case",
    "zwidth_region",
]

#: Heavy names -> the submodule that defines them, imported on first use.
_LAZY = {
    **dict.fromkeys(("linear_stability_limit", "passivity_closed_form", "passivity_limit", "passivity_limits",
                     "required_damping", "rigid_stability_polynomial", "virtual_wall"), ".passivity"),
    **dict.fromkeys(("OPTIMIZER_AREA", "ZWidthRegion", "zwidth_region"), ".zwidth"),
    **dict.fromkeys(("DEFAULT_FORCE_NOISE", "VelocityNoise", "noise_gain", "noise_limited_damping",
                     "estimate_noise"), ".velocity_noise"),
    **dict.fromkeys(("ComparisonRun", "PassivityComparison", "passivity_comparison"), ".pc_compare"),
    **dict.fromkeys(("FilterOptimum", "filter_area", "optimal_filter"), ".filter_optimum"),
    **dict.fromkeys(("MeasuredTrials", "STABLE_VALUES", "TRIAL_COLUMNS", "TrialScore", "TrialsError", "load_trials",
                     "score_trials"), ".trials"),
    **dict.fromkeys(("LoopSpec", "STABILITY_TOLERANCE", "closed_loop_matrices", "discrete_plants", "discretize_zoh",
                     "is_stable", "plant_matrices", "spectral_radius"), ".loop"),
    **dict.fromkeys(("CriticalChart", "CriticalMassChart", "SimulationResult", "StabilityMap", "Verdict",
                     "WorstCase"), ".results"),
    **dict.fromkeys(("CROSSING_RTOL", "MAP_PARAMETERS", "critical_mass", "critical_mass_chart", "critical_stiffness",
                     "critical_stiffness_chart", "radii", "stability_map", "stable_end", "worst_case"), ".sweeps"),
    **dict.fromkeys(("Simulator", "detect", "simulate"), ".simulator"),
    **dict.fromkeys(("ACCELERATION_KINDS", "AccelerationEstimate", "RenderedEnvironment", "RenderingController",
                     "handle_force_response", "handle_transmission", "rendered_force_response"), ".rendered"),
    **dict.fromkeys(("EffectiveEnvironment", "QUALITIES", "QualitySettings", "effective_environment",
                     "renders_accurately", "renders_passively", "renders_quietly", "renders_stably"), ".qualities"),
    **dict.fromkeys(("MWidth", "RenderableSpace", "m_width", "renderable_space", "space_volume"), ".renderable"),
    **dict.fromkeys(("DeviceFailed", "RobustRenderableSpace", "RobustSpace", "box_corners", "box_samples",
                     "intersect_devices", "map_devices", "robust_renderable_space"), ".batch"),
}


def __getattr__(name: str) -> object:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
