"""Hypothesis properties of the two-port machinery on random passive chains."""

from __future__ import annotations

import math

import dense
import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from strategies import random_device

from analysis import AdmittanceDisplay, ImpedanceDisplay, twoport
from analysis.chain.response import chain_response
from analysis.chain.discretize import tustin_image
from analysis.twoport.impedance import kc_upper

FAST = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
SLOW = settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow])

unit = st.floats(0.0, 1.0)


def band_points(dev, fracs):
    """Frequencies at log-fractions of [1e-4 Nyquist, 0.999 Nyquist]."""
    lo, hi = math.log(1e-4 * dev.nyquist), math.log(0.999 * dev.nyquist)
    return np.exp(lo + (hi - lo) * np.asarray(fracs))


# --- passivity: Re y11 as dissipated power --------------------------------------------------

@FAST
@given(random_device(), st.lists(unit, min_size=1, max_size=8))
def test_re_y11_is_dissipation(dev, fracs):
    w = band_points(dev, fracs)
    r = chain_response(dev, tustin_image(w, dev.sample_time))
    for direct, diss in ((r.y11, r.re_y11), (r.y22, r.re_y22)):
        assert np.all(diss >= 0)
        assert np.all(direct.real >= -1e-13 * np.abs(direct))
        ok = direct.real > 1e-3 * np.abs(direct)  # no cancellation in the direct real part
        assert np.all(np.abs(diss[ok] - direct.real[ok]) <= 1e-10 * direct.real[ok])
    assert np.all(ImpedanceDisplay(dev).two_port(w).p11.real >= -1e-13 * np.abs(r.y11))


# --- eta invariance (Rollett) ---------------------------------------------------------------

cplx = st.builds(complex, st.floats(-10, 10), st.floats(-10, 10))


def eta_scale(p):
    a, b, c, d = (np.asarray(x, complex) for x in p)
    q = b * c
    return (2 * np.abs(a.real * d.real) + np.abs(q)) / np.abs(q)


@settings(max_examples=300, deadline=None)
@given(cplx, cplx, cplx, cplx)
def test_eta_invariant_random_arrays(a, b, c, d):
    p = tuple(np.array([x]) for x in (a, b, c, d))
    assume(abs(a * d - b * c) > 0.1 and abs(a) > 0.1 and abs(d) > 0.1 and abs(b * c) > 0.1)
    e0 = twoport.eta(p)
    tol = 1e-9 * eta_scale(p)[0]  # the original's eta scale and verdict, computed once per example
    verdict = twoport.llewellyn(p)[0]
    for src in twoport.FORMS:
        q = twoport.convert(p, "z", src)
        back = twoport.convert(q, src, "z")
        for x, y in zip(back, p):
            assert abs(x[0] - y[0]) <= 1e-9 * max(abs(y[0]), 1.0)
        for dst in twoport.FORMS:
            r = twoport.convert(q, src, dst)
            assert abs(twoport.eta(r)[0] - e0[0]) <= tol
            assert twoport.llewellyn(r)[0] == verdict or abs(e0[0] - 1) < tol


def _coupled_imp(dev, w, kc, bc):
    tp = ImpedanceDisplay(dev).two_port(w)
    zc = dense_zc(w, dev.sample_time, kc, bc)
    return (tp.p11, tp.p12, tp.p21, tp.p22 + 1.0 / zc)


def dense_zc(w, T, kc, bc):
    return (bc + 0.5 * kc * T) - 0.5j * kc * T / np.tan(0.5 * w * T)


@FAST
@given(random_device(), st.lists(unit, min_size=1, max_size=6), unit, unit)
def test_eta_of_coupled_impedance_interface(dev, fracs, fk, fb):
    w = np.unique(band_points(dev, fracs))
    imp = ImpedanceDisplay(dev)
    br = imp.bound_result(w)
    Bmax = max(float(np.max(np.abs(br.bound))), 1e-300)
    bc = 10 ** (4 * fb - 2) / Bmax * 0.1
    kc = 10 ** (6 * fk - 3) * bc / dev.sample_time
    p = _coupled_imp(dev, w, kc, bc)
    e_direct = twoport.eta(p)
    margin = imp.margin(w, kc, bc)
    e_margin = imp.eta_from_margin(br.re_p11, margin, br.abs_p, br.re_p)
    scale = eta_scale(p)
    ok = scale < 1e5  # the direct eta is a difference of nearly equal numbers beyond this
    assert np.all(np.abs(e_direct[ok] - e_margin[ok]) <= 1e-8 * scale[ok])
    # invariance across the four forms of the coupled array
    for f in ("z", "h", "g"):
        q = twoport.convert(p, "y", f)
        assert np.all(np.abs(twoport.eta(q)[ok] - e_direct[ok]) <= 1e-7 * scale[ok])
    # Llewellyn's test agrees with the sign of the margin (where the margin is not at rounding level)
    cterm = imp.coupling_term(w, kc, bc)
    clear = np.abs(margin) > 1e-9 * np.maximum(np.abs(cterm), np.abs(br.bound))
    assert np.array_equal(twoport.llewellyn(p)[clear], (margin >= 0)[clear])


@FAST
@given(random_device(), st.lists(unit, min_size=1, max_size=6), unit, unit)
def test_eta_of_coupled_admittance_interface(dev, fracs, fm, fb):
    w = np.unique(band_points(dev, fracs))
    kp = 0.3 * float(min(dev.stiffnesses)) if dev.n > 1 else 1e3
    kd = 0.6 * math.sqrt(kp * dev.masses[-1])
    adm = AdmittanceDisplay(dev, kp, kd)
    mc = dev.total_mass * 10 ** (3 * fm - 1)
    bc = 10 ** (4 * fb - 1) * max(kd, 1.0)
    tp = adm.two_port(w)
    p = (tp.p11, tp.p12, tp.p21, tp.p22 + adm.coupling(w, mc, bc))
    br = adm.bound_result(w)
    margin = adm.margin(w, mc, bc)
    e_margin = adm.eta_from_margin(br.re_p11, margin, br.abs_p, br.re_p)
    e_direct = twoport.eta(p)
    scale = eta_scale(p)
    ok = scale < 1e5
    assert np.all(np.abs(e_direct[ok] - e_margin[ok]) <= 1e-8 * scale[ok])
    cterm = adm.coupling_term(w, mc, bc)
    clear = np.abs(margin) > 1e-9 * np.maximum(np.abs(cterm), np.abs(br.bound))
    assert np.array_equal(twoport.llewellyn(p)[clear], (margin >= 0)[clear])


# --- designs are conservative and tight -----------------------------------------------------

def _dense_set(disp, points=20_000):
    return np.unique(np.concatenate([dense.band(disp.device, points), disp.frequencies()]))


@SLOW
@given(random_device(n_max=8), unit)
def test_max_stiffness_conservative_and_tight(dev, fb):
    imp = ImpedanceDisplay(dev)
    w = _dense_set(imp)
    B = imp.bound_parts(w).bound
    bc = 10 ** (-2 * fb) * 0.5 / float(np.max(B))
    d = imp.max_stiffness(bc)
    T = dev.sample_time

    def f(x):
        return kc_upper(imp.bound_parts(x).bound, x, T, bc)

    ref_kc, _ = dense.refined_min(f, w, f(w), candidates=6)
    if ref_kc == math.inf:
        assert d.kc == math.inf
        return
    assert d.kc is not None and math.isfinite(d.kc)
    assert d.kc <= ref_kc
    assert (ref_kc - d.kc) <= 1e-6 * ref_kc
    m = dense.re_inv_zc(w, T, d.kc, bc) - B
    assert np.min(m) >= -1e-12 * float(np.max(np.abs(B)))


@SLOW
@given(random_device(n_max=8), unit)
def test_feasible_damping_conservative_and_tight(dev, fm):
    kp = 0.3 * float(min(dev.stiffnesses)) if dev.n > 1 else 1e3
    kd = 0.6 * math.sqrt(kp * dev.masses[-1])
    adm = AdmittanceDisplay(dev, kp, kd)
    T = dev.sample_time
    w = _dense_set(adm)
    B = adm.bound_parts(w).bound
    mc = dense.dense_min_mass(adm, w, B, rtol=1e-6) * (1.5 + 20 * fm)
    d = adm.feasible_damping(mc)

    def upper(x):
        return dense.u_limits(adm.bound_parts(x).bound, x, T, mc)[1]

    def neg_lower(x):
        return -dense.u_limits(adm.bound_parts(x).bound, x, T, mc)[0]

    L, U = dense.u_limits(B, w, T, mc)
    u_hi, _ = dense.refined_min(upper, w, U)
    u_lo, _ = dense.refined_min(neg_lower, w, -L)
    u_lo = max(-u_lo, 0.0)
    assert u_hi > u_lo * (1 + 1e-3)  # feasible with some room (mc well above the minimum)
    assert d.feasible
    ref_low = 1.0 / u_hi
    ref_high = math.inf if u_lo == 0 else 1.0 / u_lo
    assert d.low >= ref_low and d.low <= ref_low * (1 + 1e-6)
    if math.isinf(ref_high):
        assert math.isinf(d.high)
    else:
        assert d.high <= ref_high and d.high >= ref_high * (1 - 1e-6)
    for bc in (d.low, d.high) if math.isfinite(d.high) else (d.low,):
        m = dense.re_zca(w, T, mc, bc) - B
        assert np.min(m) >= -1e-12 * float(np.max(np.abs(B)))


# --- closed form of the per-frequency stiffness limit ---------------------------------------

@settings(max_examples=200, deadline=None)
@given(st.floats(-8, 2), st.floats(0.001, 0.999), st.floats(-4, -2), st.floats(-2, 4))
def test_kc_upper_matches_bisection(logB, frac, logT, logbc):
    T = 10.0 ** logT
    w = frac * math.pi / T
    bc = 10.0 ** logbc
    B = 10.0 ** logB
    k = float(kc_upper(np.array([B]), np.array([w]), T, bc)[0])

    def ok(kc):
        return dense.re_inv_zc(w, T, kc, bc) >= B

    if B * bc > 1:
        assert k == -math.inf
        return
    assert math.isfinite(k) and k >= 0
    lo, hi = 0.0, 1.0
    while ok(hi):
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if ok(mid):
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-13 * hi:
            break
    assert abs(k - lo) <= 1e-9 * lo + 1e-12 * bc / T  # absolute floor for k = 0 (B b_c = 1)
    # and the closed form sits on the boundary: Re(1/Z_c) = B there
    assert abs(dense.re_inv_zc(w, T, k, bc) - B) <= 1e-9 * B
