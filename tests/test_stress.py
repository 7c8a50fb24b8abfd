"""Stress test of numerical stability over extreme but valid devices (issue: run time
against error and stress test).

Ranges: n 1..50, masses 1e-4..1e3 kg, stiffnesses 1..1e9 N/m, damping ratios 1e-5..10,
T 1e-5..0.1 s, frequencies from 1e-5 rad/s to just below Nyquist.  Every call runs under
``np.errstate(over="raise", invalid="raise", divide="raise")`` so that any overflow, invalid operation or division by zero
that the code does not handle deliberately fails the test.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from analysis import AdmittanceDisplay, Device, ImpedanceDisplay, ValidationError
from analysis.twoport.impedance import re_inv_coupling
from analysis.twoport.llewellyn import convert, eta
from tests import reference as ref

STRESS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _logu(lo, hi):
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


@st.composite
def extreme_device(draw, n_max: int = 50):
    n = draw(st.integers(1, n_max))
    m = np.array([draw(_logu(1e-4, 1e3)) for _ in range(n)])
    k = np.array([draw(_logu(1.0, 1e9)) for _ in range(n - 1)])
    z = np.array([draw(_logu(1e-5, 10.0)) for _ in range(n - 1)])
    T = draw(_logu(1e-5, 0.1))
    g = np.zeros(n)
    g[draw(st.integers(0, n - 1))] = draw(_logu(1e-3, 1e3))
    mu = m[:-1] * m[1:] / (m[:-1] + m[1:])
    b = 2.0 * z * np.sqrt(k * mu)
    return Device(masses=m, stiffnesses=k, dampings=b, ground_dampings=g, sample_time=T,
                  band_min=min(1.0, 0.1 * math.pi / T))


def _freqs(dev: Device, points: int = 60) -> np.ndarray:
    return np.geomspace(1e-5, dev.nyquist * (1 - 1e-7), points)


@STRESS
@given(extreme_device())
def test_no_nan_no_overflow_no_warning_impedance(dev):
    w = _freqs(dev)
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        imp = ImpedanceDisplay(dev)
        br = imp.bound_result(w)
        res = imp.evaluate(1e3, 10.0, w)
        y = imp.two_port(w)
    assert not np.any(np.isnan(br.bound))
    assert np.all(np.isfinite(br.bound) | br.singular)
    assert np.all(br.re_p11 >= 0.0)  # Re Y11 >= 0 for a passive chain (dissipated power)
    assert np.all(np.isfinite(y.p11))
    for arr in (res.margin, res.coupling_term, res.eta):
        assert not np.any(np.isnan(arr))
    assert np.all(np.isfinite(res.zmin)) and np.all(np.isfinite(res.zmax))


@STRESS
@given(extreme_device())
def test_no_nan_no_overflow_no_warning_admittance(dev):
    w = _freqs(dev)
    kp = 0.3 * float(dev.stiffnesses.min()) if dev.n > 1 else 1e3
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        adm = AdmittanceDisplay(dev, kp, 0.1 * math.sqrt(kp * dev.masses[-1]))
        br = adm.bound_result(w)
        res = adm.evaluate(1.0, 100.0, w)
    assert not np.any(np.isnan(br.bound))
    assert np.all(br.re_p11 >= 0.0)
    assert not np.any(np.isnan(res.margin))


def _reactance_ratio(p: tuple) -> np.ndarray:
    """``|p_ii| / |Re p_ii|``, the larger of the two ports: how much of a diagonal entry's real
    part (which eta needs) is lost to the round-off of the complex entry."""
    with np.errstate(divide="ignore"):
        return np.maximum(np.abs(p[0]) / np.abs(p[0].real), np.abs(p[3]) / np.abs(p[3].real))


# CI, 2026-12-02: a nearly lossless port (Re p_ii = 1e-10 |p_ii|) converted to Z and back moved
# eta = 6535 by 1.19e-6 relative -- round-off of the real parts, not an error of eta.
_LOSSLESS = Device(masses=[4.03428793e+02, 6.73794700e-03, 1.0, 1.0], stiffnesses=[1.20260428e+06, 1.0, 1.0],
                   dampings=[4.89379778e+02, 2.73272714e-06, 1.41421356e+00], ground_dampings=[0.0, 0.0, 1.0, 0.0],
                   sensor_element=0, sample_time=math.exp(-4.0), band_min=1.0)


@STRESS
@given(extreme_device(n_max=12), st.sampled_from(["y", "h", "g"]))
@example(_LOSSLESS, "y")
def test_eta_invariant_across_forms(dev, form):
    """eta of the coupled interface (eq. 7) is the same in Z, Y, H and G form, to 1e-6 relative
    plus the round-off a conversion cannot avoid: each converted entry is exact to a few ulps of
    its modulus and of the 2x2 matrix's condition number, so its real part is exact only to
    ``eps * cond * |p_ii| / |Re p_ii|`` relative, and eta (``2 Re p11 Re p22 - Re p12 p21``)
    inherits the sum over both ports.  For ordinary ports this term is far below 1e-6."""
    w = np.geomspace(dev.band_min, dev.nyquist * 0.99, 25)
    imp = ImpedanceDisplay(dev)
    y = imp.two_port(w)
    T = dev.sample_time
    zc = (1e3 * 0.5 * T + 10.0) - 0.5j * 1e3 * T / np.tan(0.5 * w * T)
    arr = (y.p11, y.p12, y.p21, y.p22 + 1.0 / zc)
    e_y = eta(arr)
    z = convert(arr, "y", "z")
    other = convert(z, "z", form)
    e_other = eta(other)
    ok = np.isfinite(e_y) & (np.abs(arr[1] * arr[2]) > 1e-200) & (np.abs(e_y) < 1e12)
    cond = np.linalg.cond(np.stack(arr, axis=-1).reshape(-1, 2, 2))
    ratio = np.maximum(_reactance_ratio(arr), _reactance_ratio(other))
    rtol = 1e-6 + 16 * np.finfo(float).eps * cond * 2 * ratio
    err = np.abs(e_other - e_y)
    assert np.all(err[ok] <= rtol[ok] * np.abs(e_y[ok]) + 1e-9), (err / np.abs(e_y))[ok]


def _seeded_extreme(rng: np.random.Generator, n_lo: int, n_hi: int, ground_at_actuator: bool) -> Device:
    """A random device over the stress ranges, from a seeded generator (fixed samples)."""
    n = int(rng.integers(n_lo, n_hi))
    m = 10 ** rng.uniform(-4, 3, n)
    k = 10 ** rng.uniform(0, 9, n - 1)
    z = 10 ** rng.uniform(-5, 1, n - 1)
    T = 10 ** rng.uniform(-5, -1)
    g = np.zeros(n)
    if ground_at_actuator:
        g[-1] = 10 ** rng.uniform(-1, 2)
    else:
        g[int(rng.integers(0, n))] = 10 ** rng.uniform(-3, 3)
    return Device.from_damping_ratios(m, k, z, ground_dampings=g, sample_time=T,
                                      band_min=min(1.0, 0.1 * np.pi / T))


def test_design_conservative_on_extreme_devices():
    """Largest k_c stays conservative against a dense check for extreme random devices."""
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(25):
        dev = _seeded_extreme(rng, 2, 20, ground_at_actuator=True)
        n, T = dev.n, dev.sample_time
        imp = ImpedanceDisplay(dev)
        B = imp.bound(imp.frequencies())
        bc = 0.2 / float(B.max())
        d = imp.max_stiffness(bc)
        if d.kc is None or not math.isfinite(d.kc):
            continue
        wd = np.unique(np.concatenate([np.geomspace(dev.band_min, dev.nyquist * (1 - 1e-9), 100_000),
                                       imp.frequencies()]))
        dense = imp.bound_parts(wd).bound  # the dense check's bound, computed once for both uses
        margin = re_inv_coupling(wd, T, d.kc, bc) - dense
        assert margin.min() >= -1e-12 * float(np.abs(dense).max()), (n, T)
        checked += 1
    assert checked >= 15


def test_mpmath_agreement_on_200_fixed_cases():
    """200 (device, frequency) cases: both bounds agree with the 50-digit literal formulas to
    1e-9 relative from 1 rad/s to 0.999 Nyquist and to 1e-6 from 1e-4 rad/s up.
    (Measured when written: impedance 4.1e-13 / 7.2e-13, admittance 1.4e-11 / 2.3e-11.)"""
    rng = np.random.default_rng(2026)
    worst_hi = worst_lo = 0.0
    for case in range(200):
        dev = _seeded_extreme(rng, 1, 7, ground_at_actuator=False)
        n, m, k = dev.n, dev.masses, dev.stiffnesses
        low = case % 2 == 1 or dev.nyquist * 0.999 <= 1.0
        lo = 1e-4 if low else 1.0
        x = float(np.exp(rng.uniform(np.log(lo), np.log(dev.nyquist * 0.999))))
        ours = float(ImpedanceDisplay(dev).bound(np.array([x]))[0])
        exact = ref.impedance_bound(dev, x)
        err = float(abs(mp.mpf(ours) - exact) / abs(exact))
        kp = 0.3 * float(k.min()) if n > 1 else 1e3
        kd = 0.1 * math.sqrt(kp * m[-1])
        ours_a = float(AdmittanceDisplay(dev, kp, kd).bound(np.array([x]))[0])
        exact_a = ref.admittance_bound(dev, x, kp, kd)
        err = max(err, float(abs(mp.mpf(ours_a) - exact_a) / abs(exact_a)))
        if low:
            worst_lo = max(worst_lo, err)
        else:
            worst_hi = max(worst_hi, err)
    assert worst_hi <= 1e-9, worst_hi
    assert worst_lo <= 1e-6, worst_lo


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(masses=[1e-6, 1.0], stiffnesses=[1e9], dampings=[1.0], ground_dampings=[0.0, 1.0]),
        dict(masses=[0.2, 2.3, 2.0, 0.5], stiffnesses=[130e3, 84e3, 874e3], dampings=[30.9, 60.0, 118.3],
             ground_dampings=[0, 0, 0, 5.0], sample_time=1e-5),
        dict(masses=[0.2, 2.3, 2.0, 0.5], stiffnesses=[130e3, 84e3, 874e3], dampings=[0.0, 60.0, 118.3],
             ground_dampings=[0, 0, 0, 5.0]),
        dict(masses=np.full(500, 0.01), stiffnesses=np.full(499, 1e7), dampings=np.full(499, 10.0),
             ground_dampings=np.r_[np.zeros(499), 5.0]),
    ],
    ids=["1e-6kg-handle-on-1e9", "T=1e-5", "lossless-element", "500-masses"],
)
def test_extreme_valid_inputs_give_finite_correct_answers(kwargs):
    dev = Device(**kwargs)
    w = np.geomspace(dev.band_min, dev.nyquist * 0.999, 40)
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        imp = ImpedanceDisplay(dev)
        b = imp.bound(w)
        d = imp.max_stiffness(10.0)
    assert np.all(np.isfinite(b))
    assert d.kc is None or d.kc > 0
    # and the values are right: compare a few frequencies with the 50-digit literal formula
    if dev.n <= 10:
        for x in w[::8]:
            exact = ref.impedance_bound(dev, float(x))
            assert abs(mp.mpf(float(imp.bound(np.array([x]))[0])) - exact) <= 1e-9 * abs(exact)


@pytest.mark.parametrize(
    "field,kwargs",
    [
        ("masses", dict(masses=[1.0, 0.0], stiffnesses=[1.0], dampings=[0.0])),
        ("masses", dict(masses=[1.0, -1.0], stiffnesses=[1.0], dampings=[0.0])),
        ("masses", dict(masses=[1.0, float("nan")], stiffnesses=[1.0], dampings=[0.0])),
        ("stiffnesses", dict(masses=[1.0, 1.0], stiffnesses=[float("inf")], dampings=[0.0])),
        ("dampings", dict(masses=[1.0, 1.0], stiffnesses=[1.0], dampings=[-1.0])),
        ("sample_time", dict(masses=[1.0], sample_time=float("inf"))),
        ("ground_dampings", dict(masses=[1.0], ground_dampings=[float("nan")])),
    ],
)
def test_invalid_inputs_give_the_validation_error(field, kwargs):
    with pytest.raises(ValidationError) as info:
        Device(**kwargs)
    assert info.value.field == field
    assert field in str(info.value)
