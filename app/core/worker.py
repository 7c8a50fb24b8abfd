"""Background work: one :class:`TaskRunner` runs named jobs on its own thread pool.

A job is ``fn(progress, cancelled) -> result``; ``progress(done, total)`` reports, ``cancelled()``
says whether to stop early (the one protocol of :mod:`analysis.progress`): a job that stops
returns ``None`` or raises :class:`~analysis.progress.OperationCancelled`, and either way its end
is dropped quietly (it was cancelled or superseded, so nobody waits for it).  Submitting a job under a name supersedes the running job of that
name: its generation number becomes stale and its result is dropped when it arrives.
"""

from __future__ import annotations

import sys
import threading
import time
import traceback
from collections.abc import Callable
from typing import Any

from app import qt_compat  # noqa: F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import QObject, QRunnable, QThreadPool, Signal, Slot

from analysis.errors import ValidationError
from analysis.progress import Cancelled, OperationCancelled, Progress

__all__ = ["TaskRunner", "Job"]

Job = Callable[[Progress, Cancelled], Any]

#: The least time between two progress reports of a job that reach the GUI [s] (20 per second).
PROGRESS_INTERVAL = 0.05


class _Relay(QObject):
    """Carries a job's reports from the worker thread to the GUI thread (queued signals)."""

    progress = Signal(str, int, int, int)  # name, generation, done, total
    done = Signal(str, int)  # the result waits in the runner's mailbox (no Python objects in signals)
    error = Signal(str, int, str)


class _GilPolicy:
    """Shortens the interpreter's GIL switch interval while jobs run.

    A CPU-bound worker otherwise holds the GIL for up to 5 ms (CPython's default interval) each
    time the GUI thread wants it back, and a repaint that re-enters Python hundreds of times would
    stall for far longer than a frame.  With 0.2 ms the GUI thread keeps its frame rate; the
    worker loses a few per cent.  The previous interval is restored when the last job ends.
    """

    INTERVAL = 2e-4

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._active = 0
        self._saved = sys.getswitchinterval()

    def __enter__(self) -> None:
        with self._lock:
            if self._active == 0:
                self._saved = sys.getswitchinterval()
                sys.setswitchinterval(min(self._saved, self.INTERVAL))
            self._active += 1

    def __exit__(self, *exc: object) -> None:
        with self._lock:
            self._active -= 1
            if self._active == 0:
                sys.setswitchinterval(self._saved)


class _GuiPriority:
    """Lets the GUI thread ask running jobs to step aside for a moment.

    Under the GIL a CPU-bound job and the GUI thread take turns every switch interval, so an edit
    whose own work takes 20 ms takes twice as long while a chart is computing.  After each edit
    the GUI calls :meth:`defer` for a short window; jobs pause (sleeping, so without the GIL) at
    their next cancellation check until the window has passed.  A job that checks between grid
    points therefore delays the GUI by at most one grid point's work.
    """

    def __init__(self) -> None:
        self._until = 0.0
        self.pauses = 0  # how often a job stepped aside (benchmarks, tests)

    def defer(self, seconds: float) -> None:
        self._until = max(self._until, time.monotonic() + seconds)

    def checkpoint(self, stop: threading.Event) -> bool:
        """``True`` when the job should stop; otherwise returns once the GUI's window is over."""
        paused = False
        while not stop.is_set():
            wait = self._until - time.monotonic()
            if wait <= 0:
                break
            paused = True
            time.sleep(min(wait, 0.005))
        if paused:
            self.pauses += 1
        return stop.is_set()


class _Runnable(QRunnable):
    def __init__(self, name: str, generation: int, fn: Job, relay: _Relay, stop: threading.Event,
                 mailbox: dict, lock: threading.Lock, gil: _GilPolicy, priority: _GuiPriority) -> None:
        super().__init__()
        self._gil = gil
        self._priority = priority
        # autoDelete (Qt's default): the pool deletes the runnable after run().  Without it PySide's
        # pool wrapper kept every runnable ever started, with its job's closure and profile (found
        # by the GUI state machine's long run: about one runnable leaked per two steps).
        self._name, self._gen, self._fn, self._relay, self._stop = name, generation, fn, relay, stop
        self._mailbox, self._lock = mailbox, lock

    def run(self) -> None:
        try:
            self._run()
        finally:  # PySide may still keep a few deleted wrappers: they must not keep the job's inputs
            self._fn = self._stop = None

    def _run(self) -> None:
        name, gen = self._name, self._gen

        last = [-PROGRESS_INTERVAL]

        def progress(done: int, total: int) -> None:
            # at most one report per PROGRESS_INTERVAL (the first and the last always): a progress
            # bar repaints on every new value, and a job reporting per row would spend the GUI
            # thread's time on repaints nobody can read
            now = time.monotonic()
            if self._stop.is_set() or (now - last[0] < PROGRESS_INTERVAL and 0 < done < total):
                return
            last[0] = now
            self._relay.progress.emit(name, gen, int(done), int(total))

        try:
            with self._gil:
                result = self._fn(progress, lambda: self._priority.checkpoint(self._stop))
        except OperationCancelled:  # stopped by its cancel hook: cancelled or superseded, nothing to report
            result = None
        except ValidationError as exc:  # an input beyond its range or a work limit: the message says which
            self._relay.error.emit(name, gen, str(exc))
            return
        except MemoryError as exc:  # never a raw MemoryError (or a traceback) for the user
            self._relay.error.emit(name, gen, f"not enough memory ({exc}): use fewer points or a shorter duration")
            return
        except Exception as exc:  # noqa: BLE001 - reported to the GUI, never lost
            traceback.print_exc()
            self._relay.error.emit(name, gen, f"{type(exc).__name__}: {exc}")
            return
        with self._lock:
            self._mailbox[(name, gen)] = result
        self._relay.done.emit(name, gen)


class TaskRunner(QObject):
    """Runs named jobs; only the newest job of each name reports."""

    started = Signal(str)
    progress = Signal(str, int, int)
    finished = Signal(str, object)
    failed = Signal(str, str)
    cancelled = Signal(str)

    def __init__(self, parent: QObject | None = None, max_threads: int = 2) -> None:
        super().__init__(parent)
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(max_threads)
        self._relay = _Relay(self)
        self._relay.progress.connect(self._on_progress)
        self._relay.done.connect(self._on_done)
        self._relay.error.connect(self._on_error)
        self._generation: dict[str, int] = {}
        self._stops: dict[str, threading.Event] = {}
        self._jobs: dict[tuple[str, int], _Runnable] = {}
        self._mailbox: dict[tuple[str, int], object] = {}
        self._lock = threading.Lock()
        self._gil = _GilPolicy()
        self.priority = _GuiPriority()
        self.dropped = 0  # stale results thrown away (for tests)

    def submit(self, name: str, fn: Job) -> int:
        """Start ``fn`` under ``name``, superseding a running job of that name; returns its generation."""
        old = self._stops.get(name)
        if old is not None:
            old.set()
        gen = self._generation.get(name, 0) + 1
        self._generation[name] = gen
        stop = threading.Event()
        self._stops[name] = stop
        job = _Runnable(name, gen, fn, self._relay, stop, self._mailbox, self._lock, self._gil, self.priority)
        self._jobs[(name, gen)] = job
        self._pool.start(job)
        self.started.emit(name)
        return gen

    def cancel(self, name: str) -> None:
        """Stop the job ``name`` (its result, if any, is dropped)."""
        if self.drop(name):
            self.cancelled.emit(name)

    def drop(self, name: str) -> bool:
        """Stop the job ``name`` and throw its result away, without reporting :attr:`cancelled`
        (its inputs changed: the scheduler submits it again when it is wanted).  Returns whether
        a job was running."""
        stop = self._stops.pop(name, None)
        if stop is None:
            return False
        stop.set()
        self._generation[name] = self._generation.get(name, 0) + 1
        return True

    def cancel_all(self) -> None:
        for name in list(self._stops):
            self.cancel(name)

    def is_running(self, name: str | None = None) -> bool:
        if name is None:
            return bool(self._stops)
        return name in self._stops

    def running(self) -> list[str]:
        return list(self._stops)

    def defer_to_gui(self, seconds: float = 0.05) -> None:
        """Running jobs pause at their next check for ``seconds`` (the GUI is handling an edit)."""
        self.priority.defer(seconds)

    def wait(self, msecs: int = 10000) -> bool:
        """Block until the pool is idle (tests and shutdown only)."""
        return self._pool.waitForDone(msecs)

    def shutdown(self) -> None:
        self.cancel_all()
        self._pool.waitForDone(10000)

    def _current(self, name: str, gen: int) -> bool:
        return gen == self._generation.get(name) and name in self._stops

    @Slot(str, int, int, int)
    def _on_progress(self, name: str, gen: int, done: int, total: int) -> None:
        if self._current(name, gen):
            self.progress.emit(name, done, total)

    @Slot(str, int)
    def _on_done(self, name: str, gen: int) -> None:
        self._jobs.pop((name, gen), None)
        with self._lock:
            result = self._mailbox.pop((name, gen), None)
        if not self._current(name, gen):
            self.dropped += 1
            return
        self._stops.pop(name, None)
        self.finished.emit(name, result)

    @Slot(str, int, str)
    def _on_error(self, name: str, gen: int, message: str) -> None:
        self._jobs.pop((name, gen), None)
        if not self._current(name, gen):
            return
        self._stops.pop(name, None)
        self.failed.emit(name, message)
