"""zwidth analysis package: two-port stability and Z-width of haptic displays.

Numerics only (numpy, scipy); it never imports Qt.  Implements Adams, Moreyra & Hannaford,
*Stability and Performance of Haptic Displays: Theory and Experiments*, and (in
``analysis.transparency``) Eom, Suh & Yi's wall-controller design.
"""

from analysis.twoport.admittance import AdmittanceDisplay
from analysis.chain.device import Device, damping_from_ratio, ratio_from_damping
from analysis.errors import ValidationError
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.twoport.results import (
    BoundResult,
    DampingInterval,
    MassChart,
    MassDesign,
    StabilityResult,
    StiffnessChart,
    StiffnessDesign,
    TwoPort,
)
from analysis.twoport.llewellyn import eta, llewellyn, convert

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
    from analysis.profiles.io import Profile, ProfileError, load_profile, save_profile  # noqa: F401

    __all__ += ["Profile", "ProfileError", "load_profile", "save_profile"]
except ImportError:  # pragma: no cover
    pass
