"""The wall controller and the disturbance observer of Eom, Suh & Yi, as a profile shows them.

Wall (section 3): the transparency index J (eq. 10-11) and the robustness peak ‖L‖∞
(eq. 13-17) over the controller damping B_c (Fig. 8), the robust optimum, J and ‖L‖∞ at one
B_c, the admittances ``|Y_v|`` and ``|Y_t|`` (Fig. 9) and the answer to a human-force step (Figs. 7
and 10).  Observer (section 2, eq. 2-5): the effective plant through the observer, the
cross-axis coupling of the two-axis five-bar and the answer to a commanded force step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.profiles.model import Profile
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.study.quantities import format_number
from analysis.transparency.design import WallDesign
from analysis.transparency.five_bar import five_bar_preset
from analysis.transparency.observer import (
    CouplingResponse,
    DisturbanceObserver,
    ObserverResponse,
    ObserverSettings,
    TwoAxisObserver,
    TwoAxisStep,
)
from analysis.transparency.settings import (
    IndexResult,
    OptimalDamping,
    RobustnessPeak,
    StepResponse,
    TradeoffCurves,
    WallSettings,
)

__all__ = ["DEFAULT_BC", "PAPER_MASS", "mass_scale", "derived_wall_settings", "default_bc", "wall_device_label",
           "observer_device_label", "OBSERVER_W", "WallTradeoff", "WallPoint", "WallAdmittances", "wall_settings", "wall_design",
           "admittance_grid", "wall_tradeoff", "wall_point", "wall_admittances", "wall_step", "observer_settings",
           "observer_response", "observer_coupling", "observer_step", "WallRequest", "WallAtRequest",
           "TwoAxisRequest", "TwoAxisStepRequest"]

DEFAULT_BC = 15.0  # N s/m, the paper's example
#: The frequency grid of the observer plots (rad/s).
OBSERVER_W = np.geomspace(0.1, 1e5, 500)


@dataclass(frozen=True)
class WallTradeoff:
    """Fig. 8 over the settings' B_c range and the robust optimum (same settings).

    Attributes
    ----------
    curves : TradeoffCurves
        J(B_c) (eq. 10-11) and ‖L‖∞(B_c) (eq. 13-17) over the settings' B_c range.
    optimum : OptimalDamping
        The B_c minimizing J subject to ‖L‖∞ <= 1 (section 3).
    hold : str
        The hold model the curves were computed with (a key of
        :data:`~analysis.study.labels.HOLD_LABELS`).
    """

    curves: TradeoffCurves
    optimum: OptimalDamping
    hold: str


@dataclass(frozen=True)
class WallPoint:
    """J and ‖L‖∞ at one B_c.

    Attributes
    ----------
    bc : float
        The controller damping B_c [N·s/m].
    index : IndexResult
        The transparency index J (eq. 10-11) at ``bc``.
    peak : RobustnessPeak
        The robustness peak ‖L‖∞ (eq. 13-17) at ``bc`` and its frequency.
    """

    bc: float
    index: IndexResult
    peak: RobustnessPeak


@dataclass(frozen=True)
class WallAdmittances:
    """``|Y_v|`` and ``|Y_t|`` (Fig. 9) at ``w`` (rad/s) and one B_c.

    Attributes
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,) (:func:`admittance_grid`).
    yv : numpy.ndarray
        The virtual wall's admittance ``Y_v(jw)`` (eq. 8) [m/(N·s)], complex, shape (N,).
    yt : numpy.ndarray
        The admittance ``Y_t`` the operator feels at ``bc`` [m/(N·s)], complex, shape (N,).
    bc : float
        The controller damping B_c [N·s/m].
    nyquist : float
        The Nyquist frequency ``π/T`` [rad/s].
    """

    w: np.ndarray
    yv: np.ndarray
    yt: np.ndarray
    bc: float
    nyquist: float


#: The handle mass of the paper's example (kg), which the default wall settings are for.
PAPER_MASS = WallSettings().mass


def mass_scale(profile: Profile) -> float:
    """``s = M / 0.01 kg``: the profile device's total mass over the paper's example handle.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    float
        The scale ``s`` (dimensionless).
    """
    return profile.device.total_mass / PAPER_MASS


def derived_wall_settings(profile: Profile) -> WallSettings:
    """The wall design of a profile without a ``wall`` section: the profile's own device.

    The plant is the device as a rigid body (``m`` = total mass M, ``b`` = total ground damping,
    ``T`` = its sample period).  The paper's wall (K = 1000 N/m, B = 1 N·s/m), B_c range
    (0.5 .. 40 N·s/m) and step force (-5 N) are for a 0.01 kg handle; they are scaled by
    ``s = M / 0.01 kg`` -- M, B, K and B_c all times s keep the closed loop of the paper's
    example (same poles, same ‖L‖∞ (eq. 16-17), J (eq. 11) times 1/s²), so the robust optimum lies
    inside the range.  The device *chain* (``plant = "chain"``) is not the default: on a chain with
    structural modes inside the band (the HBFD's near 900 rad/s) no B_c reaches ‖L‖∞ <= 1.
    A device whose rigid-body values fall outside the physical ranges gets the paper's example.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    WallSettings
        The scaled settings, or the paper's example (``WallSettings()``).
    """
    base, dev = WallSettings(), profile.device
    s = mass_scale(profile)
    try:
        return base.replace(mass=dev.total_mass, damping=dev.total_ground_damping, sample_time=dev.sample_time,
                            wall_stiffness=base.wall_stiffness * s, wall_damping=base.wall_damping * s,
                            bc_min=base.bc_min * s, bc_max=base.bc_max * s, step_force=base.step_force * s)
    except ValidationError:
        return base


def wall_settings(profile: Profile) -> WallSettings:
    """The profile's wall section, or (none) the settings derived from its device.

    See :func:`derived_wall_settings`.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    WallSettings
        The wall settings.
    """
    return profile.wall if profile.wall is not None else derived_wall_settings(profile)


def default_bc(profile: Profile) -> float:
    """The B_c the Transparency tab starts at: the paper's 15 N·s/m, times ``s`` on a derived wall.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    float
        The controller damping B_c [N·s/m].
    """
    st = wall_settings(profile)
    return DEFAULT_BC if profile.wall is not None or st == WallSettings() else DEFAULT_BC * mass_scale(profile)


def wall_device_label(profile: Profile) -> str:
    """Which device the Transparency tab analyses, in words (shown in the tab).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    str
        One line naming the plant, its mass, damping and sample period, and where they come from.
    """
    st = wall_settings(profile)
    T = format_number(st.sample_time * 1e3, 4)
    if profile.wall is not None:
        plant = (f"the device chain of {profile.name}" if st.plant == "chain"
                 else f"a rigid handle of m = {format_number(st.mass, 4)} kg, b = {format_number(st.damping, 4)} N·s/m")
        return f"Device: {plant}, T = {T} ms (from the profile's wall section)"
    if st == WallSettings():
        return "Device: the paper's example (0.01 kg handle, T = 1 ms); this device is outside its ranges"
    return (f"Device: {profile.name} as a rigid body, m = {format_number(st.mass, 4)} kg, "
            f"b = {format_number(st.damping, 4)} N·s/m, T = {T} ms (the profile has no wall section: "
            f"the paper's wall and B_c range scaled by m / 0.01 kg = {format_number(mass_scale(profile), 4)})")


@dataclass(frozen=True)
class WallRequest:
    """What a :class:`WallDesign` depends on: the wall settings and the device chain.

    The chain only for ``plant = "chain"``; ``None`` otherwise, so a device edit does not touch a
    rigid-body wall.

    Attributes
    ----------
    settings : WallSettings
        The wall settings (:func:`wall_settings`).
    device : Device or None
        The device chain for ``plant = "chain"``, else ``None``.
    """

    settings: WallSettings
    device: Device | None

    @classmethod
    def of(cls, profile: Profile) -> WallRequest:
        """The request of ``profile``'s wall.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        WallRequest
            The request.
        """
        st = wall_settings(profile)
        return cls(st, profile.device if st.plant == "chain" else None)


@dataclass(frozen=True)
class WallAtRequest:
    """A wall result at one controller damping B_c (N s/m).

    Attributes
    ----------
    wall : WallRequest
        The wall design's request.
    bc : float
        The controller damping B_c [N·s/m].
    """

    wall: WallRequest
    bc: float


def wall_design(request: WallRequest | Profile) -> WallDesign:
    """A fresh :class:`WallDesign`.

    Parameters
    ----------
    request : WallRequest or Profile
        The request, or a profile: of its wall settings, the device chain only for
        ``plant = "chain"``.

    Returns
    -------
    WallDesign
        The wall design.
    """
    req = WallRequest.of(request) if isinstance(request, Profile) else request
    return WallDesign.from_settings(req.settings, req.device)


def admittance_grid(st: WallSettings, points: int = 600) -> np.ndarray:
    """1 rad/s to 10 Nyquist (to just below Nyquist for the ``discrete`` hold).

    Parameters
    ----------
    st : WallSettings
        The wall settings (their sample period and hold).
    points : int, optional
        Number of grid points.

    Returns
    -------
    numpy.ndarray
        Geometric grid of angular frequencies [rad/s], shape (points,).
    """
    nyq = math.pi / st.sample_time
    hi = 0.999 * nyq if st.hold == "discrete" else 10.0 * nyq
    return np.geomspace(min(1.0, hi / 100.0), hi, points)


@none_if_cancelled
def wall_tradeoff(request: WallRequest | Profile, *, progress: Progress | None = None,
                  cancelled: Cancelled | None = None) -> WallTradeoff | None:
    """J(B_c) and ‖L‖∞(B_c) (Fig. 8) and the robust optimum; ``None`` once cancelled.

    Parameters
    ----------
    request : WallRequest or Profile
        The request, or a profile.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    WallTradeoff or None
        The curves and the optimum, or ``None`` once cancelled.
    """
    design = wall_design(request)  # its own object: never shared across threads
    report_progress(progress, 0, 2)
    curves = design.tradeoff()
    check_cancelled(cancelled)
    report_progress(progress, 1, 2)
    optimum = design.optimal_damping()
    report_progress(progress, 2, 2)
    return WallTradeoff(curves, optimum, design.settings.hold)


def wall_point(design: WallDesign, bc: float) -> WallPoint:
    """J (eq. 10-11) and ‖L‖∞ (eq. 13-17) at ``bc``.

    Parameters
    ----------
    design : WallDesign
        The wall design (:func:`wall_design`).
    bc : float
        The controller damping B_c [N·s/m].

    Returns
    -------
    WallPoint
        J and ‖L‖∞ at ``bc``.
    """
    return WallPoint(bc, design.index_result(bc), design.robustness_peak(bc))


def wall_admittances(design: WallDesign, bc: float) -> WallAdmittances:
    """``|Y_v|`` and ``|Y_t|`` (Fig. 9) at ``bc`` on :func:`admittance_grid`.

    Parameters
    ----------
    design : WallDesign
        The wall design (:func:`wall_design`).
    bc : float
        The controller damping B_c [N·s/m].

    Returns
    -------
    WallAdmittances
        The two admittances on the grid.
    """
    w = admittance_grid(design.settings)
    yv, yt = design.admittances(w, bc)
    return WallAdmittances(w, yv, yt, bc, math.pi / design.settings.sample_time)


def wall_step(design: WallDesign, bc: float) -> StepResponse:
    """The answer to a human-force step at ``bc`` (Figs. 7 and 10).

    Parameters
    ----------
    design : WallDesign
        The wall design (:func:`wall_design`).
    bc : float
        The controller damping B_c [N·s/m].

    Returns
    -------
    StepResponse
        The exact sampled loop's answer to the settings' step force.
    """
    return design.step_response(bc)


def observer_settings(profile: Profile) -> ObserverSettings:
    """The profile's observer section, or (none) the defaults with the profile's nominal plant.

    Without a section, the nominal plant ``P_n`` of eq. (3) is taken from the profile's device as
    a rigid body (total mass, total ground damping); a device outside the observer's ranges gets
    the defaults.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    ObserverSettings
        The observer settings.
    """
    if profile.observer is not None:
        return profile.observer
    dev = profile.device
    try:
        return ObserverSettings(nominal_mass=dev.total_mass, nominal_damping=dev.total_ground_damping)
    except ValidationError:
        return ObserverSettings()


def observer_device_label(profile: Profile) -> str:
    """Which devices the Observer tab analyses, in words (shown in the tab).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    str
        One line naming the single-axis nominal plant and the two-axis five-bar preset.
    """
    st = observer_settings(profile)
    where = "the profile's observer section" if profile.observer is not None else f"{profile.name} as a rigid body"
    return (f"Single axis: P_n = 1/({format_number(st.nominal_mass, 4)} s + "
            f"{format_number(st.nominal_damping, 4)}) from {where}; two axes: the five-bar preset '{st.preset}'")


@dataclass(frozen=True)
class TwoAxisRequest:
    """What the two-axis observer depends on: the five-bar preset and the Q filter (order, cut-off).

    Attributes
    ----------
    preset : str
        The two-axis five-bar device (a key of ``OBSERVER_PRESETS``).
    order : int
        Order of the binomial Q filter.
    cutoff : float
        Cut-off of the Q filter [rad/s].
    """

    preset: str
    order: int
    cutoff: float

    @classmethod
    def of(cls, profile: Profile) -> TwoAxisRequest:
        """The request of ``profile``'s observer settings (:func:`observer_settings`).

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        TwoAxisRequest
            The request.
        """
        st = observer_settings(profile)
        return cls(st.preset, st.order, st.cutoff)

    def build(self) -> TwoAxisObserver:
        """A fresh two-axis observer of the preset's five-bar device.

        Returns
        -------
        TwoAxisObserver
            The observer with this Q filter.
        """
        M, B, _, _ = five_bar_preset(self.preset)
        return TwoAxisObserver(M, B, self.order, self.cutoff)


@dataclass(frozen=True)
class TwoAxisStepRequest:
    """The two-axis observer and the commanded force step (N, s).

    Attributes
    ----------
    observer : TwoAxisRequest
        The two-axis observer.
    step_force : float
        The commanded force step on x [N].
    step_duration : float
        The simulated duration [s].
    """

    observer: TwoAxisRequest
    step_force: float
    step_duration: float

    @classmethod
    def of(cls, profile: Profile) -> TwoAxisStepRequest:
        """The request of ``profile``'s observer settings (:func:`observer_settings`).

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        TwoAxisStepRequest
            The request.
        """
        st = observer_settings(profile)
        return cls(TwoAxisRequest.of(profile), st.step_force, st.step_duration)


def observer_response(request: ObserverSettings | Profile) -> ObserverResponse:
    """The effective plant through the observer (eq. 2-5) on :data:`OBSERVER_W`.

    Parameters
    ----------
    request : ObserverSettings or Profile
        The observer settings (the request), or a profile (its :func:`observer_settings`).

    Returns
    -------
    ObserverResponse
        The real, nominal and effective plants and the disturbance-to-velocity responses with
        and without the observer, on :data:`OBSERVER_W`.
    """
    st = observer_settings(request) if isinstance(request, Profile) else request
    return DisturbanceObserver.from_settings(st).response(OBSERVER_W, None, st.alpha, st.beta, st.delta)


def observer_coupling(request: TwoAxisRequest | Profile) -> CouplingResponse:
    """The cross-axis coupling ``|v_y/F_x|`` of the two-axis device with and without the observers.

    Parameters
    ----------
    request : TwoAxisRequest or Profile
        The request, or a profile.

    Returns
    -------
    CouplingResponse
        The coupling ``v_y/F_x`` and the direct ``v_x/F_x`` responses without and with the
        observers, on :data:`OBSERVER_W`.
    """
    req = TwoAxisRequest.of(request) if isinstance(request, Profile) else request
    return req.build().coupling(OBSERVER_W)


def observer_step(request: TwoAxisStepRequest | Profile) -> TwoAxisStep:
    """The y answer to a commanded force step on x.

    Parameters
    ----------
    request : TwoAxisStepRequest or Profile
        The request, or a profile.

    Returns
    -------
    TwoAxisStep
        Positions and velocities of both axes over time, without and with the observers.
    """
    req = TwoAxisStepRequest.of(request) if isinstance(request, Profile) else request
    return req.observer.build().step_response(req.step_force, req.step_duration)
