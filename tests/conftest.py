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

from analysis import Device  # noqa: E402

HBFD_MASSES = [0.2, 2.3, 2.0, 0.5]
HBFD_STIFFNESSES = [130e3, 84e3, 874e3]
HBFD_RATIO = 0.1


def make_hbfd(ratio: float = HBFD_RATIO, b4: float = 5.0, **kwargs) -> Device:
    """The HBFD worst-case configuration of Adams et al. (T = 1 ms)."""
    kwargs.setdefault("sample_time", 1e-3)
    return Device.from_damping_ratios(HBFD_MASSES, HBFD_STIFFNESSES, ratio, ground_dampings=[0, 0, 0, b4], **kwargs)


@pytest.fixture(scope="session")
def hbfd() -> Device:
    return make_hbfd()
