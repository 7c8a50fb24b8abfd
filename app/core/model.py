"""The one model of the GUI: a :class:`ProfileModel` holding the current ``Profile``.

Every parameter change goes through :meth:`ProfileModel.set` (normally called by an undo command),
which validates it with the analysis core's own rules (``Profile.replace`` / ``Device.replace``) and
emits :attr:`ProfileModel.fieldChanged` with the name of the field.  Loading a whole profile emits
:attr:`ProfileModel.profileReplaced` instead.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from app import qt_compat  # noqa: F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import QObject, Signal

from analysis import Device
from analysis.profiles.io import Profile

__all__ = ["DEVICE_FIELDS", "PROFILE_FIELDS", "SECTION_FIELDS", "VECTOR_FIELDS", "ALL_FIELDS", "ProfileModel"]

#: Fields of the device (``Device.replace`` keywords); ``"device"`` replaces the whole chain.
DEVICE_FIELDS: tuple[str, ...] = (
    "masses",
    "stiffnesses",
    "dampings",
    "ground_dampings",
    "sensor_element",
    "sample_time",
    "band_min",
    "device",
)
#: Fields of the profile itself (``Profile.replace`` keywords).
PROFILE_FIELDS: tuple[str, ...] = ("name", "notes", "display", "kc", "bc", "mc", "bc_adm", "kp", "kd",
                                   "wall", "observer", "simulation", "identification", "controller", "renderable",
                                   "multidof")
#: Optional profile sections (schema 2 to 7); each is replaced as a whole settings object
#: (``WallSettings``, ``ObserverSettings``, ``SimulationSection``, ``IdentificationSection``,
#: ``ControllerSection``, ``RenderableSection``, ``MultiDofSection``) or ``None``.
SECTION_FIELDS: tuple[str, ...] = ("wall", "observer", "simulation", "identification", "controller", "renderable",
                                   "multidof")
VECTOR_FIELDS: tuple[str, ...] = ("masses", "stiffnesses", "dampings", "ground_dampings")
ALL_FIELDS: tuple[str, ...] = DEVICE_FIELDS + PROFILE_FIELDS


def _same(a: object, b: object) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(np.asarray(a), np.asarray(b))
    return a == b


class ProfileModel(QObject):
    """Holds one :class:`Profile` and says which field changed."""

    fieldChanged = Signal(str)
    profileReplaced = Signal()

    def __init__(self, profile: Profile, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._profile = profile

    @property
    def profile(self) -> Profile:
        return self._profile

    @property
    def device(self) -> Device:
        return self._profile.device

    def get(self, field: str) -> object:
        """The current value of ``field`` (a device field, a profile field or ``"device"``)."""
        if field == "device":
            return self._profile.device
        if field in DEVICE_FIELDS:
            return getattr(self._profile.device, field)
        if field in PROFILE_FIELDS:
            return getattr(self._profile, field)
        raise KeyError(field)

    def validated(self, changes: Mapping[str, object]) -> Profile:
        """The profile with ``changes`` applied; raises ``ValidationError`` (nothing is changed)."""
        device_changes = {k: v for k, v in changes.items() if k in DEVICE_FIELDS and k != "device"}
        profile_changes = {k: v for k, v in changes.items() if k in PROFILE_FIELDS}
        unknown = set(changes) - set(ALL_FIELDS)
        if unknown:
            raise KeyError(", ".join(sorted(unknown)))
        device = changes.get("device", self._profile.device)
        if not isinstance(device, Device):
            raise TypeError("device must be an analysis.Device")
        if device_changes:
            device = device.replace(**device_changes)
        if device is not self._profile.device:
            profile_changes["device"] = device
        if not profile_changes:
            return self._profile
        return self._profile.replace(**profile_changes)

    def set(self, field: str, value: object) -> None:
        """Validate and apply one change; emits ``fieldChanged(field)`` if the value changed."""
        self.set_many({field: value})

    def set_many(self, changes: Mapping[str, object]) -> None:
        """Validate and apply several changes at once (all or nothing)."""
        changed = [f for f, v in changes.items() if not _same(self.get(f), v)]
        if not changed:
            return
        self._profile = self.validated({f: changes[f] for f in changed})
        for f in changed:
            self.fieldChanged.emit(f)

    def replace_profile(self, profile: Profile) -> None:
        """Load a whole new profile (file open, preset, new)."""
        if not isinstance(profile, Profile):
            raise TypeError("profile must be an analysis.profiles.Profile")
        self._profile = profile
        self.profileReplaced.emit()
