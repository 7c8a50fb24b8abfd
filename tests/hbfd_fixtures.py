"""The HBFD worst-case device of Adams et al., shared by the numerical tests.

A plain module (not conftest.py): tests/app has its own conftest, so `from conftest import`
would be ambiguous.
"""

from __future__ import annotations

import math

import numpy as np

from analysis import Device

HBFD_MASSES = [0.2, 2.3, 2.0, 0.5]
HBFD_STIFFNESSES = [130e3, 84e3, 874e3]
HBFD_RATIO = 0.1


def make_hbfd(ratio: float = HBFD_RATIO, b4: float = 5.0, **kwargs) -> Device:
    """The HBFD worst-case configuration of Adams et al. (T = 1 ms)."""
    kwargs.setdefault("sample_time", 1e-3)
    return Device.from_damping_ratios(HBFD_MASSES, HBFD_STIFFNESSES, ratio, ground_dampings=[0, 0, 0, b4], **kwargs)


def with_noise(h: np.ndarray, rng: np.random.Generator, level: float = 0.01) -> np.ndarray:
    """``h`` with complex Gaussian noise of relative size ``level``: ``h (1 + level (n1 + j n2)/sqrt 2)``
    (the issue's noise model; 0.71 % on the log-magnitude and on the phase at ``level = 0.01``)."""
    return h * (1 + level * (rng.normal(size=h.size) + 1j * rng.normal(size=h.size)) / math.sqrt(2))

