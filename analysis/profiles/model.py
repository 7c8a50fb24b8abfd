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
from analysis.chain.limits import Limit, check_simulation_size
from analysis.checks import Real, choice, string
from analysis.errors import ValidationError
from analysis.profiles.controller import ControllerSection
from analysis.profiles.identification import IdentificationSection, check_against_device
from analysis.profiles.multidof import MultiDofSection
from analysis.profiles.renderable import RenderableSection
from analysis.profiles.schema import DISPLAYS, FIELDS_BY_NAME, GAIN_NAMES, PER_MASS_LISTS, edit_per_mass, per_mass_values
from analysis.profiles.sections import SimulationSection
from analysis.transparency.settings import ObserverSettings, WallSettings

__all__ = ["DISPLAYS", "SCALAR_FIELDS", "ScalarField", "Profile", "per_mass_changes"]



class ScalarField(NamedTuple):
    """Where a scalar :class:`Profile` field lives in the JSON and its physical range.

    Parameters
    ----------
    json_path : str
        The field's JSON path in a profile file, e.g. ``"$.impedance_coupling.stiffness"``.
    limit : Limit
        Its physical range and unit (:data:`analysis.chain.limits.LIMITS`).
    """

    json_path: str
    limit: Limit

    @property
    def allowed(self) -> str:
        """The allowed range as shown in errors (the limit's text)."""
        return self.limit.text

    @property
    def positive(self) -> bool:
        """True: > 0; False: >= 0."""
        return self.limit.positive

    @property
    def rule(self) -> Real:
        """The :class:`~analysis.checks.Real` rule of the field (errors carry the float value)."""
        return self.limit.rule


#: Profile field -> its JSON path and physical range (:data:`analysis.chain.limits.LIMITS`), derived
#: from the schema's declarations (:data:`analysis.profiles.schema.SCHEMA`).
SCALAR_FIELDS: dict[str, ScalarField] = {name: ScalarField(FIELDS_BY_NAME[name][0], FIELDS_BY_NAME[name][1].rule)
                                         for name in GAIN_NAMES}


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
    identification:
        Optional section (schema 4): parameter intervals and the embedded measurements
        (:mod:`analysis.profiles.identification`).
    controller:
        Optional section (schema 5): the velocity filter, the Z-width region's B range and a
        trials file (:mod:`analysis.profiles.controller`); ``None`` is the backward difference.
    renderable:
        Optional section (schema 6): the rendered environment, its acceleration estimate, the
        qualities' settings and the renderable space's grid (:mod:`analysis.profiles.renderable`).
    multidof:
        Optional section (schema 7): a multi-DOF linkage, its handle position, the wall and the
        workspace map's grid (:mod:`analysis.profiles.multidof`).
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
    identification: IdentificationSection | None = None
    controller: ControllerSection | None = None
    renderable: RenderableSection | None = None
    multidof: MultiDofSection | None = None

    def __post_init__(self) -> None:
        for field_name, cls in (("wall", WallSettings), ("observer", ObserverSettings),
                                ("simulation", SimulationSection),
                                ("identification", IdentificationSection),
                                ("controller", ControllerSection), ("renderable", RenderableSection),
                                ("multidof", MultiDofSection)):
            value = getattr(self, field_name)
            if value is not None and not isinstance(value, cls):
                raise ValidationError(field_name, f"None or {cls.__name__}", value)
        string("name", self.name, nonempty=True)
        string("notes", self.notes)
        if not isinstance(self.device, Device):
            raise ValidationError("device", "a Device", self.device)
        choice("display", self.display, DISPLAYS, allowed=" or ".join(repr(d) for d in DISPLAYS))
        self._check_per_mass()
        if self.identification is not None:
            check_against_device(self.identification, self.device.n)
        if self.controller is not None:  # the filter's cut-off against this device's Nyquist frequency
            self.controller.check(self.device.sample_time)
        if self.renderable is not None:  # the band and the low-pass against this device's Nyquist frequency
            self.renderable.check(self.device.sample_time)
        for field_name, spec in SCALAR_FIELDS.items():
            object.__setattr__(self, field_name, spec.rule(field_name, getattr(self, field_name)))
        if self.simulation is not None:  # the work the saved scenario asks for, before any allocation
            opt = self.simulation.options
            substeps = opt.substeps if any(f > 0 for f in opt.friction) else 1
            check_simulation_size(self.simulation.scenario.duration, self.device.sample_time, substeps,
                                  self.device.n)

    def _check_per_mass(self) -> None:
        """Every list indexed by mass (:data:`~analysis.profiles.schema.PER_MASS_LISTS`) holds one value
        per mass of the device, or none where the schema allows an empty list; the error names the
        list's field, which :func:`analysis.profiles.fields.error_at` puts at its JSON path."""
        held = per_mass_values(self)
        for path, node in PER_MASS_LISTS:
            values = held.get(path)
            if values is not None and len(values) != self.device.n and not (node.empty_ok and not values):
                raise ValidationError(str(node.name), node.expected(self.device.n), list(values))

    def replace(self, **changes) -> Profile:
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New values of fields, by name (``device``, ``kc``, ``controller``, ...).

        Returns
        -------
        Profile
            The new profile.

        Raises
        ------
        TypeError
            When a name is not a field of :class:`Profile`.
        ValidationError
            When a changed value is invalid (out of its range, of the wrong type, or
            inconsistent with the device).
        """
        unknown = set(changes) - {f.name for f in dataclasses.fields(self)}
        if unknown:
            raise TypeError(f"Profile has no field(s) {', '.join(sorted(unknown))}")
        return dataclasses.replace(self, **changes)


def per_mass_changes(profile: Profile, n: int, removed: int | None = None) -> dict[str, object]:
    """The section changes that keep every list indexed by mass
    (:data:`~analysis.profiles.schema.PER_MASS_LISTS`: the simulator's ``friction``) at one value per
    mass when ``profile``'s device becomes ``n`` masses.

    Apply them with the new device (``profile.replace(device=new, **per_mass_changes(...))``): a
    profile refuses a per-mass list whose length differs from the device's masses.

    Parameters
    ----------
    profile : Profile
        The profile before the chain changes.
    n : int
        The new number of masses.
    removed : int or None
        The (0-based) mass removed; ``None``: masses added at the actuator end (with a 0 each: no
        friction) or dropped from it.

    Returns
    -------
    dict
        Profile field -> its new value (``{"simulation": SimulationSection}``) with each resized
        list, or ``{}`` when nothing changes (an empty list stays empty: none).
    """
    def resize(values: tuple[float, ...]) -> tuple[float, ...]:
        if not values or len(values) == n:
            return values
        kept = list(values)
        if removed is not None and 0 <= removed < len(kept):
            del kept[removed]
        return tuple((kept + [0.0] * n)[:n])

    return edit_per_mass(profile, resize)[0]
