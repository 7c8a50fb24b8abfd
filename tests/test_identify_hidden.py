"""A handle mode the measurements do not show (analysis.identify.hidden).

* The embedded merged chain (handle of 1e-4 of the pair's mass on an element far above the band)
  is the (n-1)-mass chain: its RSS equals that of an independent 3-mass fit of the same data.
* Data from a chain that really has no handle (the HBFD with mass 0 merged into mass 1): the
  4-mass fit does not detect a handle mode (D <= 3 ln R) and reports the handle unbounded.
* The HBFD's actuator FRF at 1 % noise, seed 2007 of the coverage benchmark: before this
  module the intervals of m_0, m_1, k_0, k_1 and b_1 all missed the truth (k_1 came out at
  83.58 kN/m in [83.48, 83.71] kN/m; truth 84 kN/m).  Now every interval holds the truth, the
  handle side is unbounded, k_1 is bounded below (above, a heavy handle on a vanishing link mass
  puts k_1 in series with k_0: unbounded, and said so), and the fitted k_c at b_c = 100 is within
  5 % of the true device's.
* Undetected, the reported device is the merged chain (the BIC's choice), not the lower-RSS chain
  whose handle fits noise: seed 2005, where least squares put k_c 8 % above the truth.  Which
  optimum least squares reaches depends on the BLAS kernel (issue 21), so it is never asserted:
  the reported device's properties are.
* With the gauge added the handle mode is detected and nothing changes: Wald intervals, no
  family, the statistic far above the criterion.
* Cancel: the fit asks ``cancelled()`` before every model evaluation and stops at the first True
  (the 20-40 s of an actuator-alone fit used to run to the end after a Cancel).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from analysis import Device, ImpedanceDisplay
from analysis.identify import (
    MERGED_SHARE,
    ChainParameters,
    FitCancelled,
    FitProblem,
    device_value,
    fit_chain,
    hidden_handle,
    merged_fit,
)
from analysis.study import identify_chain

from tests.hbfd_fixtures import hbfd_replicate, make_hbfd

pytestmark = pytest.mark.numerics

T = 1e-3
W = np.geomspace(1.0, 0.95 * math.pi / T, 400)
HANDLE = ("masses[0]", "stiffnesses[0]", "dampings[0]")


def _measurements(device: Device, seed: int, quantities=("actuator",), noise: float = 0.01):
    return hbfd_replicate(device, seed, tuple(quantities), noise)  # the draws of the benchmark


def _problem(fit, measurements) -> tuple[FitProblem, np.ndarray]:
    problem = FitProblem(tuple(measurements), fit.free_keys, ChainParameters.from_device(fit.device), 0)
    return problem, np.log([fit.value(k) for k in fit.free_keys])


def _merged_hbfd() -> Device:
    d = make_hbfd()
    return Device(masses=[2.5, 2.0, 0.5], stiffnesses=d.stiffnesses[1:], dampings=d.dampings[1:],
                  ground_dampings=[0.0, 0.0, 5.0], sensor_element=0, sample_time=T)


def test_the_embedded_merged_chain_is_the_chain_with_one_mass_less():
    ms = _measurements(make_hbfd(), 11)
    fit4 = fit_chain(ms, 4, ground_dampings=(3,), intervals="wald")
    fit3 = fit_chain(ms, 3, ground_dampings=(2,), intervals="wald")
    problem, theta = _problem(fit4, ms)
    rss, th = merged_fit(problem, theta)
    s2 = fit4.rss / fit4.dof
    assert abs(rss - fit3.rss) < 0.05 * s2  # the same optimum, reached from another parameterization
    merged = problem.chains(th)
    assert merged.masses[0, 0] + merged.masses[0, 1] == pytest.approx(fit3.value("masses[0]"), rel=1e-3)
    assert merged.stiffnesses[0, 1] == pytest.approx(fit3.value("stiffnesses[0]"), rel=1e-3)


def test_a_chain_without_a_handle_is_not_detected_and_its_handle_is_unbounded():
    truth = _merged_hbfd()
    ms = _measurements(truth, 5)
    fit = fit_chain(ms, 4, ground_dampings=(3,))
    problem, theta = _problem(fit, ms)
    h = hidden_handle(problem, theta, fit.rss)
    assert h is not None and not h.detected and h.statistic <= h.critical == pytest.approx(3 * math.log(800))
    for k in HANDLE:
        assert fit.intervals[k] == (0.0, math.inf) and k in fit.non_identifiable
    assert any("handle mode is not detected" in w for w in fit.warnings)
    # the rest of the chain is the true 3-mass chain: m_0 + m_1 is its first mass
    total = fit.value("masses[0]") + fit.value("masses[1]")
    assert total == pytest.approx(2.5, rel=0.01)
    for k4, k3 in (("masses[2]", "masses[1]"), ("stiffnesses[2]", "stiffnesses[1]"), ("ground_dampings[3]",
                                                                                       "ground_dampings[2]")):
        lo, hi = fit.intervals[k4]
        assert lo <= device_value(truth, k3) <= hi


def test_the_actuator_alone_intervals_hold_the_truth_where_they_used_to_miss():
    d = make_hbfd()
    fit = fit_chain(_measurements(d, 2007), 4, ground_dampings=(3,))
    methods = dict(zip(fit.keys, fit.interval_methods))
    for k in fit.keys:
        lo, hi = fit.intervals[k]
        assert lo <= device_value(d, k) <= hi, (k, lo, hi, methods[k])
    for k in HANDLE:
        assert fit.intervals[k] == (0.0, math.inf) and "clamped" in fit.suggestions[k]
    assert any("handle mode is not detected" in w for w in fit.warnings)
    assert "handle family" in methods["stiffnesses[1]"]
    # the link stiffness is bounded below to a per cent; above, the data allow a heavy handle with a
    # vanishing link mass, where k_1 is in series with k_0 and unbounded -- the fit says so
    lo, hi = fit.intervals["stiffnesses[1]"]
    assert lo > 0.99 * 83e3
    if not hi / lo < 10:
        assert "stiffnesses[1]" in fit.non_identifiable and "clamped" in fit.suggestions["stiffnesses[1]"]
    kc = ImpedanceDisplay(fit.device).max_stiffness(100.0).kc
    assert kc == pytest.approx(ImpedanceDisplay(d).max_stiffness(100.0).kc, rel=0.05)


def _detection(fit) -> tuple[float, float]:
    """D and 3 ln R of the "handle mode is not detected" warning (the numbers the user reads)."""
    note = next(w for w in fit.warnings if "handle mode is not detected" in w)
    found = re.search(r"higher by (\S+) s\^2, at most 3 ln R = (\S+)\)", note)
    assert found, note
    return float(found.group(1)), float(found.group(2))


def test_with_the_mode_undetected_the_fitted_device_is_the_merged_chain():
    """Seed 2005: the handle mode is not detected, and the device reported is the merged chain (the
    BIC's choice), whatever optimum least squares reaches.  On one kernel that optimum was a 1.3 g
    handle on 43 N/m fitting noise, with k_c at b_c = 100 8 % above the truth; another kernel's
    least squares (AVX-512) stopped elsewhere: which optimum the 4-mass least squares finds is its
    floating-point path, not the product, so it is not asserted.  Asserted: the detection decides
    as docs/guide/identify.md says, the reported device's RSS is an independent 3-mass fit's, its k_c
    is conservative and within 5 % of the truth, and every interval holds its values and the truth."""
    d = make_hbfd()
    ms = _measurements(d, 2005)
    fit = fit_chain(ms, 4, ground_dampings=(3,))
    fit3 = fit_chain(ms, 3, ground_dampings=(2,), intervals="wald")
    s2 = fit.rss / fit.dof
    statistic, critical = _detection(fit)
    # not detected: D <= 3 ln R with R = 800 real residuals (D ~ 7, far from 20.1 on every kernel)
    assert critical == pytest.approx(3 * math.log(800), abs=0.05) and statistic <= critical  # 3 digits
    # the merged chain is the 3-mass optimum (a well-determined fit: every kernel agrees to 1e-7 s^2)
    assert abs(fit.rss - fit3.rss) < 0.05 * s2
    m0, m1 = fit.value("masses[0]"), fit.value("masses[1]")
    assert m0 / (m0 + m1) == pytest.approx(MERGED_SHARE, rel=0.2)
    assert math.sqrt(fit.value("stiffnesses[0]") / m0) > 5 * W[-1]
    for k in HANDLE:
        assert fit.intervals[k] == (0.0, math.inf)
    kc_true = ImpedanceDisplay(d).max_stiffness(100.0).kc
    assert 0.95 * kc_true < ImpedanceDisplay(fit.device).max_stiffness(100.0).kc <= kc_true
    for k, v in zip(fit.keys, fit.values):
        lo, hi = fit.intervals[k]
        assert lo <= v <= hi, (k, lo, v, hi)
        assert lo <= device_value(d, k) <= hi, (k, lo, hi)
    assert device_value(fit.device, "stiffnesses[2]") == pytest.approx(fit.value("stiffnesses[2]"), rel=1e-12)


def test_with_the_gauge_the_handle_mode_is_detected_and_nothing_changes():
    d = make_hbfd()
    ms = _measurements(d, 2007, ("actuator", "gauge"))
    fit = fit_chain(ms, 4, ground_dampings=(3,))
    problem, theta = _problem(fit, ms)
    h = hidden_handle(problem, theta, fit.rss)
    assert h.detected and h.statistic > 100 * h.critical and h.family == ()
    assert not any("handle mode" in w for w in fit.warnings)
    assert not any("family" in m for m in fit.interval_methods)
    for k in fit.keys:
        lo, hi = fit.intervals[k]
        assert hi / lo < 1.1


def test_the_test_does_not_apply_when_a_handle_unknown_is_fixed():
    d = make_hbfd()
    ms = _measurements(d, 3)
    fit = fit_chain(ms, 4, ground_dampings=(3,), fixed={"masses[0]": 0.2}, intervals="wald")
    problem, theta = _problem(fit, ms)
    assert hidden_handle(problem, theta, fit.rss) is None
    one = fit_chain(ms, 1, intervals="wald")
    assert hidden_handle(*_problem(one, ms), one.rss) is None


def test_a_cancelled_fit_stops_at_the_next_model_evaluation():
    ms = _measurements(make_hbfd(), 2007)
    calls = {"n": 0, "after": 0}

    def cancelled() -> bool:
        calls["n"] += 1
        if calls["n"] > 40:
            calls["after"] += 1
            return True
        return False

    with pytest.raises(FitCancelled):
        fit_chain(ms, 4, ground_dampings=(3,), cancelled=cancelled)
    assert calls["after"] == 1  # no evaluation ran after the first True
    # the study layer (what the Identify view runs on the worker) answers None, at any stage
    for stop_after in (5, 400, 4000):
        count = {"n": 0}

        def late(limit: int = stop_after) -> bool:
            count["n"] += 1
            return count["n"] > limit

        assert identify_chain(ms, 4, ground_dampings=(3,), max_masses=4, cancelled=late) is None
        assert count["n"] == stop_after + 1
