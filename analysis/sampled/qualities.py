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
  rendered impedance *at the handle* ``G_h(jw)/(jw)``
  (:func:`~analysis.sampled.rendered.handle_force_response`: the chain between the handle and
  the actuator terminated by the sampled controller's impedance, less the free device's own) is
  within a relative tolerance ``eps`` of ``M s + B + K/s``:
  ``|G_h - (K + j w B - w^2 M)| <= eps |K + j w B - w^2 M|`` on
  :attr:`QualitySettings.band_points` log-spaced frequencies.  :func:`effective_environment`
  reports what the user feels at the handle: the effective stiffness ``Re G_h`` and damping
  ``Im G_h/w`` of Colonnese, Siu, Abbott & Okamura (IEEE Trans. Haptics 2015), and the
  ``(M, B, K)`` fitted to ``G_h`` over the band.  For a rigid device (handle = actuator)
  ``G_h`` is the controller's ``G``; for a chain its compliance shows, e.g. a spring ``K`` is
  felt as ``K/(1 + K/k_s)`` below the chain's modes (``1/k_s = sum 1/k_i``).
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
    handle_force_response,
    handle_transmission,
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
    "accuracy_mass_limits",
    "first_violation",
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
    """What the user feels at the handle of a rendered environment (Colonnese, Siu, Abbott & Okamura 2015).

    Parameters
    ----------
    w : numpy.ndarray
        Frequencies [rad/s], shape (N,).
    stiffness : numpy.ndarray
        Effective stiffness ``Re G_h(jw)`` [N/m] (the spring felt, mass included), shape (N,).
    damping : numpy.ndarray
        Effective damping ``Im G_h(jw)/w`` [N s/m], shape (N,).
    error : numpy.ndarray
        Relative error ``|G_h - G_target|/|G_target|``, shape (N,) (NaN where the target is 0).
    fitted_mass : float
        ``M`` [kg] of ``Re G_h ~ K - M w^2`` fitted over the band (least squares).
    fitted_damping : float
        ``B`` [N s/m]: the mean of ``Im G_h/w`` over the band.
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


def first_violation(c: np.ndarray) -> np.ndarray:
    """Per row of real coefficients ``c`` (lowest power first, shape (R, D + 1)): the smallest
    ``x > 0`` where ``q(x) = sum c_i x^i > 0`` (0 when already just above 0, inf when never).

    ``q > 0`` just above 0 when its lowest nonzero coefficient is positive.  Otherwise the
    answer is a positive real root where ``q`` turns positive: the roots of each degree (exact
    zeros of the leading coefficients lower it) are the eigenvalues of the companion matrices,
    in one batch per degree, polished by two Newton steps; a root counts where ``q`` is positive
    just beyond it (a touching root does not).  A pair within 1e-6 of the real axis (a double
    root split by round-off) is taken at its real part.

    Parameters
    ----------
    c : numpy.ndarray
        Real coefficients, shape (R, D + 1).

    Returns
    -------
    numpy.ndarray
        The first violation per row, shape (R,).
    """
    c = np.asarray(c, dtype=float)
    R, D1 = c.shape
    out = np.full(R, np.inf)
    nz = c != 0.0
    low = np.argmax(nz, axis=1)
    out[nz.any(axis=1) & (c[np.arange(R), low] > 0)] = 0.0
    deg = np.where(nz.any(axis=1), D1 - 1 - np.argmax(nz[:, ::-1], axis=1), 0)
    for n in range(1, D1):
        rows = np.flatnonzero((deg == n) & (out > 0))
        if rows.size == 0:
            continue
        cc = c[rows, :n + 1]
        comp = np.zeros((rows.size, n, n))
        comp[:, 0, :] = -cc[:, n - 1::-1] / cc[:, n:n + 1]
        comp[:, np.arange(1, n), np.arange(n - 1)] = 1.0
        r = np.linalg.eigvals(comp)
        x = np.where((r.real > 0) & (np.abs(r.imag) <= 1e-6 * np.abs(r)), r.real, np.nan)
        dc = cc[:, 1:] * np.arange(1, n + 1)
        for _ in range(2):  # Newton on the real candidates
            with np.errstate(divide="ignore", invalid="ignore"):
                step = _horner(cc, x) / _horner(dc, x)
            x = np.where(np.abs(step) < 1e-3 * x, x - step, x)
        beyond = _horner(cc, x * (1 + 1e-8))
        x = np.where((x > 0) & (beyond > 0), x, np.inf)
        out[rows] = np.minimum(out[rows], np.where(np.isnan(x), np.inf, x).min(axis=1))
    return out


def _horner(c: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``sum c[r, i] x[r, k]^i`` (rows of coefficients, lowest power first, at points ``x[r, :]``)."""
    q = np.broadcast_to(c[:, -1:], x.shape).copy()
    for i in range(c.shape[1] - 2, -1, -1):
        q = q * x + c[:, i:i + 1]
    return q


def _abs2_coefficients(p: np.ndarray) -> np.ndarray:
    """``|p(x)|^2`` for real ``x`` of complex polynomials ``p`` (lowest power first, (..., n))."""
    n = p.shape[-1]
    out = np.zeros(p.shape[:-1] + (2 * n - 1,))
    for i in range(n):
        for j in range(n):
            out[..., i + j] += np.real(p[..., i] * np.conj(p[..., j]))
    return out


def accuracy_k(device: Device, controller: RenderingController, mass: np.ndarray, damping: np.ndarray,
               settings: QualitySettings) -> np.ndarray:
    """Per (M, B): the largest K such that every K' in (0, K] is within ``eps`` at the handle (inf: no limit).

    At each frequency the rendered force per handle position is ``u/(alpha + gamma u)`` with
    ``u = K P + q`` affine in K (``P`` the hold and delay, ``q = B P V + M P A``) and
    ``gamma = beta/(jw)`` (:func:`~analysis.sampled.rendered.handle_transmission`), the target
    ``K + g0``.  Cleared of its denominator the condition is ``Q(K) = |u - (K + g0)(alpha +
    gamma u)|^2 - eps^2 |K + g0|^2 |alpha + gamma u|^2 <= 0``, a real quartic (a quadratic for a
    rigid device, ``gamma = 0``); the first K > 0 where it turns positive is
    :func:`first_violation`'s, the least over the band.
    """
    w = settings.frequencies()
    T = device.sample_time
    P = rendered_force_response(w, T, controller, RenderedEnvironment(stiffness=1.0))  # hold x delay
    V = controller.velocity_response(w, T)
    A = controller.acceleration_response(w, T)
    alpha, beta = handle_transmission(device, w)
    gamma = beta / (1j * w)
    M, B = mass[:, None], damping[:, None]
    q = B * P * V + M * P * A
    g0 = 1j * w * B - w * w * M
    d0, d1 = alpha + gamma * q, gamma * P + 0.0 * M  # alpha + gamma u
    L = np.stack([q - g0 * d0, P - g0 * d1 - d0, -d1], axis=-1)
    Rr = np.stack([g0 * d0, g0 * d1 + d0, d1], axis=-1)
    coeffs = _abs2_coefficients(L) - settings.tolerance ** 2 * _abs2_coefficients(Rr)
    k = first_violation(coeffs.reshape(-1, 5)).reshape(q.shape)
    return k.min(axis=1)


def accuracy_mass_limits(device: Device, controller: RenderingController,
                         settings: QualitySettings) -> tuple[float, float]:
    """``(m_lo, m_hi)``: the virtual masses around 0 within ``eps`` at the handle at ``B = K = 0``.

    The pure mass ``u = M P A`` against ``-w^2 M``: ``Q(M) = |P A + w^2 (alpha + gamma M P A)|^2
    - eps^2 w^4 |alpha + gamma M P A|^2 <= 0`` (divided by ``M^2``), a quadratic in M per
    frequency; for a rigid device (``gamma = 0``) it does not depend on M (all or none).
    """
    w = settings.frequencies()
    T = device.sample_time
    a = rendered_force_response(w, T, controller, RenderedEnvironment(mass=1.0))
    alpha, beta = handle_transmission(device, w)
    tg = w * w * (beta / (1j * w)) * a
    out = []
    for sign in (1.0, -1.0):
        L = np.stack([a + w * w * alpha, sign * tg], axis=-1)
        Rr = np.stack([w * w * alpha, sign * tg], axis=-1)
        c = _abs2_coefficients(L) - settings.tolerance ** 2 * _abs2_coefficients(Rr)
        out.append(float(first_violation(c).min()))
    return -out[1], out[0]


def renders_accurately(device: Device, controller: RenderingController, mass: float, damping: float,
                       stiffness: float, settings: QualitySettings | None = None) -> bool:
    """Quality ``"accurate"``: stable, and within ``eps`` of ``M s + B + K/s`` over the band.

    The rendered impedance at the handle ``G_h(jw)/(jw)`` of the sampled controller through
    the hold and the chain (:func:`~analysis.sampled.rendered.handle_force_response`;
    Colonnese, Siu, Abbott & Okamura, IEEE Trans. Haptics 2015) against the target, relative error at most
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
    """The effective stiffness, damping and mass the user feels at the handle over the band
    (Colonnese et al. 2015).

    ``K_eff(w) = Re G_h``, ``B_eff(w) = Im G_h/w`` of the rendered force per handle position
    ``G_h`` (:func:`~analysis.sampled.rendered.handle_force_response`: the free device's own
    mass and damping are not part of it); the fitted ``(M, B, K)`` are
    the least-squares ``Re G_h ~ K - M w^2`` and the mean of ``Im G_h/w`` over the band.

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
    G = handle_force_response(device, w, controller, environment)
    target = environment.target(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.where(np.abs(target) > 0, np.abs(G - target) / np.abs(target), np.nan)
    X = np.stack([np.ones_like(w), -w * w], axis=1)
    (k_fit, m_fit), *_ = np.linalg.lstsq(X, G.real, rcond=None)
    return EffectiveEnvironment(w=w, stiffness=G.real, damping=G.imag / w, error=err, fitted_mass=float(m_fit),
                                fitted_damping=float(np.mean(G.imag / w)), fitted_stiffness=float(k_fit))
