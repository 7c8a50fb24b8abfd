"""The per-device functions of tests/test_batch.py and the batch benchmark.

A pool's or a cluster's worker imports a device function by its module's name, so they live in
this light module (numpy and the sampled loop only, no pytest): a worker that imports
test_batch.py would also import pytest and the identification package, seconds under load.
"""

from __future__ import annotations

import numpy as np

from analysis import Device
from analysis.sampled import zwidth_region

B_GRID = np.geomspace(0.1, 100.0, 7)


def rigid(mass: float = 0.5, ground: float = 2.0) -> Device:
    """A rigid 1-DOF device sampled at 1 kHz."""
    return Device(masses=[mass], stiffnesses=[], dampings=[], ground_dampings=[ground], sample_time=1e-3)


def region_k(device: Device, b: np.ndarray = B_GRID) -> np.ndarray:
    """Today's per-device (B, K) computation: the Z-width region's k_max (one sample of delay)."""
    return zwidth_region(device, b=b, delay_samples=1, passive=False).k_max


def fails_at(value: int, bad: tuple[int, ...] = (7,)) -> np.ndarray:
    """A device function that fails for the values in ``bad``."""
    if value in bad:
        raise ValueError(f"no model for unit {value}")
    return np.array([float(value % 5), 10.0 - value % 3])


def nan_at_three(value: int) -> np.ndarray:
    """A result with NaN for the value 3."""
    return np.array([np.nan if value == 3 else 1.0])


def sized(value: int) -> np.ndarray:
    """A result whose shape changes at the value 2."""
    return np.zeros(3 if value < 2 else 4)


def ramp(value: int) -> np.ndarray:
    """Ties on purpose: every third value is the same, so the lowest index must bind."""
    return np.array([value % 3, 5 - value % 2, 1.0], dtype=float)


def zeros(device: object, shape: tuple[int, int] = (21, 21)) -> np.ndarray:
    """No work: a batch of it measures the per-task overhead alone."""
    return np.zeros(shape)
