"""The device chain: the lumped-mass model, its one continued fraction and state space,
the discretizations (Tustin image, holds) and the frequency grids.

Adams, Moreyra & Hannaford, *Stability and Performance of Haptic Displays* (section V, eqs. 26-28).
"""

from __future__ import annotations

from .device import (  # noqa: F401
    Device,
    damping_from_ratio,
    ratio_from_damping,
)
from .response import (  # noqa: F401
    ChainResponse,
    chain_response,
    chain_impedances,
    handle_impedance,
)
from .discretize import (  # noqa: F401
    theta_of,
    tustin_image,
    hold_factor,
    spring_damper,
    held_spring_damper,
    mass_damper_admittance,
    check_frequencies,
)
from .grids import (  # noqa: F401
    warp,
    log_grid,
    resonance_grid,
    refine_minima,
    device_modes,
    band_edges,
)

__all__ = [
    "Device",
    "damping_from_ratio",
    "ratio_from_damping",
    "ChainResponse",
    "chain_response",
    "chain_impedances",
    "handle_impedance",
    "theta_of",
    "tustin_image",
    "hold_factor",
    "spring_damper",
    "held_spring_damper",
    "mass_damper_admittance",
    "check_frequencies",
    "warp",
    "log_grid",
    "resonance_grid",
    "refine_minima",
    "device_modes",
    "band_edges",
]
