"""Velocity filters in every analysis with a damping term (issue 15).

Independent checks: the exact critical stiffness of a rigid 1-DOF device with a filtered wall
against the closed-loop characteristic polynomial built by hand, and against a brute-force
simulation of the linear loop whose growth rate must equal the spectral radius; the passivity
limit with a filter against a direct dense-grid evaluation of Colgate & Schenkel's condition.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from analysis import AdmittanceDisplay, Device, ImpedanceDisplay
from analysis.errors import ValidationError
from analysis.sampled import (
    HANDS_OFF,
    LoopSpec,
    Termination,
    VelocityFilter,
    closed_loop_matrices,
    critical_mass,
    critical_stiffness,
    god_object_wall,
    passivity_limit,
    passivity_limits,
    required_damping,
    spectral_radius,
)
from analysis.twoport.impedance import coupling_impedance, re_inv_coupling

T = 1e-3
M, BPHYS = 0.5, 2.0
FILTERS = [VelocityFilter("lowpass1", cutoff=2 * math.pi * 30), VelocityFilter("lowpass1", cutoff=2 * math.pi * 200),
           VelocityFilter("butter2", cutoff=2 * math.pi * 50), VelocityFilter("butter2", cutoff=2 * math.pi * 300)]


@pytest.fixture(scope="module")
def rigid() -> Device:
    return Device(masses=[M], stiffnesses=[], dampings=[], ground_dampings=[BPHYS], sample_time=T)


# -- the filter object -------------------------------------------------------------------------
def test_filter_responses_have_unity_dc_gain_and_the_designed_cutoff():
    w = np.array([1e-7, 2 * math.pi * 50])
    for f in FILTERS:
        h = f.filter_response(w, T)
        assert abs(h[0] - 1.0) < 1e-8
    b2 = VelocityFilter("butter2", cutoff=2 * math.pi * 50)
    assert abs(abs(b2.filter_response(np.array([2 * math.pi * 50]), T)[0]) - 1 / math.sqrt(2)) < 1e-12  # pre-warped
    lp = VelocityFilter("lowpass1", cutoff=2 * math.pi * 50)
    a = math.exp(-2 * math.pi * 50 * T)
    z = np.exp(1j * w * T)
    assert np.allclose(lp.filter_response(w, T), (1 - a) / (1 - a / z), rtol=1e-13, atol=0)
    # the whole estimate is the derivative at low frequency
    v = lp.response(np.array([0.1]), T)[0]
    assert abs(v / (0.1j) - 1) < 1e-3  # a lag of 1/w_f + T/2 at 0.1 rad/s


def test_realization_matches_the_transfer_function():
    from scipy import signal

    rng = np.random.default_rng(1)
    x = np.cumsum(rng.normal(size=200))
    for f in FILTERS:
        num, den = f.transfer_function(T)
        ref = signal.lfilter(num, den, x)
        r = f.realization(T)
        s = np.zeros(r.order)
        out, prev = [], 0.0
        for xk in x:
            d = (xk - prev) / T
            out.append(r.C @ s + r.D * d)
            s = r.A @ s + r.B * d
            prev = xk
        assert np.allclose(out, ref, rtol=1e-10, atol=1e-9)


def test_filter_validation_and_record_round_trip():
    with pytest.raises(ValidationError, match="cutoff"):
        VelocityFilter("lowpass1", cutoff=0.0)
    with pytest.raises(ValidationError, match="cutoff"):
        VelocityFilter("butter2")  # a filter needs a finite cut-off
    with pytest.raises(ValidationError, match="kind"):
        VelocityFilter("median")
    with pytest.raises(ValidationError, match="Nyquist"):
        VelocityFilter("butter2", cutoff=math.pi / T).check(T)
    VelocityFilter("lowpass1", cutoff=2 * math.pi * 500).check(T)  # the grid ends at Nyquist
    for f in FILTERS + [VelocityFilter()]:
        assert VelocityFilter.from_dict(f.to_dict()) == f
    assert VelocityFilter().to_dict() == {"kind": "backward", "cutoff": "inf"}


# -- the default stays bit-identical -------------------------------------------------------------
def test_backward_filter_is_bit_identical(rigid):
    from analysis import load_profile
    from analysis.resources import resource_path

    hb = load_profile(resource_path("profiles", "hbfd.json")).device
    assert critical_stiffness(hb, 100.0, 1, velocity_filter=VelocityFilter()) == critical_stiffness(hb, 100.0, 1)
    assert critical_mass(hb, 1550.0, velocity_filter=VelocityFilter()) == critical_mass(hb, 1550.0)
    assert passivity_limit(M, BPHYS, T, 0.5, 1, velocity_filter=VelocityFilter()) == passivity_limit(M, BPHYS, T, 0.5, 1)
    d0, d1 = ImpedanceDisplay(hb), ImpedanceDisplay(hb, velocity_filter=VelocityFilter())
    assert d0.max_stiffness(100.0) == d1.max_stiffness(100.0)


# -- exact critical stiffness: characteristic polynomial by hand -----------------------------------
def _rigid_char_poly(K: float, B: float, d: int, f: VelocityFilter) -> np.ndarray:
    """Coefficients (ascending in q = 1/z, i.e. descending in z) of the closed loop, by hand.

    Plant (ZOH, force on the device to position): ``(alpha q + beta q^2)/((1 - q)(1 - delta q))``;
    wall ``F = q^d (K + B nv(q)/dv(q)) x``; force on the device ``-F``.
    """
    delta = math.exp(-BPHYS * T / M)
    om = -math.expm1(-BPHYS * T / M)
    alpha = (T - (M / BPHYS) * om) / BPHYS
    beta = ((M / BPHYS) * om - T * delta) / BPHYS
    nv, dv = f.transfer_function(T)
    lhs = np.convolve(dv, np.convolve([1.0, -1.0], [1.0, -delta]))
    ctrl = np.polyadd(K * dv[::-1], B * nv[::-1])[::-1]  # K dv + B nv, ascending
    rhs = np.convolve(np.r_[np.zeros(d), ctrl], [0.0, alpha, beta])
    n = max(lhs.size, rhs.size)
    return np.r_[lhs, np.zeros(n - lhs.size)] + np.r_[rhs, np.zeros(n - rhs.size)]


def _radius(K: float, B: float, d: int, f: VelocityFilter) -> float:
    c = np.trim_zeros(_rigid_char_poly(K, B, d, f), "b")
    return float(np.max(np.abs(np.roots(c))))


def _critical_by_hand(B: float, d: int, f: VelocityFilter) -> float:
    ks = np.geomspace(1.0, 1e8, 161)
    bad = np.array([_radius(k, B, d, f) > 1 + 1e-12 for k in ks])
    j = int(np.argmax(bad))
    lo, hi = ks[j - 1], ks[j]
    for _ in range(40):  # 10^(1/20) / 2^40: 1e-13 relative
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if _radius(mid, B, d, f) > 1 + 1e-12 else (mid, hi)
    return lo


@pytest.mark.parametrize("d", [0, 2])
@pytest.mark.parametrize("f", FILTERS, ids=lambda f: f.label())
def test_critical_stiffness_with_filter_matches_the_hand_built_polynomial(rigid, d, f):
    for B in (1.0, 20.0):
        exact = critical_stiffness(rigid, B, d, velocity_filter=f)
        assert exact == pytest.approx(_critical_by_hand(B, d, f), rel=1e-7)
    # and the filter matters: it is not the backward-difference answer
    assert critical_stiffness(rigid, 20.0, d, velocity_filter=f) != pytest.approx(critical_stiffness(rigid, 20.0, d),
                                                                                  rel=1e-3)


# -- brute-force simulation: growth rate = spectral radius ------------------------------------------
def _simulate_by_hand(K: float, B: float, d: int, f: VelocityFilter, steps: int) -> np.ndarray:
    """The rigid device and the filtered wall, bilateral and linear, by scalar recursions."""
    delta = math.exp(-BPHYS * T / M)
    om = -math.expm1(-BPHYS * T / M)
    nv, dv = f.transfer_function(T)
    x, v = 1e-3, 0.0
    forces = [0.0] * d
    hist_x = [x] * len(nv)
    hist_v = [0.0] * len(dv)
    out = np.empty(steps)
    for k in range(steps):
        hist_x = [x] + hist_x[:-1]
        vel = (sum(nv[i] * hist_x[i] for i in range(len(nv))) - sum(dv[j] * hist_v[j - 1] for j in range(1, len(dv))))
        hist_v = [vel] + hist_v[:-1]
        forces.append(K * x + B * vel)
        F = -forces.pop(0)
        # exact ZOH step of m x'' = F - b x'
        x_new = x + v * (M / BPHYS) * om + (F / BPHYS) * (T - (M / BPHYS) * om)
        v = v * delta + (F / BPHYS) * om
        x = x_new
        out[k] = x
    return out


@pytest.mark.parametrize("f", FILTERS[::2], ids=lambda f: f.label())
def test_growth_rate_of_a_brute_force_simulation_equals_the_spectral_radius(rigid, f):
    d, B = 1, 5.0
    K = 1.3 * critical_stiffness(rigid, B, d, velocity_filter=f)
    spec = LoopSpec("impedance", (K, B), delay_samples=d, velocity_filter=f)
    rho = float(spectral_radius(closed_loop_matrices(rigid, spec, [Termination(HANDS_OFF, god_object_wall())]))[0])
    assert rho > 1
    x = _simulate_by_hand(K, B, d, f, 6000)
    env = np.array([np.max(np.abs(x[i:i + 200])) for i in (3000, 5800)])
    rate = (env[1] / env[0]) ** (1 / 2800)
    assert rate == pytest.approx(rho, abs=2e-5)


# -- Colgate-Schenkel with a filter -------------------------------------------------------------------
@pytest.mark.parametrize("d", [0, 1])
@pytest.mark.parametrize("f", FILTERS, ids=lambda f: f.label())
def test_passivity_limit_with_filter_matches_a_dense_direct_evaluation(d, f):
    B = 0.5
    kp = passivity_limit(M, BPHYS, T, B, d, velocity_filter=f)
    nv, dv = f.transfer_function(T)

    def wall(K):
        def H(z):
            q = 1.0 / z
            return q ** d * (K + B * np.polyval(nv[::-1], q) / np.polyval(dv[::-1], q))
        return H

    assert required_damping(wall(kp * (1 - 1e-6)), T, points=50001)[0] <= BPHYS
    assert required_damping(wall(kp * (1 + 1e-4)), T, points=50001)[0] > BPHYS
    vec = passivity_limits(M, BPHYS, T, np.array([0.0, B, 1.0]), d, velocity_filter=f)
    assert vec[1] == pytest.approx(kp, rel=1e-9)
    assert vec[0] == pytest.approx(passivity_limit(M, BPHYS, T, 0.0, d, velocity_filter=f), rel=1e-9)


# -- the two-port coupling ---------------------------------------------------------------------------
def test_coupling_impedance_with_filter_and_its_accuracy():
    f = VelocityFilter("lowpass1", cutoff=2 * math.pi * 30)
    w = np.array([1e-4, 1.0, 100.0, 3000.0])
    z = np.exp(1j * w * T)
    a = math.exp(-2 * math.pi * 30 * T)
    direct = 100.0 * (1 - a) / (1 - a / z) + 5e4 * T * z / (z - 1)
    assert np.allclose(coupling_impedance(w, T, 5e4, 100.0, f)[1:], direct[1:], rtol=1e-9)
    mpmath.mp.dps = 50
    for wk, got in zip(w, re_inv_coupling(w, T, 5e4, 100.0, f)):
        zz = mpmath.exp(1j * mpmath.mpf(wk) * mpmath.mpf(T))
        aa = mpmath.exp(-2 * mpmath.pi * 30 * mpmath.mpf(T))
        Z = 100 * (1 - aa) / (1 - aa / zz) + mpmath.mpf(5e4) * mpmath.mpf(T) * zz / (zz - 1)
        ref = float(mpmath.re(1 / Z))
        assert got == pytest.approx(ref, rel=1e-9)


def test_twoport_designs_with_filter_are_tight():
    from analysis import load_profile
    from analysis.resources import resource_path

    hb = load_profile(resource_path("profiles", "hbfd.json")).device
    f = VelocityFilter("lowpass1", cutoff=2 * math.pi * 30)
    disp = ImpedanceDisplay(hb, velocity_filter=f)
    d = disp.max_stiffness(100.0)
    assert d.kc < ImpedanceDisplay(hb).max_stiffness(100.0).kc  # the filter's lag costs stiffness
    assert disp.evaluate(d.kc * 0.999, 100.0).stable and not disp.evaluate(d.kc * 1.001, 100.0).stable
    # a filter at Nyquist is close to the backward difference
    near = ImpedanceDisplay(hb, velocity_filter=VelocityFilter("lowpass1", cutoff=math.pi / T)).max_stiffness(100.0)
    assert near.kc == pytest.approx(ImpedanceDisplay(hb).max_stiffness(100.0).kc, rel=2e-3)
    adm = AdmittanceDisplay(hb, 50e3, 100.0, velocity_filter=f)
    assert adm.min_mass().mc > AdmittanceDisplay(hb, 50e3, 100.0).min_mass().mc


def test_admittance_loop_with_filter_simulates_at_the_spectral_radius():
    """The PD loop's filtered derivative (filter states as controller memory) in the simulator:
    just below the exact critical m_c the free-motion run grows at the loop's spectral radius."""
    from analysis import load_profile
    from analysis.resources import resource_path
    from analysis.sampled import RIGID_GRASP, free_motion, radii, scenario, simulate

    hb = load_profile(resource_path("profiles", "hbfd.json")).device
    f = VelocityFilter("lowpass1", cutoff=2 * math.pi * 100)
    mc = critical_mass(hb, 1550.0, velocity_filter=f)
    assert mc == pytest.approx(1.6977157, rel=1e-6) and mc > critical_mass(hb, 1550.0)
    coupling = (0.97 * mc, 1550.0)
    rho = radii(hb, LoopSpec("admittance", coupling, velocity_filter=f), [Termination(RIGID_GRASP, free_motion())])[0]
    r = simulate(hb, scenario("admittance_worst_case", duration=3.0), display="admittance", coupling=coupling,
                 velocity_filter=f)
    x = r.actuator_position - np.mean(r.actuator_position[-500:])
    rate = (np.max(np.abs(x[2700:2900])) / np.max(np.abs(x[1500:1700]))) ** (1 / 1200)
    assert rho > 1 and rate == pytest.approx(rho, abs=3e-4) and r.verdict.kind == "divergent"
