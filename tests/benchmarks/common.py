"""Shared helpers for the benchmarks: timing, devices, machine description."""

from __future__ import annotations

import os
import platform
import time
from collections.abc import Callable
from typing import TypeVar

import numpy as np

from analysis import Device

from tests.hbfd_fixtures import make_hbfd

T = TypeVar("T")


def hbfd(ratio: float = 0.1, b4: float = 5.0) -> Device:
    """The paper's HBFD worst-case configuration (Adams et al., section V): the tests' device."""
    return make_hbfd(ratio, b4)


def long_chain(n: int, seed: int = 0) -> Device:
    """A random n-mass chain with a 5 N s/m damper to ground on the actuator."""
    rng = np.random.default_rng(seed)
    return Device.from_damping_ratios(rng.uniform(0.1, 1.0, n), rng.uniform(1e4, 1e6, n - 1), 0.05,
                                      ground_dampings=np.r_[np.zeros(n - 1), 5.0], sample_time=1e-3)


def timed(fn: Callable[[], T], repeat: int = 30, min_time: float = 0.0, quick: bool = False
          ) -> tuple[dict[str, float], T]:
    """:func:`timeit` and the value of the last call (so that a row's result costs no extra call)."""
    t = time.perf_counter()
    value = fn()  # the warm-up
    if quick:  # the crash check of ``zwidth bench --quick``: this one (cold) call is all
        ms = (time.perf_counter() - t) * 1e3
        return {"median_ms": ms, "p95_ms": ms, "runs": 1}, value
    ts = []
    start = time.perf_counter()
    while len(ts) < repeat or time.perf_counter() - start < min_time:
        t = time.perf_counter()
        value = fn()
        ts.append(time.perf_counter() - t)
    a = np.array(ts) * 1e3
    return {"median_ms": float(np.median(a)), "p95_ms": float(np.percentile(a, 95)), "runs": len(ts)}, value


def timeit(fn: Callable[[], object], repeat: int = 30, min_time: float = 0.0, quick: bool = False
           ) -> dict[str, float]:
    """Median and 95th percentile wall time in ms of ``repeat`` calls (after one warm-up).

    ``quick``: one call, no warm-up (``runs`` 1): ``zwidth bench --quick`` checks that every
    benchmark runs; its times are those of a single cold call, not comparable to the full run's."""
    return timed(fn, repeat, min_time, quick)[0]


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"numpy {np.__version__}, {platform.system()} {platform.release()}")
