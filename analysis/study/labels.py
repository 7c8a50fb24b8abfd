"""Names and units shown to people for the parameters the study's charts and maps sweep, and for
the wall design's hold models and plants.  One place, used by the GUI's panels and views, the CLI
and the report."""

from __future__ import annotations

__all__ = ["PARAMETER_LABELS", "HOLD_LABELS", "PLANT_LABELS", "OBSERVER_PRESET_LABELS", "SCENARIO_TITLES", "SCENARIO_TIPS", "scenario_title"]

#: Map and chart parameters: (symbol, unit).
PARAMETER_LABELS: dict[str, tuple[str, str]] = {
    "kc": ("k_c", "N/m"), "bc": ("b_c", "N·s/m"), "mc": ("m_c", "kg"), "kp": ("k_p", "N/m"),
    "kd": ("k_d", "N·s/m"), "kobj": ("k_obj", "N/m"), "bobj": ("b_obj", "N·s/m"), "me": ("m_e", "kg"),
    "grasp_mass": ("grasp mass", "kg"), "grasp_damping": ("grasp damping", "N·s/m"),
    "grasp_stiffness": ("grasp stiffness", "N/m"),
}

#: The hold models of ``WallSettings.hold`` and the plants of ``WallSettings.plant``, for people.
HOLD_LABELS = {
    "none": "none: H = 1 (no hold)",
    "pade": "Padé: half-sample delay, 1st order",
    "lowpass2": "2nd-order low-pass at Nyquist (paper)",
    "zoh": "ZOH: (1 − e^(−sT))/(sT)",
    "discrete": "exact sampled loop (discrete)",
}
PLANT_LABELS = {"rigid": "rigid handle: m, b below", "chain": "the profile's device chain"}
#: The two-axis five-bar devices of ``ObserverSettings.preset``, for people.
OBSERVER_PRESET_LABELS = {"five_bar_centre": "five-bar, centre (unequal distal links)",
                          "five_bar_offset": "five-bar, 60 mm right of centre"}

#: The built-in simulation scenarios (``SimulationSection.scenario.name``), for people.
SCENARIO_TITLES = {
    "impedance_worst_case": "Impedance worst case",
    "admittance_worst_case": "Admittance worst case",
    "wall_push": "Wall push",
    "free_sliding": "Free sliding",
}
SCENARIO_TIPS = {
    "impedance_worst_case": "Firm grasp pushes the handle into a rigid wall, then lets go at the release time",
    "admittance_worst_case": "Rigid grasp, a short push in free motion",
    "wall_push": "A force step pushes the handle into a wall and holds it there",
    "free_sliding": "A push along free space, then coasting",
}


def scenario_title(name: str) -> str:
    """The scenario's readable name (a custom name is shown as it is).

    Parameters
    ----------
    name : str
        The scenario's name (``SimulationSection.scenario.name``), e.g. ``"wall_push"``.

    Returns
    -------
    str
        Its title from :data:`SCENARIO_TITLES`, or ``name`` itself for a custom scenario.
    """
    return SCENARIO_TITLES.get(name, name)
