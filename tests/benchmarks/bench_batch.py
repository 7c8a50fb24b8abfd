"""Batch benchmarks (issue 24): the robust renderable space of 1000 devices on a 21 x 21 (M, B) grid.

The devices are 1000 seeded samples of a box around a rigid 1-DOF device (the handle's mass
0.3-0.8 kg, its ground damping 0.5-4 N s/m, T = 1 ms); each device's task is
``renderable_space(device, M, B)`` with M from -0.2 to 0.2 kg and B from 0.5 to 50.5 N s/m (21 each,
stability only, one sample of delay).  It runs in this process (1 worker), on a local pool of 2
processes and on a Dask ``LocalCluster`` of 2 worker processes (one thread each), each row with
its speed-up over the one worker and whether its result equals the one worker's bit for bit.  The per-task overhead is measured apart, with a task that
does no work (:func:`tests.batch_devices.zeros`) over the same devices and chunks: its wall time
over the number of tasks.  The pool's rows include starting its processes from the fork server
(the first pool of a process also starts the server); the cluster's rows exclude starting the
cluster (reported on its own row).

``quick`` (under 1 s): 4 devices on a 5 x 5 grid in this process, no pool and no cluster (a pool's
first start alone takes 1-4 s: the tests check the pool and the cluster).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from functools import partial

import numpy as np

from analysis.identify import parameter_box
from analysis.sampled.batch import box_samples, intersect_devices, robust_renderable_space

from tests.batch_devices import rigid, zeros

SEED = 24


def _devices(n: int) -> list:
    box = parameter_box(rigid(), {"masses[0]": (0.3, 0.8), "ground_dampings[0]": (0.5, 4.0)})
    return box_samples(box, n, seed=SEED)


def _clock(fn: Callable[[], object]) -> tuple[float, object]:
    t = time.perf_counter()
    value = fn()
    return time.perf_counter() - t, value


def _tasks(n: int, workers: int) -> int:
    size = min(16, max(1, -(-n // (4 * workers))))  # the default chunks of analysis.sampled.batch
    return -(-n // size)


def _rows(label: str, run: Callable[..., object], devices: list, grid: str, base: tuple[float, object] | None,
          **where: object) -> tuple[list[dict], tuple[float, object]]:
    n = len(devices)
    workers = 2 if "client" in where else int(where.get("workers", 1))
    tasks = n if workers == 1 and "client" not in where else _tasks(n, workers)
    t_work, r = _clock(lambda: run(devices, **where))
    t_idle, _ = _clock(lambda: intersect_devices(partial(zeros, shape=r.k_max.shape), devices, **where))
    row = {"name": f"robust space, {n} devices x {grid}, {label}", "median_ms": t_work * 1e3, "runs": 1,
           "tasks": tasks, "per_device_ms": t_work * 1e3 / n,
           "speedup": (base[0] / t_work) if base else 1.0,
           "same_as_1_worker": base is None or bool(np.array_equal(r.k_max, base[1].k_max)
                                                    and np.array_equal(r.binding, base[1].binding)),
           "overhead_per_task_ms": t_idle * 1e3 / tasks,
           "robust_volume_cells": int(np.count_nonzero(r.k_max)), "binding_devices": len(set(r.binding.flat))}
    return [row], (t_work, r)


def _cluster_rows(run: Callable[..., object], devices: list, grid: str, base: tuple[float, object]) -> list[dict]:
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        return [{"name": "robust space on a LocalCluster", "note": "the distributed extra is not installed"}]
    t_start, cluster = _clock(lambda: LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                                   dashboard_address=None))
    try:
        with Client(cluster) as client:
            rows, _ = _rows("LocalCluster of 2 processes", run, devices, grid, base, client=client)
    finally:
        cluster.close()
    rows.append({"name": "LocalCluster of 2 processes: start", "median_ms": t_start * 1e3, "runs": 1})
    return rows


def run(quick: bool = False) -> list[dict]:
    """``quick``: 4 devices, a 5 x 5 grid, in this process only."""
    n, size = (4, 5) if quick else (1000, 21)
    mass, damping = np.linspace(-0.2, 0.2, size), np.linspace(0.5, 50.5, size)
    grid = f"{size} x {size} (M, B)"
    space = partial(robust_renderable_space, mass=mass, damping=damping, delay_samples=1)
    devices = _devices(n)
    rows, base = _rows("1 worker (this process)", space, devices, grid, None, workers=1)
    if quick:
        return rows
    rows += _rows("pool of 2 processes", space, devices, grid, base, workers=2)[0]
    rows += _cluster_rows(space, devices, grid, base)
    return rows


if __name__ == "__main__":  # pragma: no cover
    for row in run(quick=True):
        print(row)
