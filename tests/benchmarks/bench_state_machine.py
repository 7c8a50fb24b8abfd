"""The GUI state machine's long run: 10^4 random steps on the real main window, and its memory.

The driver and its invariants are those of ``tests/app/test_state_machine.py`` (typed values in
and out of range, slider drags, undo/redo, display switch, add/remove mass, the design actions,
tab switches, save/load round trips, preset loads; after every step: no exception reached Qt, the
panel and the verdict agree with the model, undo back to the start restores the starting profile).
Here the steps are drawn by a seeded ``random.Random`` instead of hypothesis (whose example
buffer does not hold 10^4 steps).

Reported: the steps run, the time per step (wall and process CPU), the invariant failures (each
with its step number and the actions that led to it: the seed replays them), and the resident
memory (RSS): before the run (after every tab was drawn once in both displays), after
:data:`WARMUP_STEPS` random steps (the caches and Qt's glyph and pixmap caches filled), and at
the end.  The target is a growth under 50 MB over the whole run.  The memory compared is what
the process still uses (:func:`used_mb`: RSS after ``malloc_trim``), because zwidth's tuned
allocator keeps freed temporaries resident (the raw RSS, also reported, is a high-water mark of
the largest working set, not a leak).  The raw RSS is also printed every
:data:`PROGRESS_EVERY` steps (``python tests/benchmarks/bench_state_machine.py``), so that a
growth that keeps going can be told from one that flattens.  ``quick`` (the crash check of
``zwidth bench --quick``): :data:`QUICK_STEPS` steps from the window as it opens, without the
warm-up over every tab (drawing the Z-width tab alone takes seconds); the memory rows of so short a
run say nothing about leaks.
"""

from __future__ import annotations

import gc
import importlib.util
import os
import random
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

SEED = 20261201
STEPS, QUICK_STEPS = 10_000, 5
#: steps after which the run counts as warmed up (the "growth after warm-up" starts here)
WARMUP_STEPS = 1000
PROGRESS_EVERY = 500
#: relative weights of the actions
WEIGHTS = {"type_value": 6, "drag": 6, "undo": 4, "redo": 3, "switch_display": 1, "add_mass": 1,
           "remove_mass": 1, "design": 1, "switch_tab": 3, "save_and_load": 1, "load_preset": 0.5}


def _machine_module():
    tests = Path(__file__).resolve().parents[1]
    if str(tests) not in sys.path:  # the driver imports the test helpers (modal_guard) from tests/
        sys.path.insert(0, str(tests))
    path = tests / "app" / "test_state_machine.py"
    spec = importlib.util.spec_from_file_location("zwidth_state_machine", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def used_mb() -> float:
    """The resident memory the process still uses: :func:`rss_mb` after the heap's free memory is
    returned to the kernel (:func:`app.allocator.trim_heap`; zwidth's tuned allocator otherwise
    keeps up to 256 MB of freed temporaries resident, so the raw RSS is a high-water mark)."""
    from app.allocator import trim_heap

    gc.collect()
    trim_heap()
    return rss_mb()


def rss_mb() -> float:
    """The process's resident memory now (Linux: /proc/self/statm), in MB."""
    try:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20
    except (OSError, ValueError):
        import resource

        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def draw_step(driver, rng: random.Random, sm) -> tuple[str, tuple[Any, ...]]:
    """One random action and its arguments (the driver's method name and positional arguments)."""
    name = rng.choices(list(WEIGHTS), weights=list(WEIGHTS.values()))[0]
    if name == "type_value":
        return name, (rng.choice(driver.field_names()), rng.choice(sm.TYPED), rng.random())
    if name == "drag":
        return name, (rng.choice(driver.field_names()), [rng.randint(-40, 40) for _ in range(rng.randint(1, 6))])
    if name == "switch_display":
        return name, (rng.choice(["impedance", "admittance"]),)
    if name == "design":
        return name, (rng.choice(["maximize", "minimize"]),)
    if name == "switch_tab":
        return name, (rng.randrange(10),)
    if name == "load_preset":
        return name, (rng.choice(sm.PRESETS),)
    return name, ()


def _loadavg() -> str:
    try:
        return " ".join(f"{x:.1f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def _progress(i: int, t0: float, c0: float, driver) -> None:
    print(f"step {i}: RSS {rss_mb():.1f} MB (used {used_mb():.1f} MB), wall {time.perf_counter() - t0:.0f} s, "
          f"CPU {time.process_time() - c0:.0f} s, undo stack {driver.win.undo_stack.count()}, "
          f"load {_loadavg()}", file=sys.stderr, flush=True)


def run(quick: bool = False, steps: int | None = None) -> list[dict]:
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QSettings
    from PySide6.QtWidgets import QApplication

    from app.allocator import tune_allocator
    from app.window.main_window import make_application

    tune_allocator()
    QSettings.setDefaultFormat(QSettings.Format.IniFormat)
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, tempfile.mkdtemp())
    QApplication.instance() or make_application([])
    sm = _machine_module()
    steps = steps or (QUICK_STEPS if quick else STEPS)
    warmup = min(WARMUP_STEPS, steps // 3)
    rng = random.Random(SEED)
    driver = sm.GuiDriver(Path(tempfile.mkdtemp(prefix="zwidth-sm-")))
    counts: dict[str, int] = {}
    times: list[float] = []
    failures: list[str] = []
    recent: list[str] = []
    load_start = _loadavg()
    try:
        for i in range(0 if quick else 2 * driver.win.tabs.count()):  # every tab drawn once, in both displays
            driver.switch_display(["impedance", "admittance"][i % 2])
            driver.switch_tab(i // 2)
            driver.win.runner.wait(60000)
            driver.check()
        driver.reset_history()
        before = warm = used_mb()
        raw_before = rss_mb()
        t0, c0 = time.perf_counter(), time.process_time()
        _progress(0, t0, c0, driver)
        for i in range(1, steps + 1):
            t = time.perf_counter()
            name, args = draw_step(driver, rng, sm)
            recent = [*recent[-11:], f"{name}{args!r}"]
            try:
                getattr(driver, name)(*args)
                driver.check()
            except AssertionError as err:  # reported in the table; the run goes on from a clean state
                failures.append(f"step {i} {name}: {str(err)[:300]} | after: {'; '.join(recent)}")
                print("FAILURE", failures[-1], file=sys.stderr, flush=True)
                driver.errors.clear()
                driver.reset_history()
            times.append(time.perf_counter() - t)
            counts[name] = counts.get(name, 0) + 1
            if i == warmup:
                warm = used_mb()
            if i % PROGRESS_EVERY == 0:
                _progress(i, t0, c0, driver)
        total, cpu = time.perf_counter() - t0, time.process_time() - c0
        driver.win.runner.wait(60000)
        driver.pump(20)
        raw_after = rss_mb()
        after = used_mb()
    finally:
        driver.close()
    ms = np.array(times) * 1e3
    return [{"name": f"GUI state machine: {steps} random steps, invariants after each (seed {SEED})",
             "median_ms": float(np.median(ms)), "p95_ms": float(np.percentile(ms, 95)), "max_ms": float(ms.max()),
             "total_s": total, "cpu_s": cpu, "failures": len(failures),
             "load_start": load_start, "load_end": _loadavg()},
            {"name": "GUI state machine: resident memory over the run",
             "rss_before_mb": before, f"rss_at_step_{warmup}_mb": warm, "rss_after_mb": after,
             "raw_rss_before_mb": raw_before, "raw_rss_after_mb": raw_after,
             "growth_mb": after - before, "growth_after_warmup_mb": after - warm, "target_growth_mb": 50.0},
            {"name": "GUI state machine: actions run " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))},
            *({"name": f"GUI state machine: failure: {f}"} for f in failures[:5])]


if __name__ == "__main__":
    n = next((int(a) for a in sys.argv[1:] if a.isdigit()), None)
    for row in run(quick="--quick" in sys.argv, steps=n):
        print(row, flush=True)
