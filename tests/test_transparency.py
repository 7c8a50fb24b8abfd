"""Eom, Suh & Yi: wall-controller transparency (J, eq. 11) and robust stability (||L||_inf, eq. 16-17).

The figures come from the design notes (paper-notes.md, last section).  J is checked against scipy
quad at tight tolerance and (rational holds) the Lyapunov H2 norm; ||L||_inf against a brute-force
10^6-point grid plus local refinement; the step response against scipy's cont2discrete + dlsim.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, optimize, signal

from analysis import Device, ValidationError
from analysis.chain.response import chain_response
from analysis.transparency.holds import hold_response
from analysis.transparency.design import WallDesign, WallSettings

PAPER = dict(mass=0.01, damping=0.022, wall_stiffness=1000.0, wall_damping=1.0, sample_time=1e-3,
             weight_cutoff=100.0)


def design(hold: str, **kw) -> WallDesign:
    return WallDesign(**{**PAPER, "hold": hold, **kw})


# -- figures of the notes --------------------------------------------------------------------------
@pytest.mark.parametrize("hold,bc_star", [("none", 15.0), ("lowpass2", 15.25), ("zoh", 15.45)])
def test_optimal_damping_matches_notes(hold, bc_star):
    opt = design(hold).optimal_damping(alpha=0.5, beta=0.5)
    assert opt.feasible and not opt.constrained
    assert abs(opt.bc - bc_star) <= 0.1
    assert opt.peak <= 1.0
    assert math.isfinite(opt.index)


@pytest.mark.parametrize("hold,db1,db15", [("none", 3.9, None), ("lowpass2", 9.2, -0.30), ("zoh", 10.0, -0.87)])
def test_robustness_peak_matches_notes(hold, db1, db15):
    d = design(hold)
    p1 = d.robustness_peak(1.0, alpha=0.5, beta=0.5)
    assert abs(p1.gain_db - db1) <= 0.1
    assert 300 < p1.frequency < 350  # the closed-loop resonance near sqrt(K/m)
    p15 = d.robustness_peak(15.0, alpha=0.5, beta=0.5)
    if db15 is not None:
        assert abs(p15.gain_db - db15) <= 0.1
        assert p1.gain > 1.0 and not p1.robust
        assert p15.gain <= 1.0 and p15.robust
    else:  # no hold: the supremum at B_c = 15 is the high-frequency limit alpha
        assert p15.gain == pytest.approx(0.5, rel=1e-12) and p15.frequency == math.inf


# -- J -----------------------------------------------------------------------------------------------
def _scipy_quad_J(d: WallDesign, bc: float, hold: str) -> float:
    st = d.settings
    T = st.sample_time

    def f(w: float, oscillating: bool = True) -> float:
        s = 1j * w
        H = hold_response(hold, np.array([s]), T, st.lowpass_damping, oscillating)[0]
        P = 1.0 / (st.mass * s + st.damping)
        yt = P / (1.0 + H * P * (bc + st.kc / s))
        e = (st.weight_cutoff / (s + st.weight_cutoff)) ** st.weight_order * (s / (st.wall_stiffness
                                                                               + st.wall_damping * s) - yt)
        return abs(e) ** 2

    if hold == "zoh":  # half-period pieces up to 2e6 rad/s (the integrand oscillates), then the tail
        edges = np.concatenate([[0.0], np.geomspace(1e-2, math.pi / T, 60), np.arange(2, 637) * math.pi / T])
    else:
        edges = np.concatenate([[0.0], np.geomspace(1e-2, 1e6, 120)])
    tot = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-13, limit=200)[0] for a, b in zip(edges[:-1], edges[1:]))
    # tail w = X/u; for zoh the e^{-sT} part is dropped there (|H P C| < 1e-8 beyond 2e6 rad/s)
    X = edges[-1]
    tot += integrate.quad(lambda u: f(X / u, False) * X / u**2, 0.0, 1.0, epsabs=0, epsrel=1e-13)[0]
    return tot / math.pi


@pytest.mark.parametrize("hold", ["none", "pade", "lowpass2"])
@pytest.mark.parametrize("bc", [1.0, 15.0])
def test_J_lyapunov_against_quad_and_gauss(hold, bc):
    d = design(hold)
    lyap = d.index_result(bc, method="lyapunov")
    assert lyap.finite and lyap.method == "lyapunov"
    ref = _scipy_quad_J(d, bc, hold)
    assert lyap.index == pytest.approx(ref, rel=1e-8)
    gauss = d.index_result(bc, method="quadrature")
    assert gauss.index == pytest.approx(lyap.index, rel=1e-8)


@pytest.mark.parametrize("bc", [1.0, 15.0])
def test_J_zoh_against_quad(bc):
    d = design("zoh")
    r = d.index_result(bc)
    assert r.method == "quadrature" and r.finite
    assert r.index == pytest.approx(_scipy_quad_J(d, bc, "zoh"), rel=1e-8)


def test_J_discrete_against_quad():
    d = design("discrete")
    bc = 5.0
    st = d.settings
    A = np.array([[-st.damping / st.mass, 0.0], [1.0, 0.0]])
    B = np.array([[1.0 / st.mass], [0.0]])
    Ad, Bd, *_ = signal.cont2discrete((A, B, np.eye(2), np.zeros((2, 1))), st.sample_time, method="zoh")
    T, K = st.sample_time, st.kc
    # closed loop on [v, x, x_prev]: u = K x + bc (x - x_prev)/T
    Acl = np.zeros((3, 3))
    Acl[:2, :2] = Ad
    Acl[:2, 1] -= Bd[:, 0] * (K + bc / T)
    Acl[:2, 2] += Bd[:, 0] * bc / T
    Acl[2, 1] = 1.0
    Bcl = np.r_[Bd[:, 0], 0.0][:, None]

    def f(w):
        z = np.exp(1j * w * T)
        yt = (np.linalg.solve(z * np.eye(3) - Acl, Bcl))[0, 0]
        s = 1j * w
        return abs(100 / (s + 100) * (s / (K + s) - yt)) ** 2

    edges = np.concatenate([[0.0], np.geomspace(1e-2, math.pi / T, 80)])
    ref = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-13)[0] for a, b in zip(edges[:-1], edges[1:])) / math.pi
    assert d.performance_index(bc) == pytest.approx(ref, rel=1e-8)


# Every hold model's Fig. 8 curve (its run time, target 100 ms cold, is measured in
# tests/benchmarks/bench_transparency.py, never in a test).
@pytest.mark.parametrize("hold", ["none", "lowpass2", "zoh", "pade", "discrete"])
def test_tradeoff_curve_agrees_with_pointwise(hold):
    d = design(hold)
    bcs = np.linspace(0.5, 40, 100)
    c = d.tradeoff(bcs, alpha=0.5, beta=0.5)
    assert c.bc.shape == c.index.shape == c.peak.shape == c.peak_frequency.shape == (100,)
    for i in (0, 37, 99):
        assert c.index[i] == pytest.approx(d.performance_index(bcs[i]), rel=1e-8)
        assert c.peak[i] == pytest.approx(d.robustness_peak(bcs[i]).gain, rel=1e-12)


def test_J_infinite_cases_say_why():
    r = design("lowpass2", weight_order=0).index_result(15.0)
    assert not r.finite and r.index == math.inf and "high frequency" in r.reason
    r = design("zoh", weight_order=0).index_result(15.0)
    assert not r.finite and "order 0" in r.reason
    r = design("none").index_result(-0.5)  # b + B_c < 0: unstable
    assert r.index == math.inf and "unstable" in r.reason
    r = design("zoh").index_result(-0.5)
    assert r.index == math.inf and "unstable" in r.reason
    r = design("discrete").index_result(30.0)  # B_c T/m = 3: the sampled loop is unstable
    assert r.index == math.inf and "unstable" in r.reason
    # a wall without damping needs a second-order weight
    assert design("lowpass2", wall_damping=0.0).performance_index(15.0) == math.inf
    r2 = design("lowpass2", wall_damping=0.0, weight_order=2).index_result(15.0)
    assert r2.finite and r2.index == pytest.approx(
        design("lowpass2", wall_damping=0.0, weight_order=2).index_result(15.0, method="quadrature").index, rel=1e-8)


def test_controller_stiffness_differs_from_wall():
    # eq. (11) stays finite for K_c != K (the error vanishes at DC like s (1/K - 1/K_c))
    d = design("lowpass2", controller_stiffness=800.0)
    r = d.index_result(15.0)
    assert r.finite
    assert r.index == pytest.approx(d.index_result(15.0, method="quadrature").index, rel=1e-8)


# -- ||L||_inf -----------------------------------------------------------------------------------------
def _brute_peak(d: WallDesign, bc: float, alpha: float, beta: float) -> float:
    st = d.settings
    hi = math.pi / st.sample_time * (1 - 1e-12) if st.hold == "discrete" else 1e6
    w = np.geomspace(1e-1, hi, 1_000_000)

    def mag2(x):
        x = np.atleast_1d(x)
        _, yt = d.admittances(x, bc)
        return np.abs((alpha * st.mass * 1j * x + beta * st.damping) * yt) ** 2

    if st.hold == "discrete":  # L(z) is not W(jw) Y_t(z): the sampled W P closed through the loop
        md = d.loops.discrete.modal(np.array([bc]), alpha, beta)

        def mag2(x):  # noqa: F811
            x = np.atleast_1d(x)
            L = md.robustness(np.array([0]), np.exp(1j * x * st.sample_time))[0]
            return np.abs(L) ** 2

    v = np.concatenate([mag2(c) for c in np.array_split(w, 20)])
    i = int(np.argmax(v))
    a, b = w[max(i - 1, 0)], w[min(i + 1, w.size - 1)]
    res = optimize.minimize_scalar(lambda x: -mag2(x)[0], bounds=(a, b), method="bounded",
                                   options={"xatol": 1e-12 * b})
    peak = math.sqrt(max(v[i], -res.fun))
    if st.hold != "discrete":
        peak = max(peak, alpha)  # the high-frequency limit
    return peak


@pytest.mark.parametrize("hold,bc", [("lowpass2", 1.0), ("lowpass2", 15.0), ("zoh", 1.0), ("zoh", 15.0),
                                     ("pade", 15.0), ("none", 1.0), ("discrete", 5.0)])
def test_peak_against_brute_force(hold, bc):
    d = design(hold)
    p = d.robustness_peak(bc, alpha=0.5, beta=0.5)
    assert p.certified
    assert p.gain == pytest.approx(_brute_peak(d, bc, 0.5, 0.5), rel=1e-8)


def test_peak_lightly_damped_resonance_is_not_missed():
    # B_c close to -b: closed-loop damping ratio ~ 1e-3; a coarse grid would miss the peak
    d = design("none")
    bc = -0.022 + 0.006
    p = d.robustness_peak(bc, alpha=0.5, beta=0.5)
    assert p.gain == pytest.approx(_brute_peak(d, bc, 0.5, 0.5), rel=1e-8)
    assert p.gain > 10


# -- views --------------------------------------------------------------------------------------------
def test_admittances_closed_form():
    d = design("lowpass2")
    w = np.geomspace(1, 1e4, 50)
    yv, yt = d.admittances(w, 15.0)
    s = 1j * w
    wn = math.pi / 1e-3
    H = wn**2 / (s**2 + 2 * 0.7071 * wn * s + wn**2)
    P = 1 / (0.01 * s + 0.022)
    np.testing.assert_allclose(yv, s / (1000 + s), rtol=1e-14)
    np.testing.assert_allclose(yt, P / (1 + H * P * (15 + 1000 / s)), rtol=1e-12)


@pytest.mark.parametrize("bc", [1.0, 15.0])
def test_step_response_against_dlsim(bc):
    d = design("lowpass2")
    r = d.step_response(bc, force=-5.0, duration=0.5, substeps=4)
    T, m, b, K = 1e-3, 0.01, 0.022, 1000.0
    A = np.array([[-b / m, 0.0], [1.0, 0.0]])  # [v, x]
    B = np.array([[1 / m], [0.0]])
    Ad, Bd, *_ = signal.cont2discrete((A, B, np.eye(2), np.zeros((2, 1))), T, method="zoh")
    n = 500
    x = np.zeros(2)
    prev = 0.0
    xs, us = [], []
    for _ in range(n):
        u = K * x[1] + bc * (x[1] - prev) / T
        xs.append(x.copy())
        us.append(u)
        prev = x[1]
        x = Ad @ x + Bd[:, 0] * (-5.0 - u)
    xs = np.array(xs)
    np.testing.assert_allclose(r.position[:-1:4], xs[:, 1], rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(r.velocity[:-1:4], xs[:, 0], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(r.force[:-1:4], us, rtol=1e-9, atol=1e-10)
    # between samples: dlsim of the open plant on a fine step with the held input
    Af, Bf, *_ = signal.cont2discrete((A, B, np.eye(2), np.zeros((2, 1))), T / 4, method="zoh")
    k = 123
    z = xs[k]
    for j in range(4):
        np.testing.assert_allclose(r.position[4 * k + j], z[1], rtol=1e-10, atol=1e-14)
        z = Af @ z + Bf[:, 0] * (-5.0 - us[k])
    # the paper's picture: B_c = 1 rings, B_c = 15 does not; both settle at F/K
    assert r.position[-1] == pytest.approx(-5.0 / K, rel=1e-2)


def test_step_response_oscillation_fig7_vs_fig10():
    d = design("lowpass2")
    r1 = d.step_response(1.0)
    r15 = d.step_response(15.0)
    over1 = np.min(r1.position) / (-5e-3) - 1
    over15 = np.min(r15.position) / (-5e-3) - 1
    assert over1 > 0.3 and over15 < 0.05


# -- chain devices -------------------------------------------------------------------------------------
def test_chain_plant_is_handle_admittance():
    dev = Device.from_damping_ratios([0.004, 0.006], [2e4], 0.1, ground_dampings=[0.0, 0.022], sample_time=1e-3)
    d = WallDesign(**{**PAPER, "hold": "lowpass2"}, device=dev)
    s = 1j * np.geomspace(1, 1e4, 30)
    from analysis.chain import handle_admittance

    np.testing.assert_allclose(handle_admittance(dev, s), chain_response(dev, s).y11, rtol=1e-12)
    lyap = d.index_result(15.0)
    assert lyap.finite
    assert lyap.index == pytest.approx(d.index_result(15.0, method="quadrature").index, rel=1e-8)
    p = d.robustness_peak(15.0)
    assert p.gain == pytest.approx(_brute_peak_chain(d, 15.0), rel=1e-8)


def _brute_peak_chain(d, bc):
    w = np.geomspace(1e-1, 1e6, 1_000_000)
    mw, bw = d.plant.m_w, d.plant.b_w

    def mag2(x):
        x = np.atleast_1d(x)
        return np.abs((0.5 * mw * 1j * x + 0.5 * bw) * d.admittances(x, bc)[1]) ** 2

    v = mag2(w)
    i = int(np.argmax(v))
    res = optimize.minimize_scalar(lambda x: -mag2(x)[0], bounds=(w[i - 1], w[i + 1]), method="bounded",
                                   options={"xatol": 1e-12 * w[i]})
    return max(math.sqrt(max(v[i], -res.fun)), d.robustness.high_frequency_limit(0.5))


def test_rigid_chain_equals_rigid_plant():
    dev = Device(masses=[0.01], ground_dampings=[0.022], sample_time=1e-3)
    a = WallDesign(**{**PAPER, "hold": "zoh"}, device=dev)
    b = design("zoh")
    assert a.performance_index(15.0) == pytest.approx(b.performance_index(15.0), rel=1e-12)
    assert a.robustness_peak(1.0).gain == pytest.approx(b.robustness_peak(1.0).gain, rel=1e-12)


# -- the parts of the design ----------------------------------------------------------------------------
def test_design_parts_and_their_caches():
    d = design("lowpass2")
    assert d.loops.rational("lowpass2") is d.loops.rational("lowpass2")
    assert d.index.error_realization("lowpass2") is d.index.error_realization("lowpass2")
    assert d.loops.discrete.sampled_plant() is d.loops.discrete.sampled_plant()
    bcs = np.array([1.0, 15.0])
    np.testing.assert_allclose(d.index.h2_modal_many(bcs, "lowpass2"),
                               [d.index.lyapunov(float(b), "lowpass2").index for b in bcs], rtol=1e-9)
    assert d.robustness.high_frequency_limit(0.5) == pytest.approx(0.5, rel=1e-15)  # rigid: m_W = m_handle
    md = design("discrete").loops.discrete.modal(bcs, 0.5, 0.5)
    z = np.exp(1j * np.array([10.0, 300.0]) * 1e-3)
    yt = design("discrete").admittances(np.array([10.0, 300.0]), 15.0)[1]
    np.testing.assert_allclose(md.admittance(np.array([1]), z)[0], yt, rtol=1e-12)


# -- settings ------------------------------------------------------------------------------------------
def test_settings_roundtrip_and_validation():
    st = WallSettings(hold="zoh", controller_stiffness=900.0, weight_order=2)
    assert WallSettings.from_dict(st.to_dict()) == st
    d = WallDesign(st)
    assert d.settings.hold == "zoh" and d.kc == 900.0
    for bad, field in [({"hold": "foh"}, "hold"), ({"mass": -1.0}, "mass"), ({"weight_order": 1.5}, "weight_order"),
                       ({"alpha": 1.0}, "alpha"), ({"bc_max": 0.1}, "bc_max"), ({"colour": 1}, "colour"),
                       ({"sample_time": "1e-3"}, "sample_time"), ({"wall_stiffness": 0.0, "wall_damping": 0.0},
                                                                  "wall_damping")]:
        with pytest.raises(ValidationError) as e:
            WallSettings.from_dict(bad)
        assert e.value.field == field
    with pytest.raises(ValidationError) as e:
        design("lowpass2").performance_index(float("nan"))
    assert e.value.field == "bc"
