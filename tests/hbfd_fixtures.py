"""The HBFD worst-case device of Adams et al., shared by the numerical tests.

A plain module (not conftest.py): tests/app has its own conftest, so `from conftest import`
would be ambiguous.
"""

from __future__ import annotations

from analysis import Device

HBFD_MASSES = [0.2, 2.3, 2.0, 0.5]
HBFD_STIFFNESSES = [130e3, 84e3, 874e3]
HBFD_RATIO = 0.1


def make_hbfd(ratio: float = HBFD_RATIO, b4: float = 5.0, **kwargs) -> Device:
    """The HBFD worst-case configuration of Adams et al. (T = 1 ms)."""
    kwargs.setdefault("sample_time", 1e-3)
    return Device.from_damping_ratios(HBFD_MASSES, HBFD_STIFFNESSES, ratio, ground_dampings=[0, 0, 0, b4], **kwargs)
