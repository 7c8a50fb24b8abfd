"""The two display types as objects: what each computes, and how it is labelled.

A profile names its display with a string (``"impedance"`` or ``"admittance"``).  This module
is the one place that maps the string to a :class:`DisplayKind`; everything else (the study,
the CLI, the report, the app's views) asks the object.  The impedance display is section III
of Adams, Moreyra & Hannaford (coupling ``Z_c`` of eq. 4, bound of eq. 9, range of eq. 11-12);
the admittance display is section IV (coupling ``Z_cA`` of eq. 16, bound of eq. 21, range of
eq. 23-24, PD position loop of eq. 30).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.profiles.model import Profile
from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.display_base import DisplayBase
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.sampled.results import CriticalChart, CriticalMassChart
from analysis.twoport.results import MassChart, StabilityResult, StiffnessChart

__all__ = ["Gain", "DisplayKind", "IMPEDANCE", "ADMITTANCE", "DISPLAY_KINDS", "display_kind", "profile_filter",
           "DeviceRequest"]


@dataclass(frozen=True)
class Gain:
    """A coupling gain: the profile field that holds it, its symbol, its label and its unit."""

    field: str
    symbol: str
    label: str
    unit: str

    def axis_label(self) -> str:
        """``"k_c (N/m)"``: the label of a plot axis."""
        return f"{self.symbol} ({self.unit.replace('·', ' ')})"


@dataclass(frozen=True, eq=False)
class DisplayKind:
    """One display type: its equations, gains, labels and how to evaluate it for a profile."""

    name: str
    title: str
    causality: str
    is_impedance: bool
    bound_equation: str
    range_equations: tuple[str, str]
    coupling_term_label: str
    margin_unit: str
    gains: tuple[Gain, Gain]
    chart_x: Gain
    chart_y: Gain
    exact_y: Gain
    exact_label: str
    chart_note: str
    map_axes: tuple[tuple[str, str], ...]
    design_keys: tuple[str, ...]
    map_ranges: dict[str, tuple[float, float]] = field(default_factory=dict)

    # -- the analysis objects --------------------------------------------------------------
    def build(self, profile: Profile) -> DisplayBase:
        """A fresh :class:`ImpedanceDisplay` or :class:`AdmittanceDisplay` of the profile's device,
        with the profile's velocity filter in the coupling (eq. 4's Z_c in eq. 9, K_d in eq. 21)."""
        return DeviceRequest.of(profile, self).build()

    def coupling(self, profile: Profile) -> tuple[float, float]:
        """The coupling gains in ``evaluate()`` order: ``(k_c, b_c)`` or ``(m_c, b_c)``."""
        a, b = self.gains
        return float(getattr(profile, a.field)), float(getattr(profile, b.field))

    def evaluate(self, profile: Profile, display: DisplayBase | None = None, refine: bool = True) -> StabilityResult:
        """Eq. (9) or (21) at the profile's coupling (``display``: a built one, to reuse its cache)."""
        disp = self.build(profile) if display is None else display
        return disp.evaluate(*self.coupling(profile), refine=refine)

    # -- points and labels -------------------------------------------------------------------
    def chart_point(self, profile: Profile) -> tuple[float, float]:
        """Where the profile's coupling sits on the design chart."""
        return float(getattr(profile, self.chart_x.field)), float(getattr(profile, self.chart_y.field))

    def edits_from_chart(self, x: float, y: float) -> dict[str, float]:
        """The profile fields a click at ``(x, y)`` on the design chart sets."""
        return {self.chart_x.field: x, self.chart_y.field: y}

    def exact_point(self, profile: Profile) -> tuple[float, float]:
        """Where the profile's coupling sits on the exact limit chart (x is b_c)."""
        return float(getattr(profile, self.gains[1].field)), float(getattr(profile, self.exact_y.field))

    def range_labels(self) -> tuple[str, str]:
        """Legend labels of the impedance range plot, with their equations."""
        lo, hi = self.range_equations
        return f"|Z_min| (eq. {lo})", f"|Z_max| (eq. {hi})"

    def bound_label(self) -> str:
        """Legend label of the bound: ``"bound (eq. 9)"`` or ``"bound (eq. 21)"``."""
        return f"bound (eq. {self.bound_equation})"

    @property
    def design_chart_type(self) -> type:
        """The analysis chart record of this display: :class:`StiffnessChart` or :class:`MassChart`."""
        return StiffnessChart if self.is_impedance else MassChart

    @property
    def exact_chart_type(self) -> type:
        """The exact sampled-data chart record: :class:`CriticalChart` or :class:`CriticalMassChart`."""
        return CriticalChart if self.is_impedance else CriticalMassChart

    def describe(self) -> dict[str, Any]:
        return {"name": self.name, "title": self.title, "causality": self.causality}


IMPEDANCE = DisplayKind(
    name="impedance", title="Impedance display", causality="force out, position in", is_impedance=True,
    bound_equation="9", range_equations=("11", "12"), coupling_term_label="Re(1/Z_c)", margin_unit="m/(N·s)",
    gains=(Gain("kc", "k_c", "coupling stiffness", "N/m"), Gain("bc", "b_c", "coupling damping", "N·s/m")),
    chart_x=Gain("bc", "b_c", "coupling damping", "N·s/m"), chart_y=Gain("kc", "k_c", "coupling stiffness", "N/m"),
    exact_y=Gain("kc", "k_c", "coupling stiffness", "N/m"), exact_label="largest stable k_c",
    chart_note="two-port bound (eq. 9)", design_keys=("bc", "kc_max", "kc_max_frequency"),
    map_axes=(("kc", "kobj"), ("kc", "bc"), ("kc", "grasp_mass"), ("kc", "grasp_stiffness")),
    map_ranges={"kc": (1e3, 1e6), "kobj": (1e3, 1e7), "bc": (1.0, 1e4), "grasp_mass": (1e-2, 10.0),
                "grasp_stiffness": (10.0, 1e6)},
)

ADMITTANCE = DisplayKind(
    name="admittance", title="Admittance display", causality="position out, force in", is_impedance=False,
    bound_equation="21", range_equations=("23", "24"), coupling_term_label="Re(Z_cA)", margin_unit="N·s/m",
    gains=(Gain("mc", "m_c", "coupling mass", "kg"), Gain("bc_adm", "b_c", "coupling damping", "N·s/m")),
    chart_x=Gain("mc", "m_c", "coupling mass", "kg"), chart_y=Gain("bc_adm", "b_c", "coupling damping", "N·s/m"),
    exact_y=Gain("mc", "m_c", "coupling mass", "kg"), exact_label="smallest stable m_c",
    chart_note="two-port b_c edges (eq. 21)",
    design_keys=("mc", "bc_low", "bc_low_frequency", "bc_high", "bc_high_frequency", "min_mc", "min_mc_bc",
                 "min_mc_frequency"),
    map_axes=(("mc", "bc"), ("mc", "grasp_mass"), ("mc", "grasp_stiffness"), ("mc", "kd")),
    map_ranges={"mc": (1e-2, 1e2), "bc": (10.0, 1e4), "grasp_mass": (0.1, 10.0), "grasp_stiffness": (1e2, 1e6),
                "kd": (1.0, 1e4)},
)

#: the one mapping from the profile's display string to its object
DISPLAY_KINDS: dict[str, DisplayKind] = {IMPEDANCE.name: IMPEDANCE, ADMITTANCE.name: ADMITTANCE}


def display_kind(x: DisplayKind | Profile | StabilityResult | str) -> DisplayKind:
    """The :class:`DisplayKind` of a profile, a stability result, or a display name."""
    if isinstance(x, DisplayKind):
        return x
    name = x if isinstance(x, str) else x.display
    try:
        return DISPLAY_KINDS[name]
    except KeyError:
        raise ValueError(f"display must be 'impedance' or 'admittance', got {name!r}") from None


def profile_filter(profile: Profile) -> VelocityFilter | None:
    """The profile's velocity filter (its ``controller`` section), ``None`` for the backward
    difference: every analysis then runs its filter-free code path, bit for bit as before."""
    sec = profile.controller
    if sec is None or sec.velocity_filter.is_backward:
        return None
    return sec.velocity_filter


@dataclass(frozen=True)
class DeviceRequest:
    """What a display object (the device model) depends on: the display type, the device, the
    velocity filter and, for the admittance display only, the PD loop's gains (eq. 30).

    The coupling gains are not part of it: moving one reuses the display object and its cache.
    Equal requests build equal display objects (a cache key)."""

    display: str
    device: Device
    velocity_filter: VelocityFilter | None
    pd: tuple[float, float] | None = None

    @classmethod
    def of(cls, profile: Profile, kind: DisplayKind | str | None = None) -> DeviceRequest:
        """The request of ``profile``'s display (or of ``kind``)."""
        k = display_kind(profile if kind is None else kind)
        pd = None if k.is_impedance else (float(profile.kp), float(profile.kd))
        return cls(k.name, profile.device, profile_filter(profile), pd)

    @property
    def kind(self) -> DisplayKind:
        return display_kind(self.display)

    def build(self) -> DisplayBase:
        """A fresh :class:`ImpedanceDisplay` or :class:`AdmittanceDisplay` of the device, with the
        velocity filter in the coupling (eq. 4's Z_c in eq. 9, K_d in eq. 21)."""
        if self.pd is None:
            return ImpedanceDisplay(self.device, velocity_filter=self.velocity_filter)
        return AdmittanceDisplay(self.device, *self.pd, velocity_filter=self.velocity_filter)
