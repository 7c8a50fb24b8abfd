"""Names and units shown to people for the parameters the study's charts and maps sweep, and for
the wall design's hold models and plants.  One place, used by the GUI's panels and views, the CLI
and the report."""

from __future__ import annotations

__all__ = ["PARAMETER_LABELS", "HOLD_LABELS", "PLANT_LABELS"]

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
