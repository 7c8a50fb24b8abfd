"""Identification from chirp tests (issue 23): the issue's 3-mass device driven through the ZOH at
1 kHz by a 40 s chirp from 1 to 300 Hz, the actuator position with encoder noise
(:func:`tests.identify_data.chirp_record`), Welch's estimate, then :func:`fit_chain` on the
informative bins.

* 100 seeded replicates (50 linear, 50 logarithmic chirps; noise log-uniform in 0.1 % to 1 %):
  the share of replicates with each mass and stiffness within 5 % (goal: 100 %), the share
  within 5 % of every one, the largest error, the goodness test's verdict on the 3-mass fit
  (should pass) and on a 2-mass fit (should fail), and the fit on every bin (the defect: an FRF
  without coherence or input power, fitted over the whole band) for comparison.
* quick (``zwidth bench --quick``): 3 replicates, the 3-mass fits only.
"""

from __future__ import annotations

import numpy as np

from analysis.identify import device_value, estimate_frf, fit_chain, make_measurement

from tests.benchmarks.common import timed
from tests.identify_data import chirp_device, chirp_record

T = 1e-3
KEYS = ("masses[0]", "masses[1]", "masses[2]", "stiffnesses[0]", "stiffnesses[1]")


def replicate(seed: int) -> tuple[str, float, object]:
    """Chirp method, noise level and Welch estimate of replicate ``seed`` (even: linear, odd:
    logarithmic; noise log-uniform in [0.001, 0.01] from ``default_rng(seed)``)."""
    method = "linear" if seed % 2 == 0 else "logarithmic"
    noise = float(np.exp(np.random.default_rng(seed).uniform(np.log(1e-3), np.log(1e-2))))
    t, f, x = chirp_record(method=method, noise=noise, seed=seed, sample_time=T)
    return method, noise, estimate_frf(t, f, x, sample_time=T)


def _errors(fit, dev) -> np.ndarray:
    return np.array([abs(fit.value(k) / device_value(dev, k) - 1) for k in KEYS])


def _row(name: str, errs: list[np.ndarray], extra: dict) -> dict:
    e = np.array(errs)
    within = e < 0.05
    row = {"name": name, "replicates": len(errs)}
    row.update({f"{k}_within_5%": float(np.mean(within[:, j])) for j, k in enumerate(KEYS)})
    row.update({"all_within_5%": float(np.mean(np.all(within, axis=1))), "max_rel_error": float(e.max())})
    row.update(extra)
    return row


def run(quick: bool = False) -> list[dict]:
    dev = chirp_device(T)
    reps = 3 if quick else 100
    fits, errs, whole_errs, passed, stats, wrong_failed = [], [], [], 0, [], 0
    times = []
    for seed in range(reps):
        _, _, m = replicate(seed)
        t, fit = timed(lambda: fit_chain([m], 3, intervals="wald"), quick=True)
        times.append(t["median_ms"])
        errs.append(_errors(fit, dev))
        passed += bool(fit.goodness.passed)
        stats.append(fit.goodness.statistic)
        if not quick:
            wrong_failed += not fit_chain([m], 2, intervals="wald").goodness.passed
            every = make_measurement(m.frequency, m.response, sample_time=T)  # no coherence: every bin
            whole_errs.append(_errors(fit_chain([every], 3, intervals="wald"), dev))
        fits.append(fit)
    rows = [_row(f"3-mass fit on the informative bins, {reps} chirps (linear + log, noise 0.1-1 %)", errs,
                 {"goodness_passed": passed, "goodness_max": float(np.max(stats)),
                  "median_fit_ms": float(np.median(times)),
                  "bins_used_median": float(np.median([f.bins[0].used for f in fits]))})]
    if not quick:
        rows.append({"name": f"2-mass fit (one mass too few), {reps} chirps: goodness test fails",
                     "failed": wrong_failed, "replicates": reps})
        rows.append(_row(f"3-mass fit on every bin (no bin selection, the defect), {reps} chirps", whole_errs, {}))
    return rows
