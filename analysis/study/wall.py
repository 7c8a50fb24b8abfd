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

from analysis.profiles.model import Profile
from analysis.transparency.design import WallDesign
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
from analysis.twoport.results import Cancelled, Progress

__all__ = ["DEFAULT_BC", "OBSERVER_W", "WallTradeoff", "WallPoint", "WallAdmittances", "wall_settings", "wall_design",
           "admittance_grid", "wall_tradeoff", "wall_point", "wall_admittances", "wall_step", "observer_settings",
           "observer_response", "observer_coupling", "observer_step"]

DEFAULT_BC = 15.0  # N s/m, the paper's example
#: The frequency grid of the observer plots (rad/s).
OBSERVER_W = np.geomspace(0.1, 1e5, 500)


@dataclass(frozen=True)
class WallTradeoff:
    """Fig. 8 over the settings' B_c range and the robust optimum (same settings)."""

    curves: TradeoffCurves
    optimum: OptimalDamping
    hold: str


@dataclass(frozen=True)
class WallPoint:
    """J and ‖L‖∞ at one B_c."""

    bc: float
    index: IndexResult
    peak: RobustnessPeak


@dataclass(frozen=True)
class WallAdmittances:
    """``|Y_v|`` and ``|Y_t|`` (Fig. 9) at ``w`` (rad/s) and one B_c."""

    w: np.ndarray
    yv: np.ndarray
    yt: np.ndarray
    bc: float
    nyquist: float


def wall_settings(profile: Profile) -> WallSettings:
    """The profile's wall section, or the paper's example when it has none."""
    return profile.wall if profile.wall is not None else WallSettings()


def wall_design(profile: Profile) -> WallDesign:
    """A fresh :class:`WallDesign` for the profile (the device chain only for ``plant = "chain"``)."""
    st = wall_settings(profile)
    return WallDesign.from_settings(st, profile.device if st.plant == "chain" else None)


def admittance_grid(st: WallSettings, points: int = 600) -> np.ndarray:
    """1 rad/s to 10 Nyquist (to just below Nyquist for the ``discrete`` hold)."""
    nyq = math.pi / st.sample_time
    hi = 0.999 * nyq if st.hold == "discrete" else 10.0 * nyq
    return np.geomspace(min(1.0, hi / 100.0), hi, points)


def wall_tradeoff(profile: Profile, *, progress: Progress | None = None, cancelled: Cancelled | None = None
                  ) -> WallTradeoff | None:
    """J(B_c) and ‖L‖∞(B_c) (Fig. 8) and the robust optimum; ``None`` once cancelled."""
    design = wall_design(profile)  # its own object: never shared across threads
    if progress is not None:
        progress(0, 2)
    curves = design.tradeoff()
    if cancelled is not None and cancelled():
        return None
    if progress is not None:
        progress(1, 2)
    optimum = design.optimal_damping()
    if progress is not None:
        progress(2, 2)
    return WallTradeoff(curves, optimum, design.settings.hold)


def wall_point(design: WallDesign, bc: float) -> WallPoint:
    """J (eq. 10-11) and ‖L‖∞ (eq. 13-17) at ``bc``."""
    return WallPoint(bc, design.index_result(bc), design.robustness_peak(bc))


def wall_admittances(design: WallDesign, bc: float) -> WallAdmittances:
    """``|Y_v|`` and ``|Y_t|`` (Fig. 9) at ``bc`` on :func:`admittance_grid`."""
    w = admittance_grid(design.settings)
    yv, yt = design.admittances(w, bc)
    return WallAdmittances(w, yv, yt, bc, math.pi / design.settings.sample_time)


def wall_step(design: WallDesign, bc: float) -> StepResponse:
    """The answer to a human-force step at ``bc`` (Figs. 7 and 10)."""
    return design.step_response(bc)


def observer_settings(profile: Profile) -> ObserverSettings:
    """The profile's observer section, or the defaults when it has none."""
    return profile.observer if profile.observer is not None else ObserverSettings()


def observer_response(profile: Profile) -> ObserverResponse:
    """The effective plant through the observer (eq. 2-5) on :data:`OBSERVER_W`."""
    st = observer_settings(profile)
    return DisturbanceObserver.from_settings(st).response(OBSERVER_W, None, st.alpha, st.beta, st.delta)


def observer_coupling(profile: Profile) -> CouplingResponse:
    """The cross-axis coupling ``|v_y/F_x|`` of the two-axis device with and without the observers."""
    return TwoAxisObserver.from_settings(observer_settings(profile)).coupling(OBSERVER_W)


def observer_step(profile: Profile) -> TwoAxisStep:
    """The y answer to a commanded force step on x."""
    st = observer_settings(profile)
    return TwoAxisObserver.from_settings(st).step_response(st.step_force, st.step_duration)
