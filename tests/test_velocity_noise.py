"""Encoder-quantization noise of the velocity estimate and the noise-limited Z-width (issue 15).

The noise side of Chawda, Celik & O'Malley's trade-off (ASME JDSMC 2015): the noise gain of
``H_f(z)(1 - z^{-1})/T`` is checked against closed forms, a dense frequency integral and a
brute-force quantized record; with the noise criterion a rigid device with a delay has the
interior optimum cut-off that the noise-free analysis does not have.
"""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest
from scipy import signal

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.profiles import ControllerSection, ProfileError, bundled_profiles, load_profile, profile_from_dict, \
    profile_to_dict, save_profile
from analysis.sampled import (
    DEFAULT_FORCE_NOISE,
    VelocityFilter,
    estimate_noise,
    noise_gain,
    noise_limited_damping,
    optimal_filter,
    zwidth_region,
)
from analysis.study import noise_options
from analysis.study import zwidth_region as study_region

T = 1e-3
Q = 1e-5  # m at the handle: a 2^14-count encoder on a 26 mm radius, direct drive
FILTERS = [VelocityFilter("lowpass1", 2 * math.pi * f) for f in (5.0, 30.0, 200.0)] + \
          [VelocityFilter("butter2", 2 * math.pi * f) for f in (5.0, 30.0, 200.0, 450.0)]


@pytest.fixture(scope="module")
def rigid() -> Device:
    return Device(masses=[0.5], stiffnesses=[], dampings=[], ground_dampings=[2.0], sample_time=T)


def test_backward_difference_and_lowpass1_closed_forms():
    assert noise_gain(None, T) ** 2 == pytest.approx(2.0 / T**2, rel=1e-13)
    assert noise_gain(VelocityFilter(), 1e-4) ** 2 == pytest.approx(2.0 / 1e-8, rel=1e-13)
    for f in (1.0, 30.0, 499.0):
        a = math.exp(-2 * math.pi * f * T)
        g2 = 2.0 * (1.0 - a) ** 2 / (T**2 * (1.0 + a))
        assert noise_gain(VelocityFilter("lowpass1", 2 * math.pi * f), T) ** 2 == pytest.approx(g2, rel=1e-12)
    # g -> w_f as w_f T -> 0 (a first-order roll-off of a differentiator's w^2 spectrum)
    assert noise_gain(VelocityFilter("lowpass1", 2 * math.pi), T) == pytest.approx(2 * math.pi, rel=2e-3)


@pytest.mark.parametrize("vf", FILTERS, ids=lambda v: f"{v.kind}-{v.cutoff / (2 * math.pi):g}Hz")
def test_noise_gain_equals_the_frequency_integral(vf):
    th = np.linspace(0.0, math.pi, 400_001)
    g2 = np.trapezoid(np.abs(vf.response(th / T, T)) ** 2, th) / math.pi
    assert noise_gain(vf, T) ** 2 == pytest.approx(g2, rel=1e-8)


def estimate_realization(vf: VelocityFilter, T: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``V(z)`` from the position, states ``[x[k-1], s]``, written here from the filter's realization."""
    r = vf.realization(T)
    n = r.order
    A = np.zeros((n + 1, n + 1))
    A[1:, 0] = -r.B / T
    A[1:, 1:] = r.A
    return A, np.r_[1.0, r.B / T], np.r_[-r.D / T, r.C], r.D / T


def kronecker_gain(vf: VelocityFilter, T: float) -> float:
    """The previous route: ``(I - A (x) A) vec P = vec B B'`` solved directly."""
    A, B, C, D = estimate_realization(vf, T)
    P = np.linalg.solve(np.eye(A.size) - np.kron(A, A), np.outer(B, B).reshape(-1)).reshape(A.shape)
    return math.sqrt(float(C @ P @ C) + D * D)


def lyapunov_gain_60_digits(vf: VelocityFilter, T: float) -> float:
    """The same Kronecker system solved with 60 digits (the floats of the realization, exactly)."""
    import mpmath as mp

    A, B, C, D = estimate_realization(vf, T)
    n = A.shape[0]
    with mp.workdps(60):
        M = mp.matrix(n * n, n * n)
        for i, j, k, m in np.ndindex(n, n, n, n):
            M[i * n + k, j * n + m] = (1 if (i == j and k == m) else 0) - mp.mpf(A[i, j]) * mp.mpf(A[k, m])
        p = mp.lu_solve(M, mp.matrix([mp.mpf(B[i]) * mp.mpf(B[k]) for i in range(n) for k in range(n)]))
        g2 = mp.fsum(mp.mpf(C[i]) * p[i * n + k] * mp.mpf(C[k]) for i in range(n) for k in range(n)) + mp.mpf(D) ** 2
        return float(mp.sqrt(g2))


@pytest.mark.parametrize("vf", [VelocityFilter()] + FILTERS, ids=lambda v: f"{v.kind}-{v.cutoff / (2 * math.pi):g}Hz")
def test_noise_gain_agrees_with_the_kronecker_route(vf):
    """scipy's solver (bilinear) against the previous direct Kronecker solve: 1e-12 relative from
    a 30 Hz cut-off up (measured: 2e-14 at most); at 5 Hz the Kronecker route's own error against
    a 60-digit solution is 2e-12 (butter2), so 1e-10 there."""
    rel = 1e-12 if vf.cutoff >= 2 * math.pi * 29.0 else 1e-10
    assert noise_gain(vf, T) == pytest.approx(kronecker_gain(vf, T), rel=rel)


@pytest.mark.parametrize("hz", [0.1, 1.0, 5.0, 30.0])
def test_noise_gain_matches_a_60_digit_solution_at_low_cutoffs(hz):
    """At a low butter2 cut-off the Kronecker system is nearly singular (condition 3e18 at 1 Hz):
    the previous route was off by 1e-9 there and 1e-6 at 0.1 Hz; scipy's bilinear route is not."""
    vf = VelocityFilter("butter2", 2 * math.pi * hz)
    ref = lyapunov_gain_60_digits(vf, T)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no LinAlgWarning of an ill-conditioned solve
        g = noise_gain(vf, T)
    assert g == pytest.approx(ref, rel=1e-8)
    if hz <= 0.1:
        assert abs(kronecker_gain(vf, T) - ref) > 1e-8 * ref  # the check can tell the routes apart


@pytest.mark.parametrize("vf", [None, FILTERS[1], FILTERS[5]], ids=["backward", "lowpass1", "butter2"])
def test_noise_gain_equals_a_quantized_record(vf):
    """Truncate a seeded random walk to q, run the estimate on the error: std within 2 %."""
    rng = np.random.default_rng(15)
    x = np.cumsum(rng.normal(0.0, 7.3 * Q, 400_000))
    err = Q * np.floor(x / Q) - x
    num, den = (VelocityFilter() if vf is None else vf).transfer_function(T)
    v = signal.lfilter(num, den, err)[1000:]
    noise = estimate_noise(vf, T, Q)
    assert np.std(err) == pytest.approx(Q / math.sqrt(12), rel=0.01)
    assert np.std(v) == pytest.approx(noise.velocity_rms, rel=0.02)
    assert noise.velocity_rms == pytest.approx(Q * noise_gain(vf, T) / math.sqrt(12), rel=1e-15)


def test_noise_limited_damping_and_validation():
    n = estimate_noise(None, T, Q)
    assert n.velocity_rms == pytest.approx(Q * math.sqrt(2) / T / math.sqrt(12), rel=1e-13)  # 4.08 mm/s
    assert n.damping_limit() == pytest.approx(DEFAULT_FORCE_NOISE / n.velocity_rms, rel=1e-15)
    assert n.damping_limit() == pytest.approx(24.49, rel=1e-3)
    assert float(n.force_rms(24.49)) == pytest.approx(0.1, rel=1e-3)
    assert noise_limited_damping(None, T, None) == math.inf
    assert noise_limited_damping(None, T, Q, 0.2) == pytest.approx(2 * n.damping_limit(), rel=1e-14)
    with pytest.raises(ValidationError, match="encoder_resolution"):
        noise_limited_damping(None, T, None, 0.1)
    for bad in (0.0, -1e-6, 1.0, math.nan):
        with pytest.raises(ValidationError, match=r"\(m\)"):
            estimate_noise(None, T, bad)
    with pytest.raises(ValidationError, match=r"\(N\)"):
        n.damping_limit(0.0)


def test_region_rows_above_the_noise_limit_are_not_renderable(rigid):
    b = np.geomspace(1, 1000, 30)
    vf = VelocityFilter("lowpass1", 2 * math.pi * 50)
    free = zwidth_region(rigid, b=b, delay_samples=1, velocity_filter=vf, passive=False)
    assert free.b_noise == math.inf and free.force_noise is None
    noisy = zwidth_region(rigid, b=b, delay_samples=1, velocity_filter=vf, passive=False, encoder_resolution=Q)
    bn = noise_limited_damping(vf, T, Q, 0.1)
    assert noisy.b_noise == bn and noisy.force_noise == 0.1 and 100 < bn < 130
    ok = b <= bn
    assert np.all(noisy.k_max[~ok] == 0) and np.count_nonzero(free.k_max[~ok] > 0) >= 4
    np.testing.assert_allclose(noisy.k_max[ok], free.k_max[ok], rtol=1e-9)
    assert noisy.area_linear < 0.5 * free.area_linear


def test_rigid_device_with_a_delay_has_a_noise_limited_interior_optimum(rigid):
    """0.5 kg, 2 N s/m, T = 1 ms, one sample of delay, q = 10 um, 0.1 N rms, B 1-1000 (100 points).

    Noise-free, the area only rises with the cut-off (5-450 Hz); with the noise criterion the
    lag bounds it at low cut-offs and the noise at high ones: lowpass1 peaks near 28 Hz,
    butter2 near 108 Hz, each ~2.5e6 N^2 s/m^2, at least twice both ends of the range.
    """
    b = np.geomspace(1, 1000, 100)
    cut = np.geomspace(2 * math.pi * 5, 2 * math.pi * 450, 16)
    expect = {"lowpass1": (20, 40), "butter2": (80, 140)}
    for kind, (lo, hi) in expect.items():
        o = optimal_filter(rigid, kind, cut, b=b, delay_samples=1, encoder_resolution=Q, force_noise=0.1)
        assert o.interior and o.encoder_resolution == Q and o.force_noise == 0.1
        assert 2 * math.pi * lo < o.cutoff < 2 * math.pi * hi
        assert o.area > 2.0 * max(o.areas[0], o.areas[-1]) and o.area > 5 * o.backward_area
        free = zwidth_region(rigid, b=b, delay_samples=1, velocity_filter=VelocityFilter(kind, o.cutoff),
                             passive=False)
        assert free.area_linear > 1.1 * o.area  # the noise criterion removes the top of the B range
    off = optimal_filter(rigid, "lowpass1", cut[::3], b=b, delay_samples=1)
    assert off.encoder_resolution is None and not off.interior and np.all(np.diff(off.areas) > 0)


def test_profile_keys_round_trip_and_reach_the_study(tmp_path):
    base = load_profile(bundled_profiles()["hbfd"])
    d = profile_to_dict(base)
    d["controller"] = {"velocity_filter": {"kind": "lowpass1", "cutoff": 2 * math.pi * 30},
                       "b_range": {"min": 1.0, "max": 1000.0, "points": 12}, "encoder_resolution": 15e-6,
                       "force_noise": 0.2}
    p = profile_from_dict(d)
    assert p.controller.encoder_resolution == 15e-6 and p.controller.force_noise == 0.2
    save_profile(p, tmp_path / "p.json")
    raw = json.loads((tmp_path / "p.json").read_text())["controller"]
    assert raw["encoder_resolution"] == 15e-6 and raw["force_noise"] == 0.2
    assert load_profile(tmp_path / "p.json") == p
    assert noise_options(p) == {"encoder_resolution": 15e-6, "force_noise": 0.2}
    r = study_region(p)
    assert r.b_noise == pytest.approx(noise_limited_damping(VelocityFilter("lowpass1", 2 * math.pi * 30),
                                                            p.device.sample_time, 15e-6, 0.2), rel=1e-15)
    assert np.all(r.k_max[r.b > r.b_noise] == 0)
    plain = ControllerSection()
    assert "encoder_resolution" not in plain.to_dict() and noise_options(base) == {"encoder_resolution": None,
                                                                                   "force_noise": None}


@pytest.mark.parametrize(("section", "path"), [
    ({"encoder_resolution": 0.0}, "$.controller.encoder_resolution"),
    ({"encoder_resolution": "10 um"}, "$.controller.encoder_resolution"),
    ({"encoder_resolution": 1e-5, "force_noise": -0.1}, "$.controller.force_noise"),
    ({"force_noise": 0.1}, "$.controller.force_noise"),
])
def test_bad_noise_keys_name_their_json_path(section, path):
    d = profile_to_dict(load_profile(bundled_profiles()["hbfd"]))
    d["controller"] = section
    with pytest.raises(ProfileError) as exc:
        profile_from_dict(d)
    assert path in str(exc.value)
    with pytest.raises(ValidationError):
        ControllerSection(force_noise=0.1)
