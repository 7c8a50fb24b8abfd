"""The :class:`Profile` record: a named device with its couplings, gains and optional sections.

Building one validates every field (raising :class:`~analysis.errors.ValidationError`);
reading and writing profiles as JSON is :mod:`analysis.profiles`.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.transparency.observer import ObserverSettings
from analysis.profiles.sections import SimulationSection
from analysis.transparency.settings import WallSettings

__all__ = ["DISPLAYS", "Profile"]

#: The two display types (section III impedance display, section IV admittance display).
DISPLAYS = ("impedance", "admittance")

# Profile field -> (JSON path, allowed range); used for validation and error translation.
_SCALARS: dict[str, tuple[str, str, bool]] = {
    # name: (json path, allowed text, strictly positive)
    "kc": ("$.impedance_coupling.stiffness", ">= 0 and finite (N/m)", False),
    "bc": ("$.impedance_coupling.damping", ">= 0 and finite (N s/m)", False),
    "mc": ("$.admittance_coupling.mass", "> 0 and finite (kg)", True),
    "bc_adm": ("$.admittance_coupling.damping", "> 0 and finite (N s/m)", True),
    "kp": ("$.pd_gains.stiffness", ">= 0 and finite (N/m)", False),
    "kd": ("$.pd_gains.damping", ">= 0 and finite (N s/m)", False),
}


def _is_real(value: object) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_)
    )


@dataclass(frozen=True)
class Profile:
    """A named device with its virtual coupling and PD wall settings.

    Parameters
    ----------
    name, notes:
        Display name and free text (sources, caveats).
    device:
        The device chain, sample period and analysis band.
    display:
        ``"impedance"`` or ``"admittance"``: which display type the GUI starts with.
    kc, bc:
        Impedance-display virtual coupling stiffness (N/m) and damping (N s/m), >= 0.
    mc, bc_adm:
        Admittance-display virtual coupling mass (kg) and damping (N s/m), > 0.
    kp, kd:
        PD position-loop stiffness (N/m) and damping (N s/m) of the admittance display
        (eq. 30), >= 0.
    wall, observer, simulation:
        Optional sections (schema 2 and 3): the wall-controller design (Eom, Suh & Yi),
        the disturbance observer, and the sampled-data simulator's options and scenario.
    """

    name: str
    notes: str
    device: Device
    display: str
    kc: float
    bc: float
    mc: float
    bc_adm: float
    kp: float
    kd: float
    wall: WallSettings | None = None
    observer: ObserverSettings | None = None
    simulation: SimulationSection | None = None

    def __post_init__(self) -> None:
        for field_name, cls in (("wall", WallSettings), ("observer", ObserverSettings),
                                ("simulation", SimulationSection)):
            value = getattr(self, field_name)
            if value is not None and not isinstance(value, cls):
                raise ValidationError(field_name, f"None or {cls.__name__}", value)
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValidationError("name", "a non-empty string", self.name)
        if not isinstance(self.notes, str):
            raise ValidationError("notes", "a string", self.notes)
        if not isinstance(self.device, Device):
            raise ValidationError("device", "a Device", self.device)
        if not isinstance(self.display, str) or self.display not in DISPLAYS:
            raise ValidationError("display", " or ".join(repr(d) for d in DISPLAYS), self.display)
        for field_name, (_, allowed, positive) in _SCALARS.items():
            value = getattr(self, field_name)
            if not _is_real(value):
                raise ValidationError(field_name, "a real number " + allowed, value)
            try:
                x = float(value)
            except OverflowError:
                raise ValidationError(field_name, allowed, value) from None
            if not math.isfinite(x) or (x <= 0 if positive else x < 0):
                raise ValidationError(field_name, allowed, x)
            object.__setattr__(self, field_name, x)

    def replace(self, **changes) -> Profile:
        """A copy with some fields changed, validated again (raises ValidationError)."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise TypeError(f"Profile has no field(s) {', '.join(sorted(unknown))}")
        return dataclasses.replace(self, **changes)
