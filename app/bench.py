"""``zwidth bench``: run the benchmarks in ``tests/benchmarks/`` and print their table.

Every module ``tests/benchmarks/bench_*.py`` exposes ``run(quick: bool) -> list[dict]``.
Each row has a ``name`` and timing columns (``median_ms``, ``p95_ms``), and may carry a
``target_ms`` or ``target_ratio`` and error columns.  Timing limits are not tests: the
command prints the table and fails on nothing but a crash.  The full run (without
``--quick``) also writes the table into ``BENCHMARKS.md`` between markers, with the date
and the machine.

``--quick`` (run by ``make test``, about 30 s) is a crash check of every benchmark: each timed
call once without warm-up (``tests.benchmarks.common.timed``), the smallest sizes, a few steps of
the GUI state machine and one identification replicate; the long runs belong to the full run.
Its times are those of single cold calls, not comparable with the full run's.
"""

from __future__ import annotations

import datetime as _dt
import importlib
import math
import re
import sys
import time
from pathlib import Path

__all__ = ["run_bench", "format_rows", "merge_tables"]

BEGIN = "<!-- bench:begin -->"
END = "<!-- bench:end -->"


def _repo_root() -> Path | None:
    here = Path(__file__).resolve().parent.parent
    return here if (here / "tests" / "benchmarks").is_dir() else None


def _fmt(v: object) -> str:
    if isinstance(v, float):
        if math.isinf(v) or math.isnan(v):
            return str(v)
        return f"{v:.4g}"
    return str(v)


def format_rows(module: str, rows: list[dict]) -> str:
    """A Markdown table of one benchmark module's rows."""
    cols: list[str] = []
    for r in rows:
        for k in r:
            if k != "name" and k not in cols:
                cols.append(k)
    lines = [f"### {module}", "", "| benchmark | " + " | ".join(cols) + " |",
             "|---|" + "---|" * len(cols)]
    for r in rows:
        lines.append(f"| {r.get('name', '')} | " + " | ".join(_fmt(r.get(c, "")) for c in cols) + " |")
    return "\n".join(lines)


def run_bench(quick: bool = False, only: str | None = None, write: bool | None = None) -> int:
    root = _repo_root()
    if root is None:
        print("zwidth bench: the benchmarks live in tests/benchmarks of a source checkout; "
              "run it from a clone (pip install -e .)", file=sys.stderr)
        return 1
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    names = sorted(p.stem for p in (root / "tests" / "benchmarks").glob("bench_*.py"))
    if only:
        names = [n for n in names if only in n]
    sections = []
    t0, c0 = time.perf_counter(), time.process_time()
    for name in names:
        mod = importlib.import_module(f"tests.benchmarks.{name}")
        start, cpu = time.perf_counter(), time.process_time()
        rows = mod.run(quick=quick)
        table = format_rows(name, rows)
        print(table)
        print(f"({name}: {time.perf_counter() - start:.1f} s, CPU {time.process_time() - cpu:.1f} s)\n", flush=True)
        sections.append(table)
    total = time.perf_counter() - t0
    # the CPU time (this process's threads, not its children) says what the run cost on a shared machine
    print(f"all benchmarks: {total:.1f} s, CPU {time.process_time() - c0:.1f} s ({'quick' if quick else 'full'})")
    if write if write is not None else not quick:
        from tests.benchmarks.common import machine

        stamp = _dt.datetime.now().strftime("%Y-%m-%d %H:%M")
        run = "quick" if quick else "full"
        path = root / "BENCHMARKS.md"
        text = path.read_text() if path.exists() else f"# Benchmarks\n\n{BEGIN}\n{END}\n"
        path.write_text(merge_tables(text, sections, f"{stamp} on {machine()} ({run} run, {total:.0f} s)",
                                     partial=bool(only)))
        print(f"wrote {path}")
    return 0


def merge_tables(text: str, sections: list[str], run: str, partial: bool = False) -> str:
    """``text`` (BENCHMARKS.md) with its tables block holding ``sections``.

    A full run replaces the block.  A partial run (``--only``) replaces only the modules it ran
    (``### bench_name`` sections) and keeps every other table, with a line saying which tables
    are newer (an earlier partial run's line keeps the modules not re-run since)."""
    if BEGIN not in text or END not in text:
        text += f"\n{BEGIN}\n{END}\n"
    head, rest = text.split(BEGIN, 1)
    old, tail = rest.split(END, 1)
    if not partial:
        return f"{head}{BEGIN}\nRun on {run}.\n\n" + "\n\n".join(sections) + f"\n{END}{tail}"
    parts = re.split(r"(?m)^(?=### )", old)
    intro = [q for q in parts if not q.startswith("### ")]
    tables = {q.split("\n", 1)[0][4:].strip(): q.strip() for q in parts if q.startswith("### ")}
    for sec in sections:
        tables[sec.split("\n", 1)[0][4:].strip()] = sec.strip()
    ran = [sec.split("\n", 1)[0][4:].strip() for sec in sections]
    lines = []
    for ln in "".join(intro).strip().splitlines():
        if ln.startswith("Partly re-run"):  # an earlier partial run: keep the modules this one did not re-run
            head_, _, mods = ln.rstrip(".").rpartition(": ")
            kept = [m for m in mods.split(", ") if m not in ran]
            if not kept:
                continue
            ln = f"{head_}: {', '.join(kept)}."
        lines.append(ln)
    lines.append(f"Partly re-run on {run}: {', '.join(ran)}.")
    return f"{head}{BEGIN}\n" + "\n".join(lines) + "\n\n" + "\n\n".join(tables.values()) + f"\n{END}{tail}"
