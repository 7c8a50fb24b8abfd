"""The rigid single-mass device: closed forms for the bound, Z_max and the design.

The design notes say that with this discretization a rigid device is "passive for any
coupling stiffness (Re Z = b + B(1 + cos wT)/2)".  That is a statement about the one-port
Z_max (device + coupling, environment port open): its real part is exactly
``b + b_c (1 + cos wT)/2 >= 0`` whatever k_c.  Unconditional stability of the two-port
(eq. 9) asks more: it must hold for every passive environment, and for a rigid mass the
bound is ``cos(theta) sin^2(theta/2) / b > 0`` (theta = wT/2), so k_c *is* limited.  Both
facts are checked here against closed forms; the largest k_c is checked against the
per-frequency closed form minimized by brute force.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from analysis import Device, ImpedanceDisplay


@pytest.mark.parametrize("m,b,T", [(0.5, 2.0, 1e-3), (0.05, 0.1, 1e-4), (3.0, 20.0, 5e-3)])
def test_rigid_bound_closed_form(m, b, T):
    dev = Device(masses=[m], ground_dampings=[b], sample_time=T)
    w = np.geomspace(1e-3, dev.nyquist * 0.999, 500)
    th = 0.5 * w * T
    expected = np.cos(th) * np.sin(0.5 * th) ** 2 / b
    np.testing.assert_allclose(ImpedanceDisplay(dev).bound(w), expected, rtol=1e-13)


@pytest.mark.parametrize("kc,bc", [(1e3, 0.0), (1e6, 5.0), (1e9, 50.0)])
def test_rigid_zmax_is_passive_for_any_stiffness(kc, bc):
    m, b, T = 0.5, 2.0, 1e-3
    dev = Device(masses=[m], ground_dampings=[b], sample_time=T)
    w = np.geomspace(1e-2, dev.nyquist * 0.999, 400)
    _, zmax = ImpedanceDisplay(dev).impedance_range(w, kc, bc)
    np.testing.assert_allclose(zmax.real, b + bc * (1 + np.cos(w * T)) / 2, rtol=1e-12)
    assert np.all(zmax.real > 0)


def test_rigid_largest_stiffness_is_finite_and_matches_brute_force():
    m, b, T, bc = 0.5, 2.0, 1e-3, 5.0
    dev = Device(masses=[m], ground_dampings=[b], sample_time=T)
    imp = ImpedanceDisplay(dev)
    d = imp.max_stiffness(bc)
    assert d.kc is not None and math.isfinite(d.kc)
    # brute force: bisection on k at each of 2e5 frequencies of Re(1/Z_c) >= cos sin^2 / b
    w = np.geomspace(dev.band_min, dev.nyquist * (1 - 1e-9), 200_000)
    th = 0.5 * w * T
    B = np.cos(th) * np.sin(0.5 * th) ** 2 / b
    lo, hi = np.zeros_like(w), np.full_like(w, 1e9)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        ok = (bc + 0.5 * mid * T) >= B * ((bc + 0.5 * mid * T) ** 2 + (0.5 * mid * T / np.tan(th)) ** 2)
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
    ref = float(lo.min())
    assert d.kc <= ref * (1 + 1e-9)
    assert d.kc >= ref * (1 - 1e-6)
