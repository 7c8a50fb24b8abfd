"""What each study computation depends on: frozen, hashable requests built from a profile.

A request holds exactly the inputs its computation reads, so two profiles that differ only in
a field it does not read give equal requests (a cache hit), and a change of a field it reads
gives a different one.  The computations of :mod:`analysis.study.compute` take a request (or a
profile, from which they build it with the request's ``of``); the GUI's compute graph keys its
cache on the request and passes it to the computation, so a key can never miss an input.

* :class:`StabilityRequest` -- eq. (9) or (21) at the coupling, on a :class:`DeviceRequest`;
* :class:`ChartRequest` -- the design chart's grid on a :class:`DeviceRequest`;
* :class:`LoopRequest` -- the exact sampled loop (device, filter, display, coupling, PD, delays),
  which :class:`MapRequest`, :class:`PointRequest`, :class:`ExactChartRequest`,
  :class:`ExactLimitRequest` and :class:`SimulationRequest` extend.

This module also holds what the simulation section means for the loop (:func:`simulation_section`,
:func:`delays`), since every loop request reads it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.profiles.model import Profile
from analysis.profiles.sections import SimulationSection
from analysis.sampled import SCENARIOS, Scenario, SimulationOptions, scenario
from analysis.study.displays import DeviceRequest, DisplayKind, display_kind, profile_filter

__all__ = ["StabilityRequest", "ChartRequest", "LoopRequest", "MapRequest", "PointRequest", "ExactChartRequest",
           "ExactLimitRequest", "SimulationRequest", "scenario_matches", "simulation_section", "delays"]

Range = tuple[float, float]


def scenario_matches(profile: Profile, sc: Scenario) -> bool:
    """False for the paper's worst case of the *other* display (e.g. ``impedance_worst_case``, a
    penalty wall, on an admittance display); any other scenario is the user's choice and matches.

    Parameters
    ----------
    profile : Profile
        The device profile (its display).
    sc : Scenario
        The scenario.

    Returns
    -------
    bool
        Whether the scenario fits the profile's display."""
    own = f"{display_kind(profile).name}_worst_case"
    return not (sc.name.endswith("_worst_case") and sc.name in SCENARIOS and sc.name != own)


def simulation_section(profile: Profile) -> SimulationSection:
    """What the Sampled-data tab simulates: the profile's simulation section, its scenario following
    the display (:func:`scenario_matches`: the other display's worst case becomes this display's,
    the options kept), or, without a section, ideal sensors and the paper's worst case for its display.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    SimulationSection
        The scenario and the simulation options."""
    own = scenario(f"{display_kind(profile).name}_worst_case")
    if profile.simulation is None:
        return SimulationSection(options=SimulationOptions(), scenario=own)
    if scenario_matches(profile, profile.simulation.scenario):
        return profile.simulation
    return SimulationSection(options=profile.simulation.options, scenario=own)


def delays(profile: Profile) -> tuple[int, bool]:
    """``(delay_samples, implementation_delay)`` of the profile's simulation section.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    tuple of (int, bool)
        The loop's delay in samples and its implementation delay (:func:`simulation_section`)."""
    o = simulation_section(profile).options
    return o.delay_samples, o.implementation_delay


@dataclass(frozen=True)
class StabilityRequest:
    """Eq. (9) or (21): the device model and the coupling gains (``(k_c, b_c)`` or ``(m_c, b_c)``).

    Attributes
    ----------
    model : DeviceRequest
        The device model of the profile's display.
    coupling : tuple of (float, float)
        ``(k_c [N/m], b_c [N·s/m])`` or ``(m_c [kg], b_c [N·s/m])``."""

    model: DeviceRequest
    coupling: tuple[float, float]

    @classmethod
    def of(cls, profile: Profile) -> StabilityRequest:
        """The request of ``profile`` at its display and coupling.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        StabilityRequest"""
        return cls(DeviceRequest.of(profile), display_kind(profile).coupling(profile))


@dataclass(frozen=True)
class ChartRequest:
    """The design chart: the device model and its grid (b_c for impedance, m_c for admittance).

    Attributes
    ----------
    model : DeviceRequest
        The device model of the chart's display.
    grid : tuple of (float, float)
        The range of the geometric grid: b_c [N·s/m] (impedance) or m_c [kg] (admittance).
    points : int
        Number of grid points."""

    model: DeviceRequest
    grid: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, kind: DisplayKind | str | None = None, *, bc_range: Range, mc_range: Range,
           points: int) -> ChartRequest:
        """The request of ``profile``'s display (or of ``kind``) on the grid of that display.

        Parameters
        ----------
        profile : Profile
            The device profile.
        kind : DisplayKind or str or None, optional
            The display type; ``None`` takes the profile's.
        bc_range : tuple of (float, float)
            The b_c range [N·s/m], used for the impedance display.
        mc_range : tuple of (float, float)
            The m_c range [kg], used for the admittance display.
        points : int
            Number of grid points.

        Returns
        -------
        ChartRequest"""
        model = DeviceRequest.of(profile, kind)
        grid = bc_range if model.pd is None else mc_range
        return cls(model, (float(grid[0]), float(grid[1])), int(points))


@dataclass(frozen=True)
class LoopRequest:
    """The exact sampled-data loop: device, velocity filter, display, coupling, PD gains, delays.

    Attributes
    ----------
    display : str
        The display type: ``"impedance"`` or ``"admittance"``.
    device : Device
        The device chain.
    velocity_filter : VelocityFilter or None
        The controller's velocity filter, ``None`` for the backward difference.
    coupling : tuple of (float, float) or None
        ``(k_c [N/m], b_c [N·s/m])`` or ``(m_c [kg], b_c [N·s/m])``; ``None`` where the
        computation sweeps it.
    pd : tuple of (float, float) or None
        The PD position-loop gains ``(k_p [N/m], k_d [N·s/m])`` (eq. 30); ``None`` where unused.
    delay_samples : int
        The loop's delay, in samples.
    implementation_delay : bool
        Whether the loop has the one-sample implementation delay."""

    display: str
    device: Device
    velocity_filter: VelocityFilter | None
    coupling: tuple[float, float] | None
    pd: tuple[float, float] | None
    delay_samples: int
    implementation_delay: bool

    @classmethod
    def of(cls, profile: Profile, *, coupling: bool = True, pd: bool = True) -> LoopRequest:
        """The loop of ``profile``.

        ``coupling=False`` leaves the coupling out; ``pd=False`` leaves the PD gains out on the
        impedance display (where the computation does not read them).

        Parameters
        ----------
        profile : Profile
            The device profile.
        coupling : bool, optional
            Include the coupling gains (default ``True``).
        pd : bool, optional
            Include the PD gains on the impedance display (default ``True``; the admittance
            display always has them).

        Returns
        -------
        LoopRequest"""
        kind = display_kind(profile)
        d, impl = delays(profile)
        gains = (float(profile.kp), float(profile.kd)) if pd or not kind.is_impedance else None
        return cls(kind.name, profile.device, profile_filter(profile), kind.coupling(profile) if coupling else None,
                   gains, int(d), bool(impl))

    @property
    def kind(self) -> DisplayKind:
        return display_kind(self.display)


@dataclass(frozen=True)
class MapRequest:
    """The sampled-data stability map: the loop and its two axes (names, ranges, points per axis).

    Attributes
    ----------
    loop : LoopRequest
        The loop, with its coupling and PD gains.
    x, y : str
        The axes' parameters (keys of :data:`~analysis.study.labels.PARAMETER_LABELS`).
    x_range, y_range : tuple of (float, float)
        The axes' ranges (geometric grids), in the parameters' units.
    points : int
        Grid points per axis."""

    loop: LoopRequest
    x: str
    x_range: Range
    y: str
    y_range: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, params: dict[str, Any]) -> MapRequest:
        """The map of ``profile`` with the map parameters ``params``.

        Parameters
        ----------
        profile : Profile
            The device profile.
        params : dict of str to Any
            ``x``, ``x_range``, ``y``, ``y_range`` and ``points``, as
            :func:`~analysis.study.compute.map_params` gives them.

        Returns
        -------
        MapRequest
            The request.

        Raises
        ------
        KeyError
            When ``params`` lacks one of its keys."""
        return cls(LoopRequest.of(profile), str(params["x"]), tuple(params["x_range"]), str(params["y"]),
                   tuple(params["y_range"]), int(params["points"]))


@dataclass(frozen=True)
class PointRequest:
    """The current design on a map of ``x`` and ``y`` (one point of :class:`MapRequest`).

    Attributes
    ----------
    loop : LoopRequest
        The loop, with its coupling and PD gains.
    x, y : str
        The map's parameters (keys of :data:`~analysis.study.labels.PARAMETER_LABELS`)."""

    loop: LoopRequest
    x: str
    y: str

    @classmethod
    def of(cls, profile: Profile, x: str, y: str) -> PointRequest:
        """The current design of ``profile`` on a map of ``x`` and ``y``.

        Parameters
        ----------
        profile : Profile
            The device profile.
        x : str
            The map's x parameter.
        y : str
            The map's y parameter.

        Returns
        -------
        PointRequest"""
        return cls(LoopRequest.of(profile), str(x), str(y))


@dataclass(frozen=True)
class ExactChartRequest:
    """The exact limit over b_c: the loop without its coupling (swept), its b_c grid.

    Attributes
    ----------
    loop : LoopRequest
        The loop without its coupling (and without the PD gains on the impedance display).
    bc_range : tuple of (float, float)
        The range of the geometric b_c grid [N·s/m].
    points : int
        Number of b_c grid points."""

    loop: LoopRequest
    bc_range: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, bc_range: Range, points: int) -> ExactChartRequest:
        """The exact limit chart of ``profile`` on the b_c grid.

        Parameters
        ----------
        profile : Profile
            The device profile.
        bc_range : tuple of (float, float)
            The b_c range [N·s/m].
        points : int
            Number of b_c grid points.

        Returns
        -------
        ExactChartRequest"""
        return cls(LoopRequest.of(profile, coupling=False, pd=False), (float(bc_range[0]), float(bc_range[1])),
                   int(points))


@dataclass(frozen=True)
class ExactLimitRequest:
    """The exact limit at one b_c (the coupling's damping; the other gain is what is found).

    Attributes
    ----------
    loop : LoopRequest
        The loop without its coupling (and without the PD gains on the impedance display).
    bc : float
        The coupling damping b_c [N·s/m]."""

    loop: LoopRequest
    bc: float

    @classmethod
    def of(cls, profile: Profile) -> ExactLimitRequest:
        """The exact limit of ``profile`` at its b_c.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        ExactLimitRequest"""
        return cls(LoopRequest.of(profile, coupling=False, pd=False), display_kind(profile).coupling(profile)[1])


@dataclass(frozen=True)
class SimulationRequest:
    """One simulator run: the loop and the simulation section (scenario and options) it runs.

    Attributes
    ----------
    loop : LoopRequest
        The loop, with its coupling and PD gains.
    section : SimulationSection
        The scenario and the options (:func:`simulation_section`)."""

    loop: LoopRequest
    section: SimulationSection

    @classmethod
    def of(cls, profile: Profile) -> SimulationRequest:
        """The simulator run of ``profile``.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        SimulationRequest"""
        return cls(LoopRequest.of(profile), simulation_section(profile))
