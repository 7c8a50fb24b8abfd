"""The device chain: the lumped-mass model, its one continued fraction and state space,
the discretizations (Tustin image, holds, exact ZOH) and the frequency grids.

Adams, Moreyra & Hannaford, *Stability and Performance of Haptic Displays* (section V, eqs. 25-28).
"""

from __future__ import annotations

from .device import (  # noqa: F401
    Device,
    damping_from_ratio,
    ratio_from_damping,
)
from .limits import (  # noqa: F401
    LIMITS,
    Limit,
    check_count,
    check_simulation_size,
)
from .continued_fraction import (  # noqa: F401
    continued_fraction,
    node_element_impedances,
    chain_impedances,
    frozen_impedances,
    handle_impedance,
    terminated_handle_impedance,
    handle_impedance_at,
    handle_admittance,
)
from .response import (  # noqa: F401
    ChainResponse,
    chain_response,
)
from .state_space import (  # noqa: F401
    chain_state_space,
    handle_state_space,
)
from .discretize import (  # noqa: F401
    discretize_zoh,
    theta_of,
    tustin_image,
    hold_factor,
    spring_damper,
    held_spring_damper,
    mass_damper_admittance,
    check_frequencies,
)
from .velocity_filter import (  # noqa: F401
    BACKWARD,
    FILTER_KINDS,
    FilterRealization,
    VelocityFilter,
    display_filter,
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
    "LIMITS",
    "Limit",
    "check_count",
    "check_simulation_size",
    "continued_fraction",
    "node_element_impedances",
    "chain_impedances",
    "frozen_impedances",
    "handle_impedance",
    "terminated_handle_impedance",
    "handle_impedance_at",
    "handle_admittance",
    "ChainResponse",
    "chain_response",
    "chain_state_space",
    "handle_state_space",
    "discretize_zoh",
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
    "BACKWARD",
    "FILTER_KINDS",
    "FilterRealization",
    "VelocityFilter",
    "display_filter",
]
