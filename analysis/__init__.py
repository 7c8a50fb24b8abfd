"""zwidth analysis package: two-port stability and Z-width of haptic displays.

Numerics only (numpy, scipy); it never imports Qt.  Implements Adams, Moreyra & Hannaford,
*Stability and Performance of Haptic Displays: Theory and Experiments*, and (in
``analysis.transparency``) Eom, Suh & Yi's wall-controller design.
"""

from .admittance import AdmittanceDisplay
from .device import Device, damping_from_ratio, ratio_from_damping
from .errors import ValidationError
from .impedance import ImpedanceDisplay
from .results import (
    BoundResult,
    DampingInterval,
    MassChart,
    MassDesign,
    StabilityResult,
    StiffnessChart,
    StiffnessDesign,
    TwoPort,
)
from .twoport import eta, llewellyn, convert

__all__ = [
    "AdmittanceDisplay",
    "BoundResult",
    "DampingInterval",
    "Device",
    "ImpedanceDisplay",
    "MassChart",
    "MassDesign",
    "StabilityResult",
    "StiffnessChart",
    "StiffnessDesign",
    "TwoPort",
    "ValidationError",
    "convert",
    "damping_from_ratio",
    "eta",
    "llewellyn",
    "ratio_from_damping",
]

try:  # profiles are written alongside; re-export when present
    from .profiles import Profile, ProfileError, load_profile, save_profile  # noqa: F401

    __all__ += ["Profile", "ProfileError", "load_profile", "save_profile"]
except ImportError:  # pragma: no cover
    pass
