"""Shared fixtures of the numerical test suite."""

from __future__ import annotations

import faulthandler
import os
import sys

import pytest

# The suite is headless: Qt renders offscreen unless the caller asks for a real platform.
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
# One BLAS thread per test process, as the GUI and `zwidth bench` run (app/cli.py): the xdist workers
# are the parallelism, and OpenBLAS threads on top of them spin for the same cores (scipy's expm of
# an 11x11 matrix took 4.9 ms instead of 0.04 ms, the HBFD simulation 0.9 CPU-s instead of 0.08).
# Set before numpy is imported; an explicit OPENBLAS_NUM_THREADS (issue 21's check with 2) wins.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

_HERE = os.path.dirname(os.path.abspath(__file__))
for _p in (os.path.dirname(_HERE), _HERE):  # the repository root (analysis) and tests/ (reference, strategies)
    if _p not in sys.path:
        sys.path.insert(0, _p)

from hbfd_fixtures import make_hbfd  # noqa: E402

from analysis import Device  # noqa: E402


@pytest.fixture(scope="session")
def hbfd() -> Device:
    return make_hbfd()


# -- the hang watchdog ------------------------------------------------------------------------------
#: seconds one test may take before the run is stopped with every thread's stack (the slowest test,
#: the GUI state machine, takes about 100 s here): a hang fails CI at once, and says where
HANG_LIMIT = 900.0
_STDERR = pytest.StashKey[int]()


def pytest_configure(config: pytest.Config) -> None:
    # a copy of the real stderr, taken while capture is suspended: the dump must reach the log
    config.stash[_STDERR] = os.dup(2)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item, nextitem: pytest.Item | None):
    fd = item.config.stash[_STDERR]
    faulthandler.dump_traceback_later(HANG_LIMIT, exit=True, file=fd)
    try:
        yield
    finally:
        faulthandler.cancel_dump_traceback_later()
