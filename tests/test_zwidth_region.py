"""The classic Z-width region, its area, the optimum velocity filter and measured trials (issue 15)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from analysis import Device, ImpedanceDisplay, load_profile
from analysis.errors import ValidationError
from analysis.resources import resource_path
from analysis.sampled import (
    OPTIMIZER_AREA,
    VelocityFilter,
    ZWidthRegion,
    critical_stiffness,
    load_trials,
    optimal_filter,
    passivity_limit,
    score_trials,
    zwidth_region,
)

T = 1e-3


@pytest.fixture(scope="module")
def hbfd() -> Device:
    return load_profile(resource_path("profiles", "hbfd.json")).device


@pytest.fixture(scope="module")
def rigid() -> Device:
    return Device(masses=[0.5], stiffnesses=[], dampings=[], ground_dampings=[2.0], sample_time=T)


def test_region_is_the_exact_first_crossing(hbfd):
    f = VelocityFilter("lowpass1", cutoff=2 * math.pi * 30)
    b = np.geomspace(0.1, 100, 12)
    r = zwidth_region(hbfd, b=b, delay_samples=1, velocity_filter=f)
    assert isinstance(r, ZWidthRegion) and r.velocity_filter == f and r.delay_samples == 1
    for i in (0, 6, 11):
        assert r.k_max[i] == pytest.approx(critical_stiffness(hbfd, b[i], 1, velocity_filter=f), rel=1e-8)
    # the HBFD's region with the backward difference at B = 100: the same number as the bench row
    r0 = zwidth_region(hbfd, b=np.array([50.0, 100.0]), delay_samples=1, passive=False)
    assert r0.k_max[1] == pytest.approx(critical_stiffness(hbfd, 100.0, 1), rel=1e-8)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.area_linear = 0.0  # type: ignore[misc]


def test_region_areas_and_the_passive_and_twoport_edges(rigid):
    b = np.geomspace(0.1, 50, 30)
    disp = ImpedanceDisplay(rigid)

    def eq9(bb: np.ndarray) -> np.ndarray:
        return np.array([np.nan if (d := disp.max_stiffness(float(x))).kc is None else d.kc for x in bb])

    r = zwidth_region(rigid, b=b, delay_samples=0, twoport_limit=eq9)
    assert r.area_linear == pytest.approx(np.trapezoid(r.k_max, b), rel=1e-12)
    assert r.area_log == pytest.approx(np.trapezoid(np.log10(r.k_max / 1.0), np.log10(b)), rel=1e-12)
    assert OPTIMIZER_AREA == "area_linear"
    # Colgate-Schenkel: K < 2 (b - |B|)/T without delay; NaN once B >= b
    ok = b < 2.0
    assert np.allclose(r.k_passive[ok], 2 * (2.0 - b[ok]) / T, rtol=1e-6)
    assert np.all(np.isnan(r.k_passive[~ok]))
    assert r.k_passive[0] == pytest.approx(passivity_limit(0.5, 2.0, T, b[0]), rel=1e-9)
    # passive implies stable (hands-off, god-object wall); eq. 9's limit is carried as given
    assert np.all(r.k_passive[ok] <= r.k_max[ok])
    assert np.array_equal(r.k_twoport, eq9(b), equal_nan=True) and np.isfinite(r.k_twoport[0])
    assert r.stable(1.0, 0.9 * r.k_limit(np.array([1.0]))[0]) and not r.stable(1.0, 1.1 * r.k_limit(np.array([1.0]))[0])


def test_region_validation(rigid):
    with pytest.raises(ValidationError, match="b"):
        zwidth_region(rigid, b=[1.0])
    with pytest.raises(ValidationError, match="b"):
        zwidth_region(rigid, b=[2.0, 1.0])
    with pytest.raises(ValidationError, match="b"):
        zwidth_region(rigid, b=[-1.0, 1.0])
    with pytest.raises(ValidationError, match="cutoff"):
        zwidth_region(rigid, b=[1.0, 2.0], velocity_filter=VelocityFilter("butter2", cutoff=4000.0))


def test_hbfd_has_an_interior_optimum_cutoff(hbfd):
    """Chawda et al.'s shape: the area rises, peaks and falls with the cut-off (HBFD, 1 sample delay)."""
    cut = np.geomspace(2 * math.pi * 10, 2 * math.pi * 400, 8)
    seen = []
    o = optimal_filter(hbfd, "lowpass1", cut, b=np.geomspace(1, 1000, 16), delay_samples=1,
                       progress=lambda d, t: seen.append((d, t)))
    assert o.interior and o.kind == "lowpass1"
    j = int(np.argmax(o.areas))
    assert 0 < j < cut.size - 1 and o.areas[0] < o.areas[j] > o.areas[-1]
    assert o.area >= o.areas[j] and o.area > 3 * o.backward_area
    assert 2 * math.pi * 20 < o.cutoff < 2 * math.pi * 120
    assert seen[-1][0] == seen[-1][1] and [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert optimal_filter(hbfd, "lowpass1", cut, b=np.geomspace(1, 1000, 16), cancelled=lambda: True) is None


def _rigid_loop_roots(K: float, B: float, d: int, f: VelocityFilter, m: float = 0.5, c: float = 2.0) -> np.ndarray:
    """Closed-loop poles (in z) of a rigid mass under the wall ``K + B V(z)``, built by hand.

    Exact ZOH of ``m x'' = F - c x'`` from force to position, in ``q = 1/z``:
    ``q (g1 + g2 q)/((1 - q)(1 - e q))`` with ``e = exp(-cT/m)``; the wall force
    ``-q^d (K + B n_v(q)/d_v(q)) x`` with ``V = n_v/d_v`` (the filter's transfer function).  The
    characteristic polynomial is ``(1 - q)(1 - e q) d_v + q^(d+1) (g1 + g2 q)(K d_v + B n_v)``;
    ascending powers of q are descending powers of z.
    """
    e = math.exp(-c * T / m)
    tau = m / c
    g1 = (T - tau * (1 - e)) / c
    g2 = (tau * (1 - e) - T * e) / c
    nv, dv = f.transfer_function(T)
    n = max(nv.size, dv.size)
    nv, dv = np.pad(nv, (0, n - nv.size)), np.pad(dv, (0, n - dv.size))
    lhs = np.convolve(np.convolve([1.0, -1.0], [1.0, -e]), dv)
    rhs = np.convolve(np.r_[np.zeros(d + 1), g1, g2], K * dv + B * nv)
    size = max(lhs.size, rhs.size)
    poly = np.pad(lhs, (0, size - lhs.size)) + np.pad(rhs, (0, size - rhs.size))
    return np.roots(np.trim_zeros(poly, "b"))


def _hand_radius(K: float, B: float, d: int, f: VelocityFilter, m: float = 0.5, c: float = 2.0) -> float:
    return float(np.max(np.abs(_rigid_loop_roots(K, B, d, f, m, c))))


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_rigid_damping_limit_has_a_closed_form(d):
    """Backward difference, ideal mass, ZOH, d samples of delay: as K -> 0 the loop is
    ``z^(d+1)(z - 1) + g (z + 1)``, g = BT/(2m).  The phase of ``(z + 1)/(z^(d+1)(z - 1))`` on the
    unit circle is ``-pi/2 - (d+1) theta`` and its gain ``cot(theta/2)``, so the loop is stable up
    to g = tan(pi/(4(d+1))): B_max = 2m/T, 0.828 m/T, 0.536 m/T, 0.398 m/T.  The exact region
    (first crossing from a 1e-3 N/m floor) ends there."""
    ideal = Device(masses=[0.5], stiffnesses=[], dampings=[], ground_dampings=[0.0], sample_time=T)
    g = math.tan(math.pi / (4 * (d + 1)))
    b_max = 2 * 0.5 / T * g
    k = zwidth_region(ideal, b=np.array([0.99, 1.01]) * b_max, delay_samples=d, k_range=(1e-3, 1e9),
                      passive=False).k_max
    assert k[0] > 1e-3 and k[1] == 0.0
    loop = np.r_[1.0, -1.0, np.zeros(d + 1)] + g * np.r_[np.zeros(d + 1), 1.0, 1.0]
    assert np.max(np.abs(np.roots(loop))) == pytest.approx(1.0, abs=1e-9)


def test_rigid_device_with_delay_has_no_interior_optimum(rigid):
    """Chawda et al.'s interior optimum does not appear on a rigid device in this noise-free
    linear analysis, even with the B range past the backward difference's damping limit.

    The ZOH rigid mass has a zero at z = -1, so the 2B/T Nyquist gain of the backward
    difference never reaches the loop; its damping limit (415.7 N s/m here, one sample of delay)
    is a phase limit at fs/8, where a filter's lag costs more than its attenuation saves.  A
    filter never raises K_max where the backward difference has a region, and at cut-offs from
    5 Hz up nowhere; the area against the cut-off is U-shaped (an interior *minimum*).  Its left
    branch is the degenerate limit w_f -> 0: the wall's B is then not rendered at all, and the
    region stretches past B_max (roughly ``m/tau + c/(w_f tau)``, tau = 1.5 T) at small K.
    """
    b = np.geomspace(1, 1000, 16)
    k_back = zwidth_region(rigid, b=b, delay_samples=1, passive=False).k_max
    assert k_back[b < 400].min() > 0 and np.all(k_back[b > 420] == 0)
    inside = k_back > 0
    cut = np.geomspace(2 * math.pi * 0.2, 2 * math.pi * 450, 10)
    for kind in ("lowpass1", "butter2"):
        o = optimal_filter(rigid, kind, cut, b=b, delay_samples=1)
        j = int(np.argmin(o.areas))
        assert not o.interior and o.cutoff == cut[-1] and o.area < 0.95 * o.backward_area
        assert 0 < j < cut.size - 1 and o.areas[0] > o.areas[j] and np.all(np.diff(o.areas[j:]) > 0)
        for c in cut:
            k = zwidth_region(rigid, b=b, delay_samples=1, velocity_filter=VelocityFilter(kind, c), passive=False).k_max
            assert np.all(k[inside] <= k_back[inside] * (1 + 1e-9))
            if c >= 2 * math.pi * 5:
                assert np.all(k <= k_back * (1 + 1e-9))
    tail = zwidth_region(rigid, b=b, delay_samples=1, velocity_filter=VelocityFilter("lowpass1", cut[0]),
                         passive=False).k_max
    assert tail[b > 600].min() > 300  # past B_max: the w_f -> 0 branch


def test_rigid_region_point_is_where_the_hand_built_poles_cross_the_unit_circle(rigid):
    """An independent check of the region: the hand-built closed loop crosses |z| = 1 at K_max."""
    for f, B, d, hz in ((VelocityFilter("lowpass1", cutoff=2 * math.pi * 30), 100.0, 1, 37.457),
                        (VelocityFilter("butter2", cutoff=2 * math.pi * 200), 10.0, 2, None)):
        K = float(zwidth_region(rigid, b=np.array([B, 2 * B]), delay_samples=d, velocity_filter=f,
                                passive=False).k_max[0])
        assert _hand_radius(K * (1 - 1e-6), B, d, f) < 1 < _hand_radius(K * (1 + 1e-6), B, d, f)
        if hz is not None:
            roots = _rigid_loop_roots(K, B, d, f)
            z = roots[np.argmax(np.abs(roots))]
            assert abs(abs(z) - 1) < 1e-8 and abs(np.angle(z)) / (2 * math.pi * T) == pytest.approx(hz, abs=0.01)


def test_a_stable_window_above_the_k_floor_is_not_reported():
    """Conservative by construction: the region is the first crossing *from* ``k_floor``.  A light,
    damped device with a 1 Hz Butterworth at B = 50 N s/m is unstable at small K and stable on a
    window [~35, ~1300] N/m (hand-built poles); the region reports K_max = 0 there."""
    light = Device(masses=[0.05], stiffnesses=[], dampings=[], ground_dampings=[2.0], sample_time=T)
    f = VelocityFilter("butter2", cutoff=2 * math.pi * 1)
    radius = [_hand_radius(k, 50.0, 1, f, m=0.05) for k in (1.0, 10.0, 100.0, 1000.0, 1400.0)]
    assert radius[0] > 1 and radius[1] > 1 and radius[2] < 1 and radius[3] < 1 and radius[4] > 1
    r = zwidth_region(light, b=np.array([50.0, 60.0]), delay_samples=1, velocity_filter=f, passive=False)
    assert r.k_max[0] == 0.0


def test_trials_are_loaded_and_scored(tmp_path, rigid):
    r = zwidth_region(rigid, b=np.geomspace(1, 100, 20), passive=False)
    k10 = float(r.k_limit(np.array([10.0]))[0])
    p = tmp_path / "trials.csv"
    p.write_text("# hardware, 2026\nb,k,stable,note\n10,%r,1,x\n10,%r,0,y\n\n10,%r,0,wrong\n500,1000,1,outside\n"
                 % (0.5 * k10, 2 * k10, 0.5 * k10))
    tr = load_trials(p)
    assert len(tr) == 4 and list(tr.lines) == [3, 4, 6, 7]
    s = score_trials(r, tr)
    assert s.scored == 3 and s.wrong_count == 1 and list(s.wrong) == [2] and list(s.outside) == [3]
    assert "line 6" in s.describe(tr)[0] and "measured unstable, predicted stable" in s.describe(tr)[0]
    bad = tmp_path / "bad.csv"
    bad.write_text("b,k,stable\n1,2,1\n1,x,0\n")
    with pytest.raises(ValidationError) as e:
        load_trials(bad)
    assert "bad.csv" in str(e.value) and "line 3" in str(e.value) and "column 'k'" in str(e.value)
    bad.write_text("b,k,stable\n1,2,yes\n")
    with pytest.raises(ValidationError, match="column 'stable'"):
        load_trials(bad)
    bad.write_text("b,stable\n1,1\n")
    with pytest.raises(ValidationError, match="column 'k'"):
        load_trials(bad)
