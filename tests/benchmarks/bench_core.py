"""Analysis-core benchmarks (issue: analysis core, speed targets).

* one full evaluation (Y, bound, margin, Z_min, Z_max) of the HBFD at 2000 frequencies;
* the same for a 200-mass chain, with peak memory;
* the python-control route for the same Y(z) and bound (``ss`` -> ``c2d(tustin)`` ->
  frequency response, plus the hold factor of eq. 2), timed in the same run, with each
  route's error against a 50-digit mpmath evaluation;
* the largest k_c of the HBFD (``max_stiffness``).
"""

from __future__ import annotations

import tracemalloc

import numpy as np

from analysis import ImpedanceDisplay
from analysis.chain.discretize import hold_factor

from tests.benchmarks.common import hbfd, long_chain, timed, timeit


def control_route(device, w: np.ndarray):
    """Y(z) and the bound of eq. (9) through python-control, evaluated literally."""
    import control

    M, B, K = device.matrices()
    n = device.n
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ B]])
    Bu = np.zeros((2 * n, 2))
    Bu[n, 0] = 1.0 / M[0, 0]
    Bu[2 * n - 1, 1] = -1.0 / M[n - 1, n - 1]
    C = np.zeros((2, 2 * n))
    C[0, n] = 1.0
    C[1, 2 * n - 1] = -1.0
    sysc = control.ss(A, Bu, C, np.zeros((2, 2)))
    sysd = control.c2d(sysc, device.sample_time, method="tustin")
    resp = sysd(np.exp(1j * w * device.sample_time))  # (2, 2, N)
    h = hold_factor(w, device.sample_time)
    y11, y12, y21, y22 = resp[0, 0], resp[0, 1] * h, resp[1, 0], resp[1, 1] * h
    p = y12 * y21
    bound = (np.abs(p) + p.real) / (2 * y11.real) - y22.real
    return (y11, y12, y21, y22), bound


def _mp_errors(device, w_check, ours, ctrl) -> tuple[float, float]:
    from tests import reference as ref

    exact = np.array([float(ref.impedance_bound(device, x)) for x in w_check])
    e1 = float(np.max(np.abs(ours - exact) / np.abs(exact)))
    e2 = float(np.max(np.abs(ctrl - exact) / np.abs(exact)))
    return e1, e2


def _evaluations(quick: bool, tuned: bool) -> list[dict]:
    """The two full-evaluation rows, timed in this process with the allocator as given."""
    from app.allocator import tune_allocator

    if tuned and not tune_allocator(True):
        return []
    dev = hbfd()
    w = np.geomspace(1.0, dev.nyquist * 0.999, 2000)

    def full_eval():
        imp = ImpedanceDisplay(dev)  # fresh object: nothing cached
        imp.two_port(w)
        imp.evaluate(50e3, 100.0, w, refine=False)

    big = long_chain(200)
    wb = np.geomspace(1.0, big.nyquist * 0.999, 2000)
    label = "tuned allocator" if tuned else "default allocator"
    rows = [{"name": f"HBFD full evaluation, 2000 frequencies ({label})",
             **timeit(full_eval, repeat=300, quick=quick), "target_ms": 1.0},
            {"name": f"200-mass chain full evaluation, 2000 frequencies ({label})",
             **timeit(lambda: ImpedanceDisplay(big).evaluate(1e4, 10.0, wb, refine=False), repeat=30, quick=quick),
             "target_ms": 20.0}]
    return rows


def _evaluations_in_fresh_process(quick: bool, tuned: bool) -> list[dict]:
    """zwidth's own processes tune glibc's allocator at start (app/allocator.py); as a library in
    another process the defaults apply.  Each state is timed in a fresh interpreter: switching
    the allocator in the middle of a process measures the heap it inherited, not the setting."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    code = ("import json, sys; from tests.benchmarks.bench_core import _evaluations; "
            f"print(json.dumps(_evaluations({quick!r}, {tuned!r})))")
    out = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def run(quick: bool = False) -> list[dict]:
    """``quick``: one call of each; only the default allocator in a fresh process (this process,
    ``zwidth bench``'s, has the tuned one), 8 mpmath points instead of 40."""
    rows: list[dict] = []
    dev = hbfd()
    w = np.geomspace(1.0, dev.nyquist * 0.999, 2000)
    big = long_chain(200)
    wb = np.geomspace(1.0, big.nyquist * 0.999, 2000)

    def big_eval():
        ImpedanceDisplay(big).evaluate(1e4, 10.0, wb, refine=False)

    rows += _evaluations_in_fresh_process(quick, False)
    rows += _evaluations(quick, True) if quick else _evaluations_in_fresh_process(quick, True)
    from app.allocator import tune_allocator

    tune_allocator(True)
    tracemalloc.start()
    big_eval()
    peak = tracemalloc.get_traced_memory()[1] / 2**20
    tracemalloc.stop()
    rows.append({"name": "200-mass chain full evaluation: peak memory", "peak_MiB": round(peak, 2),
                 "N_times_n_MiB": round(2000 * 200 * 16 / 2**20, 2)})

    # python-control side by side (same Y(z), same bound)
    ours = timeit(lambda: ImpedanceDisplay(dev).bound_result(w), repeat=100, quick=quick)
    ctrl = timeit(lambda: control_route(dev, w), repeat=20, quick=quick)
    w_check = np.geomspace(1.0, dev.nyquist * 0.999, 8 if quick else 40)
    e_ours, e_ctrl = _mp_errors(dev, w_check, ImpedanceDisplay(dev).bound(w_check), control_route(dev, w_check)[1])
    rows.append({"name": "bound via zwidth (Y + eq. 9), 2000 frequencies", **ours,
                 "max_rel_err_vs_mpmath": e_ours})
    rows.append({"name": "bound via python-control (ss, c2d tustin, response), 2000 frequencies", **ctrl,
                 "max_rel_err_vs_mpmath": e_ctrl, "ratio": ctrl["median_ms"] / ours["median_ms"],
                 "target_ratio": 30.0})

    t, d = timed(lambda: ImpedanceDisplay(dev).max_stiffness(100.0), repeat=50, quick=quick)
    rows.append({"name": "largest k_c (b_c = 100), HBFD, cold", **t, "target_ms": 20.0,
                 "kc": d.kc, "frequencies_evaluated": d.evaluations})
    return rows


if __name__ == "__main__":
    for row in run(quick=False):
        print(row)
