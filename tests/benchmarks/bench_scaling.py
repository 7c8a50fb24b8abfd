"""Scaling of the bound evaluation with the number of frequencies N and of masses n.

Time (median) and peak traced memory of ``ImpedanceDisplay(dev).bound_result(w)`` for
N = 10^2 .. 10^5 (HBFD) and n = 1 .. 500 (random chains, N = 2000), with the exponents of
least-squares power-law fits over the upper part of each range (where fixed per-call
overhead no longer dominates).  The method is O(N n) in time and memory by construction.
"""

from __future__ import annotations

import tracemalloc

import numpy as np

from analysis import ImpedanceDisplay

from tests.benchmarks.common import hbfd, long_chain, timeit


def _peak_mib(fn) -> float:
    tracemalloc.start()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


def _fit(x, y) -> float:
    return float(np.polyfit(np.log(x), np.log(y), 1)[0])


def run(quick: bool = False) -> list[dict]:
    """``quick``: one call per size, N up to 10^4 and n up to 100."""
    rows: list[dict] = []
    dev = hbfd()
    Ns = [100, 1000, 10_000] if quick else [100, 300, 1000, 3000, 10_000, 30_000, 100_000]
    times, mems = [], []
    for N in Ns:
        w = np.geomspace(1.0, dev.nyquist * 0.999, N)
        t = timeit(lambda w=w: ImpedanceDisplay(dev).bound_result(w), repeat=10, quick=quick)
        m = _peak_mib(lambda w=w: ImpedanceDisplay(dev).bound_result(w))
        times.append(t["median_ms"])
        mems.append(m)
        rows.append({"name": f"HBFD bound, N = {N}", "median_ms": t["median_ms"], "peak_MiB": round(m, 3)})
    k = len(Ns) // 2
    rows.append({"name": "fitted exponent in N (upper half)", "time_exponent": _fit(Ns[k:], times[k:]),
                 "memory_exponent": _fit(Ns[k:], mems[k:])})
    ns = [1, 10, 100] if quick else [1, 2, 5, 10, 20, 50, 100, 200, 500]
    times, mems = [], []
    w = np.geomspace(1.0, dev.nyquist * 0.999, 2000)
    for n in ns:
        d = long_chain(n) if n > 1 else long_chain(2).replace(masses=[1.0], stiffnesses=[], dampings=[],
                                                              ground_dampings=[5.0], sensor_element=0)
        t = timeit(lambda d=d: ImpedanceDisplay(d).bound_result(w), repeat=10, quick=quick)
        m = _peak_mib(lambda d=d: ImpedanceDisplay(d).bound_result(w))
        times.append(t["median_ms"])
        mems.append(m)
        rows.append({"name": f"bound, n = {n} masses, N = 2000", "median_ms": t["median_ms"],
                     "peak_MiB": round(m, 3)})
    k = len(ns) // 2
    rows.append({"name": "fitted exponent in n (upper half)", "time_exponent": _fit(ns[k:], times[k:]),
                 "memory_exponent": _fit(ns[k:], mems[k:])})
    return rows


if __name__ == "__main__":
    for r in run(quick=False):
        print(r)
