"""Model responses of analysis.identify (continuous and exact ZOH) and the spectral start."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from analysis import ValidationError
from analysis.chain import chain_state_space, discretize_zoh
from analysis.identify import chain_from_spectrum, device_response, spectrum_from_chain

from tests.hbfd_fixtures import make_hbfd

pytestmark = pytest.mark.numerics

T = 1e-3
W = np.geomspace(1.0, 0.95 * np.pi / T, 60)


def _direct(device, w, quantity, boundary):
    """Dense solve of (M s^2 + B s + K) x = e_actuator (an independent reference)."""
    M, B, K = device.matrices()
    lo = 0 if boundary == "free" else 1
    out = []
    for wi in w:
        s = 1j * wi
        D = (M * s * s + B * s + K)[lo:, lo:]
        f = np.zeros(D.shape[0], complex)
        f[-1] = 1.0
        x = np.r_[np.zeros(lo), np.linalg.solve(D, f)]
        k, b = device.stiffnesses[0], device.dampings[0]
        out.append({"actuator": x[-1], "handle": x[0], "gauge": (k + b * s) * (x[0] - x[1])}[quantity])
    return np.array(out)


def _zoh_reference(device, w, quantity):
    """C (zI - Phi)^{-1} Gamma with Phi, Gamma from analysis.chain.discretize_zoh (free handle)."""
    A, B = chain_state_space(device)
    Phi, Gam = discretize_zoh(A[0], -B[0][:, :1], T)  # force *on* the actuator is -F_d (eq. 25)
    n = device.n
    C = np.zeros(2 * n)
    if quantity == "actuator":
        C[n - 1] = 1.0
    elif quantity == "handle":
        C[0] = 1.0
    else:
        C[[0, 1, n, n + 1]] = [device.stiffnesses[0], -device.stiffnesses[0], device.dampings[0], -device.dampings[0]]
    z = np.exp(1j * w * T)
    return np.array([C @ np.linalg.solve(zi * np.eye(2 * n) - Phi, Gam)[:, 0] for zi in z])


@pytest.mark.parametrize("quantity,boundary", [("actuator", "free"), ("handle", "free"), ("gauge", "free"),
                                               ("actuator", "clamped"), ("gauge", "clamped")])
def test_continuous_matches_dense_solve(quantity, boundary):
    d = make_hbfd()
    h = device_response(d, W, quantity, boundary)
    ref = _direct(d, W, quantity, boundary)
    assert np.max(np.abs(h / ref - 1)) < 1e-8


@pytest.mark.parametrize("quantity", ["actuator", "handle", "gauge"])
def test_sampled_is_the_exact_zoh_response(quantity):
    d = make_hbfd()
    h = device_response(d, W, quantity, "free", sample_time=T)
    ref = _zoh_reference(d, W, quantity)
    assert np.max(np.abs(h / ref - 1)) < 1e-8


def test_sampled_tends_to_continuous_with_half_sample_lag_and_delay():
    d = make_hbfd()
    Ts = 1e-6
    w = W[W < 300]
    h = device_response(d, w, sample_time=Ts, delay_samples=3) * np.exp(1j * w * Ts * 3.5)
    assert np.max(np.abs(h / device_response(d, w) - 1)) < 1e-6
    h2 = device_response(d, W, sample_time=T, delay_samples=2) / device_response(d, W, sample_time=T)
    np.testing.assert_allclose(h2, np.exp(-2j * W * T), rtol=1e-12)


def test_dc_values_of_the_gauge_and_the_mass_line():
    d = make_hbfd(b4=0.0)
    w = np.array([1e-3])
    g_free = device_response(d, w, "gauge", "free")[0]
    assert g_free.real == pytest.approx(-0.2 / 5.0, rel=1e-6)  # -m_0 / M
    assert device_response(d, w, "gauge", "clamped")[0].real == pytest.approx(-1.0, rel=1e-6)
    x = device_response(d, w, "actuator", "free")[0]
    assert x.real == pytest.approx(-1.0 / (5.0 * 1e-6), rel=1e-6)  # 1/(M s^2)
    # no damper to ground at all: the sampled model has no defective eigenvalue problem
    xs = device_response(d, np.array([1.0]), sample_time=T)[0]
    assert xs.real == pytest.approx(-0.2, rel=1e-4)


def test_clamped_handle_quantity_is_refused():
    with pytest.raises(ValidationError):
        device_response(make_hbfd(), W, "handle", "clamped")


def test_hbfd_spectrum_and_its_inverse():
    m, k = [0.2, 2.3, 2.0, 0.5], [130e3, 84e3, 874e3]
    p, z = spectrum_from_chain(m, k)
    # the handle mode's pole and zero nearly cancel at the actuator (842.45 vs 842.72 rad/s)
    np.testing.assert_allclose(p, [258.1309, 842.4541, 1481.1087], rtol=1e-6)
    np.testing.assert_allclose(z, [174.1719, 693.9228, 842.7210], rtol=1e-6)
    mm, kk = chain_from_spectrum(p, z, 5.0)
    np.testing.assert_allclose(mm, m, rtol=1e-12)
    np.testing.assert_allclose(kk, k, rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0.05, 5.0), min_size=1, max_size=7), st.data())
def test_continued_fraction_start_recovers_random_undamped_chains(masses, data):
    n = len(masses)
    k = data.draw(st.lists(st.floats(1e3, 1e6), min_size=n - 1, max_size=n - 1))
    p, z = spectrum_from_chain(masses, k)
    # the inverse problem is as well conditioned as the poles and zeros are separated: a nearly
    # cancelled pair (relative gap g) loses digits ~ 1e-16 / g.  Exact up to that.
    both = np.sort(np.r_[p, z])
    gap = float(np.min(np.diff(both) / both[1:])) if both.size > 1 else 1.0
    assume(gap > 1e-8)
    mm, kk = chain_from_spectrum(p, z, float(np.sum(masses)))
    tol = max(1e-10, 1e-13 / gap)
    np.testing.assert_allclose(mm, masses, rtol=tol)
    np.testing.assert_allclose(kk, k, rtol=tol)
