"""Coverage of the 95 % intervals of analysis.identify.fit_chain under 1 % complex Gaussian noise.

HBFD, 1 kHz, 400 log-spaced points from 1 rad/s to 0.95 Nyquist, the actuator FRF plus the
force-gauge FRF (both with the handle free).  The gauge is needed: with the actuator alone the
handle mode (pole 842.45, zero 842.72 rad/s at the actuator) is invisible at 1 % noise and the
handle-side parameters are not identifiable (see test_identify_fit.py).  The full check (slow
tier) runs 20 seeded replicates (100 in tests/benchmarks/bench_identify.py); every parameter's
interval must cover the truth in at least 80 % of them (16 of 20; nominally 95 %).  The default
tier runs the first 5 of those seeds and asks for 3 of 5: at the lowest coverage measured over
100 replicates (87 %, ground_dampings[3]) an interval misses 3 times in 5 with probability 1.8 %,
at the nominal 95 % with 0.1 %, while the actuator-alone intervals before analysis.identify.hidden
(15-46 of 47) fail it.  On seeds 1000-1004 stiffnesses[2] covers 3 of 5, every other parameter
5 of 5.  In both tiers the fitted device's largest k_c at b_c = 100 N s/m (eq. 9) must lie within
5 % of the true device's in every replicate, and the robust k_c over the fitted intervals (every
device in the box) must not exceed the true device's k_c by more than 0.1 % (the box of 95 %
intervals does not always hold the truth; measured over 94 replicates: at most +0.025 %, 92 of 94
strictly below).

With the gauge the problem is nearly linear over the intervals and well determined: every kernel
reaches the same optimum, so the counts do not depend on the BLAS kernel (issue 21).
"""

from __future__ import annotations

import numpy as np
import pytest

from analysis import ImpedanceDisplay
from analysis.identify import device_value, fit_chain, robust_max_stiffness

from tests.hbfd_fixtures import hbfd_replicate, make_hbfd

pytestmark = pytest.mark.numerics

FIRST_SEED = 1000
REPLICATES = 20  # the slow tier
QUICK_REPLICATES = 5  # the default tier: the first seeds of the same draws


def _check_coverage(replicates: int, min_covered: int, robust_every: int) -> dict[str, int]:
    """Fit ``replicates`` seeds, check coverage and k_c; the number of intervals covering each truth."""
    d = make_hbfd()
    kc_true = ImpedanceDisplay(d).max_stiffness(100.0).kc
    covered = None
    kc_err = []
    for r in range(replicates):
        ms = hbfd_replicate(d, FIRST_SEED + r, ("actuator", "gauge"))
        fit = fit_chain(ms, 4, ground_dampings=(3,))
        tv = np.array([device_value(d, k) for k in fit.keys])
        hit = (fit.lower <= tv) & (tv <= fit.upper)
        covered = hit.astype(int) if covered is None else covered + hit
        kc_err.append(ImpedanceDisplay(fit.device).max_stiffness(100.0).kc / kc_true - 1)
        if r % robust_every == 0:  # the robust design over the fitted box (2 s each)
            assert set(fit.interval_methods) == {"wald"}  # nearly linear: the curvature check passes
            box = {k: iv for k, iv in fit.intervals.items() if k in fit.free_keys}
            assert robust_max_stiffness(fit.device, 100.0, box).kc <= kc_true * (1 + 1e-3)
    assert np.all(covered >= min_covered), dict(zip(fit.keys, covered))
    assert np.max(np.abs(kc_err)) < 0.05
    return dict(zip(fit.keys, covered.tolist()))


def test_intervals_cover_the_truth_and_the_design_holds_on_the_first_seeds():
    _check_coverage(QUICK_REPLICATES, min_covered=3, robust_every=QUICK_REPLICATES)


@pytest.mark.slow
def test_intervals_cover_the_truth_and_the_design_holds():
    _check_coverage(REPLICATES, min_covered=16, robust_every=4)
