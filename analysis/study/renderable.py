"""The renderable (M, B, K) space and the M-width of a profile (issue 24): one request, one result.

The impedance display renders ``F = M a^ + B v^ + K x`` (:mod:`analysis.sampled.rendered`).  For the
(M, B) grid of the profile's ``renderable`` section (:class:`~analysis.profiles.RenderableSection`,
its defaults without one) this builds the space of Colonnese & Chan (IEEE Haptics Symposium 2016)
with :func:`analysis.sampled.renderable_space` and the M-width of Colonnese & Okamura (RSS 2012)
with :func:`analysis.sampled.m_width`, with the profile's velocity filter (controller section) and
delay (simulation section).  The GUI's graph node, the command line and the report build from
:func:`renderable_study`.

The grid: masses linear from ``mass_min`` to ``mass_max``; dampings uniform on the signed-log axis
of the space's volume, ``u(B) = sign(B) log10(1 + |B|/b_ref)`` (:func:`damping_axis`, ``b_ref`` =
1 N s/m), so that a heat map's pixels are equal on that axis and negative dampings get as many
values as positive ones.  The rendered environment itself (M, B, K) is not part of the request:
moving it recomputes nothing.

The robust space (issue 24: "the robust-space overlay when a box or batch is given"): when the
profile's ``identification`` section bounds a parameter box (:func:`robust_box_reason` says why
not), ``RenderableRequest.of(profile, robust="corners")`` or ``robust="samples"`` adds a
:class:`RobustBox` (the box's intervals, its corners or N seeded samples) and :func:`robust_study`
computes the space every device of that batch has
(:func:`analysis.sampled.robust_renderable_space` on the request's grid, qualities and settings, in
the calling thread: ``workers=1``, so that the GUI's worker thread starts no process pool);
:func:`robust_m_width` is the M-width every device of that batch has (the report's robust rows).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.identify import open_intervals, parameter_box
from analysis.chain.velocity_filter import VelocityFilter
from analysis.profiles.model import Profile
from analysis.profiles.renderable import RenderableSection
from analysis.profiles.schema import GRASP_SETS
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled import (
    FIRM_GRASP,
    HANDS_OFF,
    QUALITIES,
    RIGID_GRASP,
    AccelerationEstimate,
    MWidth,
    QualitySettings,
    RenderableSpace,
    RobustRenderableSpace,
    box_corners,
    box_samples,
    m_width,
    renderable_space,
    robust_renderable_space,
)
from analysis.sampled.terminations import Grasp
from analysis.study.displays import profile_filter
from analysis.study.requests import delays

__all__ = ["GRASPS", "QUALITY_LABELS", "ROBUST_KINDS", "ROBUST_SAMPLES", "RenderableRequest", "RenderableStudy",
           "RobustBox", "renderable_section", "damping_axis", "damping_from_axis", "renderable_study", "k_max_at",
           "environment_edits", "robust_box_reason", "robust_study", "robust_m_width"]

#: The grasp sets of the ``stable`` quality by name (the keys of :data:`analysis.profiles.schema.GRASP_SETS`).
GRASPS: dict[str, tuple[Grasp, ...]] = {"hands_off": (HANDS_OFF,), "firm": (HANDS_OFF, FIRM_GRASP),
                                        "all": (HANDS_OFF, FIRM_GRASP, RIGID_GRASP)}
assert set(GRASPS) == set(GRASP_SETS)
#: What people read for each quality (and ``"all"``: every quality asked).
QUALITY_LABELS = {"all": "all qualities", "stable": "stable", "passive": "passive", "accurate": "accurate",
                  "quiet": "quiet"}
assert set(QUALITY_LABELS) == {"all", *QUALITIES}
#: The damping scale of the signed-log axis [N s/m] (QualitySettings.b_ref's default).
B_REF = QualitySettings().b_ref
#: How the robust space takes the identified box: not at all, its 2^p corners, or N seeded samples.
ROBUST_KINDS = {"off": "off", "corners": "the box's corners", "samples": "samples of the box"}
#: The robust space's default number of samples of the box.
ROBUST_SAMPLES = 16


def renderable_section(profile: Profile) -> RenderableSection:
    """The profile's ``renderable`` section, or the default one (M = B = K = 0, stable, the default grid).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    RenderableSection
        The section.
    """
    return RenderableSection() if profile.renderable is None else profile.renderable


def damping_axis(b: object, b_ref: float = B_REF) -> np.ndarray:
    """The signed-log damping axis ``u = sign(B) log10(1 + |B|/b_ref)`` of the space's volume.

    Parameters
    ----------
    b : array_like
        Dampings B [N s/m].
    b_ref : float, optional
        The scale [N s/m] (default 1).

    Returns
    -------
    numpy.ndarray
        ``u``, same shape as ``b`` (decades beyond ``b_ref``; linear through 0).
    """
    b = np.asarray(b, dtype=float)
    return np.sign(b) * np.log10(1.0 + np.abs(b) / b_ref)


def damping_from_axis(u: object, b_ref: float = B_REF) -> np.ndarray:
    """The inverse of :func:`damping_axis`: ``B = sign(u) b_ref (10^|u| - 1)``.

    Parameters
    ----------
    u : array_like
        Positions on the signed-log axis.
    b_ref : float, optional
        The scale [N s/m] (default 1).

    Returns
    -------
    numpy.ndarray
        Dampings B [N s/m], same shape as ``u``.
    """
    u = np.asarray(u, dtype=float)
    return np.sign(u) * b_ref * (10.0 ** np.abs(u) - 1.0)


def _closed_intervals(profile: Profile) -> tuple[tuple[str, float, float], ...] | str:
    """The identification section's intervals as a hashable tuple, or why they bound no box."""
    sec = profile.identification
    if sec is None or not sec.intervals:
        return "the profile has no identified intervals (Identify tab or zwidth identify)"
    open_keys = open_intervals(sec.intervals, len(profile.device.masses))
    if open_keys:
        return f"the data leave {', '.join(open_keys)} open: no box"
    return tuple((k, float(lo), float(hi)) for k, (lo, hi) in sec.intervals.items())


def robust_box_reason(profile: Profile) -> str | None:
    """Why the profile offers no robust space (``None`` when its identified intervals bound a box).

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    str or None
        The reason in words, or ``None``.
    """
    box = _closed_intervals(profile)
    return box if isinstance(box, str) else None


@dataclass(frozen=True)
class RobustBox:
    """A batch of devices from the identified parameter box (module docstring); hashable.

    Attributes
    ----------
    intervals : tuple of (str, float, float)
        The identification section's ``(key, low, high)``, in its order.
    kind : str
        ``"corners"`` (the box's ``2^p`` corners) or ``"samples"`` (``samples`` devices drawn by
        :func:`analysis.sampled.box_samples` with ``seed``).
    samples : int
        Number of samples (``kind == "samples"``).
    seed : int
        Seed of the samples: the same seed gives the same devices.
    """

    intervals: tuple[tuple[str, float, float], ...]
    kind: str
    samples: int = ROBUST_SAMPLES
    seed: int = 0

    @classmethod
    def of(cls, profile: Profile, kind: str, samples: int = ROBUST_SAMPLES, seed: int = 0) -> RobustBox | str:
        """The batch of the profile's identified box, or why there is none (:func:`robust_box_reason`).

        Parameters
        ----------
        profile : Profile
            The device profile, with its identification section's intervals.
        kind : str
            ``"corners"`` or ``"samples"``.
        samples : int, optional
            Number of samples (``"samples"`` only).
        seed : int, optional
            Seed of the samples.

        Returns
        -------
        RobustBox or str
            The batch, or the reason in words.
        """
        box = _closed_intervals(profile)
        return box if isinstance(box, str) else cls(box, kind, int(samples), int(seed))

    def devices(self, device: Device) -> list[Device]:
        """The batch: ``device`` with the boxed parameters at the corners or samples of the box.

        Parameters
        ----------
        device : Device
            The profile's device (the parameters the box leaves out).

        Returns
        -------
        list of Device
            The devices, corners in binary order or samples in draw order.

        Raises
        ------
        ValidationError
            When the box is refused (:func:`analysis.identify.parameter_box`) or too large.
        """
        box = parameter_box(device, {k: (lo, hi) for k, lo, hi in self.intervals})
        return box_corners(box) if self.kind == "corners" else box_samples(box, self.samples, self.seed)

    def label(self, device: Device) -> str:
        """``"4 corners of the identified box"`` or ``"16 samples of the identified box"``.

        Parameters
        ----------
        device : Device
            The profile's device.

        Returns
        -------
        str
            The batch in words.
        """
        if self.kind == "corners":
            dim = parameter_box(device, {k: (lo, hi) for k, lo, hi in self.intervals}).dim
            return f"{2 ** dim} corners of the identified box"
        return f"{self.samples} samples of the identified box"


@dataclass(frozen=True)
class RenderableRequest:
    """What the space and the M-width depend on (hashable: the graph's cache key).

    Attributes
    ----------
    device : Device
        The device chain.
    velocity_filter : VelocityFilter or None
        The controller's velocity filter, ``None`` for the backward difference.
    delay_samples : int
        The loop's delay, in samples: the simulation section's, plus one for its implementation delay
        (the force applied one sample later, which the rendered loop counts as computation delay).
    acceleration : AccelerationEstimate
        The acceleration estimate.
    qualities : tuple of str
        The qualities asked.
    settings : QualitySettings
        The qualities' settings (grasps, band, tolerance, noise limit).
    mass : tuple of float
        The grid's virtual masses [kg].
    damping : tuple of float
        The grid's virtual dampings [N s/m].
    robust : RobustBox or None
        The batch of the robust space (:func:`robust_study`), ``None`` for none.
    """

    device: Device
    velocity_filter: VelocityFilter | None
    delay_samples: int
    acceleration: AccelerationEstimate
    qualities: tuple[str, ...]
    settings: QualitySettings
    mass: tuple[float, ...]
    damping: tuple[float, ...]
    robust: RobustBox | None = None

    @classmethod
    def of(cls, profile: Profile, robust: str = "off", samples: int = ROBUST_SAMPLES, seed: int = 0) -> RenderableRequest:
        """The request of ``profile``'s device, filter, delay and renderable section.

        Parameters
        ----------
        profile : Profile
            The device profile.
        robust : str, optional
            A key of :data:`ROBUST_KINDS`: ``"off"`` (default), ``"corners"`` or ``"samples"`` of the
            identified box; without a box (:func:`robust_box_reason`) the request has none.
        samples : int, optional
            Number of samples for ``robust="samples"``.
        seed : int, optional
            Seed of the samples.

        Returns
        -------
        RenderableRequest
            The request.

        Raises
        ------
        ValidationError
            When ``robust`` is not a key of :data:`ROBUST_KINDS`.
        """
        if robust not in ROBUST_KINDS:
            raise ValidationError("robust", f"one of {', '.join(ROBUST_KINDS)}", robust)
        drawn = robust == "samples"  # the corners have no count or seed: changing them recomputes nothing
        box = None if robust == "off" else RobustBox.of(profile, robust, int(samples) if drawn else 0,
                                                        int(seed) if drawn else 0)
        sec = renderable_section(profile)
        settings = QualitySettings(grasps=GRASPS[sec.grasps], band=(sec.band_low, sec.band_high),
                                   tolerance=sec.tolerance, encoder_resolution=sec.quiet_resolution,
                                   force_noise=sec.quiet_force_noise)
        mass = np.linspace(sec.mass_min, sec.mass_max, sec.mass_points)
        u = np.linspace(float(damping_axis(sec.damping_min)), float(damping_axis(sec.damping_max)), sec.damping_points)
        damping = damping_from_axis(u)
        damping[0], damping[-1] = sec.damping_min, sec.damping_max  # the ends exactly as given
        d, implementation = delays(profile)
        batch = box if isinstance(box, RobustBox) else None
        return cls(profile.device, profile_filter(profile), int(d) + int(implementation), sec.acceleration,
                   tuple(sec.qualities), settings, tuple(float(m) for m in mass), tuple(float(b) for b in damping),
                   batch)


@dataclass(frozen=True)
class RenderableStudy:
    """The renderable space on the request's grid and the M-width, with the same qualities.

    Attributes
    ----------
    space : RenderableSpace
        ``k_max`` [N/m] per (M, B), for all qualities and for each.
    width : MWidth
        The M-width [kg] (at B = K = 0), for all qualities and for each.
    """

    space: RenderableSpace
    width: MWidth


@none_if_cancelled
def renderable_study(request: RenderableRequest | Profile, *, progress: Progress | None = None,
                     cancelled: Cancelled | None = None) -> RenderableStudy | None:
    """The renderable space and the M-width of a profile (module docstring).

    Progress: the space's steps (one per batch of masses and grasp, one per other quality), then
    one for the M-width; ``None`` once cancelled.

    Parameters
    ----------
    request : RenderableRequest or Profile
        The request, or a profile.
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    RenderableStudy or None
        The space and the M-width, or ``None`` once cancelled.

    Raises
    ------
    ValidationError
        When a setting does not fit the device (e.g. the band above Nyquist).
    """
    req = RenderableRequest.of(request) if isinstance(request, Profile) else request
    steps = [1]

    def space_progress(done: int, total: int) -> None:
        steps[0] = total + 1
        report_progress(progress, done, total + 1)

    space = renderable_space(req.device, req.mass, req.damping, req.delay_samples, req.velocity_filter,
                             req.acceleration, req.qualities, settings=req.settings, progress=space_progress,
                             cancelled=cancelled)
    check_cancelled(cancelled)
    width = m_width(req.device, req.delay_samples, req.velocity_filter, req.acceleration, req.qualities,
                    settings=req.settings)
    report_progress(progress, steps[0], steps[0])
    return RenderableStudy(space, width)


@none_if_cancelled
def robust_study(request: RenderableRequest, *, progress: Progress | None = None,
                 cancelled: Cancelled | None = None) -> RobustRenderableSpace | None:
    """The space every device of the request's batch has (module docstring), in this thread.

    Progress counts devices; ``None`` once cancelled.

    Parameters
    ----------
    request : RenderableRequest
        A request with a batch (``RenderableRequest.of(profile, robust="corners")``).
    progress : Progress or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : Cancelled or None, optional
        Polled as ``cancelled() -> bool`` between devices; once true it returns ``None``.

    Returns
    -------
    RobustRenderableSpace or None
        The smallest ``k_max`` over the batch (and per quality), its binding device and volume, on
        the request's grid; ``None`` once cancelled.

    Raises
    ------
    ValidationError
        When the request has no batch (``robust``) or the box is refused.
    DeviceFailed
        When one device's space fails (named by its index).
    """
    if request.robust is None:
        raise ValidationError("robust", "a batch: RenderableRequest.of(profile, robust='corners' or 'samples')", None)
    devices = request.robust.devices(request.device)
    return robust_renderable_space(devices, request.mass, request.damping, request.delay_samples,
                                   request.velocity_filter, request.acceleration, request.qualities,
                                   settings=request.settings, workers=1, progress=progress, cancelled=cancelled)


def robust_m_width(request: RenderableRequest) -> MWidth:
    """The M-width every device of the request's batch has: the intersection of their M-widths.

    Each device's M-width (:func:`analysis.sampled.m_width`, at ``B = K = 0``) is an interval around
    ``M = 0`` for every quality, so the masses that every device renders are
    ``[max m_min, min m_max]``, for all qualities and for each.

    Parameters
    ----------
    request : RenderableRequest
        A request with a batch (``RenderableRequest.of(profile, robust="corners")``).

    Returns
    -------
    MWidth
        The batch's M-width [kg] (its ``controller`` is the request's, the same for every device).

    Raises
    ------
    ValidationError
        When the request has no batch (``robust``) or the box is refused.
    """
    if request.robust is None:
        raise ValidationError("robust", "a batch: RenderableRequest.of(profile, robust='corners' or 'samples')", None)
    widths = [m_width(d, request.delay_samples, request.velocity_filter, request.acceleration, request.qualities,
                      settings=request.settings) for d in request.robust.devices(request.device)]
    by_quality = {q: (max(w.by_quality[q][0] for w in widths), min(w.by_quality[q][1] for w in widths))
                  for q in widths[0].qualities}
    return MWidth(max(w.m_min for w in widths), min(w.m_max for w in widths), by_quality, widths[0].qualities,
                  widths[0].controller)


def k_max_at(space: RenderableSpace | RobustRenderableSpace, mass: float, damping: float, quality: str = "all") -> float:
    """``k_max`` [N/m] of the grid point nearest ``(M, B)`` (nearest on the signed-log damping axis).

    Parameters
    ----------
    space : RenderableSpace or RobustRenderableSpace
        The space (a device's or a batch's).
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].
    quality : str, optional
        ``"all"`` (every quality asked) or one of ``space.qualities``.

    Returns
    -------
    float
        The largest K [N/m] there; NaN outside the grid's ranges.
    """
    m, b = np.asarray(space.mass), np.asarray(space.damping)
    if not (m[0] <= mass <= m[-1] and b[0] <= damping <= b[-1]):
        return float("nan")
    i = int(np.argmin(np.abs(m - mass)))
    j = int(np.argmin(np.abs(damping_axis(b) - damping_axis(damping))))
    k = space.k_max if quality == "all" else space.by_quality[quality]
    return float(k[i, j])


def environment_edits(mass: float, damping: float) -> dict[str, float]:
    """The section's fields that set the rendered environment's ``(M, B)`` (a click on the space).

    Parameters
    ----------
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].

    Returns
    -------
    dict of str to float
        ``{"virtual_mass": M, "virtual_damping": B}``.
    """
    return {"virtual_mass": float(mass), "virtual_damping": float(damping)}
