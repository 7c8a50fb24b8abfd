"""Robust designs of analysis.identify: the admittance display's b_c interval (eq. 21), the exact
sampled-data critical k_c, and a fit's intervals feeding the robust k_c (eq. 9)."""

from __future__ import annotations

import numpy as np
import pytest

from analysis import AdmittanceDisplay, ImpedanceDisplay
from analysis.identify import (
    device_response,
    device_with,
    fit_chain,
    make_measurement,
    robust_critical_stiffness,
    robust_feasible_damping,
    robust_max_stiffness,
)
from analysis.sampled import critical_stiffness

from tests.hbfd_fixtures import make_hbfd

pytestmark = pytest.mark.numerics


def _sample(box_intervals, count, seed):
    keys = list(box_intervals)
    lo = np.array([box_intervals[k][0] for k in keys])
    hi = np.array([box_intervals[k][1] for k in keys])
    u = np.random.default_rng(seed).random((count, len(keys)))
    return [dict(zip(keys, row)) for row in lo + u * (hi - lo)]


def test_robust_feasible_damping_holds_for_sampled_devices():
    d = make_hbfd()
    iv = {"ground_dampings[3]": (1.2, 5.0), "masses[0]": (0.15, 0.25), "stiffnesses[0]": (1e5, 1.6e5)}
    r = robust_feasible_damping(d, 31.0, 50e3, 100.0, iv)
    nominal = AdmittanceDisplay(d, 50e3, 100.0).feasible_damping(31.0)
    assert r.feasible and nominal.low <= r.low < r.high <= nominal.high
    assert r.nominal == (nominal.low, nominal.high)
    for dev in (r.low_device, r.high_device):
        edge = AdmittanceDisplay(dev, 50e3, 100.0).feasible_damping(31.0)
        assert r.low >= edge.low and r.high <= edge.high
    for values in _sample(iv, 300, seed=11):
        disp = AdmittanceDisplay(device_with(d, values), 50e3, 100.0)
        w = disp.frequencies()
        B = disp.bound(w)
        for bc in (r.low, r.high):
            assert float(np.min(disp.coupling_term(w, 31.0, bc) - B)) >= 0.0


def test_robust_exact_sampled_critical_stiffness():
    d = make_hbfd()
    r = robust_critical_stiffness(d, 100.0, {"ground_dampings[3]": (1.2, 5.0)}, random=4)
    assert r.binding == {"ground_dampings[3]": 1.2}
    assert r.kc == critical_stiffness(r.device, 100.0)
    assert r.kc < r.nominal_kc == critical_stiffness(d, 100.0)
    for b4 in (2.0, 3.3):
        assert critical_stiffness(d.replace(ground_dampings=[0, 0, 0, b4]), 100.0) >= r.kc


def test_fit_intervals_feed_the_robust_design():
    """1 % noise, actuator + gauge FRFs -> 95 % box -> robust k_c below the true device's limit."""
    d = make_hbfd()
    T = 1e-3
    w = np.geomspace(1.0, 0.95 * np.pi / T, 400)
    rng = np.random.default_rng(5)
    ms = []
    for q in ("actuator", "gauge"):
        noise = 0.01 * (rng.normal(size=w.size) + 1j * rng.normal(size=w.size)) / np.sqrt(2)
        ms.append(make_measurement(w, device_response(d, w, q, sample_time=T) * (1 + noise), q, sample_time=T))
    fit = fit_chain(ms, 4, ground_dampings=(3,))
    r = robust_max_stiffness(fit.device, 100.0, fit.intervals)
    kc_true = ImpedanceDisplay(d).max_stiffness(100.0).kc
    assert len(r.keys) == 11 and r.kc <= r.nominal_kc
    assert 0.98 * kc_true < r.kc <= kc_true
