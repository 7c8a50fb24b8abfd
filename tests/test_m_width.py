"""The rendered environment's mass term and the M-width (issue 24), against independent routes.

The rigid 1-DOF device ``m x'' = -b x' - F`` under a zero-order hold has the pulse transfer
function ``(alpha z + beta)/((z - 1)(z - delta))`` (``delta = e^{-bT/m}``); with the controller
``z^{-d}(K + B (1 - z^{-1})/T + M (1 - z^{-1})^2/T^2)`` the closed loop's characteristic
polynomial is, built here by hand (not by the code under test)::

    z^{d+2} (z - 1)(z - delta) + (K z^2 + (B/T)(z^2 - z) + (M/T^2)(z - 1)^2)(alpha z + beta).

At ``B = K = 0`` it has the factor ``(z - 1)`` (the free device's position); for ``b = 0``
(``alpha = beta = T^2/2m``) it is ``(z - 1)^2 (z^{d+2} + mu (z + 1))``, ``mu = M/(2m)``, and
Jury's test gives the M-width of Colonnese & Okamura's canonical system (a rigid mass rendering
a pure virtual mass through the second backward difference):

* ``d = 0``: ``z^2 + mu z + mu``: ``1 + 2 mu > 0`` and ``|mu| < 1``, so ``-m < M < 2 m``;
* ``d = 1``: ``z^3 + mu z + mu``: ``1 + 2 mu > 0`` and ``1 - mu^2 > |mu|``, so
  ``-m < M < (sqrt(5) - 1) m``.

(Colonnese & Okamura, "M-width: stability and accuracy of haptic rendering of virtual mass",
RSS 2012: only the abstract is in the searchable corpus, so the paper's own figures are not
quoted here; these are the Jury limits of the system the abstract describes.  The lower limit is
the device's inertia compensated in full.)
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from scipy import optimize

from analysis import Device
from analysis.errors import ValidationError
from analysis.sampled import (
    AccelerationEstimate,
    QualitySettings,
    VelocityFilter,
    m_width,
)
from analysis.sampled.loop import LoopSpec, closed_loop_matrices, is_stable, spectral_radius
from analysis.sampled.passivity import mass_passivity_term, passivity_limits, required_damping
from analysis.sampled.renderable import free_motion_radius
from analysis.sampled.terminations import HANDS_OFF, Termination, god_object_wall

T = 1e-3


def rigid(m: float = 0.5, b: float = 2.0) -> Device:
    return Device(masses=[m], stiffnesses=[], dampings=[], ground_dampings=[b], sensor_element=0, sample_time=T)


def zoh_coefficients(m: float, b: float) -> tuple[float, float, float]:
    """The ZOH discretization of the rigid mass-damper: its pole delta and numerator (alpha, beta)."""
    if b > 0:
        delta = math.exp(-b * T / m)
        om = -math.expm1(-b * T / m)
        return delta, (T - (m / b) * om) / b, ((m / b) * om - T * delta) / b
    return 1.0, T * T / (2 * m), T * T / (2 * m)


def hand_polynomial(m: float, b: float, M: float, B: float, K: float, d: int) -> np.ndarray:
    """The characteristic polynomial of the module docstring (highest power first)."""
    delta, alpha, beta = zoh_coefficients(m, b)
    lhs = np.polymul(np.r_[1.0, np.zeros(d + 2)], np.polymul([1.0, -1.0], [1.0, -delta]))
    ctrl = K * np.array([1.0, 0, 0]) + (B / T) * np.array([1.0, -1.0, 0]) + (M / T ** 2) * np.array([1.0, -2.0, 1.0])
    return np.polyadd(lhs, np.polymul(ctrl, [alpha, beta]))


def hand_radius(m: float, b: float, M: float, B: float, K: float, d: int) -> float:
    p = hand_polynomial(m, b, M, B, K, d)
    if B == 0 and K == 0:  # the free device's z = 1, and for b = 0 the second one
        p, _ = np.polydiv(p, [1.0, -1.0])
        if b == 0:
            p, _ = np.polydiv(p, [1.0, -1.0])
    return float(np.abs(np.roots(p)).max())


def hand_radii(m: float, b: float, M: float, B: float, K: np.ndarray, d: int) -> np.ndarray:
    """:func:`hand_radius` at every stiffness of ``K`` at once, bit for bit: the same coefficients
    (each a sum of two terms, the same in any order) and the same companion matrices as
    ``np.roots``, their eigenvalues in one batched call.  A stiffness whose polynomial has a
    trailing zero coefficient (``np.roots`` deflates it) or is 0 takes :func:`hand_radius` itself."""
    K = np.asarray(K, dtype=float)
    delta, alpha, beta = zoh_coefficients(m, b)
    lhs = np.polymul(np.r_[1.0, np.zeros(d + 2)], np.polymul([1.0, -1.0], [1.0, -delta]))
    ctrl = (K[:, None] * np.array([1.0, 0, 0]) + (B / T) * np.array([1.0, -1.0, 0])
            + (M / T ** 2) * np.array([1.0, -2.0, 1.0]))
    prod = np.zeros((K.size, 4))
    prod[:, :3] += ctrl * alpha
    prod[:, 1:] += ctrl * beta
    p = np.tile(lhs, (K.size, 1))
    p[:, -4:] += prod
    out = np.empty(K.size)
    exact = (p[:, -1] != 0.0) & (K != 0.0)
    n = p.shape[1] - 1
    A = np.zeros((int(exact.sum()), n, n))
    A[:, 1:, :-1] = np.eye(n - 1)
    A[:, 0, :] = -p[exact, 1:] / p[exact, :1]
    out[exact] = np.abs(np.linalg.eigvals(A)).max(axis=1)
    for i in np.flatnonzero(~exact):
        out[i] = hand_radius(m, b, M, B, float(K[i]), d)
    return out


def loop_radius(device: Device, M: float, B: float, K: float, d: int, acceleration=None, velocity_filter=None) -> float:
    spec = LoopSpec("impedance", (1.0, 1.0), delay_samples=d, velocity_filter=velocity_filter,
                    acceleration=acceleration or AccelerationEstimate())
    Phi = closed_loop_matrices(device, spec, [Termination(HANDS_OFF, god_object_wall())],
                               overrides={"kc": np.array([K]), "bc": np.array([B]), "mv": np.array([M])})
    return float(spectral_radius(Phi)[0])


@pytest.mark.parametrize(("M", "B", "K", "d"), [(0.3, 5.0, 1e3, 1), (-0.2, 1.0, 300.0, 0), (0.8, 0.0, 0.0, 1),
                                                 (-0.4, 0.0, 0.0, 1), (1.2, 3.0, 2e3, 2), (-0.45, -1.0, 50.0, 0)])
def test_the_loop_is_the_hand_built_characteristic_polynomial(M, B, K, d):
    """The exact loop's spectral radius equals the largest root of the hand-built polynomial."""
    hand = hand_radius(0.5, 2.0, M, B, K, d)
    if B == 0 and K == 0:  # the free position's z = 1 (deflated by hand) counts as 1 in the loop
        hand = max(hand, 1.0)
    assert loop_radius(rigid(), M, B, K, d) == pytest.approx(hand, rel=1e-9)


@pytest.mark.parametrize(("m", "b", "M", "B", "d"), [(0.5, 2.0, 0.2, 3.0, 1), (0.5, 2.0, -0.1, -1.0, 2),
                                                     (0.5, 0.0, 0.3, 0.0, 0), (0.4, 1.2, -0.06, 30.0, 1)])
def test_the_batched_hand_radii_are_the_hand_radius_at_each_stiffness(m, b, M, B, d):
    """The brute-force scans' batched route (hand_radii) gives hand_radius at every K, including
    K = 0 (deflated by hand) and a singular object step (M = -(m_e + BT + KT^2) at K = 1e4)."""
    K = np.r_[0.0, np.geomspace(1.0, 1e9, 100), 1e4]
    ref = np.array([hand_radius(m, b, M, B, k, d) for k in K])
    assert hand_radii(m, b, M, B, K, d) == pytest.approx(ref, rel=1e-12)


def test_a_brute_force_simulation_grows_at_the_spectral_radius():
    """Simulated by hand with the exact ZOH recursion, the state grows by rho per sample."""
    m, b, M, B, K, d = 0.5, 2.0, 0.7, 1.0, 400.0, 1
    rho = loop_radius(rigid(m, b), M, B, K, d)
    assert rho > 1.005  # an unstable loop, so the growth rate is measurable
    delta = math.exp(-b * T / m)
    om = -math.expm1(-b * T / m)
    xs = [1e-6, 0.0, 0.0]  # x[k], x[k-1], x[k-2]
    v, forces, norms = 0.0, [0.0] * d, []
    for _ in range(3000):
        x, x1, x2 = xs
        forces.append(K * x + B * (x - x1) / T + M * (x - 2 * x1 + x2) / (T * T))
        F = forces.pop(0)  # the force computed d samples ago, held on this interval
        x_new = x + (m / b) * om * v - (T / b - (m / b) * om / b) * F
        v = delta * v - (om / b) * F
        xs = [x_new, x, x1]
        norms.append(math.log(abs(x_new) + abs(x) + abs(x1)))
    slope = np.polyfit(np.arange(2000), norms[-2000:], 1)[0]  # a complex pair makes the norm wobble
    assert math.exp(slope) == pytest.approx(rho, rel=1e-4)


def test_a_zero_mass_with_an_estimate_changes_no_eigenvalue_that_matters():
    """M = 0 with the estimate's states in the loop: the same spectral radius as the plain loop."""
    dev = rigid()
    spec = LoopSpec("impedance", (1.0, 1.0), delay_samples=1)
    plain = closed_loop_matrices(dev, spec, [Termination(HANDS_OFF, god_object_wall())],
                                 overrides={"kc": np.array([800.0]), "bc": np.array([3.0])})
    assert loop_radius(dev, 0.0, 3.0, 800.0, 1) == pytest.approx(float(spectral_radius(plain)[0]), rel=1e-12)


def mp_radius(m: float, b: float, M: float, d: int) -> mpmath.mpf:
    """Largest root modulus of the hand polynomial at ``B = K = 0`` in 50 digits, with the free
    motion's ``(z - 1)`` (and for ``b = 0`` the second one) divided out exactly."""
    with mpmath.workdps(50):
        m, b, M, h = mpmath.mpf(m), mpmath.mpf(b), mpmath.mpf(M), mpmath.mpf(T)
        if b > 0:
            delta = mpmath.exp(-b * h / m)
            alpha = (h - (m / b) * (1 - delta)) / b
            beta = ((m / b) * (1 - delta) - h * delta) / b
            # z^{d+2} (z - delta) + (M/T^2)(z - 1)(alpha z + beta)
            q = [mpmath.mpf(0)] * (d + 4)
            q[0], q[1] = mpmath.mpf(1), -delta
            g = M / h ** 2
            q[-3] += g * alpha
            q[-2] += g * (beta - alpha)
            q[-1] += -g * beta
        else:  # z^{d+2} + mu (z + 1), mu = M/(2 m)
            q = [mpmath.mpf(1)] + [mpmath.mpf(0)] * (d + 2)
            q[-2] += M / (2 * m)
            q[-1] += M / (2 * m)
        roots = mpmath.polyroots(q[::-1], maxsteps=200, extraprec=200, asc=True)
        return max(abs(r) for r in roots)


@pytest.mark.parametrize(("d", "upper"), [(0, 2.0), (1, math.sqrt(5.0) - 1.0)])
def test_m_width_of_the_canonical_undamped_mass_is_the_jury_interval(d, upper):
    """Jury: -m < M < 2m (d = 0), -m < M < (sqrt(5) - 1) m (d = 1), to 1e-9, never beyond.

    The lower limit is a real root crossing z = 1, where free motion's double root sits: the
    free translation and velocity are deflated exactly (free_motion_radius), so the crossing is
    not blurred by the rigid-body clamp, and it is traced against rho = 1 (conservative)."""
    m = 0.5
    w = m_width(rigid(m, 0.0), delay_samples=d)
    assert w.m_max == pytest.approx(upper * m, rel=1e-9)
    assert w.m_min == pytest.approx(-m, rel=1e-9)
    # never beyond the exact limits (up to the eigenvalues' round-off, ~1e-15)
    assert -m * (1.0 + 1e-13) <= w.m_min and w.m_max <= upper * m * (1.0 + 1e-13)
    assert w.width == pytest.approx(w.m_max - w.m_min)


@pytest.mark.parametrize("b", [0.0, 2.0, 20.0])
@pytest.mark.parametrize("d", [0, 1, 2])
def test_m_width_is_the_50_digit_root_crossing_and_conservative(b, d):
    """Against the roots of the hand polynomial in 50 digits: every root at the reported limits
    is inside the unit circle (to 1e-12), and 1e-9 beyond them one is outside."""
    m = 0.5
    w = m_width(rigid(m, b), delay_samples=d)
    for limit in (w.m_min, w.m_max):
        assert mp_radius(m, b, limit, d) <= 1 + 1e-12
        assert mp_radius(m, b, limit * (1 + 1e-9), d) > 1
        assert mp_radius(m, b, 0.999 * limit, d) < 1


@pytest.mark.parametrize("d", [0, 1, 2])
def test_m_width_of_a_damped_mass_matches_the_roots_of_the_hand_polynomial(d):
    m, b = 0.5, 2.0
    w = m_width(rigid(m, b), delay_samples=d)

    def g(M: float) -> float:
        return hand_radius(m, b, M, 0.0, 0.0, d) - 1.0

    assert g(0.5 * w.m_max) < 0 < g(1.01 * w.m_max)
    assert w.m_max == pytest.approx(optimize.brentq(g, 0.5 * w.m_max, 1.01 * w.m_max, xtol=1e-14), rel=1e-8)
    assert g(0.5 * w.m_min) < 0 < g(1.01 * w.m_min)
    assert w.m_min == pytest.approx(optimize.brentq(g, 1.01 * w.m_min, 0.5 * w.m_min, xtol=1e-14), rel=1e-8)


def test_free_motion_is_deflated_exactly_and_nothing_else():
    """free_motion_radius drops the z = 1 roots of free motion only: a root 1e-9 from z = 1 stays."""
    P = np.diag([1.0, 1.0 + 1e-9, 0.5])
    P[0, 1] = 1.0  # a Jordan-like coupling
    Q, _ = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))
    assert free_motion_radius((Q @ P @ Q.T)[None])[0] == pytest.approx(1.0 + 1e-9, abs=1e-13)
    J = np.array([[1.0, 1e-3, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -0.7]])  # free position and velocity
    assert free_motion_radius((Q @ J @ Q.T)[None])[0] == pytest.approx(0.7, rel=1e-12)


def test_delay_narrows_the_m_width_from_above():
    widths = [m_width(rigid(), delay_samples=d) for d in (0, 1, 2, 4)]
    tops = [w.m_max for w in widths]
    assert all(a > b for a, b in zip(tops, tops[1:]))


def test_a_low_pass_on_the_acceleration_is_in_the_loop():
    """The low-passed estimate's loop still matches a hand-built polynomial (the filter's poles added)."""
    m, b, d, M = 0.5, 2.0, 1, 0.4
    wa = 2 * math.pi * 50
    acc = AccelerationEstimate(lowpass="lowpass1", cutoff=wa)
    a = math.exp(-wa * T)
    delta = math.exp(-b * T / m)
    om = -math.expm1(-b * T / m)
    alpha, beta = (T - (m / b) * om) / b, ((m / b) * om - T * delta) / b
    # z^{d+2}(z - 1)(z - delta)(z - a) + (1 - a) z (M/T^2)(z - 1)^2 (alpha z + beta), over (z - 1)
    lhs = np.polymul(np.r_[1.0, np.zeros(d + 2)], np.polymul([1.0, -delta], [1.0, -a]))
    rhs = np.polymul((1 - a) * M / T ** 2 * np.array([1.0, -1.0, 0.0]), [alpha, beta])
    hand = float(np.abs(np.roots(np.polyadd(lhs, rhs))).max())
    assert loop_radius(rigid(m, b), M, 0.0, 0.0, d, acceleration=acc) == pytest.approx(max(hand, 1.0), rel=1e-9)


def test_the_filtered_velocity_estimate_equals_the_second_difference_through_the_filter():
    """"filtered_velocity" is H_f (1 - z^-1)^2/T^2: with H_f the low-pass, the same loop as a
    second difference followed by that low-pass."""
    f = VelocityFilter("lowpass1", cutoff=2 * math.pi * 40)
    via_velocity = AccelerationEstimate("filtered_velocity")
    via_lowpass = AccelerationEstimate(lowpass="lowpass1", cutoff=f.cutoff)
    r1 = loop_radius(rigid(), 0.3, 0.0, 200.0, 1, via_velocity, f)
    r2 = loop_radius(rigid(), 0.3, 0.0, 200.0, 1, via_lowpass, f)
    assert r1 == pytest.approx(r2, rel=1e-12)


def test_mass_passivity_term_is_the_colgate_schenkel_right_hand_side():
    """c_M/M equals required_damping's right-hand side for the controller A(z) z^{-d}."""
    d = 1
    th = np.linspace(0.01, math.pi, 50)
    num, den = AccelerationEstimate().transfer_function(T)
    z = np.exp(1j * th)
    H = z ** (-d) * np.polyval(num[::-1], 1 / z) / np.polyval(den[::-1], 1 / z)
    rhs = 0.5 * T * np.real((1 - 1 / z) * H) / (1 - np.cos(th))
    assert mass_passivity_term(th, T, d) == pytest.approx(rhs, rel=1e-9, abs=1e-9)
    # passivity at K = B = 0: M passive iff b >= M c_M everywhere, the interval of m_width
    w = m_width(rigid(), delay_samples=d, qualities=("passive",))
    up, _ = required_damping(lambda zz: zz ** (-d) * (1 - 1 / zz) ** 2 / T ** 2, T)
    assert w.m_max == pytest.approx(2.0 / up, rel=1e-9)
    k = passivity_limits(0.5, 2.0, T, np.zeros(2), d, virtual_masses=np.array([0.9, 1.1]) * w.m_max)
    assert k[0] > 0 and math.isnan(k[1])


def test_m_width_with_every_quality_is_the_intersection():
    s = QualitySettings(encoder_resolution=1e-6, force_noise=1.0, band=(1.0, 10.0), tolerance=0.2)
    w = m_width(rigid(), delay_samples=1, qualities=("stable", "passive", "accurate", "quiet"), settings=s)
    lo = max(v[0] for v in w.by_quality.values())
    hi = min(v[1] for v in w.by_quality.values())
    assert (w.m_min, w.m_max) == (min(lo, 0.0), max(hi, 0.0))
    assert w.by_quality["accurate"] == w.by_quality["stable"]  # a pure mass is accurate at 10 rad/s
    # the quiet limit: |M| sigma_a <= F_noise, sigma_a = q sqrt(6)/(sqrt(12) T^2) for the second difference
    assert w.by_quality["quiet"][1] == pytest.approx(1.0 / (1e-6 * math.sqrt(6.0 / 12.0) / T ** 2), rel=1e-9)


def test_an_inaccurate_band_gives_an_empty_accurate_m_width():
    s = QualitySettings(band=(100.0, 2000.0), tolerance=0.01)
    w = m_width(rigid(), delay_samples=1, qualities=("accurate",), settings=s)
    assert (w.m_min, w.m_max) == (0.0, 0.0)


def test_is_stable_on_both_sides_of_the_m_width():
    w = m_width(rigid(), delay_samples=1)
    for M, ok in ((0.999 * w.m_max, True), (1.001 * w.m_max, False), (0.99 * w.m_min, True),
                  (1.01 * w.m_min, False)):
        assert bool(is_stable(loop_radius(rigid(), M, 0.0, 0.0, 1))) is ok


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"qualities": ("stable", "smooth")}, "qualities"),
    ({"qualities": ()}, "qualities"),
    ({"m_range": (0.0, 1.0)}, "m_range"),
    ({"qualities": ("quiet",)}, "encoder_resolution"),
    ({"qualities": ("accurate",), "settings": QualitySettings(band=(1.0, 4000.0))}, "band"),
    ({"delay_samples": -1}, "delay_samples"),
])
def test_bad_input_names_the_field(kwargs, field):
    with pytest.raises(ValidationError) as err:
        m_width(rigid(), **kwargs)
    assert err.value.field == field


def test_a_mass_term_on_an_admittance_display_is_refused():
    with pytest.raises(ValidationError) as err:
        LoopSpec("admittance", (1.0, 100.0), mass=0.1)
    assert err.value.field == "mass"
    with pytest.raises(ValidationError) as err:
        LoopSpec("impedance", mass=float("nan"))
    assert err.value.field == "mass"
