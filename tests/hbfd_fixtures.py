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



def hbfd_replicate(device: Device, seed: int, quantities: tuple[str, ...] = ("actuator",), noise: float = 0.01,
                   n_freq: int = 400, sample_time: float = 1e-3) -> list:
    """One seeded replicate of the issue's setting: each quantity's FRF (handle free, exact
    ZOH-sampled) at ``n_freq`` log-spaced frequencies from 1 rad/s to 0.95 Nyquist, with
    :func:`with_noise` drawn from ``default_rng(seed)`` in the order of ``quantities`` (the
    draws of the coverage benchmark and tests)."""
    from analysis.identify import device_response, make_measurement

    w = np.geomspace(1.0, 0.95 * math.pi / sample_time, n_freq)
    rng = np.random.default_rng(seed)
    return [make_measurement(w, with_noise(device_response(device, w, q, "free", sample_time=sample_time), rng,
                                           noise), q, "free", sample_time=sample_time) for q in quantities]
