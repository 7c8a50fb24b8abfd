"""The analysis as a library (issue 21): a full evaluation with glibc's default allocator settings.

zwidth's own processes tune glibc's allocator at start (:func:`app.allocator.tune_allocator`); a
script that imports only ``analysis`` runs with the defaults, under which freed memory at the top
of the heap is given back to the kernel and page-faulted in again by the next evaluation.  The
chain responses therefore keep their work arrays in a per-thread workspace
(``analysis.chain.response``).  This benchmark times the full evaluations of the HBFD at 2000
frequencies (the impedance display as in ``bench_core``: Y, bound, margin, Z_min, Z_max; and the
admittance display with a PD loop) in fresh interpreters, alternately with and without the
tuning, and reports the median over the processes of each process's median, the ratio untuned /
tuned and the minor page faults per evaluation (the cost the tuning avoided: about 170 per
impedance evaluation before the workspace).  ``quick`` (the crash check) starts one fresh
interpreter, the default allocator's, and measures the tuned state in ``zwidth bench``'s own
process (as ``bench_core``'s quick run does).  The allocator is never switched inside a process:
that would measure the heap the process inherited, not the setting.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np

from analysis import AdmittanceDisplay, ImpedanceDisplay

from tests.benchmarks.common import hbfd, timeit

DISPLAYS = ("impedance", "admittance")


def full_evaluation(display: str) -> Callable[[], None]:
    """One full evaluation of the HBFD at 2000 frequencies from a fresh display (nothing cached)."""
    dev = hbfd()
    w = np.geomspace(1.0, dev.nyquist * 0.999, 2000)
    if display == "impedance":
        def run() -> None:
            imp = ImpedanceDisplay(dev)
            imp.two_port(w)
            imp.evaluate(50e3, 100.0, w, refine=False)
    else:
        def run() -> None:
            adm = AdmittanceDisplay(dev, 1e4, 20.0)
            adm.two_port(w)
            adm.evaluate(0.5, 50.0, w, refine=False)
    return run


def _minflt() -> int:
    """Minor page faults of this process so far (0 where there is no ``resource`` module)."""
    try:
        import resource
    except ImportError:  # Windows
        return 0
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


def measure(repeat: int = 300, quick: bool = False) -> dict[str, dict[str, float]]:
    """Median time and minor page faults per evaluation of each display, in this process with
    the allocator as it is (``quick``: one call of each, the crash check of ``zwidth bench --quick``)."""
    out = {}
    for display in DISPLAYS:
        fn = full_evaluation(display)
        for _ in range(1 if quick else 20):  # warm up: the workspace and the heap reach their steady state
            fn()
        f0 = _minflt()
        for _ in range(repeat):
            fn()
        faults = (_minflt() - f0) / repeat
        out[display] = {**timeit(fn, repeat=repeat, quick=quick), "minflt_per_eval": faults}
    return out


def measure_in_fresh_process(tuned: bool, repeat: int = 300, quick: bool = False) -> dict[str, dict[str, float]]:
    """:func:`measure` in a new interpreter, with ``tune_allocator()`` called first or not at all."""
    root = Path(__file__).resolve().parents[2]
    tune = "from app.allocator import tune_allocator; assert tune_allocator(True); " if tuned else ""
    code = (f"import json; {tune}from tests.benchmarks.bench_untuned import measure; "
            f"print(json.dumps(measure({repeat!r}, {quick!r})))")
    proc = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True, check=True,
                          timeout=600)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _measure_tuned_here(quick: bool) -> dict[str, dict[str, float]]:
    """:func:`measure` in this process with the tuned allocator (``zwidth bench``'s own setting)."""
    from app.allocator import tune_allocator

    tune_allocator(True)
    return measure(1, quick)


def run(quick: bool = False) -> list[dict]:
    if not sys.platform.startswith("linux"):  # tune_allocator acts on glibc only: nothing to compare
        return [{"name": "default vs tuned allocator: not Linux, not measured"}]
    rounds, repeat = (1, 1) if quick else (10, 300)
    runs: dict[tuple[str, bool], list[dict[str, float]]] = {(d, t): [] for d in DISPLAYS for t in (False, True)}
    for i in range(rounds):
        for tuned in ((False, True) if i % 2 == 0 else (True, False)):  # alternate which state goes first
            # quick (a crash check): the tuned state in this process, as bench_core's quick run, one
            # interpreter fewer to start
            res = _measure_tuned_here(quick) if quick and tuned else measure_in_fresh_process(tuned, repeat, quick)
            for d in DISPLAYS:
                runs[(d, tuned)].append(res[d])
    rows: list[dict] = []
    for d in DISPLAYS:
        med = {}
        for tuned in (False, True):
            rs = runs[(d, tuned)]
            med[tuned] = statistics.median(r["median_ms"] for r in rs)
            label = "tuned allocator" if tuned else "default allocator"
            rows.append({"name": f"HBFD {d} display full evaluation, 2000 frequencies ({label})",
                         "median_ms": med[tuned], "p95_ms": statistics.median(r["p95_ms"] for r in rs),
                         "runs": sum(r["runs"] for r in rs), "processes": len(rs),
                         "minflt_per_eval": statistics.median(r["minflt_per_eval"] for r in rs)})
        rows.append({"name": f"HBFD {d} display: default / tuned allocator", "ratio": med[False] / med[True],
                     "target_ratio": 1.15})
    return rows


if __name__ == "__main__":
    for row in run(quick="--quick" in sys.argv):
        print(row)
