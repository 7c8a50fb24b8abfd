"""Rigid device with a discrete wall controller: exact passivity and stability limits.

Passivity (Colgate & Schenkel)
------------------------------
J. E. Colgate and G. G. Schenkel, "Passivity of a class of sampled-data systems: application
to haptic interfaces", *Journal of Robotic Systems* 14(1), 37-47, 1997: a rigid mass ``m``
with physical damping ``b``, a zero-order hold on the force and a discrete controller
``H(z)`` from sampled position to force (force on the device ``-H x``) is passive iff::

    b > (T/2) / (1 - cos wT) * Re{(1 - e^{-jwT}) H(e^{jwT})}     for 0 <= w <= pi/T.

The mass does not enter.  With ``theta = wT``, ``(1 - e^{-j theta})/(1 - cos theta) =
j e^{-j theta/2} / sin(theta/2)``, which removes the 0/0 at DC.  For the virtual wall
``H = z^{-d} (K + B (1 - z^{-1})/T)`` (spring, backward-difference damper, ``d`` samples of
delay) the condition is, exactly::

    b >= K (T/2) sin((d + 1/2) theta) / sin(theta/2) - B cos((d + 1) theta)   for all theta,

which gives the familiar ``b > K T/2 + |B|`` for ``d = 0`` and ``K < b / (T (d + 1/2))``
for ``B = 0`` (the Dirichlet-kernel bound ``sin((2d+1)x)/sin x <= 2d+1``).

Stability
---------
Gil, Avello, Rubio and Flórez, "Stability analysis of a 1 DOF haptic interface using the
Routh-Hurwitz criterion", *IEEE Trans. Control Systems Technology* 12(4), 583-588, 2004,
derive the exact stability region of the same loop (no delay) from the characteristic
polynomial ``z^{d+1} (z-1)(z-delta) + (K z + (B/T)(z-1)) (alpha z + beta)`` with
``delta = e^{-bT/m}``, ``alpha = (T - (m/b)(1-delta))/b``, ``beta = ((m/b)(1-delta) - T delta)/b``;
for small ``bT/m`` it reduces to ``K < 2 (b + B)/T``.  Hulin, Preusche and Hirzinger
("Stability boundary for haptic rendering: influence of physical damping", IROS 2006) and
Diolaiti et al. (IEEE Trans. Robotics 22(2), 2006) give the delayed form
``K < (b + B) / (T (d + 1/2))``.  :func:`rigid_stability_polynomial` builds that
polynomial (an independent route to the state-space loop of :mod:`analysis.sampled.loop`);
:func:`linear_stability_limit` is the closed form, accurate when ``(b + B) T (d + 1/2) / m``
is small (checked to 0.5 % in the tests).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy import optimize

from analysis.chain.velocity_filter import VelocityFilter
from analysis.sampled.rendered import AccelerationEstimate
from analysis.checks import Real, integer
from analysis.errors import ValidationError

__all__ = [
    "required_damping",
    "passivity_limit",
    "passivity_limits",
    "mass_passivity_term",
    "passivity_closed_form",
    "linear_stability_limit",
    "rigid_stability_polynomial",
    "virtual_wall",
]


# "> 0 and finite" / ">= 0 and finite", and "a real number" for a value that is not one.
_POS = Real(lo=0.0, lo_open=True, not_real="a real number")
_NONNEG = Real(lo=0.0, not_real="a real number")
_VIRTUAL_DAMPING = Real(allowed="a finite real number (N s/m)")


def virtual_wall(stiffness: float, damping: float, sample_time: float, delay_samples: int = 0) -> Callable:
    """``H(z) = z^{-d} (K + B (1 - z^{-1})/T)`` as a function of complex ``z``.

    Parameters
    ----------
    stiffness : float
        Wall stiffness ``K`` [N/m].
    damping : float
        Virtual damping ``B`` [N s/m] on the backward difference.
    sample_time : float
        Sample period ``T`` [s].
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.

    Returns
    -------
    Callable
        ``H(z)``: complex array of ``z`` to the force per position [N/m], same shape.

    Raises
    ------
    ValidationError
        When ``delay_samples`` is not an integer of at least 0.
    """
    d = integer("delay_samples", delay_samples, 0)

    def H(z: np.ndarray) -> np.ndarray:
        return z ** (-d) * (stiffness + damping * (1.0 - 1.0 / z) / sample_time)

    return H


def _theta_grid(points: int) -> np.ndarray:
    return np.linspace(0.0, math.pi, points)[1:]


def required_damping(H: Callable[[np.ndarray], np.ndarray], sample_time: float, points: int = 20001) -> tuple[float, float]:
    """Smallest physical damping making the rigid device passive with controller ``H`` (Colgate-Schenkel).

    Returns ``(b_required, w)``: the supremum over ``0 < w <= pi/T`` of the right-hand side
    and the frequency (rad/s) where it is attained (dense grid plus Brent refinement).

    Parameters
    ----------
    H : Callable
        The discrete controller ``H(z)`` [N/m] from sampled position to force, vectorized over
        complex ``z`` (e.g. :func:`virtual_wall`).
    sample_time : float
        Sample period ``T`` [s], greater than 0.
    points : int, optional
        Points of the grid over ``0 < theta <= pi``.

    Returns
    -------
    tuple of (float, float)
        ``(b_required [N s/m], w [rad/s])``; ``w = 0`` when the supremum is the DC limit.

    Raises
    ------
    ValidationError
        When ``sample_time`` is not greater than 0.
    """
    T = _POS("sample_time", sample_time)

    def rhs(th: np.ndarray) -> np.ndarray:
        z = np.exp(1j * th)
        return 0.5 * T * np.real(1j * np.exp(-0.5j * th) / np.sin(0.5 * th) * H(z))

    th = _theta_grid(points)
    vals = rhs(th)
    i = int(np.argmax(vals))
    best, arg = float(vals[i]), float(th[i])
    lo, hi = th[max(i - 1, 0)], th[min(i + 1, th.size - 1)]
    if hi > lo:
        r = optimize.minimize_scalar(lambda x: -float(rhs(np.array([x]))[0]), bounds=(lo, hi), method="bounded",
                                     options={"xatol": 1e-12})
        if -r.fun > best:
            best, arg = float(-r.fun), float(r.x)
    # the DC end: the limit theta -> 0 of the right-hand side
    dc = float(rhs(np.array([1e-9]))[0])
    if dc > best:
        best, arg = dc, 0.0
    return best, arg / T


def passivity_limit(mass: float, damping: float, sample_time: float, virtual_damping: float = 0.0,
                    delay_samples: int = 0, points: int = 20001, *,
                    velocity_filter: VelocityFilter | None = None) -> float:
    """Largest passive wall stiffness K (N/m) of a rigid device, exactly (Colgate & Schenkel 1997).

    The controller is the virtual wall ``z^{-d} (K + B V(z))`` with the velocity estimate
    ``V(z) = H_f(z) (1 - z^{-1})/T`` (``H_f = 1``, the backward difference, by default; see
    :class:`~analysis.chain.velocity_filter.VelocityFilter`).  The criterion is linear in K,
    ``b >= K a(theta) + c(theta)`` with ``a = (T/2) sin((d+1/2) theta)/sin(theta/2)`` and, from
    ``(1 - e^{-j theta})^2 = -4 sin^2(theta/2) e^{-j theta}`` and ``1 - cos theta = 2
    sin^2(theta/2)``::

        c(theta) = (T/2) B Re{(1 - e^{-j theta})^2 e^{-j d theta} H_f / T} / (1 - cos theta)
                 = -B Re{e^{-j (d+1) theta} H_f(e^{j theta})},

    which is ``-B cos((d+1) theta)`` for ``H_f = 1``.  So ``K_max = min over a > 0 of
    (b - c)/a``, found on a dense grid and refined.  ``mass`` is validated but does not enter
    (the criterion is independent of it).  Returns NaN when no K >= 0 is passive (e.g.
    ``|B| >= b`` without delay).

    Parameters
    ----------
    mass : float
        Device mass ``m`` [kg], greater than 0 (validated only).
    damping : float
        Physical damping ``b`` [N s/m], at least 0.
    sample_time : float
        Sample period ``T`` [s], greater than 0.
    virtual_damping : float, optional
        Virtual damping ``B`` [N s/m], any finite sign.
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.
    points : int, optional
        Points of the grid over ``0 < theta <= pi`` before the refinement.
    velocity_filter : VelocityFilter or None, optional
        Filter ``H_f`` of the velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    float
        ``K_max`` [N/m], or NaN when no ``K >= 0`` is passive.

    Raises
    ------
    ValidationError
        When a parameter is out of range.
    """
    _POS("mass", mass)
    b = _NONNEG("damping", damping)
    T = _POS("sample_time", sample_time)
    B = _VIRTUAL_DAMPING("virtual_damping", virtual_damping)
    d = integer("delay_samples", delay_samples, 0)
    filt = velocity_filter is not None and not velocity_filter.is_backward

    def parts(th):
        a = 0.5 * T * np.sin((d + 0.5) * th) / np.sin(0.5 * th)
        if filt:
            hf = velocity_filter.filter_response(th / T, T)
            c = -B * np.real(np.exp(-1j * (d + 1) * th) * hf)
        else:
            c = -B * np.cos((d + 1) * th)
        return a, c

    th = np.r_[1e-9, _theta_grid(points)]
    a, c = parts(th)
    if np.any((a <= 0) & (c > b)):
        return math.nan
    pos = a > 0
    ratio = np.where(pos, (b - c) / np.where(pos, a, 1.0), np.inf)
    i = int(np.argmin(ratio))
    kmax = float(ratio[i])
    if 0 < i < th.size - 1:
        def f(x: float) -> float:
            aa, cc = parts(np.array([x]))
            return float((b - cc[0]) / aa[0]) if aa[0] > 0 else math.inf

        r = optimize.minimize_scalar(f, bounds=(th[i - 1], th[i + 1]), method="bounded", options={"xatol": 1e-13})
        kmax = min(kmax, float(r.fun))
    return kmax if kmax >= 0 else math.nan


def mass_passivity_term(theta: np.ndarray, sample_time: float, delay_samples: int = 0,
                        acceleration: AccelerationEstimate | None = None,
                        velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """The virtual mass's share of the Colgate-Schenkel criterion, per kg: ``c_M(theta)/M``.

    With the acceleration estimate ``A(z) = H_a(z) (1 - z^{-1})^2/T^2``
    (:class:`~analysis.sampled.rendered.AccelerationEstimate`) in the controller ``z^{-d} M A``,
    the right-hand side ``(T/2) Re{(1 - e^{-j theta}) z^{-d} M A}/(1 - cos theta)`` is, from
    ``(1 - e^{-j theta}) = 2j sin(theta/2) e^{-j theta/2}`` and ``1 - cos theta = 2 sin^2(theta/2)``::

        c_M(theta) = -(2 M/T) sin(theta/2) Re{j e^{-j (d + 3/2) theta} H_a(e^{j theta})},

    which is ``-(2 M/T) sin(theta/2) sin((d + 3/2) theta)`` for the second backward difference
    (no 0/0 at DC).  The criterion with the whole rendered environment is
    ``b >= K a(theta) - B r(theta) + M c_M(theta)/M`` (:func:`passivity_limits`).

    Parameters
    ----------
    theta : numpy.ndarray
        Normalized frequencies ``w T`` in ``(0, pi]``, any shape.
    sample_time : float
        Sample period ``T`` [s].
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate; ``None`` for the second backward difference.
    velocity_filter : VelocityFilter or None, optional
        The velocity filter ``H_f`` (its share of ``H_a`` for ``"filtered_velocity"``).

    Returns
    -------
    numpy.ndarray
        ``c_M/M`` [N s/m per kg], the shape of ``theta``.
    """
    T = float(sample_time)
    th = np.asarray(theta, dtype=float)
    acc = AccelerationEstimate() if acceleration is None else acceleration
    h = acc.filter_response(th / T, T, velocity_filter)
    return -(2.0 / T) * np.sin(0.5 * th) * np.real(1j * np.exp(-1j * (delay_samples + 1.5) * th) * h)


def passivity_limits(mass: float, damping: float, sample_time: float, virtual_dampings: np.ndarray,
                     delay_samples: int = 0, points: int = 4001, *,
                     velocity_filter: VelocityFilter | None = None, virtual_masses: np.ndarray | None = None,
                     acceleration: AccelerationEstimate | None = None, fine_points: int | None = None) -> np.ndarray:
    """:func:`passivity_limit` for many virtual dampings B at once (the Z-width region's passive edge).

    Numerical kernel: ``K_max(B) = min over a(theta) > 0 of (b + B r(theta))/a(theta)`` with
    ``r = Re{e^{-j(d+1) theta} H_f}`` on one grid of ``points`` for every B, then a second grid of
    ``points`` between the neighbours of each minimum (error ~ (grid step / points)^2); NaN
    where some ``a <= 0`` has ``c > b`` or the limit is negative, as :func:`passivity_limit`.
    With ``virtual_masses`` (one M per B, kg) the rendered environment's mass term
    ``M c_M(theta)/M`` (:func:`mass_passivity_term`, estimate ``acceleration``) is added to ``c``:
    the Colgate-Schenkel test of ``F = M a^ + B v^ + K x``.

    Parameters
    ----------
    mass : float
        Device mass ``m`` [kg], greater than 0 (validated only).
    damping : float
        Physical damping ``b`` [N s/m], at least 0.
    sample_time : float
        Sample period ``T`` [s], greater than 0.
    virtual_dampings : numpy.ndarray
        Virtual dampings ``B`` [N s/m], shape (M,) (flattened).
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.
    points : int, optional
        Points of each of the two grids.
    velocity_filter : VelocityFilter or None, optional
        Filter ``H_f`` of the velocity estimate; ``None`` for the backward difference.
    virtual_masses : numpy.ndarray or None, optional
        Virtual masses ``M`` [kg], one per B (flattened, broadcast); ``None`` for no mass term.
    acceleration : AccelerationEstimate or None, optional
        The mass term's acceleration estimate; ``None`` for the second backward difference.
    fine_points : int or None, optional
        Points of the second grid; ``None`` for ``points``.

    Returns
    -------
    numpy.ndarray
        ``K_max`` [N/m] for each B, shape (M,); NaN where no ``K >= 0`` is passive.

    Raises
    ------
    ValidationError
        When a parameter is out of range.
    """
    _POS("mass", mass)
    b = _NONNEG("damping", damping)
    T = _POS("sample_time", sample_time)
    d = integer("delay_samples", delay_samples, 0)
    B = np.asarray(virtual_dampings, float).reshape(-1, 1)
    vf = velocity_filter
    Mv = None if virtual_masses is None else np.broadcast_to(np.asarray(virtual_masses, float).reshape(-1, 1), B.shape)

    def ratio(th: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a = 0.5 * T * np.sin((d + 0.5) * th) / np.sin(0.5 * th)
        e = np.exp(-1j * (d + 1) * th)
        r = np.real(e if vf is None or vf.is_backward else e * vf.filter_response(th / T, T))
        c = -B * r
        if Mv is not None:
            c = c + Mv * mass_passivity_term(th, T, d, acceleration, vf)
        with np.errstate(divide="ignore", invalid="ignore"):
            q = np.where(a > 0, (b - c) / np.where(a > 0, a, 1.0), np.inf)
        return q, (a <= 0) & (c > b)

    th = np.r_[1e-9, _theta_grid(points)]
    q, bad = ratio(th)
    i = np.argmin(q, axis=1)
    lo, hi = th[np.maximum(i - 1, 0)], th[np.minimum(i + 1, th.size - 1)]
    fine = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, points if fine_points is None else
                                                          integer("fine_points", fine_points, 2))[None, :]
    qf = ratio(fine)[0]  # row i of the fine grid belongs to B[i]: elementwise broadcast
    kmax = np.minimum(q.min(axis=1), qf.min(axis=1))
    return np.where(bad.any(axis=1) | (kmax < 0), np.nan, kmax)


def passivity_closed_form(damping: float, sample_time: float, virtual_damping: float = 0.0,
                          delay_samples: int = 0) -> float:
    """Closed forms of the Colgate-Schenkel limit: ``2(b - |B|)/T`` (d = 0), ``b/(T(d + 1/2))`` (B = 0).

    Parameters
    ----------
    damping : float
        Physical damping ``b`` [N s/m].
    sample_time : float
        Sample period ``T`` [s].
    virtual_damping : float, optional
        Virtual damping ``B`` [N s/m]; must be 0 when ``delay_samples > 0``.
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.

    Returns
    -------
    float
        ``K_max`` [N/m]; NaN when it would be negative (d = 0).

    Raises
    ------
    ValidationError
        When ``virtual_damping`` is not 0 with ``delay_samples > 0`` (no closed form), or
        ``delay_samples`` is not an integer of at least 0.
    """
    d = integer("delay_samples", delay_samples, 0)
    if d == 0:
        k = 2.0 * (damping - abs(virtual_damping)) / sample_time
        return k if k >= 0 else math.nan
    if virtual_damping == 0:
        return damping / (sample_time * (d + 0.5))
    raise ValidationError("virtual_damping", "0 when delay_samples > 0 (no closed form; use passivity_limit)",
                          virtual_damping)


def linear_stability_limit(damping: float, sample_time: float, virtual_damping: float = 0.0,
                           delay_samples: int = 0) -> float:
    """``K_max ~ (b + B) / (T (d + 1/2))`` (Gil et al. 2004 for d = 0; Hulin et al. 2006 with delay).

    Parameters
    ----------
    damping : float
        Physical damping ``b`` [N s/m].
    sample_time : float
        Sample period ``T`` [s].
    virtual_damping : float, optional
        Virtual damping ``B`` [N s/m].
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.

    Returns
    -------
    float
        The approximate stability limit ``K_max`` [N/m].
    """
    d = integer("delay_samples", delay_samples, 0)
    return (damping + virtual_damping) / (sample_time * (d + 0.5))


def rigid_stability_polynomial(mass: float, damping: float, sample_time: float, stiffness: float,
                               virtual_damping: float = 0.0, delay_samples: int = 0) -> np.ndarray:
    """Characteristic polynomial (highest power first) of the rigid device with a virtual wall.

    ``z^{d+1} (z - 1)(z - delta) + (K z + (B/T)(z - 1)) (alpha z + beta)``, from the ZOH
    transfer function ``(alpha z + beta)/((z-1)(z-delta))`` of ``1/(s (m s + b))``.

    Parameters
    ----------
    mass : float
        Device mass ``m`` [kg].
    damping : float
        Physical damping ``b`` [N s/m]; 0 for the double integrator.
    sample_time : float
        Sample period ``T`` [s].
    stiffness : float
        Wall stiffness ``K`` [N/m].
    virtual_damping : float, optional
        Virtual damping ``B`` [N s/m].
    delay_samples : int, optional
        Computation delay ``d`` in samples, at least 0.

    Returns
    -------
    numpy.ndarray
        Polynomial coefficients in ``z``, highest power first, shape (d + 4,); the loop is
        stable when every root lies inside the unit circle.
    """
    m, b, T = float(mass), float(damping), float(sample_time)
    K, B, d = float(stiffness), float(virtual_damping), integer("delay_samples", delay_samples, 0)
    if b > 0:
        delta = math.exp(-b * T / m)
        one_minus = -math.expm1(-b * T / m)
        alpha = (T - (m / b) * one_minus) / b
        beta = ((m / b) * one_minus - T * delta) / b
    else:  # double integrator
        delta, alpha, beta = 1.0, T * T / (2 * m), T * T / (2 * m)
    lhs = np.polymul(np.r_[1.0, np.zeros(d + 1)], np.polymul([1.0, -1.0], [1.0, -delta]))
    ctrl = np.array([K + B / T, -B / T])
    rhs = np.polymul(ctrl, [alpha, beta])
    return np.polyadd(lhs, rhs)
