"""Sampled-data truth: exact closed-loop stability and time-domain simulation (public facade).

The two-port bounds of Adams, Moreyra & Hannaford rest on Tustin's method for the plant, a
half-sample model of the hold and passive terminations.  This module gives the ground truth
for the real sampled loop:

* :func:`critical_stiffness` -- exact largest stable k_c of an impedance display (rigid wall,
  hands-off), and :func:`critical_stiffness_chart` to overlay on the two-port design chart;
  :func:`critical_mass` / :func:`critical_mass_chart` for the admittance display's m_c;
* :func:`worst_case` -- worst spectral radius over human grasps x environments;
* :func:`stability_map` -- spectral radius over two parameters in one batched sweep;
* :func:`passivity_limit` -- Colgate & Schenkel's exact passivity limit of a rigid device;
* :func:`simulate` -- the nonlinear time-domain simulator with scenario presets.

The loop model is documented in :mod:`analysis.sampled_loop`, the terminations in
:mod:`analysis.terminations`, passivity in :mod:`analysis.passivity`, the simulator and its
verdict detector in :mod:`analysis.simulator`, options and scenarios in
:mod:`analysis.scenarios`.  Numpy and scipy only.
"""

from __future__ import annotations

from analysis.sampled.passivity import (
    linear_stability_limit,
    passivity_closed_form,
    passivity_limit,
    required_damping,
    rigid_stability_polynomial,
    virtual_wall,
)
from analysis.sampled.loop import LoopSpec, closed_loop_matrices, discretize_zoh, plant_matrices, spectral_radius
from analysis.sampled.results import (
    CriticalChart,
    CriticalMassChart,
    SimulationResult,
    StabilityMap,
    Verdict,
    WorstCase,
)
from analysis.sampled.sweeps import (
    MAP_PARAMETERS,
    critical_mass,
    critical_mass_chart,
    critical_stiffness,
    critical_stiffness_chart,
    radii,
    stability_map,
    worst_case,
)
from analysis.sampled.scenarios import SCENARIOS, Scenario, SimulationOptions, hbfd_options, scenario
from analysis.sampled.simulator import Simulator, detect, simulate
from analysis.sampled.terminations import (
    CLAMPED,
    FIRM_GRASP,
    HANDS_OFF,
    RIGID_GRASP,
    Environment,
    Grasp,
    Termination,
    default_environments,
    default_grasps,
    default_terminations,
    free_motion,
    god_object_wall,
    penalty_wall,
)

__all__ = [
    "CLAMPED",
    "CriticalChart",
    "CriticalMassChart",
    "Environment",
    "FIRM_GRASP",
    "Grasp",
    "HANDS_OFF",
    "LoopSpec",
    "MAP_PARAMETERS",
    "RIGID_GRASP",
    "SCENARIOS",
    "Scenario",
    "SimulationOptions",
    "SimulationResult",
    "Simulator",
    "StabilityMap",
    "Termination",
    "Verdict",
    "WorstCase",
    "closed_loop_matrices",
    "critical_mass",
    "critical_mass_chart",
    "critical_stiffness",
    "critical_stiffness_chart",
    "default_environments",
    "default_grasps",
    "default_terminations",
    "detect",
    "discretize_zoh",
    "free_motion",
    "god_object_wall",
    "hbfd_options",
    "linear_stability_limit",
    "passivity_closed_form",
    "passivity_limit",
    "penalty_wall",
    "plant_matrices",
    "radii",
    "required_damping",
    "rigid_stability_polynomial",
    "scenario",
    "simulate",
    "spectral_radius",
    "stability_map",
    "virtual_wall",
    "worst_case",
]
