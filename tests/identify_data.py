"""Seeded time-series records for the identification tests and benchmarks (issue 23).

A plain module (not conftest.py), like :mod:`tests.hbfd_fixtures`.  :func:`chirp_record` drives a
chain through the zero-order hold at the controller's rate with a chirp and samples the actuator
position (the collocated encoder) with Gaussian noise, the way a lab records an FRF test.  The
simulation is the exact ZOH discretization of the chain's state space
(:func:`analysis.chain.discretize_zoh`, the same ``Phi`` and ``Gamma`` as the sampled model of
:mod:`analysis.identify.model`), run in modal coordinates by :func:`scipy.signal.lfilter` (one
first-order recursion per eigenvalue of ``Phi``): the same numbers as
:func:`scipy.signal.dlsim` to round-off, about a hundred times faster on a 40 000-sample record.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import signal

from analysis import Device
from analysis.chain import chain_state_space, discretize_zoh
from analysis.identify import device_response

__all__ = ["CHIRP_DEVICE", "chirp_device", "chirp_record", "zoh_simulate"]

#: The issue's 3-mass device: handle 0.12 kg, 0.45, 0.30 (actuator); k 6e4 and 1.5e5 N/m;
#: element dampings 3 and 6 N s/m (about 2 % of critical); 3 N s/m to ground on the actuator.
CHIRP_DEVICE = dict(masses=[0.12, 0.45, 0.30], stiffnesses=[6e4, 1.5e5], dampings=[3.0, 6.0],
                    ground_dampings=[0.0, 0.0, 3.0])


def chirp_device(sample_time: float = 1e-3) -> Device:
    """The issue's 3-mass device (:data:`CHIRP_DEVICE`) at ``sample_time``."""
    return Device(sample_time=sample_time, **CHIRP_DEVICE)


def zoh_simulate(device: Device, force: np.ndarray, sample_time: float, output: int | None = None) -> np.ndarray:
    """Sampled position of mass ``output`` (default: the actuator) for ``force`` held by a ZOH.

    ``x[k+1] = Phi x[k] + Gamma u[k]``, ``y[k] = x_output[k]``, from rest, with the force on the
    actuator positive along ``x`` (the convention of :mod:`analysis.identify.model`).
    """
    A, B = chain_state_space(device)
    Phi, Gam = discretize_zoh(A[0], -B[0][:, :1], sample_time)
    lam, V = np.linalg.eig(Phi)
    b = np.linalg.solve(V, Gam[:, 0])
    c = V[device.n - 1 if output is None else int(output), :]
    u = np.asarray(force, float)
    y = np.zeros(u.size)
    for i in range(lam.size):
        if c[i] * b[i] != 0:
            y += np.real(c[i] * b[i] * signal.lfilter([0.0, 1.0], [1.0, -lam[i]], u.astype(complex)))
    return y


def chirp_record(device: Device | None = None, *, seconds: float = 40.0, f0: float = 1.0, f1: float = 300.0,
                 method: str = "linear", noise: float = 0.003, amplitude: float = 10.0, seed: int = 0,
                 sample_time: float = 1e-3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(t, force, position)`` of a chirp test: a ``method`` (``"linear"`` or ``"logarithmic"``)
    chirp of ``amplitude`` N from ``f0`` to ``f1`` Hz over ``seconds``, through the ZOH at
    ``sample_time``, the actuator position sampled with Gaussian encoder noise (drawn from
    ``default_rng(seed)``) of standard deviation ``noise`` times the smallest response amplitude
    of the test, ``amplitude |H(f1)|`` (the actuator's compliance falls as ``1/w^2`` above its
    modes, so this is the signal at the top of the band: 0.3 % is 28 nm on the issue's device,
    where the record's RMS is about 0.3 m of rigid-body motion)."""
    dev = chirp_device(sample_time) if device is None else device
    n = int(round(seconds / sample_time))
    t = np.arange(n) * sample_time
    force = amplitude * signal.chirp(t, f0, seconds, f1, method=method, phi=-90.0)
    x = zoh_simulate(dev, force, sample_time)
    top = float(np.abs(device_response(dev, np.array([2 * math.pi * f1]), sample_time=sample_time))[0])
    x = x + noise * amplitude * top * np.random.default_rng(seed).normal(size=n)
    return t, force, x
