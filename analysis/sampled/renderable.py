"""Qualities of a rendered environment, the renderable (M, B, K) space and the M-width (issue 24).

Colonnese & Chan ("Z-qualities and renderable mass-damping-stiffness spaces", IEEE Haptics
Symposium 2016) read a display's performance as the set of ``F = M a^ + B v^ + K x`` it renders
with chosen qualities; Colonnese & Okamura ("M-width: stability and accuracy of haptic rendering
of virtual mass", RSS 2012) call the interval of stably rendered virtual masses (at B = K = 0)
the M-width.  Here the environment is the impedance display's controller of
:mod:`analysis.sampled.rendered` in the exact sampled loop of :mod:`analysis.sampled.loop`.

The qualities (:data:`QUALITIES`: ``"stable"``, ``"passive"``, ``"accurate"``, ``"quiet"``) are
defined, one predicate each, in :mod:`analysis.sampled.qualities`.

The space (:func:`renderable_space`): for each ``(M, B)`` of a grid the largest K such that every
K in ``(0, K]`` (from ``k_range[0]``, 1 N/m, for stability) has each quality, 0 where none; each
quality's set in K is an interval from 0 by construction, so the space's ``k_max`` is the
smallest over the qualities.  Stability is traced along K by the batched first-crossing scan and
bracketing of :func:`~analysis.sampled.zwidth.stiffness_limits` (one ``expm`` per grasp from
:func:`~analysis.sampled.loop.discrete_plants`, one batch of eigenvalue problems per step over
every B of one M; never a 3-D grid); passivity, accuracy and quiet are closed forms over the grid.
At M = 0 the row is exactly :func:`~analysis.sampled.zwidth.zwidth_region`'s ``k_max`` (no mass
term is built).

Volume (:func:`space_volume`): ``int int log10(max(k_max, k_floor)/k_floor) du dM`` over the
grid by the trapezoid rule (kg decades^2), with the damping axis ``u(B) = sign(B) log10(1 + |B|/b_ref)`` (``b_ref`` = 1 N s/m
by default): logarithmic for ``|B| >> b_ref``, linear through 0, so negative dampings count
symmetrically.  The M-width (:func:`m_width`) is the interval of M around 0 in which every M has
every chosen quality at ``B = K = 0``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg

from analysis.chain.device import Device
from analysis.chain.limits import MAX_MAP_POINTS, check_count
from analysis.chain.velocity_filter import VelocityFilter
from analysis.errors import ValidationError
from analysis.progress import Cancelled, Progress, check_cancelled, report_progress
from analysis.sampled.passivity import required_damping
from analysis.sampled.qualities import (
    QualitySettings,
    accuracy_k,
    accuracy_mass_limits,
    check_qualities,
    quantization_force_noise,
    passive_k,
)
from analysis.sampled.rendered import (
    AccelerationEstimate,
    RenderingController,
    check_virtual_damping,
    check_virtual_mass,
)
from analysis.sampled.loop import (
    STABILITY_TOLERANCE,
    LoopSpec,
    closed_loop_matrices,
    discrete_plants,
    is_stable,
)
from analysis.sampled.sweeps import first_crossing
from analysis.sampled.terminations import Termination, god_object_wall
from analysis.sampled.zwidth import stiffness_limits

__all__ = ["RenderableSpace", "MWidth", "renderable_space", "m_width", "space_volume"]


@dataclass(frozen=True)
class RenderableSpace:
    """The renderable (M, B, K) space (module docstring); arrays are read-only.

    Parameters
    ----------
    mass : numpy.ndarray
        Virtual masses M [kg], strictly increasing, shape (NM,).
    damping : numpy.ndarray
        Virtual dampings B [N s/m], strictly increasing, shape (NB,).
    k_max : numpy.ndarray
        ``k_max[i, j]`` [N/m]: the largest K of ``(mass[i], damping[j])`` with every quality,
        0 where none; shape (NM, NB).
    by_quality : Mapping of str to numpy.ndarray
        The same for each quality asked, shape (NM, NB) each.
    volume : float
        The volume of the space [kg decades^2] (module docstring).
    qualities : tuple of str
        The qualities asked.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    settings : QualitySettings
        The qualities' settings.
    """

    mass: np.ndarray
    damping: np.ndarray
    k_max: np.ndarray
    by_quality: Mapping[str, np.ndarray]
    volume: float
    qualities: tuple[str, ...]
    controller: RenderingController
    settings: QualitySettings = field(default_factory=QualitySettings)


@dataclass(frozen=True)
class MWidth:
    """The M-width: the interval ``[m_min, m_max]`` of virtual masses at ``B = K = 0`` (module docstring).

    Parameters
    ----------
    m_min : float
        Lowest mass [kg] (at most 0; ``-inf`` when no limit within ``m_range``).
    m_max : float
        Highest mass [kg] (at least 0; ``inf`` when no limit within ``m_range``).
    by_quality : Mapping of str to tuple of (float, float)
        The interval of each quality asked.
    qualities : tuple of str
        The qualities asked.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    """

    m_min: float
    m_max: float
    by_quality: Mapping[str, tuple[float, float]]
    qualities: tuple[str, ...]
    controller: RenderingController

    @property
    def width(self) -> float:
        """``m_max - m_min`` [kg]."""
        return self.m_max - self.m_min


# -- validation ------------------------------------------------------------------------------
def _grid(name: str, values: object, check) -> np.ndarray:
    try:
        arr = np.asarray(values, dtype=float).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise ValidationError(name, "real numbers", values) from exc
    if arr.size == 0:
        raise ValidationError(name, "at least one value", values)
    for i, x in enumerate(arr.tolist()):
        check(name, x, i)
    if np.any(np.diff(arr) <= 0):
        raise ValidationError(name, "strictly increasing values", values)
    arr.flags.writeable = False
    return arr


def _controller(delay_samples: int, velocity_filter: VelocityFilter | None,
                acceleration: AccelerationEstimate | None, device: Device) -> RenderingController:
    c = RenderingController(delay_samples, velocity_filter, acceleration)
    c.check(device.sample_time)
    return c


# -- the space -------------------------------------------------------------------------------
#: Rows (M, B) per batch of the stability trace: enough to amortize the loop's construction.
_ROWS_PER_BATCH = 400


def _stable_k(device: Device, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
              s: QualitySettings, step) -> np.ndarray:
    """Largest stable K per (M, B): M = 0 alone without a mass term (the Z-width region's own
    trace), the other masses in batches of about :data:`_ROWS_PER_BATCH` rows, per grasp."""
    out = np.full((mass.size, damping.size), np.inf)
    nb = damping.size
    zero = np.flatnonzero(mass == 0.0)
    rest = np.flatnonzero(mass != 0.0)
    per = max(1, _ROWS_PER_BATCH // nb)
    batches = [(zero, False)] if zero.size else []
    batches += [(rest[i:i + per], True) for i in range(0, rest.size, per)]
    for idx, inertial in batches:
        for g in s.grasps:
            step()
            term = Termination(g, god_object_wall())
            kw = {"mass": np.repeat(mass[idx], nb), "acceleration": controller.acceleration} if inertial else {}
            k = stiffness_limits(device, np.tile(damping, idx.size), controller.delay_samples,
                                 controller.velocity_filter, termination=term, k_range=s.k_range, **kw)
            out[idx] = np.minimum(out[idx], k.reshape(idx.size, nb))
    return out


def _stable_steps(mass: np.ndarray, damping: np.ndarray, s: QualitySettings) -> int:
    per = max(1, _ROWS_PER_BATCH // damping.size)
    nz = int(np.count_nonzero(mass != 0.0))
    return (int(nz < mass.size) + -(-nz // per)) * len(s.grasps)


def space_volume(mass, damping, k_max, settings: QualitySettings | None = None) -> float:
    """The volume of a renderable space: M linear, B and K on logarithmic axes (module docstring).

    ``int int log10(min(max(k_max, k_lo), k_hi)/k_lo) du dM`` over the grid by the trapezoid
    rule, with ``(k_lo, k_hi) = settings.k_range`` and the signed-log damping axis
    ``u(B) = sign(B) log10(1 + |B|/b_ref)`` (``b_ref = settings.b_ref``): logarithmic for
    ``|B| >> b_ref``, linear through 0.  A cell with no K (``k_max = 0``) adds nothing; a grid
    with one mass or one damping has volume 0.  The one rule for the volume of
    :class:`RenderableSpace` and of a batch's robust space
    (:class:`~analysis.sampled.batch.RobustRenderableSpace`), so that the two compare (Colonnese &
    Chan, "Z-qualities and renderable mass-damping-stiffness spaces", IEEE Haptics Symposium
    2016, compare displays by the extent of their spaces).

    Parameters
    ----------
    mass : array_like
        Virtual masses M [kg], strictly increasing, shape (NM,).
    damping : array_like
        Virtual dampings B [N s/m], strictly increasing, shape (NB,).
    k_max : array_like
        ``k_max[i, j]`` [N/m] of ``(mass[i], damping[j])``, at least 0, shape (NM, NB).
    settings : QualitySettings or None, optional
        Gives ``k_range`` and ``b_ref``; ``None`` for the defaults (1 to 1e9 N/m, 1 N s/m).

    Returns
    -------
    float
        The volume [kg decades^2].

    Raises
    ------
    ValidationError
        When ``k_max``'s shape is not (NM, NB) (``k_max``), a value is NaN or negative
        (``k_max``), or ``settings`` is not a QualitySettings.
    """
    s = QualitySettings() if settings is None else settings
    if not isinstance(s, QualitySettings):
        raise ValidationError("settings", "a QualitySettings or None", settings)
    m = np.asarray(mass, dtype=float).reshape(-1)
    b = np.asarray(damping, dtype=float).reshape(-1)
    k = np.asarray(k_max, dtype=float)
    if k.shape != (m.size, b.size):
        raise ValidationError("k_max", f"shape ({m.size}, {b.size}) (masses, dampings)", k.shape)
    if np.isnan(k).any() or np.any(k < 0):
        raise ValidationError("k_max", "values >= 0 (N/m)", k)
    if m.size < 2 or b.size < 2:
        return 0.0
    lo, hi = s.k_range
    h = np.log10(np.maximum(np.minimum(k, hi), lo) / lo)
    u = np.sign(b) * np.log10(1.0 + np.abs(b) / s.b_ref)
    return float(np.trapezoid(np.trapezoid(h, u, axis=1), m))


def renderable_space(device: Device, mass, damping, delay_samples: int = 1,
                     velocity_filter: VelocityFilter | None = None, acceleration: AccelerationEstimate | None = None,
                     qualities: Sequence[str] = ("stable",), *, settings: QualitySettings | None = None,
                     progress: Progress | None = None, cancelled: Cancelled | None = None) -> RenderableSpace:
    """The renderable (M, B, K) space with chosen qualities (module docstring).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    mass : array_like
        Virtual masses M [kg], strictly increasing, either sign, ``|M| <= 1e3``, shape (NM,).
    damping : array_like
        Virtual dampings B [N s/m], strictly increasing, either sign, ``|B| <= 1e8``, shape (NB,).
    delay_samples : int, optional
        Computation delay ``d`` in samples (default 1).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter; ``None`` for the backward difference.
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate; ``None`` for the second backward difference.
    qualities : sequence of str, optional
        Names of :data:`QUALITIES` (default ``("stable",)``).
    settings : QualitySettings or None, optional
        The qualities' settings; ``None`` for the defaults.
    progress : callable, optional
        ``progress(done, total)`` after each step (one per mass and grasp, and one per other quality).
    cancelled : callable, optional
        ``cancelled() -> bool``, polled between steps.

    Returns
    -------
    RenderableSpace
        ``k_max`` [N/m] per ``(M, B)`` for all qualities and for each, and the volume.

    Raises
    ------
    ValidationError
        When a grid is empty, not strictly increasing or has a value out of range (naming
        ``mass`` or ``damping``), a quality is unknown, or a setting is out of range.
    OperationCancelled
        When ``cancelled()`` turns true.
    """
    M = _grid("mass", mass, check_virtual_mass)
    B = _grid("damping", damping, check_virtual_damping)
    check_count("renderable space points", M.size * B.size, MAX_MAP_POINTS, f"{M.size} × {B.size}")
    names = check_qualities(qualities)
    s = QualitySettings() if settings is None else settings
    if not isinstance(s, QualitySettings):
        raise ValidationError("settings", "a QualitySettings or None", settings)
    s.check(device.sample_time, names)
    ctrl = _controller(delay_samples, velocity_filter, acceleration, device)
    T, ceiling = device.sample_time, s.k_range[1]
    need_stable = "stable" in names or "accurate" in names
    total = (_stable_steps(M, B, s) if need_stable else 0) + sum(q in names for q in ("passive", "accurate", "quiet"))
    done = [0]

    def step() -> None:
        check_cancelled(cancelled)
        if done[0]:
            report_progress(progress, done[0], total)
        done[0] += 1

    Mg, Bg = np.meshgrid(M, B, indexing="ij")
    by: dict[str, np.ndarray] = {}
    stable = _stable_k(device, ctrl, M, B, s, step) if need_stable else None
    if "stable" in names:
        by["stable"] = stable
    if "passive" in names:
        step()
        by["passive"] = passive_k(device, ctrl, Mg.ravel(), Bg.ravel(), ceiling).reshape(Mg.shape)
    if "accurate" in names:
        step()
        acc = accuracy_k(device, ctrl, Mg.ravel(), Bg.ravel(), s).reshape(Mg.shape)
        by["accurate"] = np.minimum(np.minimum(acc, ceiling), stable)
    if "quiet" in names:
        step()
        f = quantization_force_noise(T, ctrl, Mg.ravel(), Bg.ravel(), s.encoder_resolution).reshape(Mg.shape)
        by["quiet"] = np.where(f <= s.force_noise, ceiling, 0.0)
    report_progress(progress, done[0], total)
    ordered = {q: by[q] for q in names}
    for a in ordered.values():
        a.flags.writeable = False
    k = np.min(np.stack(list(ordered.values())), axis=0)
    k.flags.writeable = False
    return RenderableSpace(mass=M, damping=B, k_max=k, by_quality=dict(ordered),
                           volume=space_volume(M, B, k, s), qualities=names, controller=ctrl, settings=s)


# -- the M-width -----------------------------------------------------------------------------
#: A unit-1 eigenvalue of a balanced ``Phi`` is structural (free motion) when the smallest singular
#: value of ``Phi - I`` is at most this, relative to ``max(1, ||Phi||_2)``: about 1e-17 for the
#: free position and the free velocity, and a root ``eps`` away from 1 leaves ~``eps``, so only a
#: root within ~1e-13 of z = 1 (inside the one stability rule's 1e-12) is taken for one.
FREE_MOTION_TOL = 1e-13
#: A loop whose deflated radius at M = 0 is within this of 1 has a marginal (undamped) root.
_MARGINAL = 1e-9


def free_motion_radius(Phi: np.ndarray) -> np.ndarray:
    """Spectral radius of each closed loop without its exact z = 1 modes of free motion.

    At ``B = K = 0`` the controller sees no position, so the loop keeps the free translation at
    ``z = 1`` (and, with no damping to ground, the free velocity: a Jordan block there); at the
    M-width's lower limit of a mass without damping a third, real root crosses the unit circle at
    ``z = 1`` itself (Jury: ``mu = -1/2`` in ``z^{d+2} + mu (z + 1)``).  The rigid-body clamp of
    :func:`~analysis.sampled.loop.spectral_radius` (``|z - 1| < RIGID_TOL`` counts as 1) would hide
    that root within 1e-6 and the clustered roots (split by ``eps^{1/3}``) blur the crossing; here
    the structural roots are deflated exactly instead: ``Phi`` is balanced
    (:func:`scipy.linalg.matrix_balance`), and while ``Phi - I`` is singular
    (:data:`FREE_MOTION_TOL`) its null vector ``v`` (the SVD's last right singular vector, well
    conditioned for a Jordan block too) is rotated onto ``e_1`` by a Householder reflection ``Q``
    (``Q Phi Q = [[1, *], [0, Phi_2]]``) and ``Phi_2`` is kept.  The radius of what is left is
    not clamped.

    Parameters
    ----------
    Phi : numpy.ndarray
        Closed-loop state matrices, shape (B, N, N).

    Returns
    -------
    numpy.ndarray
        Spectral radii without the free-motion roots, shape (B,) (0 when nothing is left).
    """
    out = np.zeros(Phi.shape[0])
    for i, A in enumerate(Phi):
        A, _ = linalg.matrix_balance(A, permute=False)
        while A.shape[0]:
            n = A.shape[0]
            _, sv, vh = np.linalg.svd(A - np.eye(n))
            if sv[-1] > FREE_MOTION_TOL * max(1.0, float(sv[0])):
                break
            h = vh[-1].copy()
            h[0] += math.copysign(1.0, h[0])
            h /= np.linalg.norm(h)
            A = A - 2.0 * np.outer(h, h @ A)
            A = (A - 2.0 * np.outer(A @ h, h))[1:, 1:]
        out[i] = float(np.abs(np.linalg.eigvals(A)).max()) if A.shape[0] else 0.0
    return out


def free_radius(device: Device, ctrl: RenderingController, mass: np.ndarray, grasps: Sequence) -> np.ndarray:
    """Worst free-motion-deflated radius (:func:`free_motion_radius`) over ``grasps`` of each
    virtual mass at ``B = K = 0`` against the god-object wall (the loop of ``"stable"``)."""
    spec = LoopSpec("impedance", (1.0, 1.0), delay_samples=ctrl.delay_samples,
                    velocity_filter=ctrl.velocity_filter, acceleration=ctrl.acceleration)
    gs = tuple(grasps)
    plants = discrete_plants(device, gs)
    wall, n = god_object_wall(), mass.size
    terms = [Termination(g, wall) for g in gs for _ in range(n)]
    z = np.zeros(n * len(gs))
    Phi = closed_loop_matrices(device, spec, terms, plants, np.repeat(np.arange(len(gs)), n),
                               {"kc": z, "bc": z, "mv": np.tile(mass, len(gs))})
    return free_motion_radius(Phi).reshape(len(gs), n).max(axis=0)


def _stable_interval(device: Device, ctrl: RenderingController, s: QualitySettings,
                     m_range: tuple[float, float]) -> tuple[float, float]:
    r0 = float(free_radius(device, ctrl, np.zeros(1), s.grasps)[0])
    if not is_stable(r0):
        return 0.0, 0.0
    # no marginal root at M = 0 (an undamped mode): trace rho = 1 itself, so that no reported
    # limit passes the exact one (the one stability rule's 1e-12 would allow ~1e-12 kg beyond)
    margin = STABILITY_TOLERANCE if r0 < 1.0 - _MARGINAL else 0.0

    def rho(values: np.ndarray) -> np.ndarray:
        return free_radius(device, ctrl, values, s.grasps) + margin

    hi = first_crossing(rho, m_range[0], m_range[1], True)
    lo = first_crossing(lambda v: rho(-v), m_range[0], m_range[1], True)
    return -lo, hi


def _mass_controller(ctrl: RenderingController, T: float, sign: float):
    num, den = ctrl.acceleration.transfer_function(T, ctrl.velocity_filter)
    d = ctrl.delay_samples

    def H(z: np.ndarray) -> np.ndarray:
        zi = 1.0 / z
        return sign * zi ** d * np.polyval(num[::-1], zi) / np.polyval(den[::-1], zi)

    return H


def _passive_interval(device: Device, ctrl: RenderingController) -> tuple[float, float]:
    b, T = device.total_ground_damping, device.sample_time
    up, _ = required_damping(_mass_controller(ctrl, T, 1.0), T)
    down, _ = required_damping(_mass_controller(ctrl, T, -1.0), T)
    hi = b / up if up > 0 else math.inf
    lo = -b / down if down > 0 else -math.inf
    return lo, hi


def m_width(device: Device, delay_samples: int = 1, velocity_filter: VelocityFilter | None = None,
            acceleration: AccelerationEstimate | None = None, qualities: Sequence[str] = ("stable",), *,
            settings: QualitySettings | None = None, m_range: tuple[float, float] = (1e-6, 1e3)) -> MWidth:
    """The M-width of Colonnese & Okamura (RSS 2012): the virtual masses renderable at ``B = K = 0``.

    For each quality the interval around ``M = 0`` in which every M has it (the first crossing
    each way, by the scan and Brent bracketing of :func:`~analysis.sampled.sweeps.first_crossing`
    for stability: 24 points per decade of ``|M|`` from ``m_range[0]`` to ``m_range[1]``, on the
    radius without the exact free-motion roots at z = 1 (:func:`free_motion_radius`), traced
    against ``rho = 1`` itself when the loop at M = 0 has no undamped root, so that no reported
    limit lies beyond the exact one);
    ``"passive"`` from the Colgate-Schenkel criterion ``b >= M c_M(theta)``
    (:func:`~analysis.sampled.passivity.required_damping` of ``+-A(z) z^{-d}``); ``"accurate"``
    is the stable interval cut to the masses whose pure mass is within the tolerance at the
    handle over the band (:func:`~analysis.sampled.qualities.accuracy_mass_limits`; for a rigid
    device the relative error does not depend on M: all of it or ``(0, 0)``); ``"quiet"`` is
    ``|M| <= F_noise/sigma_a``.  The M-width is their intersection.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    delay_samples : int, optional
        Computation delay ``d`` in samples (default 1).
    velocity_filter : VelocityFilter or None, optional
        The velocity filter (used by the ``"filtered_velocity"`` acceleration estimate).
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate; ``None`` for the second backward difference.
    qualities : sequence of str, optional
        Names of :data:`QUALITIES` (default ``("stable",)``).
    settings : QualitySettings or None, optional
        The qualities' settings; ``None`` for the defaults.
    m_range : tuple of (float, float), optional
        The scanned ``|M|`` [kg], ``(low, high)``; ``inf`` is reported beyond ``high``.

    Returns
    -------
    MWidth
        ``m_min <= 0 <= m_max`` [kg] and the interval of each quality.

    Raises
    ------
    ValidationError
        When a quality is unknown, ``m_range`` is not ``0 < low < high``, or a setting is out of
        range.
    """
    names = check_qualities(qualities)
    s = QualitySettings() if settings is None else settings
    s.check(device.sample_time, names)
    lo_m, hi_m = (float(x) for x in m_range)
    if not (0 < lo_m < hi_m and math.isfinite(hi_m)):
        raise ValidationError("m_range", "0 < low < high, finite (kg)", m_range)
    ctrl = _controller(delay_samples, velocity_filter, acceleration, device)
    T = device.sample_time
    by: dict[str, tuple[float, float]] = {}
    if "stable" in names or "accurate" in names:
        stable = _stable_interval(device, ctrl, s, (lo_m, hi_m))
        by["stable"] = stable
    if "passive" in names:
        by["passive"] = _passive_interval(device, ctrl)
    if "accurate" in names:
        a_lo, a_hi = accuracy_mass_limits(device, ctrl, s)
        lo_a, hi_a = max(stable[0], a_lo), min(stable[1], a_hi)
        by["accurate"] = (lo_a, hi_a) if lo_a < hi_a else (0.0, 0.0)
    if "quiet" in names:
        f = float(quantization_force_noise(T, ctrl, np.ones(1), np.zeros(1), s.encoder_resolution)[0])
        by["quiet"] = (-s.force_noise / f, s.force_noise / f)
    ordered = {q: by[q] for q in names}
    lo = max(v[0] for v in ordered.values())
    hi = min(v[1] for v in ordered.values())
    return MWidth(m_min=min(lo, 0.0), m_max=max(hi, 0.0), by_quality=dict(ordered), qualities=names,
                  controller=ctrl)
