"""Sampled-data benchmarks (issue 5: exact sweeps and time-domain simulation).

* worst spectral radius over 1000 terminations of the HBFD (100 grasps x 10 environments),
  impedance and admittance display (target 500 ms);
* exact critical k_c of the HBFD (scan + bisection);
* 10 s of simulated time at 1 kHz, HBFD, every nonlinear option on (quantized encoder and
  gauge, friction, saturation) and one sample of delay (target 1000 ms);
* simulator run time against error for the sub-step count (friction and saturation on,
  quantization off; error = max position difference against 64 sub-steps, relative).
"""

from __future__ import annotations

import numpy as np

from analysis.sampled import (
    Grasp,
    Termination,
    critical_stiffness,
    free_motion,
    god_object_wall,
    hbfd_options,
    penalty_wall,
    simulate,
    worst_case,
)

from tests.benchmarks.common import hbfd, timed


def thousand_terminations() -> list[Termination]:
    grasps = [Grasp(m, b, k) for m in np.linspace(0.0, 3.0, 5) for b in (0.0, 20.0, 200.0, 1000.0)
              for k in (0.0, 2e3, 2e4, 2e5, 2e6)]
    envs = [penalty_wall(k) for k in (0.0, 1e3, 1e4, 1e5, 5e5, 1e6)]
    envs += [free_motion("admittance", m) for m in (0.02, 0.2, 2.0)] + [god_object_wall()]
    out = [Termination(g, e) for g in grasps for e in envs]
    assert len(out) == 1000
    return out


def run(quick: bool = False) -> list[dict]:
    """``quick``: one call of each, 1 s instead of 10 s simulated, 0.2 s with 1 and 16 sub-steps."""
    rows: list[dict] = []
    dev = hbfd()
    terms = thousand_terminations()
    for display, c in (("impedance", (50e3, 100.0)), ("admittance", (31.0, 1550.0))):
        t, res = timed(lambda: worst_case(dev, display, c, terms), repeat=15, quick=quick)
        rows.append({"name": f"worst case over 1000 terminations ({display} display)", **t, "target_ms": 500.0,
                     "spectral_radius": res.spectral_radius})
    t, k1 = timed(lambda: critical_stiffness(dev, 100.0, 1), repeat=10, quick=quick)
    rows.append({"name": "exact critical k_c of the HBFD (b_c = 100, 1 sample delay)", **t, "kc": k1})

    opt = hbfd_options(delay_samples=1)
    seconds = 1.0 if quick else 10.0
    for name, display, c in (("impedance_worst_case", "impedance", (50e3, 100.0)),
                             ("wall_push", "impedance", (50e3, 100.0)),
                             ("admittance_worst_case", "admittance", (31.0, 1550.0))):
        t, r = timed(lambda: simulate(dev, name, seconds, display=display, coupling=c, options=opt),
                     repeat=5, quick=quick)
        rows.append({"name": f"simulate {seconds:g} s, nonlinear on: {name}", **t,
                     "target_ms": 100.0 * seconds, "verdict": r.verdict.kind, "split_steps": r.events})

    base = hbfd_options(encoder_resolution=0.0, force_resolution=0.0).to_dict()
    dur = 0.2 if quick else 2.0

    def sim(sub: int):
        return simulate(dev, "wall_push", dur, options=type(opt).from_dict({**base, "substeps": sub}))

    ref = sim(64).positions
    scale = float(np.max(np.abs(ref)))
    for sub in (1, 16) if quick else (1, 2, 4, 8, 16):
        t, r = timed(lambda: sim(sub), repeat=3, quick=quick)
        err = float(np.max(np.abs(r.positions - ref)) / scale)
        rows.append({"name": f"wall push {dur:g} s, friction on, {sub} sub-steps", **t, "rel_error": err})
    return rows


if __name__ == "__main__":  # pragma: no cover
    for row in run(quick=True):
        print(row)
