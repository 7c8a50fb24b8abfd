"""Two-port tools and the two displays of Adams, Moreyra & Hannaford.

Llewellyn's criterion and eta (eqs. 1-3), the impedance display (section III, eqs. 4-11) and the
admittance display (section IV, eqs. 12-22), their result records and design searches.
"""

from __future__ import annotations

from .llewellyn import (  # noqa: F401
    llewellyn,
    eta,
    convert,
    FORMS,
)
from .results import (  # noqa: F401
    Progress,
    Cancelled,
    TwoPort,
    BoundResult,
    StabilityResult,
    StiffnessDesign,
    StiffnessChart,
    DampingInterval,
    MassDesign,
    MassChart,
)
from .display_base import (  # noqa: F401
    DisplayBase,
    APPARENT_FREQUENCY,
    safe_ratio,
    FrequencyGrid,
)
from .impedance import (  # noqa: F401
    ImpedanceDisplay,
    coupling_impedance,
    kc_upper,
)
from .admittance import (  # noqa: F401
    AdmittanceDisplay,
    re_coupling_impedance,
    coupling_admittance,
)

__all__ = [
    "llewellyn",
    "eta",
    "convert",
    "FORMS",
    "Progress",
    "Cancelled",
    "TwoPort",
    "BoundResult",
    "StabilityResult",
    "StiffnessDesign",
    "StiffnessChart",
    "DampingInterval",
    "MassDesign",
    "MassChart",
    "DisplayBase",
    "APPARENT_FREQUENCY",
    "safe_ratio",
    "FrequencyGrid",
    "ImpedanceDisplay",
    "coupling_impedance",
    "kc_upper",
    "AdmittanceDisplay",
    "re_coupling_impedance",
    "coupling_admittance",
]
