"""Eom, Suh & Yi's wall controller: transparency index J, robust stability ||L||inf, the
design of B_c, the disturbance observer and the five-bar device.
"""

from __future__ import annotations

from .settings import (  # noqa: F401
    PLANTS,
    WallSettings,
    IndexResult,
    RobustnessPeak,
    OptimalDamping,
    TradeoffCurves,
    StepResponse,
)
from .holds import (  # noqa: F401
    HOLDS,
    RATIONAL_HOLDS,
    hold_response,
    hold_state_space,
)
from .design import (  # noqa: F401
    WallDesign,
    handle_admittance,
)
from .observer import (  # noqa: F401
    ObserverSettings,
    DisturbanceObserver,
    ObserverResponse,
    TwoAxisObserver,
    CouplingResponse,
    TwoAxisStep,
)
from .five_bar import (  # noqa: F401
    FiveBar,
    FIVE_BAR_PRESETS,
    five_bar_preset,
)

__all__ = [
    "PLANTS",
    "WallSettings",
    "IndexResult",
    "RobustnessPeak",
    "OptimalDamping",
    "TradeoffCurves",
    "StepResponse",
    "HOLDS",
    "RATIONAL_HOLDS",
    "hold_response",
    "hold_state_space",
    "WallDesign",
    "handle_admittance",
    "ObserverSettings",
    "DisturbanceObserver",
    "ObserverResponse",
    "TwoAxisObserver",
    "CouplingResponse",
    "TwoAxisStep",
    "FiveBar",
    "FIVE_BAR_PRESETS",
    "five_bar_preset",
]
