"""Measurement files as a lab writes them, for the end-to-end identification tests (issue 23).

A plain module (not conftest.py), like :mod:`tests.identify_data`, whose seeded chirp record
:func:`write_chirp_csv` writes as a time-series CSV; :func:`write_frf_csv` writes a noisy
ZOH-sampled FRF of another quantity or boundary of the same device.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from analysis.identify import device_response
from tests.identify_data import chirp_device, chirp_record

__all__ = ["T", "write_chirp_csv", "write_frf_csv"]

#: The controller's sample time of every file [s].
T = 1e-3


def write_chirp_csv(path: Path, seed: int = 0, seconds: float = 40.0) -> Path:
    """The issue's chirp test (1 to 300 Hz, 0.3 % encoder noise, :func:`tests.identify_data.chirp_record`)
    as ``time_s,force_n,position_m``."""
    t, force, x = chirp_record(seconds=seconds, noise=0.003, seed=seed, sample_time=T)
    path.write_text("time_s,force_n,position_m\n" + "\n".join(
        f"{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), force.tolist(), x.tolist())) + "\n")
    return path


def write_frf_csv(path: Path, quantity: str, boundary: str = "free", points: int = 300, noise: float = 0.005,
                  seed: int = 0) -> Path:
    """A ZOH-sampled FRF of the chirp device (``frequency_rad_s,real,imag``), 2 Hz to 0.9 Nyquist, with
    complex Gaussian noise of relative size ``noise`` drawn from ``default_rng(seed)``."""
    w = np.logspace(np.log10(2 * np.pi * 2.0), np.log10(0.9 * np.pi / T), points)
    h = device_response(chirp_device(T), w, quantity, boundary, T, 0)
    rng = np.random.default_rng(seed)
    h = h * (1 + noise * (rng.standard_normal(w.size) + 1j * rng.standard_normal(w.size)) / np.sqrt(2))
    path.write_text("frequency_rad_s,real,imag\n" + "\n".join(
        f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(w, h)) + "\n")
    return path
