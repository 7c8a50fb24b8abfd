"""The study layer's Z-width (issue 15): the profile's filter reaches every analysis, the region
matches analysis.sampled.zwidth_region, eq. 9's edge is ImpedanceDisplay(velocity_filter=f)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analysis import ImpedanceDisplay
from analysis.profiles import ControllerSection, bundled_profiles, load_profile
from analysis.sampled import VelocityFilter, critical_stiffness, score_trials
from analysis.sampled import load_trials, zwidth_region as sampled_zwidth_region
from analysis import study

F30 = VelocityFilter("lowpass1", cutoff=2 * math.pi * 30)


@pytest.fixture(scope="module")
def hbfd():
    return load_profile(bundled_profiles()["hbfd"])


@pytest.fixture(scope="module")
def filtered(hbfd):
    return hbfd.replace(controller=ControllerSection(F30, (0.5, 80.0), 20))


@pytest.fixture(scope="module")
def region(filtered):
    return study.zwidth_region(filtered)


def test_region_matches_the_sampled_layer_directly(filtered, region):
    b = np.geomspace(0.5, 80.0, 20)
    direct = sampled_zwidth_region(filtered.device, b, 0, F30)
    np.testing.assert_array_equal(region.b, b)
    np.testing.assert_array_equal(region.k_max, direct.k_max)
    np.testing.assert_array_equal(region.k_passive, direct.k_passive)
    assert region.area_linear == direct.area_linear and region.area_log == direct.area_log
    assert region.velocity_filter == F30
    # the filter matters: the backward difference gives another region
    back = sampled_zwidth_region(filtered.device, b, 0)
    assert not np.allclose(back.k_max, region.k_max, rtol=1e-3)


def test_eq9_edge_is_the_filtered_impedance_display(filtered, region):
    disp = ImpedanceDisplay(filtered.device, velocity_filter=F30)
    for i in (0, 7, 13, 19):
        kc = disp.max_stiffness(float(region.b[i])).kc
        if kc is None:
            assert math.isnan(region.k_twoport[i])
        else:
            assert region.k_twoport[i] == pytest.approx(kc, rel=1e-12)
    assert np.count_nonzero(np.isfinite(region.k_twoport)) >= 10
    unfiltered = ImpedanceDisplay(filtered.device).max_stiffness(float(region.b[7])).kc
    assert region.k_twoport[7] != pytest.approx(unfiltered, rel=1e-6)


def test_exact_limit_and_displays_use_the_profile_filter(hbfd, filtered):
    assert study.profile_filter(hbfd) is None
    assert study.profile_filter(hbfd.replace(controller=ControllerSection())) is None
    assert study.profile_filter(filtered) == F30
    assert study.exact_limit(filtered) == critical_stiffness(filtered.device, float(filtered.bc), 0,
                                                             velocity_filter=F30)
    r = study.stability(filtered)
    expect = ImpedanceDisplay(filtered.device, velocity_filter=F30).evaluate(filtered.kc, filtered.bc)
    assert r.worst_margin == expect.worst_margin and r.k_max == expect.k_max
    np.testing.assert_array_equal(r.coupling_term, expect.coupling_term)
    assert study.max_stiffness(filtered).kc == ImpedanceDisplay(filtered.device, velocity_filter=F30) \
        .max_stiffness(filtered.bc).kc


def test_backward_section_is_bit_identical_to_no_section(hbfd):
    with_section = hbfd.replace(controller=ControllerSection())
    assert study.exact_limit(with_section) == study.exact_limit(hbfd)
    a, b = study.stability(with_section), study.stability(hbfd)
    assert a.worst_margin == b.worst_margin and a.relative_margin == b.relative_margin
    np.testing.assert_array_equal(a.margin, b.margin)
    assert study.max_stiffness(with_section).kc == study.max_stiffness(hbfd).kc


def test_trials_are_scored_against_the_region(filtered, region, tmp_path):
    kmax = region.k_limit(np.array([1.0, 10.0]))
    path = tmp_path / "trials.csv"
    path.write_text("b,k,stable\n"
                    f"1,{0.5 * kmax[0]},1\n"       # right
                    f"1,{2.0 * kmax[0]},1\n"       # wrong: measured stable, predicted unstable
                    f"10,{2.0 * kmax[1]},0\n"      # right
                    f"10,{0.5 * kmax[1]},0\n"      # wrong
                    "500,1000,1\n")                # outside the B range
    p = filtered.replace(controller=filtered.controller.replace(trials=str(path)))
    trials = study.profile_trials(p)
    s = study.trial_score(region, trials)
    assert s.score.wrong_count == 2 and s.score.scored == 4 and list(s.score.outside) == [4]
    assert list(s.score.wrong) == [1, 3]
    assert s.score.wrong_count == score_trials(region, load_trials(path)).wrong_count


def test_filter_optimum_reports_progress_and_cancels(filtered):
    cutoffs = 2 * math.pi * np.array([10.0, 30.0, 100.0])
    seen = []
    o = study.filter_optimum(filtered, cutoffs=cutoffs, progress=lambda d, n: seen.append((d, n)))
    assert o.kind == "lowpass1" and o.cutoffs.size == 3
    assert o.cutoffs[0] <= o.cutoff <= o.cutoffs[-1] and o.area >= o.areas.max() * (1 - 1e-9)
    assert seen[-1][0] == seen[-1][1]
    assert study.filter_optimum(filtered, cutoffs=cutoffs, cancelled=lambda: True) is None


def test_wall_edits_and_region_wall(hbfd):
    assert study.wall_edits(12.5, 3.0e4) == {"bc": 12.5, "kc": 3.0e4}
    p = hbfd.replace(**study.wall_edits(12.5, 3.0e4))
    assert study.region_wall(p) == (12.5, 3.0e4)
