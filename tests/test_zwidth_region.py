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


def test_rigid_device_area_grows_with_the_cutoff(rigid):
    """In the exact linear analysis a rigid device gains nothing from filtering: the filter only
    adds phase lag (the interior optimum of Chawda et al. needs more than the linear loop)."""
    o = optimal_filter(rigid, "lowpass1", np.geomspace(2 * math.pi * 10, 2 * math.pi * 450, 6),
                       b=np.geomspace(1, 1000, 16), delay_samples=1)
    assert np.all(np.diff(o.areas) > 0) and o.area <= o.backward_area


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
    assert "bad.csv" in str(e.value) and "line 3" in str(e.value) and "column k" in str(e.value)
    bad.write_text("b,k,stable\n1,2,yes\n")
    with pytest.raises(ValidationError, match="column stable"):
        load_trials(bad)
    bad.write_text("b,stable\n1,1\n")
    with pytest.raises(ValidationError, match="column k"):
        load_trials(bad)
