"""The :class:`Profile` record: a named device with its couplings, gains and optional sections.

Building one validates every field (raising :class:`~analysis.errors.ValidationError`, by the
validators of :mod:`analysis.checks`); reading and writing profiles as JSON is
:mod:`analysis.profiles.io`.  This module imports only light modules (the device, the settings
records of :mod:`analysis.transparency.settings` and :mod:`analysis.sampled.scenarios`), never
the wall design or the simulator.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import NamedTuple

from analysis.chain.device import Device
from analysis.checks import Real, choice, string
from analysis.errors import ValidationError
from analysis.profiles.sections import SimulationSection
from analysis.transparency.settings import ObserverSettings, WallSettings

__all__ = ["DISPLAYS", "SCALAR_FIELDS", "ScalarField", "Profile"]

#: The two display types (section III impedance display, section IV admittance display).
DISPLAYS = ("impedance", "admittance")


class ScalarField(NamedTuple):
    """Where a scalar :class:`Profile` field lives in the JSON and which values it takes."""

    json_path: str
    allowed: str
    positive: bool  # > 0 (True) or >= 0 (False)

    @property
    def rule(self) -> Real:
        """The :class:`~analysis.checks.Real` rule of the field (errors carry the float value)."""
        return Real(lo=0.0, lo_open=self.positive, allowed=self.allowed, not_real="a real number " + self.allowed,
                    report_float=True)


#: Profile field -> its JSON path and allowed range; used for validation and error translation.
SCALAR_FIELDS: dict[str, ScalarField] = {
    "kc": ScalarField("$.impedance_coupling.stiffness", ">= 0 and finite (N/m)", False),
    "bc": ScalarField("$.impedance_coupling.damping", ">= 0 and finite (N s/m)", False),
    "mc": ScalarField("$.admittance_coupling.mass", "> 0 and finite (kg)", True),
    "bc_adm": ScalarField("$.admittance_coupling.damping", "> 0 and finite (N s/m)", True),
    "kp": ScalarField("$.pd_gains.stiffness", ">= 0 and finite (N/m)", False),
    "kd": ScalarField("$.pd_gains.damping", ">= 0 and finite (N s/m)", False),
}


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
        string("name", self.name, nonempty=True)
        string("notes", self.notes)
        if not isinstance(self.device, Device):
            raise ValidationError("device", "a Device", self.device)
        choice("display", self.display, DISPLAYS, allowed=" or ".join(repr(d) for d in DISPLAYS))
        for field_name, spec in SCALAR_FIELDS.items():
            object.__setattr__(self, field_name, spec.rule(field_name, getattr(self, field_name)))

    def replace(self, **changes) -> Profile:
        """A copy with some fields changed, validated again (raises ValidationError)."""
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise TypeError(f"Profile has no field(s) {', '.join(sorted(unknown))}")
        return dataclasses.replace(self, **changes)
