"""What zwidth computes for a profile: one definition shared by the GUI, the CLI and the report.

* :mod:`.displays` -- the two display types as objects (the only place that reads the
  profile's display string);
* :mod:`.quantities` -- names, units and the one rule that prints a number;
* :mod:`.headline` -- the verdict, the impedance range and the designs (eq. 9/21, 11-12/23-24);
* :mod:`.compute` -- stability, designs, design chart, exact sampled-data limits, stability
  map and simulation, with progress and cancel hooks;
* :mod:`.wall` -- the wall controller and the disturbance observer of Eom, Suh & Yi;
* :mod:`.summary` -- the plain-data summaries of ``zwidth analyze`` and ``zwidth design``.
"""

from __future__ import annotations

from .displays import ADMITTANCE, DISPLAY_KINDS, IMPEDANCE, DisplayKind, Gain, display_kind
from .quantities import DIGITS, QUANTITIES, Quantity, format_number, quantity
from .headline import DESIGN_KEYS, HEADLINE_KEYS, Headline, designs, headline
from .compute import (
    DESIGN_CHART,
    EXACT_CHART,
    MAP_POINTS,
    ChartResult,
    delays,
    design_chart,
    exact_chart,
    exact_limit,
    feasible_damping,
    map_arguments,
    map_params,
    map_point,
    max_stiffness,
    min_mass,
    simulation,
    simulation_section,
    stability,
    stability_map,
)
from .wall import (
    DEFAULT_BC,
    OBSERVER_W,
    WallAdmittances,
    WallPoint,
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
from .summary import SUMMARY_VERSION, design_summary, format_design, format_summary, summarize

__all__ = [
    "ADMITTANCE", "DISPLAY_KINDS", "IMPEDANCE", "DisplayKind", "Gain", "display_kind",
    "DIGITS", "QUANTITIES", "Quantity", "format_number", "quantity",
    "DESIGN_KEYS", "HEADLINE_KEYS", "Headline", "designs", "headline",
    "DESIGN_CHART", "EXACT_CHART", "MAP_POINTS", "ChartResult", "delays", "design_chart", "exact_chart",
    "exact_limit", "feasible_damping", "map_arguments", "map_params", "map_point", "max_stiffness", "min_mass",
    "simulation", "simulation_section", "stability", "stability_map",
    "DEFAULT_BC", "OBSERVER_W", "WallAdmittances", "WallPoint", "WallTradeoff", "admittance_grid",
    "observer_coupling", "observer_response", "observer_settings", "observer_step", "wall_admittances",
    "wall_design", "wall_point", "wall_settings", "wall_step", "wall_tradeoff",
    "SUMMARY_VERSION", "design_summary", "format_design", "format_summary", "summarize",
]
