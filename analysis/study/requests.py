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
    penalty wall, on an admittance display); any other scenario is the user's choice and matches."""
    own = f"{display_kind(profile).name}_worst_case"
    return not (sc.name.endswith("_worst_case") and sc.name in SCENARIOS and sc.name != own)


def simulation_section(profile: Profile) -> SimulationSection:
    """What the Sampled-data tab simulates: the profile's simulation section, its scenario following
    the display (:func:`scenario_matches`: the other display's worst case becomes this display's,
    the options kept), or, without a section, ideal sensors and the paper's worst case for its display."""
    own = scenario(f"{display_kind(profile).name}_worst_case")
    if profile.simulation is None:
        return SimulationSection(options=SimulationOptions(), scenario=own)
    if scenario_matches(profile, profile.simulation.scenario):
        return profile.simulation
    return SimulationSection(options=profile.simulation.options, scenario=own)


def delays(profile: Profile) -> tuple[int, bool]:
    """``(delay_samples, implementation_delay)`` of the profile's simulation section."""
    o = simulation_section(profile).options
    return o.delay_samples, o.implementation_delay


@dataclass(frozen=True)
class StabilityRequest:
    """Eq. (9) or (21): the device model and the coupling gains (``(k_c, b_c)`` or ``(m_c, b_c)``)."""

    model: DeviceRequest
    coupling: tuple[float, float]

    @classmethod
    def of(cls, profile: Profile) -> StabilityRequest:
        return cls(DeviceRequest.of(profile), display_kind(profile).coupling(profile))


@dataclass(frozen=True)
class ChartRequest:
    """The design chart: the device model and its grid (b_c for impedance, m_c for admittance)."""

    model: DeviceRequest
    grid: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, kind: DisplayKind | str | None = None, *, bc_range: Range, mc_range: Range,
           points: int) -> ChartRequest:
        model = DeviceRequest.of(profile, kind)
        grid = bc_range if model.pd is None else mc_range
        return cls(model, (float(grid[0]), float(grid[1])), int(points))


@dataclass(frozen=True)
class LoopRequest:
    """The exact sampled-data loop: device, velocity filter, display, coupling (``None`` where the
    computation sweeps it), PD gains (``None`` where unused) and the delays."""

    display: str
    device: Device
    velocity_filter: VelocityFilter | None
    coupling: tuple[float, float] | None
    pd: tuple[float, float] | None
    delay_samples: int
    implementation_delay: bool

    @classmethod
    def of(cls, profile: Profile, *, coupling: bool = True, pd: bool = True) -> LoopRequest:
        """``coupling=False`` leaves the coupling out; ``pd=False`` leaves the PD gains out on the
        impedance display (where the computation does not read them)."""
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
    """The sampled-data stability map: the loop and its two axes (names, ranges, points per axis)."""

    loop: LoopRequest
    x: str
    x_range: Range
    y: str
    y_range: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, params: dict[str, Any]) -> MapRequest:
        return cls(LoopRequest.of(profile), str(params["x"]), tuple(params["x_range"]), str(params["y"]),
                   tuple(params["y_range"]), int(params["points"]))


@dataclass(frozen=True)
class PointRequest:
    """The current design on a map of ``x`` and ``y`` (one point of :class:`MapRequest`)."""

    loop: LoopRequest
    x: str
    y: str

    @classmethod
    def of(cls, profile: Profile, x: str, y: str) -> PointRequest:
        return cls(LoopRequest.of(profile), str(x), str(y))


@dataclass(frozen=True)
class ExactChartRequest:
    """The exact limit over b_c: the loop without its coupling (swept), its b_c grid."""

    loop: LoopRequest
    bc_range: Range
    points: int

    @classmethod
    def of(cls, profile: Profile, bc_range: Range, points: int) -> ExactChartRequest:
        return cls(LoopRequest.of(profile, coupling=False, pd=False), (float(bc_range[0]), float(bc_range[1])),
                   int(points))


@dataclass(frozen=True)
class ExactLimitRequest:
    """The exact limit at one b_c (the coupling's damping; the other gain is what is found)."""

    loop: LoopRequest
    bc: float

    @classmethod
    def of(cls, profile: Profile) -> ExactLimitRequest:
        return cls(LoopRequest.of(profile, coupling=False, pd=False), display_kind(profile).coupling(profile)[1])


@dataclass(frozen=True)
class SimulationRequest:
    """One simulator run: the loop and the simulation section (scenario and options) it runs."""

    loop: LoopRequest
    section: SimulationSection

    @classmethod
    def of(cls, profile: Profile) -> SimulationRequest:
        return cls(LoopRequest.of(profile), simulation_section(profile))
