"""Z-width benchmarks (issue 15: velocity filters, the (B, K) region, its optimum, passivity control).

* the exact (B, K) region of the HBFD at 100 values of B (0.1-100 N s/m, one sample of delay,
  passive edge included; target 1000 ms), with the backward difference and a 30 Hz low-pass;
* the area against the cut-off of each filter kind, 30 cut-offs from 5 Hz to Nyquist (500 Hz;
  the butter2 grid stops just below it), B 1-1000 N s/m, one sample of delay, refined optimum
  (target 10 000 ms), with the optimum cut-off, its area and the backward-difference area;
* the same optimum for a rigid 1-DOF device (0.5 kg, 2 N s/m), where the exact linear analysis
  finds no interior optimum;
* the passivity-control comparison on the HBFD (K = 1.5 k_c at B = 10 N s/m, no delay), with
  the verdicts, peak forces, spikes and penetrations of the three runs.
"""

from __future__ import annotations

import math

import numpy as np

from analysis import Device
from analysis.sampled import SimulationOptions, VelocityFilter, optimal_filter, passivity_comparison, zwidth_region

from tests.benchmarks.common import hbfd, timed


def _optimum_rows(dev: Device, label: str, quick: bool) -> list[dict]:
    rows = []
    top = math.pi / dev.sample_time
    n_cut, n_b = (4, 10) if quick else (30, 100)  # quick: still an interior optimum refined on the HBFD
    for kind in ("lowpass1", "butter2"):
        cut = np.geomspace(2 * math.pi * 5, top if kind == "lowpass1" else 0.98 * top, n_cut)
        b = np.geomspace(1.0, 1000.0, n_b)
        t, o = timed(lambda: optimal_filter(dev, kind, cut, b=b, delay_samples=1), repeat=3, quick=quick)
        row = {"name": f"optimum {kind} cut-off, {label}, {n_cut} cut-offs, {n_b} B", **t,
               "cutoff_hz": o.cutoff / (2 * math.pi), "area": o.area, "backward_area": o.backward_area,
               "interior": o.interior}
        if label == "HBFD" and not quick:
            row["target_ms"] = 10000.0
        rows.append(row)
    return rows


def run(quick: bool = False) -> list[dict]:
    """``quick``: one call of each; the region on 20 values of B instead of 100, the filter optimum
    on 4 cut-offs and 10 values of B instead of 30 and 100."""
    rows: list[dict] = []
    dev = hbfd()
    n_b = 20 if quick else 100
    b = np.geomspace(0.1, 100.0, n_b)
    for f in (None, VelocityFilter("lowpass1", cutoff=2 * math.pi * 30)):
        t, r = timed(lambda: zwidth_region(dev, b=b, delay_samples=1, velocity_filter=f), repeat=10, quick=quick)
        rows.append({"name": f"Z-width region of the HBFD, {n_b} B, 1 sample delay, "
                             f"{'backward' if f is None else f.label()}", **t,
                     **({} if quick else {"target_ms": 1000.0}),
                     "area_linear": r.area_linear, "area_log": r.area_log, "k_max_at_100": float(r.k_max[-1])})
    rows += _optimum_rows(dev, "HBFD", quick)
    rigid = Device(masses=[0.5], stiffnesses=[], dampings=[], ground_dampings=[2.0], sample_time=1e-3)
    rows += _optimum_rows(rigid, "rigid 0.5 kg", quick)
    for name, opt in (("unbounded PC", SimulationOptions(force_peak=400.0, force_continuous=400.0)),
                      ("PC capped at 1000 N s/m", SimulationOptions(force_peak=400.0, force_continuous=400.0,
                                                                    passivity_max_damping=1000.0))):
        c = passivity_comparison(dev, b=10.0, factor=1.5, options=opt)
        for run_ in c.runs:
            rows.append({"name": f"PC comparison HBFD ({name}): {run_.name}", "verdict": run_.verdict,
                         "peak_force": run_.peak_force, "max_jump": run_.max_jump, "spikes": run_.spikes,
                         "penetration_m": run_.penetration, "final_energy": run_.final_energy,
                         "min_observed_energy": run_.min_observed_energy, "wall_k": c.wall[0],
                         "k_critical": c.k_critical})
    return rows


if __name__ == "__main__":  # pragma: no cover
    for row in run(quick=True):
        print(row)
