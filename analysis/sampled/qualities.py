"""The qualities of a rendered environment: one predicate each (issue 24).

Colonnese & Chan ("Z-qualities and renderable mass-damping-stiffness spaces", IEEE Haptics
Symposium 2016) qualify a rendered ``F = M a^ + B v^ + K x`` (:mod:`analysis.sampled.rendered`)
by properties beyond stability.  Qualities (one predicate each, :data:`QUALITIES`):

* ``"stable"`` (:func:`renders_stably`): the exact loop against the god-object wall (the
  environment acts on the encoder position itself) has spectral radius at most
  ``1 + STABILITY_TOLERANCE`` (:func:`~analysis.sampled.loop.is_stable`), for every grasp of
  :attr:`QualitySettings.grasps` (hands-off by default).
* ``"passive"`` (:func:`renders_passively`): Colgate & Schenkel's sampled-data passivity test of
  the rigid-body device (total mass, total damping to ground), extended with the mass term
  (:func:`~analysis.sampled.passivity.passivity_limits`, ``virtual_masses``).
* ``"accurate"`` (:func:`renders_accurately`): stable, and over the band ``[w1, w2]`` the
  rendered impedance ``G(jw)/(jw)`` (:func:`~analysis.sampled.rendered.rendered_force_response`)
  is within a relative tolerance ``eps`` of ``M s + B + K/s``:
  ``|G - (K + j w B - w^2 M)| <= eps |K + j w B - w^2 M|`` on :attr:`QualitySettings.band_points`
  log-spaced frequencies.  :func:`effective_environment` reports what the user feels: the
  effective stiffness ``Re G`` and damping ``Im G/w`` of Colonnese, Siu, Abbott & Okamura
  (IEEE Trans. Haptics 2015), and the ``(M, B, K)`` fitted to ``G`` over the band.  The
  impedance is the controller's, at the encoder (the handle of a rigid device).
* ``"quiet"`` (:func:`renders_quietly`): the force noise of encoder quantization (white, ``q^2/12``)
  through ``B V(z) + M A(z)`` is at most ``F_noise`` (the Z-width tab's criterion of
  :mod:`analysis.sampled.velocity_noise`, with the mass term; the spring's ``K q/sqrt(12)`` is
  left out as there, so quiet does not depend on K).

Each predicate has a vectorized kernel over a grid of ``(M, B)`` that
:mod:`analysis.sampled.renderable` uses for the space.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import Real, integer
from analysis.errors import ValidationError
from analysis.sampled.loop import LoopSpec, is_stable
from analysis.sampled.passivity import passivity_limits
from analysis.sampled.rendered import (
    RenderedEnvironment,
    RenderingController,
    check_virtual_damping,
    check_virtual_mass,
    rendered_force_response,
)
from analysis.sampled.sweeps import radii
from analysis.sampled.terminations import HANDS_OFF, Grasp, Termination, god_object_wall
from analysis.sampled.velocity_noise import (
    DEFAULT_FORCE_NOISE,
    ENCODER_RESOLUTION,
    FORCE_NOISE,
    transfer_noise_gain,
)

__all__ = [
    "QUALITIES",
    "QualitySettings",
    "EffectiveEnvironment",
    "renders_stably",
    "renders_passively",
    "renders_accurately",
    "renders_quietly",
    "effective_environment",
    "check_qualities",
    "stable_radius",
    "passive_k",
    "accuracy_k",
    "quantization_force_noise",
]

#: The qualities and their definitions (module docstring).
QUALITIES = {
    "stable": "the exact sampled loop is stable for every grasp of the set",
    "passive": "the rigid-body device is passive (Colgate & Schenkel, with the mass term)",
    "accurate": "stable, and the rendered impedance within the tolerance over the band",
    "quiet": "the force noise of encoder quantization is within the limit",
}
_TOL = Real(lo=0.0, lo_open=True, hi=10.0, unit="")
_BAND = Real(lo=0.0, lo_open=True, unit="rad/s")
_BREF = Real(lo=0.0, lo_open=True, unit="N s/m")


@dataclass(frozen=True)
class QualitySettings:
    """The settings of the qualities (module docstring).

    Parameters
    ----------
    grasps : tuple of Grasp, optional
        The grasps for ``"stable"`` (and so ``"accurate"``); hands-off only by default.
    band : tuple of (float, float), optional
        ``(w1, w2)`` [rad/s] of ``"accurate"``, ``0 < w1 <= w2 <`` Nyquist; 0.5 to 5 Hz (the band
        of voluntary hand motion) by default.
    tolerance : float, optional
        Relative tolerance ``eps`` of ``"accurate"`` (default 0.1), in ``(0, 10]``.
    encoder_resolution : float or None, optional
        Encoder resolution ``q`` [m] of ``"quiet"`` (required by it), 1e-9 to 1e-2.
    force_noise : float, optional
        Force-noise limit ``F_noise`` [N rms] of ``"quiet"`` (default 0.1).
    k_range : tuple of (float, float), optional
        The scanned K [N/m] ``(k_floor, k_ceiling)``: stability is traced from ``k_floor``; K
        beyond ``k_ceiling`` is not looked at (``k_max`` is capped there).
    band_points : int, optional
        Log-spaced frequencies of the band (default 64), 2 to 10000.
    b_ref : float, optional
        The damping scale [N s/m] of the volume's damping axis (default 1).

    Raises
    ------
    ValidationError
        When a value is out of range or of the wrong type.
    """

    grasps: tuple[Grasp, ...] = (HANDS_OFF,)
    band: tuple[float, float] = (math.pi, 10.0 * math.pi)
    tolerance: float = 0.1
    encoder_resolution: float | None = None
    force_noise: float = DEFAULT_FORCE_NOISE
    k_range: tuple[float, float] = (1.0, 1e9)
    band_points: int = 64
    b_ref: float = 1.0

    def __post_init__(self) -> None:
        gs = tuple(self.grasps) if isinstance(self.grasps, Sequence) else None
        if not gs or not all(isinstance(g, Grasp) for g in gs):
            raise ValidationError("grasps", "a non-empty sequence of Grasp", self.grasps)
        object.__setattr__(self, "grasps", gs)
        try:
            w1, w2 = (_BAND("band", w, i) for i, w in enumerate(self.band))
        except (TypeError, ValueError) as exc:
            if isinstance(exc, ValidationError):
                raise
            raise ValidationError("band", "a pair (w1, w2) of rad/s", self.band) from exc
        if w2 < w1:
            raise ValidationError("band", "w1 <= w2 (rad/s)", self.band)
        object.__setattr__(self, "band", (w1, w2))
        object.__setattr__(self, "tolerance", _TOL("tolerance", self.tolerance))
        if self.encoder_resolution is not None:
            object.__setattr__(self, "encoder_resolution",
                               ENCODER_RESOLUTION("encoder_resolution", self.encoder_resolution))
        object.__setattr__(self, "force_noise", FORCE_NOISE("force_noise", self.force_noise))
        lo, hi = (float(x) for x in self.k_range)
        if not (0 < lo < hi and math.isfinite(hi)):
            raise ValidationError("k_range", "0 < low < high, finite (N/m)", self.k_range)
        object.__setattr__(self, "k_range", (lo, hi))
        object.__setattr__(self, "band_points", integer("band_points", self.band_points, 2, 10_000))
        object.__setattr__(self, "b_ref", _BREF("b_ref", self.b_ref))

    def check(self, sample_time: float, qualities: Sequence[str]) -> None:
        """Check the settings that the ``qualities`` use against the device.

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s].
        qualities : sequence of str
            The qualities asked.

        Raises
        ------
        ValidationError
            When the band reaches Nyquist ``pi/T`` (``"accurate"``), or ``"quiet"`` has no
            encoder resolution.
        """
        if "accurate" in qualities and not self.band[1] < math.pi / sample_time:
            raise ValidationError("band", f"below Nyquist = {math.pi / sample_time:.6g} rad/s", self.band)
        if "quiet" in qualities and self.encoder_resolution is None:
            raise ValidationError("encoder_resolution", "an encoder resolution (m) for the quiet quality", None)

    def frequencies(self) -> np.ndarray:
        """The band's ``band_points`` log-spaced frequencies [rad/s].

        Returns
        -------
        numpy.ndarray
            Shape (band_points,).
        """
        return np.geomspace(self.band[0], self.band[1], self.band_points)


@dataclass(frozen=True)
class EffectiveEnvironment:
    """What the user feels of a rendered environment (Colonnese, Siu, Abbott & Okamura 2015).

    Parameters
    ----------
    w : numpy.ndarray
        Frequencies [rad/s], shape (N,).
    stiffness : numpy.ndarray
        Effective stiffness ``Re G(jw)`` [N/m] (the spring felt, mass included), shape (N,).
    damping : numpy.ndarray
        Effective damping ``Im G(jw)/w`` [N s/m], shape (N,).
    error : numpy.ndarray
        Relative error ``|G - G_target|/|G_target|``, shape (N,) (NaN where the target is 0).
    fitted_mass : float
        ``M`` [kg] of ``Re G ~ K - M w^2`` fitted over the band (least squares).
    fitted_damping : float
        ``B`` [N s/m]: the mean of ``Im G/w`` over the band.
    fitted_stiffness : float
        ``K`` [N/m] of the same fit as ``fitted_mass``.
    """

    w: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    error: np.ndarray
    fitted_mass: float
    fitted_damping: float
    fitted_stiffness: float


def check_qualities(qualities: object) -> tuple[str, ...]:
    """The quality names, validated (``ValidationError`` on ``qualities``), without repeats."""
    names = (qualities,) if isinstance(qualities, str) else qualities
    try:
        out = tuple(dict.fromkeys(names))
    except TypeError as exc:
        raise ValidationError("qualities", ", ".join(QUALITIES), qualities) from exc
    if not out:
        raise ValidationError("qualities", "at least one of " + ", ".join(QUALITIES), qualities)
    for q in out:
        if q not in QUALITIES:
            raise ValidationError("qualities", ", ".join(QUALITIES), q)
    return out


def stable_radius(device: Device, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
                  stiffness: np.ndarray, grasps: Sequence[Grasp]) -> np.ndarray:
    """Worst spectral radius over ``grasps`` of each ``(M, B, K)`` (flat arrays of one size)."""
    spec = LoopSpec("impedance", (1.0, 1.0), delay_samples=controller.delay_samples,
                    velocity_filter=controller.velocity_filter, acceleration=controller.acceleration)
    wall = god_object_wall()
    n, G = mass.size, len(grasps)
    terms = [Termination(g, wall) for g in grasps for _ in range(n)]
    ov = {"kc": np.tile(stiffness, G), "bc": np.tile(damping, G), "mv": np.tile(mass, G)}
    return radii(device, spec, terms, ov).reshape(G, n).max(axis=0)


def renders_stably(device: Device, controller: RenderingController, mass: float, damping: float,
                   stiffness: float, settings: QualitySettings | None = None) -> bool:
    """Quality ``"stable"``: the exact sampled loop is stable for every grasp (module docstring).

    Colgate & Brown's criterion of the Z-width (ICRA 1994), on the exact loop: spectral radius at
    most ``1 + STABILITY_TOLERANCE`` against the god-object wall, hands-off or for every grasp
    of ``settings.grasps``.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].
    stiffness : float
        Virtual stiffness K [N/m].
    settings : QualitySettings or None, optional
        The grasps; ``None`` for the defaults.

    Returns
    -------
    bool
        Whether the loop is stable.
    """
    env = RenderedEnvironment(mass, damping, stiffness)
    s = settings or QualitySettings()
    r = stable_radius(device, controller, np.array([env.mass]), np.array([env.damping]),
                       np.array([env.stiffness]), s.grasps)
    return bool(is_stable(r[0]))


def passive_k(device: Device, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
              ceiling: float) -> np.ndarray:
    """Largest passive K per (M, B) (flat arrays), 0 where none, capped at ``ceiling``: the
    Colgate-Schenkel limit with the mass term on a 2001-point grid refined on 65 points."""
    k = passivity_limits(device.total_mass, device.total_ground_damping, device.sample_time, damping,
                         controller.delay_samples, 2001, velocity_filter=controller.velocity_filter,
                         virtual_masses=mass, acceleration=controller.acceleration, fine_points=65)
    return np.minimum(np.where(np.isnan(k), 0.0, k), ceiling)


def renders_passively(device: Device, controller: RenderingController, mass: float, damping: float,
                      stiffness: float, settings: QualitySettings | None = None) -> bool:
    """Quality ``"passive"``: Colgate & Schenkel's test with the mass term (module docstring).

    J. E. Colgate and G. G. Schenkel, J. Robotic Systems 14(1), 1997: the rigid-body device
    (total mass, total damping ``b`` to ground) with the controller ``z^{-d}(K + B V + M A)``
    through the hold is passive iff ``b >= K a(theta) - B r(theta) + c_M(theta)`` for every
    ``theta`` (:func:`~analysis.sampled.passivity.mass_passivity_term`).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].
    stiffness : float
        Virtual stiffness K [N/m].
    settings : QualitySettings or None, optional
        Unused (the predicates share one signature; passivity has no setting).

    Returns
    -------
    bool
        Whether every K' in ``(0, stiffness]`` is passive.
    """
    env = RenderedEnvironment(mass, damping, stiffness)
    k = passive_k(device, controller, np.array([env.mass]), np.array([env.damping]), math.inf)
    return bool(env.stiffness <= k[0] and k[0] > 0)


def accuracy_k(T: float, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
                settings: QualitySettings) -> np.ndarray:
    """Per (M, B): the largest K such that every K' in (0, K] is within ``eps`` (inf: no limit).

    Per frequency the condition ``|K alpha + beta| <= eps |K + gamma|`` is ``q(K) <= 0`` for a
    quadratic ``q``; the first K > 0 where ``q`` turns positive is a root (or 0).
    """
    w = settings.frequencies()
    P = rendered_force_response(w, T, controller, RenderedEnvironment(stiffness=1.0))  # hold x delay
    V = controller.velocity_response(w, T)
    A = controller.acceleration_response(w, T)
    M, B = mass[:, None], damping[:, None]
    alpha = P - 1.0
    beta = B * (P * V - 1j * w) + M * (P * A + w * w)
    gamma = 1j * w * B - w * w * M
    e2 = settings.tolerance ** 2
    qa = np.abs(alpha) ** 2 - e2 + 0.0 * M
    qb = 2.0 * (np.real(alpha * np.conj(beta)) - e2 * np.real(gamma))
    qc = np.abs(beta) ** 2 - e2 * np.abs(gamma) ** 2
    disc = np.maximum(qb * qb - 4.0 * qa * qc, 0.0)
    sq = np.sqrt(disc)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_lo = np.where(qa != 0, np.minimum((-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)), np.nan)
        r_hi = np.where(qa != 0, np.maximum((-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)), np.nan)
        lin = np.where(qb > 0, -qc / qb, np.inf)
    k = np.where(qa > 0, r_hi, np.where(qa < 0, np.where((qb * qb - 4 * qa * qc > 0) & (r_lo >= 0), r_lo, np.inf),
                                        lin))
    bad0 = (qc > 0) | ((qc == 0) & ((qb > 0) | ((qb == 0) & (qa > 0))))
    k = np.where(bad0, 0.0, np.maximum(k, 0.0))
    return k.min(axis=1)


def renders_accurately(device: Device, controller: RenderingController, mass: float, damping: float,
                       stiffness: float, settings: QualitySettings | None = None) -> bool:
    """Quality ``"accurate"``: stable, and within ``eps`` of ``M s + B + K/s`` over the band.

    The rendered impedance ``G(jw)/(jw)`` of the sampled controller through the hold
    (:func:`~analysis.sampled.rendered.rendered_force_response`; Colonnese, Siu, Abbott &
    Okamura, IEEE Trans. Haptics 2015) against the target, relative error at most
    ``settings.tolerance`` at every frequency of the band; and :func:`renders_stably`.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].
    stiffness : float
        Virtual stiffness K [N/m].
    settings : QualitySettings or None, optional
        Band, tolerance and grasps; ``None`` for the defaults.

    Returns
    -------
    bool
        Whether the environment renders stably and accurately.

    Raises
    ------
    ValidationError
        When the band reaches Nyquist.
    """
    s = settings or QualitySettings()
    s.check(device.sample_time, ("accurate",))
    env = RenderedEnvironment(mass, damping, stiffness)
    eff = effective_environment(device, env, controller, s)
    ok = bool(np.all(eff.error <= s.tolerance)) if env != RenderedEnvironment() else True
    return ok and renders_stably(device, controller, mass, damping, stiffness, s)


def _noise_gains(T: float, controller: RenderingController) -> tuple[float, float, float]:
    """``(g_V^2, g_A^2, g_VA)``: the force noise gain of ``B V + M A`` is ``B^2 g_V^2 + 2 B M g_VA + M^2 g_A^2``."""
    nv, dv = (controller.velocity_filter or VelocityFilter()).transfer_function(T)
    na, da = controller.acceleration.transfer_function(T, controller.velocity_filter)
    gv, ga = transfer_noise_gain(nv, dv) ** 2, transfer_noise_gain(na, da) ** 2
    both = transfer_noise_gain(np.polyadd(np.polymul(nv, da)[::-1], np.polymul(na, dv)[::-1])[::-1],
                               np.polymul(dv, da)) ** 2
    return gv, ga, 0.5 * (both - gv - ga)


def quantization_force_noise(T: float, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
                             q: float) -> np.ndarray:
    """Rms force noise [N] of ``B V + M A`` per (M, B) (flat arrays) for an encoder of resolution ``q``."""
    gv, ga, gva = _noise_gains(T, controller)
    g2 = damping * damping * gv + 2.0 * damping * mass * gva + mass * mass * ga
    return (q / math.sqrt(12.0)) * np.sqrt(np.maximum(g2, 0.0))


def renders_quietly(device: Device, controller: RenderingController, mass: float, damping: float,
                    stiffness: float = 0.0, settings: QualitySettings | None = None) -> bool:
    """Quality ``"quiet"``: the quantization force noise of ``B V + M A`` is within the limit.

    The four predicates share the signature ``(device, controller, mass, damping, stiffness,
    settings)``.

    The noise criterion of :mod:`analysis.sampled.velocity_noise` (Chawda, Celik & O'Malley,
    ASME JDSMC 2015; Colgate & Brown 1994) through the velocity and the acceleration estimates:
    white noise ``q^2/12`` through ``B V(z) + M A(z)`` has rms ``(q/sqrt(12)) ||B V + M A||_2``,
    at most ``settings.force_noise``.  It does not depend on K (module docstring).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    mass : float
        Virtual mass M [kg].
    damping : float
        Virtual damping B [N s/m].
    stiffness : float, optional
        Virtual stiffness K [N/m]: validated, does not enter (module docstring).
    settings : QualitySettings or None, optional
        Encoder resolution (required) and force-noise limit.

    Returns
    -------
    bool
        Whether the force noise is within the limit.

    Raises
    ------
    ValidationError
        When ``settings`` has no encoder resolution.
    """
    settings = settings or QualitySettings()
    RenderedEnvironment(mass, damping, stiffness)
    settings.check(device.sample_time, ("quiet",))
    M, B = check_virtual_mass("mass", mass), check_virtual_damping("damping", damping)
    f = quantization_force_noise(device.sample_time, controller, np.array([M]), np.array([B]),
                                 settings.encoder_resolution)
    return bool(f[0] <= settings.force_noise)


def effective_environment(device: Device, environment: RenderedEnvironment, controller: RenderingController,
                          settings: QualitySettings | None = None) -> EffectiveEnvironment:
    """The effective stiffness, damping and mass the user feels over the band (Colonnese et al. 2015).

    ``K_eff(w) = Re G``, ``B_eff(w) = Im G/w`` of the sampled force per position ``G``
    (:func:`~analysis.sampled.rendered.rendered_force_response`); the fitted ``(M, B, K)`` are
    the least-squares ``Re G ~ K - M w^2`` and the mean of ``Im G/w`` over the band.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    environment : RenderedEnvironment
        ``(M, B, K)``.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    settings : QualitySettings or None, optional
        The band; ``None`` for the defaults.

    Returns
    -------
    EffectiveEnvironment
        The effective values and the relative error at each frequency of the band.

    Raises
    ------
    ValidationError
        When the band reaches Nyquist.
    """
    s = settings or QualitySettings()
    s.check(device.sample_time, ("accurate",))
    w = s.frequencies()
    G = rendered_force_response(w, device.sample_time, controller, environment)
    target = environment.target(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.where(np.abs(target) > 0, np.abs(G - target) / np.abs(target), np.nan)
    X = np.stack([np.ones_like(w), -w * w], axis=1)
    (k_fit, m_fit), *_ = np.linalg.lstsq(X, G.real, rcond=None)
    return EffectiveEnvironment(w=w, stiffness=G.real, damping=G.imag / w, error=err, fitted_mass=float(m_fit),
                                fitted_damping=float(np.mean(G.imag / w)), fitted_stiffness=float(k_fit))
