"""The one progress and cancel protocol in the app (issue 21): the worker, the graph and the report.

The worker drops a job stopped by :class:`~analysis.progress.OperationCancelled` as quietly as one
that returned ``None`` (no failure, no traceback); a real fit on the worker stops at its next model
evaluation; the report's build stops between stages through ``cancelled()`` and raises the same
exception (its former name ``ReportCancelled``), and File → Export Report answers False.
Deterministic: the jobs wait on events the test sets; the test waits for signals, never for time.
"""

from __future__ import annotations

import threading
from types import SimpleNamespace

import numpy as np
import pytest
from PySide6.QtWidgets import QProgressDialog, QWidget

from analysis.identify import device_response, fit_chain, make_measurement
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.progress import Cancelled, OperationCancelled, Progress, check_cancelled
from app.core.worker import TaskRunner


@pytest.fixture
def runner(qapp):
    r = TaskRunner(max_threads=2)
    yield r
    r.shutdown()


def _record(runner: TaskRunner) -> dict[str, list]:
    seen: dict[str, list] = {"finished": [], "cancelled": [], "failed": []}
    runner.finished.connect(lambda n, v: seen["finished"].append((n, v)))
    runner.cancelled.connect(lambda n: seen["cancelled"].append(n))
    runner.failed.connect(lambda n, m: seen["failed"].append((n, m)))
    return seen


def test_the_graph_uses_the_one_protocol():
    import app.core.compute_graph as graph
    import app.core.worker as worker
    from app.report.content import ReportCancelled

    assert graph.Progress is Progress and graph.Cancelled is Cancelled
    assert worker.Job.__args__[:2] == (Progress, Cancelled)
    assert ReportCancelled is OperationCancelled


def test_the_worker_drops_a_job_that_raises_the_one_exception(runner, qtbot, capfd):
    seen = _record(runner)
    started = threading.Event()

    def job(progress, cancelled):
        started.set()
        while True:
            check_cancelled(cancelled)
            threading.Event().wait(0.001)

    runner.submit("map", job)
    assert started.wait(30)
    runner.cancel("map")
    assert runner.wait(30000)
    qtbot.waitUntil(lambda: runner.dropped == 1, timeout=30000)
    assert seen == {"finished": [], "cancelled": ["map"], "failed": []}
    assert "Traceback" not in capfd.readouterr().err  # a cancel is not an error


def test_a_fit_on_the_worker_stops_at_its_next_model_evaluation(runner, qtbot):
    device = load_profile(bundled_profiles()["rigid"]).device
    w = np.geomspace(1.0, 1e3, 40)
    m = make_measurement(w, device_response(device, w), "actuator", "free")
    seen = _record(runner)
    first_poll, go = threading.Event(), threading.Event()
    polls = {"after_cancel": 0}

    def job(progress, cancelled):
        def hook() -> bool:
            if not first_poll.is_set():
                first_poll.set()
                go.wait(30)  # the test cancels now
            stop = cancelled()
            polls["after_cancel"] += stop
            return stop

        return fit_chain([m], 1, cancelled=hook)

    runner.submit("fit", job)
    assert first_poll.wait(30)
    runner.cancel("fit")
    go.set()
    assert runner.wait(30000)
    qtbot.waitUntil(lambda: runner.dropped == 1, timeout=30000)
    assert polls["after_cancel"] == 1  # no model evaluation after the first true
    assert seen["finished"] == [] and seen["failed"] == []


@pytest.fixture
def rigid(qapp):
    from app.report.figures import ensure_app

    ensure_app()
    return load_profile(bundled_profiles()["rigid"])


def test_the_report_reports_each_stage_and_stops_between_them(rigid, tmp_path):
    from app.report import build_report, report_stages

    steps: list[tuple[int, int]] = []
    page = tmp_path / "r.html"
    build_report(rigid, page, sampled=False, progress=lambda d, t: steps.append((d, t)))
    total = len(report_stages("html")) - 1
    assert steps == [(i, total) for i in range(total + 1)] and page.stat().st_size > 0

    from app.report.model import ReportCancelled

    done: list[int] = []
    stopped = tmp_path / "stopped.html"
    with pytest.raises(ReportCancelled, match="the report was cancelled"):
        build_report(rigid, stopped, sampled=False, progress=lambda d, t: done.append(d),
                     cancelled=lambda: len(done) >= 2)
    assert done == [0, 1] and not stopped.exists()


def test_export_report_answers_false_on_cancel(rigid, tmp_path, monkeypatch, qtbot):
    from app.report.action import export_report

    window = QWidget()
    qtbot.addWidget(window)
    window.model = SimpleNamespace(profile=rigid)
    polls = []
    monkeypatch.setattr(QProgressDialog, "wasCanceled", lambda self: polls.append(1) or True)
    target = tmp_path / "cancelled.pdf"
    assert export_report(window, str(target)) is False
    assert len(polls) == 1 and not target.exists()  # stopped before the analysis
