"""Hypothesis strategies and seeded generators of random device chains.

Dampings follow eq. (28) with the reduced mass, computed here (not by the code under test):
``b_i = 2 zeta_i sqrt(k_i m_i m_{i+1} / (m_i + m_{i+1}))``.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from analysis import Device


def _logu(lo: float, hi: float):
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


def _eq28(k, ma, mb, zeta):
    return 2.0 * zeta * math.sqrt(k * ma * mb / (ma + mb))


@st.composite
def random_device(draw, n_min: int = 1, n_max: int = 12, allow_lossless_ground: bool = False):
    """A random chain: n in [n_min, n_max], masses 1e-2..1e2 kg, stiffnesses 1e2..1e7 N/m,
    damping ratios 1e-3..1 (eq. 28), T 1e-4..1e-2 s, sensor element in range.

    At least one ground damping is > 0 (so Re y11 > 0 and the bounds are finite) unless
    ``allow_lossless_ground``.
    """
    n = draw(st.integers(n_min, n_max))
    m = [draw(_logu(1e-2, 1e2)) for _ in range(n)]
    k = [draw(_logu(1e2, 1e7)) for _ in range(n - 1)]
    z = [draw(_logu(1e-3, 1.0)) for _ in range(n - 1)]
    b = [_eq28(k[i], m[i], m[i + 1], z[i]) for i in range(n - 1)]
    g = [draw(st.one_of(st.just(0.0), _logu(1e-2, 1e2))) for _ in range(n)]
    if not allow_lossless_ground and not any(x > 0 for x in g):
        g[draw(st.integers(0, n - 1))] = draw(_logu(1e-2, 1e2))
    T = draw(_logu(1e-4, 1e-2))
    se = draw(st.integers(0, max(n - 2, 0)))
    return Device(masses=m, stiffnesses=k, dampings=b, ground_dampings=g, sensor_element=se, sample_time=T)


def seeded_device(rng: np.random.Generator, n_min: int = 1, n_max: int = 6) -> Device:
    """The same distribution as :func:`random_device`, from a numpy generator (seeded loops)."""

    def lu(lo, hi, size=None):
        return np.exp(rng.uniform(math.log(lo), math.log(hi), size))

    n = int(rng.integers(n_min, n_max + 1))
    m = lu(1e-2, 1e2, n)
    k = lu(1e2, 1e7, n - 1)
    z = lu(1e-3, 1.0, n - 1)
    b = [_eq28(k[i], m[i], m[i + 1], z[i]) for i in range(n - 1)]
    g = np.where(rng.random(n) < 0.5, lu(1e-2, 1e2, n), 0.0)
    if not np.any(g > 0):
        g[int(rng.integers(0, n))] = float(lu(1e-2, 1e2))
    T = float(lu(1e-4, 1e-2))
    se = int(rng.integers(0, max(n - 2, 0) + 1))
    return Device(masses=m, stiffnesses=k, dampings=b, ground_dampings=g, sensor_element=se, sample_time=T)
