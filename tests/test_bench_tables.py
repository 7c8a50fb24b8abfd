"""`zwidth bench --only X --write` merges its tables into BENCHMARKS.md and keeps the others; the
quick run times each benchmark once."""

from __future__ import annotations

from app.bench import merge_tables

DOC = """# Benchmarks

prose kept

<!-- bench:begin -->
Run on day 1 (full run).

### bench_a

| benchmark | ms |
|---|---|
| a | 1 |

### bench_b

| benchmark | ms |
|---|---|
| b | 2 |
<!-- bench:end -->
after
"""


def test_partial_run_replaces_only_its_tables():
    new_b = "### bench_b\n\n| benchmark | ms |\n|---|---|\n| b | 3 |"
    out = merge_tables(DOC, [new_b], "day 2", partial=True)
    assert "| a | 1 |" in out and "| b | 3 |" in out and "| b | 2 |" not in out
    assert "Run on day 1 (full run)." in out and "Partly re-run on day 2: bench_b." in out
    assert out.startswith("# Benchmarks\n\nprose kept") and out.rstrip().endswith("after")
    again = merge_tables(out, [new_b], "day 3", partial=True)
    assert again.count("Partly re-run") == 1 and "day 3" in again
    new_a = "### bench_a\n\n| benchmark | ms |\n|---|---|\n| a | 5 |"
    both = merge_tables(merge_tables(DOC, [new_a, new_b], "day 2", partial=True), [new_a], "day 3", partial=True)
    # each table's date stays said: b's day-2 run is kept, a's moves to day 3
    assert "Partly re-run on day 2: bench_b." in both and "Partly re-run on day 3: bench_a." in both
    assert both.count("Partly re-run") == 2 and "| a | 5 |" in both and "| b | 3 |" in both


def test_full_run_replaces_the_block():
    out = merge_tables(DOC, ["### bench_c\n\n| c |"], "day 2")
    assert "bench_a" not in out and "bench_b" not in out and "### bench_c" in out
    assert "Run on day 2." in out and out.rstrip().endswith("after")


def test_quick_timing_is_one_call_and_the_full_one_repeats():
    """`zwidth bench --quick` calls each timed function once (no warm-up); the full run warms up,
    then times ``repeat`` calls; both return the last call's value."""
    from tests.benchmarks.common import timed, timeit

    calls: list[int] = []

    def fn() -> int:
        calls.append(len(calls))
        return len(calls)

    stats, value = timed(fn, repeat=7, quick=True)
    assert calls == [0] and value == 1 and stats["runs"] == 1 and stats["median_ms"] >= 0.0
    calls.clear()
    stats, value = timed(fn, repeat=7)
    assert len(calls) == 8 and value == 8 and stats["runs"] == 7
    assert stats["p95_ms"] >= stats["median_ms"] >= 0.0
    calls.clear()
    assert timeit(fn, repeat=3, quick=True)["runs"] == 1 and len(calls) == 1
