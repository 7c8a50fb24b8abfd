"""Eom, Suh & Yi's wall controller: transparency index J, robust stability ||L||inf, the
design of B_c, the disturbance observer and the five-bar device.

:class:`WallDesign` (:mod:`.design`) is a facade over one object per concept: the plant ``P(s)``
(:mod:`.plant`, eq. 7), the loop realisations (:mod:`.loops`, :mod:`.discrete_loop`, eq. 9), the
closed-loop stability (:mod:`.stability`), the index ``J`` (:mod:`.index`, eq. 10-11), the
robustness peak ``||L||_inf`` (:mod:`.robustness`, eq. 13-17), the design search for ``B_c``
(:mod:`.search`, Fig. 8) and the step response (:mod:`.step`, Figs. 7, 10).

Loading is layered: the settings and result records (:mod:`.settings`), the holds and the
five-bar device are light and imported with the package; the wall design and the observer
(:mod:`.design`, :mod:`.observer` and what they import) are heavy and imported on first use of one
of their names (a PEP 562 module ``__getattr__``).  ``from analysis.transparency import
WallDesign``, ``__all__`` and ``dir()`` work as before; importing a settings record (e.g. for the
profile) does not load the design stack.
"""

from __future__ import annotations

import importlib

from .settings import (  # noqa: F401
    PLANTS,
    OBSERVER_PRESETS,
    ObserverSettings,
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
from .five_bar import (  # noqa: F401
    FiveBar,
    FIVE_BAR_PRESETS,
    five_bar_preset,
)

__all__ = [
    "PLANTS",
    "OBSERVER_PRESETS",
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
    "WallPlant",
    "AugmentedPlant",
    "LoopRealizations",
    "RationalLoop",
    "check_bc",
    "DiscreteLoop",
    "DiscreteLoopMatrices",
    "DiscreteModal",
    "SampledPlant",
    "ClosedLoopStability",
    "TransparencyIndex",
    "ErrorRealization",
    "RobustnessAnalysis",
    "DampingSearch",
    "StepSimulation",
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

#: Heavy names, imported from their module on first use.
_LAZY = {
    "WallDesign": ".design",
    "handle_admittance": ".design",
    "WallPlant": ".plant",
    "AugmentedPlant": ".plant",
    "LoopRealizations": ".loops",
    "RationalLoop": ".loops",
    "check_bc": ".loops",
    "DiscreteLoop": ".discrete_loop",
    "DiscreteLoopMatrices": ".discrete_loop",
    "DiscreteModal": ".discrete_loop",
    "SampledPlant": ".discrete_loop",
    "ClosedLoopStability": ".stability",
    "TransparencyIndex": ".index",
    "ErrorRealization": ".index",
    "RobustnessAnalysis": ".robustness",
    "DampingSearch": ".search",
    "StepSimulation": ".step",
    "DisturbanceObserver": ".observer",
    "ObserverResponse": ".observer",
    "TwoAxisObserver": ".observer",
    "CouplingResponse": ".observer",
    "TwoAxisStep": ".observer",
}


def __getattr__(name: str) -> object:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
