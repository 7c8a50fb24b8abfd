"""Disturbance observer (Eom, Suh & Yi, section 2) and the five-bar Cartesian inertia preset."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal

from analysis import Device, ValidationError
from analysis.transparency.five_bar import FiveBar, five_bar_preset
from analysis.transparency.observer import DisturbanceObserver, ObserverSettings, TwoAxisObserver


# -- five-bar -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["five_bar_centre", "five_bar_offset"])
def test_cartesian_inertia_from_link_kinetic_energy(name):
    M, B, fb, p = five_bar_preset(name)
    rng = np.random.default_rng(1)
    for _ in range(5):
        v = rng.normal(size=2)
        assert 0.5 * v @ M @ v == pytest.approx(fb.kinetic_energy(p, v), rel=1e-5)
    assert np.all(np.linalg.eigvalsh(M) > 0) and np.all(np.linalg.eigvalsh(B) > 0)


def test_jacobian_against_finite_differences():
    fb = FiveBar()
    p = fb.centre() + np.array([0.03, -0.02])
    Jinv = np.linalg.inv(fb.jacobian(p))
    h = 1e-7
    num = np.stack([(fb.inverse_kinematics(p + h * e) - fb.inverse_kinematics(p - h * e)) / (2 * h)
                    for e in np.eye(2)], axis=1)
    np.testing.assert_allclose(Jinv, num, rtol=1e-6)


def test_symmetric_linkage_is_decoupled_at_its_centre():
    M, B = FiveBar(distal_masses=(0.015, 0.015)).cartesian_matrices()
    assert abs(M[0, 1]) < 1e-14 * M[0, 0] and abs(B[0, 1]) < 1e-14 * B[0, 0]
    M, _, _, _ = five_bar_preset("five_bar_centre")  # unequal distal masses: coupled
    assert abs(M[0, 1]) > 0.05 * np.sqrt(M[0, 0] * M[1, 1])


# -- single axis ----------------------------------------------------------------------------------------
def test_single_axis_effective_plant_and_disturbance():
    obs = DisturbanceObserver(0.01, 0.022, order=2, cutoff=200.0)
    w = np.geomspace(0.1, 1e5, 300)
    r = obs.response(w, alpha=0.5, beta=0.5, delta=1.0)  # real plant 1.5x heavier and more damped
    lo, hi = w < 2.0, w > 2e4
    np.testing.assert_allclose(r.effective[lo], r.nominal[lo], rtol=0.02)
    np.testing.assert_allclose(r.effective[hi], r.plant[hi], rtol=0.02)
    # closed form of the Fig. 1 loop
    s = 1j * w
    Q = (200 / (s + 200)) ** 2
    P = 1 / (0.015 * s + 0.033)
    Pn = 1 / (0.01 * s + 0.022)
    np.testing.assert_allclose(r.effective, P * Pn / (Pn * (1 - Q) + P * Q), rtol=1e-12)
    assert np.all(np.abs(r.disturbance_with[w < 5]) < 0.25 * np.abs(r.disturbance_without[w < 5]))


def test_single_axis_chain_plant():
    dev = Device.from_damping_ratios([0.004, 0.006], [2e4], 0.05, ground_dampings=[0, 0.022])
    obs = DisturbanceObserver(0.01, 0.022, order=3, cutoff=100.0)
    w = np.geomspace(0.1, 10, 20)
    r = obs.response(w, plant=dev)
    np.testing.assert_allclose(r.effective, r.nominal, rtol=0.05)


# -- two axes -------------------------------------------------------------------------------------------
@pytest.mark.parametrize("order,cutoff", [(1, 100.0), (2, 200.0), (3, 500.0)])
def test_coupling_reduction_matches_closed_form(order, cutoff):
    o = TwoAxisObserver.from_settings(ObserverSettings(order=order, cutoff=cutoff))
    w = np.geomspace(0.01 * cutoff, 100 * cutoff, 200)
    c = o.coupling(w)
    np.testing.assert_allclose(c.ratio, c.ratio_closed_form, rtol=1e-9)
    # below w_Q the coupling is divided by ~ r w / w_Q: at w_Q/10 at least 10/r times (order 1: 20 dB)
    i = np.searchsorted(w, 0.1 * cutoff)
    assert abs(c.ratio[i]) < 1.05 * order * w[i] / cutoff
    assert abs(c.ratio[i]) == pytest.approx(abs(c.ratio_closed_form[i]), rel=1e-9)
    # above w_Q the observer does nothing
    assert abs(c.ratio[-1]) == pytest.approx(1.0, abs=0.02 * order)
    # the direct axis becomes the nominal one below w_Q
    Mn, Bn = o.Mn[0], o.Bn[0]
    s = 1j * w[0]
    assert c.direct_with[0] == pytest.approx(1 / (Mn * s + Bn), rel=0.05)


def test_step_on_x_disturbs_y_less_with_observer():
    o = TwoAxisObserver.from_settings(ObserverSettings())
    r = o.step_response(force=1.0, duration=0.2, points=401)
    assert abs(r.y_with[-1]) < 0.2 * abs(r.y_without[-1])
    assert abs(r.vy_with).max() < 0.5 * abs(r.vy_without).max()
    # exact discretization against scipy (ZOH of a step is exact)
    for obs, y in ((False, r.y_without), (True, r.y_with)):
        A, Bu, C = o.state_space(obs)
        sysd = signal.cont2discrete((A, Bu[:, :1], C, np.zeros((4, 1))), r.t[1] - r.t[0], method="zoh")
        _, yd, _ = signal.dlsim(sysd, np.ones((r.t.size, 1)), t=r.t)
        np.testing.assert_allclose(y, yd[:, 1], rtol=1e-8, atol=1e-14)


def test_observer_settings_roundtrip_and_validation():
    st = ObserverSettings(order=3, cutoff=150.0, preset="five_bar_offset")
    assert ObserverSettings.from_dict(st.to_dict()) == st
    for bad, field in [({"order": 0}, "order"), ({"cutoff": -1.0}, "cutoff"), ({"preset": "delta"}, "preset"),
                       ({"delta": 2.0}, "delta"), ({"nominal_mass": 0.0}, "nominal_mass"), ({"x": 1}, "x")]:
        with pytest.raises(ValidationError) as e:
            ObserverSettings.from_dict(bad)
        assert e.value.field == field
    with pytest.raises(ValidationError):
        TwoAxisObserver(np.eye(2), [[1.0, 2.0], [0.0, 1.0]])
