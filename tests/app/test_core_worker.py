"""The TaskRunner on its own: a newer job supersedes the running one; a cancelled job never finishes.

Deterministic: the jobs wait on events the test sets, and the test waits for signals, never for time.
"""

from __future__ import annotations

import threading
import time

import pytest

from app.core.worker import TaskRunner


@pytest.fixture
def runner(qapp):
    r = TaskRunner(max_threads=2)
    yield r
    r.shutdown()


def record(runner: TaskRunner) -> dict[str, list]:
    seen: dict[str, list] = {"finished": [], "cancelled": [], "failed": [], "progress": []}
    runner.finished.connect(lambda n, v: seen["finished"].append((n, v)))
    runner.cancelled.connect(lambda n: seen["cancelled"].append(n))
    runner.failed.connect(lambda n, m: seen["failed"].append((n, m)))
    runner.progress.connect(lambda n, d, t: seen["progress"].append((n, d, t)))
    return seen


def blocking_job(started: threading.Event, release: threading.Event, result: object):
    def job(progress, cancelled):
        started.set()
        release.wait(30)
        progress(1, 1)
        return result
    return job


def test_a_newer_job_supersedes_the_running_one(runner, qtbot):
    seen = record(runner)
    started, release = threading.Event(), threading.Event()
    first = runner.submit("chart", blocking_job(started, release, "old"))
    assert started.wait(30)
    second = runner.submit("chart", lambda progress, cancelled: "new")
    assert second == first + 1
    with qtbot.waitSignal(runner.finished, timeout=30000):
        pass
    assert seen["finished"] == [("chart", "new")]
    release.set()  # the superseded job now finishes: its result is dropped
    assert runner.wait(30000)
    qtbot.waitUntil(lambda: runner.dropped == 1, timeout=30000)
    assert seen["finished"] == [("chart", "new")]
    assert ("chart", 1, 1) not in seen["progress"]  # a stale job's progress is not reported either
    assert not runner.is_running("chart")


def test_a_cancelled_job_reports_cancelled_not_finished(runner, qtbot):
    seen = record(runner)
    started, stopped = threading.Event(), threading.Event()

    def job(progress, cancelled):
        started.set()
        while not cancelled():
            stopped.wait(0.001)
        stopped.set()
        return "should be dropped"

    runner.submit("map", job)
    assert started.wait(30)
    assert runner.is_running("map")
    runner.cancel("map")
    assert seen["cancelled"] == ["map"]
    assert not runner.is_running("map")
    assert stopped.wait(30)  # the job saw the cancellation
    assert runner.wait(30000)
    qtbot.waitUntil(lambda: runner.dropped == 1, timeout=30000)
    assert seen["finished"] == [] and seen["failed"] == []


def test_jobs_of_different_names_run_side_by_side(runner, qtbot):
    seen = record(runner)
    started, release = threading.Event(), threading.Event()
    runner.submit("slow", blocking_job(started, release, 1))
    assert started.wait(30)
    with qtbot.waitSignal(runner.finished, timeout=30000):
        runner.submit("fast", lambda progress, cancelled: 2)
    assert seen["finished"] == [("fast", 2)]
    assert runner.is_running("slow")
    with qtbot.waitSignal(runner.finished, timeout=30000):
        release.set()
    assert seen["finished"] == [("fast", 2), ("slow", 1)]
    assert runner.running() == []


def test_a_failing_job_reports_its_error(runner, qtbot):
    seen = record(runner)

    def job(progress, cancelled):
        raise ValueError("no such design")

    with qtbot.waitSignal(runner.failed, timeout=30000):
        runner.submit("bad", job)
    assert seen["failed"] == [("bad", "ValueError: no such design")]
    assert seen["finished"] == [] and not runner.is_running("bad")


def test_progress_reaches_the_gui_at_most_twenty_times_a_second_with_its_first_and_last(runner, qtbot):
    """A job reporting per step (10 000 steps) sends the GUI its first report, its last and at most
    one every PROGRESS_INTERVAL between them: a progress bar repaints on every new value."""
    from app.core.worker import PROGRESS_INTERVAL

    seen = record(runner)
    elapsed: list[float] = []

    def job(progress, cancelled):
        start = time.monotonic()
        for i in range(10_001):
            progress(i, 10_000)
        elapsed.append(time.monotonic() - start)
        return "done"

    with qtbot.waitSignal(runner.finished, timeout=30000):
        runner.submit("rows", job)
    qtbot.waitUntil(lambda: seen["progress"] and seen["progress"][-1][1] == 10_000, timeout=30000)
    done = [d for _n, d, _t in seen["progress"]]
    assert done[0] == 0 and done[-1] == 10_000 and done == sorted(done)
    assert len(done) <= 2 + elapsed[0] / PROGRESS_INTERVAL + 1, (len(done), elapsed)
    assert len(done) < 10_001
