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
    """A coupling gain: the profile field that holds it, its symbol, its label and its unit.

    Attributes
    ----------
    field : str
        The :class:`~analysis.profiles.model.Profile` field that holds it, e.g. ``"kc"``.
    symbol : str
        Plain-text symbol, e.g. ``"k_c"``.
    label : str
        Name for people, e.g. ``"coupling stiffness"``.
    unit : str
        Unit, e.g. ``"N/m"``."""

    field: str
    symbol: str
    label: str
    unit: str

    def axis_label(self) -> str:
        """``"k_c (N/m)"``: the label of a plot axis.

        Returns
        -------
        str
            The symbol and the unit in parentheses (a space for the unit's ``·``)."""
        return f"{self.symbol} ({self.unit.replace('·', ' ')})"


@dataclass(frozen=True, eq=False)
class DisplayKind:
    """One display type: its equations, gains, labels and how to evaluate it for a profile.

    Attributes
    ----------
    name : str
        The profile's display string: ``"impedance"`` or ``"admittance"``.
    title : str
        Title for people, e.g. ``"Impedance display"``.
    causality : str
        What the device outputs and takes in, e.g. ``"force out, position in"``.
    is_impedance : bool
        ``True`` for the impedance display (section III), ``False`` for the admittance display
        (section IV).
    bound_equation : str
        Number of the paper's bound equation: ``"9"`` or ``"21"``.
    range_equations : tuple of (str, str)
        Numbers of the equations of ``|Z_min|`` and ``|Z_max|``: ``("11", "12")`` or
        ``("23", "24")``.
    coupling_term_label : str
        Label of the coupling term the bound is compared with: ``"Re(1/Z_c)"`` or ``"Re(Z_cA)"``.
    margin_unit : str
        Unit of the bound's margin (eq. 9 or 21): ``"m/(N·s)"`` or ``"N·s/m"``.
    gains : tuple of (Gain, Gain)
        The coupling gains in :meth:`evaluate` order: ``(k_c, b_c)`` or ``(m_c, b_c)``.
    chart_x, chart_y : Gain
        The gains on the design chart's x and y axes.
    exact_y : Gain
        The gain on the exact limit chart's y axis (its x axis is ``b_c``).
    exact_label : str
        Legend label of the exact limit, e.g. ``"largest stable k_c"``.
    chart_note : str
        Note on the design chart naming the two-port bound it draws.
    map_axes : tuple of (str, str)
        The stability map's parameter pairs (x, y), keys of
        :data:`~analysis.study.labels.PARAMETER_LABELS`.
    design_keys : tuple of str
        Keys of the design quantities (:data:`~analysis.study.quantities.QUANTITIES`) this
        display reports.
    map_ranges : dict of str to (float, float)
        Default sweep range (low, high) of each map parameter, in its unit."""

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
        """A fresh :class:`ImpedanceDisplay` or :class:`AdmittanceDisplay` of the profile's device.

        The profile's velocity filter is in the coupling (eq. 4's Z_c in eq. 9, K_d in eq. 21).

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        DisplayBase
            The display object of this type (see :meth:`DeviceRequest.build`)."""
        return DeviceRequest.of(profile, self).build()

    def coupling(self, profile: Profile) -> tuple[float, float]:
        """The coupling gains in ``evaluate()`` order: ``(k_c, b_c)`` or ``(m_c, b_c)``.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        tuple of (float, float)
            ``(k_c [N/m], b_c [N·s/m])`` or ``(m_c [kg], b_c [N·s/m])``."""
        a, b = self.gains
        return float(getattr(profile, a.field)), float(getattr(profile, b.field))

    def evaluate(self, profile: Profile, display: DisplayBase | None = None, refine: bool = True) -> StabilityResult:
        """Eq. (9) or (21) at the profile's coupling.

        Parameters
        ----------
        profile : Profile
            The device profile.
        display : DisplayBase or None, optional
            A built display object of the profile (:meth:`build`), to reuse its cache; ``None``
            builds a fresh one.
        refine : bool, optional
            Refine the worst margin between grid points (default ``True``).

        Returns
        -------
        StabilityResult
            The bound, the coupling term and their margins over the frequency grid."""
        disp = self.build(profile) if display is None else display
        return disp.evaluate(*self.coupling(profile), refine=refine)

    # -- points and labels -------------------------------------------------------------------
    def chart_point(self, profile: Profile) -> tuple[float, float]:
        """Where the profile's coupling sits on the design chart.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        tuple of (float, float)
            The profile's values of :attr:`chart_x` and :attr:`chart_y`, in their units."""
        return float(getattr(profile, self.chart_x.field)), float(getattr(profile, self.chart_y.field))

    def edits_from_chart(self, x: float, y: float) -> dict[str, float]:
        """The profile fields a click at ``(x, y)`` on the design chart sets.

        Parameters
        ----------
        x : float
            Value of :attr:`chart_x`, in its unit.
        y : float
            Value of :attr:`chart_y`, in its unit.

        Returns
        -------
        dict of str to float
            Profile field -> new value."""
        return {self.chart_x.field: x, self.chart_y.field: y}

    def exact_point(self, profile: Profile) -> tuple[float, float]:
        """Where the profile's coupling sits on the exact limit chart (x is b_c).

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        tuple of (float, float)
            ``(b_c [N·s/m], y)`` with y the profile's value of :attr:`exact_y`."""
        return float(getattr(profile, self.gains[1].field)), float(getattr(profile, self.exact_y.field))

    def range_labels(self) -> tuple[str, str]:
        """Legend labels of the impedance range plot, with their equations.

        Returns
        -------
        tuple of (str, str)
            The labels of ``|Z_min|`` and ``|Z_max|``, e.g. ``"|Z_min| (eq. 11)"``."""
        lo, hi = self.range_equations
        return f"|Z_min| (eq. {lo})", f"|Z_max| (eq. {hi})"

    def bound_label(self) -> str:
        """Legend label of the bound: ``"bound (eq. 9)"`` or ``"bound (eq. 21)"``.

        Returns
        -------
        str
            The label."""
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
        """The display type as plain data (for JSON outputs).

        Returns
        -------
        dict of str to Any
            ``{"name": ..., "title": ..., "causality": ...}``."""
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
    """The :class:`DisplayKind` of a profile, a stability result, or a display name.

    Parameters
    ----------
    x : DisplayKind or Profile or StabilityResult or str
        A display kind (returned as it is), an object with a ``display`` string, or the string
        itself.

    Returns
    -------
    DisplayKind
        :data:`IMPEDANCE` or :data:`ADMITTANCE`.

    Raises
    ------
    ValueError
        When the display is neither ``"impedance"`` nor ``"admittance"``."""
    if isinstance(x, DisplayKind):
        return x
    name = x if isinstance(x, str) else x.display
    try:
        return DISPLAY_KINDS[name]
    except KeyError:
        raise ValueError(f"display must be 'impedance' or 'admittance', got {name!r}") from None


def profile_filter(profile: Profile) -> VelocityFilter | None:
    """The profile's velocity filter (its ``controller`` section), ``None`` for the backward difference.

    With ``None`` every analysis runs its filter-free code path, bit for bit as before.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    VelocityFilter or None
        The section's filter, or ``None`` when the profile has no ``controller`` section or its
        filter is the backward difference."""
    sec = profile.controller
    if sec is None or sec.velocity_filter.is_backward:
        return None
    return sec.velocity_filter


@dataclass(frozen=True)
class DeviceRequest:
    """What a display object (the device model) depends on: the display type, the device, the
    velocity filter and, for the admittance display only, the PD loop's gains (eq. 30).

    The coupling gains are not part of it: moving one reuses the display object and its cache.
    Equal requests build equal display objects (a cache key).

    Attributes
    ----------
    display : str
        The display type: ``"impedance"`` or ``"admittance"``.
    device : Device
        The device chain.
    velocity_filter : VelocityFilter or None
        The controller's velocity filter, ``None`` for the backward difference
        (:func:`profile_filter`).
    pd : tuple of (float, float) or None
        The admittance display's PD position-loop gains ``(k_p [N/m], k_d [N·s/m])`` (eq. 30);
        ``None`` for the impedance display."""

    display: str
    device: Device
    velocity_filter: VelocityFilter | None
    pd: tuple[float, float] | None = None

    @classmethod
    def of(cls, profile: Profile, kind: DisplayKind | str | None = None) -> DeviceRequest:
        """The request of ``profile``'s display (or of ``kind``).

        Parameters
        ----------
        profile : Profile
            The device profile.
        kind : DisplayKind or str or None, optional
            The display type; ``None`` takes the profile's.

        Returns
        -------
        DeviceRequest
            The request."""
        k = display_kind(profile if kind is None else kind)
        pd = None if k.is_impedance else (float(profile.kp), float(profile.kd))
        return cls(k.name, profile.device, profile_filter(profile), pd)

    @property
    def kind(self) -> DisplayKind:
        return display_kind(self.display)

    def build(self) -> DisplayBase:
        """A fresh :class:`ImpedanceDisplay` or :class:`AdmittanceDisplay` of the device.

        The velocity filter is in the coupling (eq. 4's Z_c in eq. 9, K_d in eq. 21).

        Returns
        -------
        DisplayBase
            The display object (an :class:`AdmittanceDisplay` with the PD gains when :attr:`pd`
            is set)."""
        if self.pd is None:
            return ImpedanceDisplay(self.device, velocity_filter=self.velocity_filter)
        return AdmittanceDisplay(self.device, *self.pd, velocity_filter=self.velocity_filter)
