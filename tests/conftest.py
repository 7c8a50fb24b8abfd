"""Shared fixtures of the numerical test suite."""

from __future__ import annotations

import os
import sys

import pytest

# The suite is headless: Qt renders offscreen unless the caller asks for a real platform.
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

_HERE = os.path.dirname(os.path.abspath(__file__))
for _p in (os.path.dirname(_HERE), _HERE):  # the repository root (analysis) and tests/ (reference, strategies)
    if _p not in sys.path:
        sys.path.insert(0, _p)

from hbfd_fixtures import make_hbfd  # noqa: E402

from analysis import Device  # noqa: E402


@pytest.fixture(scope="session")
def hbfd() -> Device:
    return make_hbfd()
