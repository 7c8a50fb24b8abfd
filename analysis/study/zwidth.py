"""The controller as built, for a profile: the Z-width region and the trials (the optimum filter
is :mod:`analysis.study.optimum`).

The classic Z-width picture of Colgate & Brown ("Factors affecting the Z-width of a haptic
display", ICRA 1994): the stable region of the virtual wall ``K + B V(z)`` in the (B, K) plane,
computed exactly (:func:`analysis.sampled.zwidth_region`, hands-off against the god-object wall)
with the profile's velocity filter and delays, the passive region of Colgate & Schenkel, and
eq. (9)'s two-port limit of Adams & Hannaford built here from
:class:`~analysis.twoport.impedance.ImpedanceDisplay` ``(device, velocity_filter=f)`` (the
sampled layer cannot import the two-port layer, the study layer can).  The area against the
cut-off and its maximum follow Chawda, Celik & O'Malley (ASME JDSMC 137(2), 2015), in
:mod:`analysis.study.optimum`.

The wall of the region is the impedance display's virtual coupling of the profile: B is
``bc`` (N s/m) and K is ``kc`` (N/m), the gains :func:`analysis.sampled.critical_stiffness`
analyses at the profile's b_c (:func:`wall_edits`).

When the profile's controller section names an ``encoder_resolution`` (and optionally a
``force_noise``), the region and the optimum apply the noise criterion of
:mod:`analysis.sampled.velocity_noise` (:func:`noise_options`).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.profiles.controller import ControllerSection
from analysis.profiles.model import Profile
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled import (
    MeasuredTrials,
    TrialScore,
    ZWidthRegion,
    load_trials,
    score_trials,
)
from analysis.sampled import zwidth_region as sampled_zwidth_region
from analysis.study.requests import delays
from analysis.study.displays import profile_filter
from analysis.twoport.impedance import ImpedanceDisplay

__all__ = ["ZWidthStudy", "controller_section", "region_b", "noise_options", "twoport_limit",
           "zwidth_region", "zwidth_region_result", "ZWidthRequest", "TrialsRequest",
           "profile_trials", "resolve_trials", "trials_path", "trial_score", "wall_edits", "region_wall", "with_filter"]


@dataclass(frozen=True)
class ZWidthStudy:
    """A region with the trials scored against it (``trials``/``score`` ``None`` without a file).

    Attributes
    ----------
    region : ZWidthRegion
        The exact (B, K) region of the wall.
    trials : MeasuredTrials or None
        The hardware trials, or ``None`` without a trials file.
    score : TrialScore or None
        The trials against the region, or ``None`` without a trials file.
    """

    region: ZWidthRegion
    trials: MeasuredTrials | None = None
    score: TrialScore | None = None


def controller_section(profile: Profile) -> ControllerSection:
    """The profile's controller section, or the default one (backward difference, B 0.1-100).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    ControllerSection
        The section.
    """
    return ControllerSection() if profile.controller is None else profile.controller


def region_b(profile: Profile) -> np.ndarray:
    """The region's B values (N s/m): geometric over the section's ``b_range``.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    numpy.ndarray
        Wall dampings B [N·s/m], shape (b_points,).
    """
    sec = controller_section(profile)
    return np.geomspace(sec.b_range[0], sec.b_range[1], sec.b_points)


def noise_options(profile: Profile) -> dict[str, float | None]:
    """The noise criterion's keywords from the section: ``encoder_resolution`` (m), ``force_noise`` (N).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    dict of str to float or None
        ``encoder_resolution`` [m] and ``force_noise`` [N rms]; ``None`` where the criterion is
        off.
    """
    sec = controller_section(profile)
    return {"encoder_resolution": sec.encoder_resolution, "force_noise": sec.force_noise}


@dataclass(frozen=True)
class ZWidthRequest:
    """What the (B, K) region depends on: the device, the velocity filter, the B grid
    (``b_range``, ``b_points``), the noise criterion and the delays -- not the wall's gains.

    Attributes
    ----------
    device : Device
        The device chain.
    velocity_filter : VelocityFilter or None
        The controller's velocity filter, ``None`` for the backward difference.
    b_range : tuple of (float, float)
        The range of the geometric B grid [N·s/m].
    b_points : int
        Number of B grid points.
    encoder_resolution : float or None
        Encoder resolution at the handle [m]; ``None``: the noise criterion is off.
    force_noise : float or None
        The noise criterion's force-noise tolerance [N rms]; ``None`` for the default or off.
    delay_samples : int
        The loop's delay, in samples.
    implementation_delay : bool
        Whether the loop has the one-sample implementation delay.
    """

    device: Device
    velocity_filter: VelocityFilter | None
    b_range: tuple[float, float]
    b_points: int
    encoder_resolution: float | None
    force_noise: float | None
    delay_samples: int
    implementation_delay: bool

    @classmethod
    def of(cls, profile: Profile) -> ZWidthRequest:
        """The request of ``profile``'s device, controller section and delays.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        ZWidthRequest
            The request.
        """
        sec = controller_section(profile)
        d, impl = delays(profile)
        return cls(profile.device, profile_filter(profile), tuple(sec.b_range), int(sec.b_points),
                   sec.encoder_resolution, sec.force_noise, int(d), bool(impl))

    @property
    def b(self) -> np.ndarray:
        """The region's B values (N s/m)."""
        return np.geomspace(self.b_range[0], self.b_range[1], self.b_points)

    @property
    def noise(self) -> dict[str, float | None]:
        return {"encoder_resolution": self.encoder_resolution, "force_noise": self.force_noise}


def twoport_limit(request: ZWidthRequest | Profile) -> Callable[[np.ndarray], np.ndarray]:
    """Eq. (9)'s edge: ``b -> largest k_c`` of ``ImpedanceDisplay(device, velocity_filter=f)``.

    Parameters
    ----------
    request : ZWidthRequest or Profile
        The request, or a profile.

    Returns
    -------
    callable
        ``limit(b)``: the largest k_c [N/m] at each damping of ``b`` [N·s/m], same shape as
        ``b`` (NaN where eq. 9 has no feasible k_c).
    """
    req = ZWidthRequest.of(request) if isinstance(request, Profile) else request
    disp = ImpedanceDisplay(req.device, velocity_filter=req.velocity_filter)

    def limit(b: np.ndarray) -> np.ndarray:
        return np.asarray(disp.stiffness_chart(np.asarray(b, float)).kc, float)

    return limit


@none_if_cancelled
def zwidth_region_result(request: ZWidthRequest | Profile, *, progress: Progress | None = None,
                         cancelled: Cancelled | None = None) -> ZWidthRegion | None:
    """The exact (B, K) region of the wall with its filter and delays, the passive region and
    eq. (9)'s limit (:func:`analysis.sampled.zwidth_region` is the sampled layer's computation).

    One piece: reports 0/1 and 1/1; ``None`` once cancelled.

    Parameters
    ----------
    request : ZWidthRequest or Profile
        The request, or a profile.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    ZWidthRegion or None
        The region on the request's B grid, or ``None`` once cancelled.
    """
    req = ZWidthRequest.of(request) if isinstance(request, Profile) else request
    report_progress(progress, 0, 1)
    check_cancelled(cancelled)
    r = sampled_zwidth_region(req.device, req.b, req.delay_samples, req.velocity_filter,
                              implementation_delay=req.implementation_delay, twoport_limit=twoport_limit(req),
                              **req.noise)
    report_progress(progress, 1, 1)
    check_cancelled(cancelled)
    return r


def trials_path(path: str | os.PathLike | None, base: str | os.PathLike | None = None) -> str | None:
    """A profile's ``trials`` path, made relative to ``base`` when given: the one rule by which the
    command line, the report and the GUI's compute graph find a profile's trials file
    (:func:`resolve_trials`, :meth:`TrialsRequest.of`).

    A relative path is relative to ``base`` (the profile's folder) when given, else to the
    working directory; ``None`` stays ``None``.

    Parameters
    ----------
    path : str or os.PathLike or None
        The trials path as the controller section names it.
    base : str or os.PathLike or None, optional
        The folder a relative path is relative to.

    Returns
    -------
    str or None
        The path (joined to the absolute ``base`` when it is relative and ``base`` is given), or
        ``None``.
    """
    if path is None:
        return None
    path = os.fspath(path)
    if base is not None and not os.path.isabs(path):
        return os.path.join(os.path.abspath(base), path)
    return path


def resolve_trials(profile: Profile, base: str | os.PathLike) -> Profile:
    """The profile with a relative ``trials`` path made relative to ``base``, the folder of the
    profile's file (:func:`trials_path`), so that a profile run from another folder still finds
    the trials file beside it; the profile itself when it names no file or an absolute one.

    Parameters
    ----------
    profile : Profile
        The device profile.
    base : str or os.PathLike
        The folder of the profile's file.

    Returns
    -------
    Profile
        The profile with an absolute ``trials`` path, or ``profile`` itself.
    """
    sec = profile.controller
    if sec is None or sec.trials is None or os.path.isabs(sec.trials):
        return profile
    return profile.replace(controller=sec.replace(trials=trials_path(sec.trials, base)))


@dataclass(frozen=True)
class TrialsRequest:
    """The trials file named by the controller section, as an absolute path, and its modification time.

    The path is resolved when the request is made (:func:`trials_path`: a relative one against the
    profile's folder, or the working directory without one), so a file in another folder, or the
    same name seen from another folder, is another request; a rewritten file is read again.
    ``path`` is ``None`` without a file.

    Attributes
    ----------
    path : str or None
        The trials file (absolute), or ``None`` when the section names none.
    mtime_ns : int or None
        The file's modification time [ns], or ``None`` when it cannot be read.
    """

    path: str | None
    mtime_ns: int | None = None

    @classmethod
    def of(cls, profile: Profile, base: str | os.PathLike | None = None) -> TrialsRequest:
        """The request of ``profile``; a relative path is relative to ``base`` when given (:func:`trials_path`).

        Parameters
        ----------
        profile : Profile
            The device profile.
        base : str or os.PathLike or None, optional
            The folder a relative path is relative to; ``None``: the working directory.

        Returns
        -------
        TrialsRequest
            The request.
        """
        path = trials_path(controller_section(profile).trials, base)
        if path is None:
            return cls(None)
        path = os.path.abspath(path)
        try:
            return cls(path, os.stat(path).st_mtime_ns)
        except OSError:
            return cls(path, None)


def profile_trials(profile: TrialsRequest | Profile, base: str | os.PathLike | None = None) -> MeasuredTrials | None:
    """The trials file named by the profile's section (relative to ``base`` when given), or ``None``.

    Parameters
    ----------
    profile : TrialsRequest or Profile
        The request, or a profile.
    base : str or os.PathLike or None, optional
        The folder a relative path is relative to; ``None``: the working directory.

    Returns
    -------
    MeasuredTrials or None
        The trials, or ``None`` when the section names no file.

    Raises
    ------
    TrialsError
        A :class:`~analysis.errors.ValidationError` naming the file, the line and the column for
        a missing, unreadable or malformed file (:class:`~analysis.sampled.TrialsError`).
    """
    if isinstance(profile, Profile):
        path = TrialsRequest.of(profile, base).path
    else:
        path = trials_path(profile.path, base)
    if path is None:
        return None
    return load_trials(path)


def trial_score(region: ZWidthRegion, trials: MeasuredTrials | None) -> ZWidthStudy:
    """The region with ``trials`` scored against it (:func:`analysis.sampled.score_trials`).

    Parameters
    ----------
    region : ZWidthRegion
        The (B, K) region.
    trials : MeasuredTrials or None
        The hardware trials, or ``None``.

    Returns
    -------
    ZWidthStudy
        The region with the trials and their score (both ``None`` without trials).
    """
    if trials is None:
        return ZWidthStudy(region)
    return ZWidthStudy(region, trials, score_trials(region, trials))


def wall_edits(b: float, k: float) -> dict[str, float]:
    """The profile fields a pick at ``(B, K)`` on the region sets: the virtual coupling ``bc``, ``kc``.

    Parameters
    ----------
    b : float
        The picked wall damping B [N·s/m].
    k : float
        The picked wall stiffness K [N/m].

    Returns
    -------
    dict of str to float
        ``{"bc": b, "kc": k}``.
    """
    return {"bc": float(b), "kc": float(k)}


def region_wall(profile: Profile) -> tuple[float, float]:
    """Where the profile's wall sits on the region: ``(bc, kc)``.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    tuple of (float, float)
        ``(b_c [N·s/m], k_c [N/m])``.
    """
    return float(profile.bc), float(profile.kc)


def with_filter(profile: Profile, velocity_filter: VelocityFilter) -> Profile:
    """The profile with its controller section's filter replaced (the section created if absent).

    Parameters
    ----------
    profile : Profile
        The device profile.
    velocity_filter : VelocityFilter
        The new velocity filter.

    Returns
    -------
    Profile
        The updated profile (a new record; ``profile`` is unchanged).
    """
    return profile.replace(controller=controller_section(profile).replace(velocity_filter=velocity_filter))


#: deprecated alias of :func:`zwidth_region_result` (one release): :func:`analysis.sampled.zwidth_region`
#: is the sampled layer's computation of the same name
zwidth_region = zwidth_region_result
