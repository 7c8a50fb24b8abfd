"""Run the ``zwidth`` command in the test process, or, for the few tests that need one, in a real one.

Every CLI test calls :func:`run_cli`: :func:`app.cli.main` with the output captured by pytest's
``capsys`` or ``capfd`` fixture (``capfd`` also sees what C code writes to the file descriptors).
Starting ``python -m app.cli`` costs a second or more of imports per call on a loaded 2-core
machine (the CLI tests took about 75 s that way, issue 21).

:func:`main` touches process-wide state; :func:`run_cli` keeps the test process as it was:

* the environment is restored afterwards (``bench`` and ``gui`` set ``OPENBLAS_NUM_THREADS``,
  ``export-plot`` and ``report`` may set ``QT_QPA_PLATFORM``), and ``ZWIDTH_SELFTEST`` is removed
  while the command runs;
* :func:`app.allocator.tune_allocator` is not called: glibc's thresholds stay whatever the worker
  had, so no test depends on which test ran first in its worker;
* ``sys.argv`` is ``["zwidth", *argv]`` during the call and the working directory is restored;
* for ``export-plot`` and ``report``, Qt's messages go to ``stderr`` instead of to pytest-qt's
  log, so that ``stderr == ""`` still means what it meant for a real process (the offscreen
  platform's :data:`OFFSCREEN_NOTICE` is dropped, as the real command's handler does).  The
  QApplication the command creates (offscreen: the suite sets ``QT_QPA_PLATFORM``) is the
  worker's, as for every Qt test.

Never run ``gui`` with a valid profile in process: it would open a window and wait for it.

What only a real process can show keeps one (:func:`run_process`), in an explicit, small set:
the ``python -m app.cli`` and console-script wiring and their exit codes
(``test_cli.test_module_entry_point_exit_codes``), export going headless by itself with no display
variables (``test_cli.test_export_plot_headless_process``), the GUI refusing to start without a
display instead of Qt aborting the process (``test_no_display``), the commands that must not
import Qt (``test_no_qt``, through :mod:`import_probe`'s one interpreter), and Ctrl-C cancelling a fit
(``test_identify_cli_mixed.test_ctrl_c_cancels_cleanly``: a signal needs a process of its own).
"""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import sys
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import NamedTuple, Protocol
from unittest import mock

ROOT = Path(__file__).resolve().parents[1]
#: the subcommands that draw with Qt (their Qt messages are routed to stderr)
QT_COMMANDS = ("export-plot", "report")
#: the offscreen platform's notice that the command's own handler drops (``app.report.figures.ensure_app``)
OFFSCREEN_NOTICE = "propagateSizeHints"
#: the variables that tell Qt where to draw; a "no display" process runs without them
DISPLAY_VARIABLES = ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")


class Capture(Protocol):
    """pytest's ``capsys`` or ``capfd`` fixture."""

    def readouterr(self) -> tuple[str, str]: ...


class CliResult(NamedTuple):
    """The exit code and output of one command (named as in :class:`subprocess.CompletedProcess`)."""

    returncode: int
    stdout: str
    stderr: str


def exit_code(code: object) -> int:
    """The process exit code of ``SystemExit(code)``: ``None`` is 0, an int itself, anything else 1."""
    if code is None:
        return 0
    return code if isinstance(code, int) else 1


@contextlib.contextmanager
def _qt_messages_to_stderr(command: str) -> Iterator[None]:
    if command not in QT_COMMANDS:
        yield
        return
    from PySide6.QtCore import qInstallMessageHandler

    def to_stderr(_kind: object, _context: object, message: str) -> None:
        if OFFSCREEN_NOTICE not in message:
            sys.stderr.write(message + "\n")

    previous = qInstallMessageHandler(to_stderr)
    try:
        yield
    finally:
        qInstallMessageHandler(previous)


@contextlib.contextmanager
def isolated(argv: list[str]) -> Iterator[None]:
    """The process state :func:`app.cli.main` may change, restored afterwards (see the module doc)."""
    cwd = os.getcwd()
    with contextlib.ExitStack() as stack:
        stack.enter_context(mock.patch.dict(os.environ))
        os.environ.pop("ZWIDTH_SELFTEST", None)
        stack.enter_context(mock.patch("app.allocator.tune_allocator", return_value=False))
        stack.enter_context(mock.patch.object(sys, "argv", ["zwidth", *argv]))
        stack.enter_context(_qt_messages_to_stderr(argv[0] if argv else ""))
        try:
            yield
        finally:
            os.chdir(cwd)


def run_cli(capture: Capture, *argv: str | os.PathLike[str]) -> CliResult:
    """``zwidth ARGV...`` in this process: exit code, stdout and stderr (what it printed only)."""
    from app.cli import main

    args = [os.fspath(a) for a in argv]
    capture.readouterr()  # drop what the test printed before
    with isolated(args):
        try:
            code = main(args)
        except SystemExit as exc:  # main returns its code; a stray exit is still reported as one
            code = exit_code(exc.code)
    out, err = capture.readouterr()
    return CliResult(code, out, err)


def environment(display: bool = True, extra: Mapping[str, str] | None = None) -> dict[str, str]:
    """The test's environment for a real process, with this checkout first on ``PYTHONPATH``;
    ``display=False`` removes :data:`DISPLAY_VARIABLES`."""
    env = {k: v for k, v in os.environ.items() if display or k not in DISPLAY_VARIABLES}
    env.pop("ZWIDTH_SELFTEST", None)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    env.update(extra or {})
    return env


def console_script() -> Path | None:
    """The installed ``zwidth`` console script beside this interpreter (``pip install -e .``), if any."""
    name = "zwidth.exe" if sys.platform == "win32" else "zwidth"
    here = Path(sys.executable).with_name(name)
    if here.exists():
        return here
    found = shutil.which("zwidth")
    return Path(found) if found else None


def run_process(*argv: str | os.PathLike[str], display: bool = True, script: Path | None = None,
                timeout: float = 300) -> subprocess.CompletedProcess[str]:
    """``python -m app.cli ARGV...`` (or ``script ARGV...``) in a new process, from the checkout."""
    cmd = [str(script)] if script is not None else [sys.executable, "-m", "app.cli"]
    return subprocess.run([*cmd, *(os.fspath(a) for a in argv)], cwd=ROOT, env=environment(display),
                          capture_output=True, text=True, timeout=timeout)
