"""Start chains for the fit, built from the data (see :mod:`analysis.identify.start`).

:func:`start_chains` returns a seeded list of full parameter sets (one :class:`ChainParameters`
row each) for an ``n``-mass chain: the spectrum read off the driving-point actuator
measurement gives the undamped chain (Lanczos / Stieltjes inverse), the mass line gives the total
mass and the actuator's ground damping, element dampings start at a damping ratio of 5 %
(eq. 28) and other selected ground dampings at 1 % of the critical value of the total mass at the
lowest measured frequency.  Resonance pairs the data do not show are added as seeded candidates.
Without an ``actuator``/``free`` measurement, the modes are spread log-uniformly over the band.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from analysis.identify.measurement import Measurement
from analysis.identify.params import ChainParameters, parse_key
from scipy import signal

from analysis.identify.start import chain_from_spectrum, hidden_pair_starts, mass_line, read_spectrum

__all__ = ["start_chains", "visible_spectrum", "other_peaks", "START_RATIO"]

#: Damping ratio of the element dampings at the start (eq. 28 with the reduced mass).
START_RATIO = 0.05


def _driving_point(measurements: Sequence[Measurement]) -> tuple[np.ndarray, np.ndarray] | None:
    """Frequencies and continuous-equivalent response of the first actuator/free measurement
    (a sampled one is corrected for the half-sample ZOH lag and the delay)."""
    for m in measurements:
        if m.quantity == "actuator" and m.boundary == "free":
            h = m.response
            if m.sample_time is not None:
                h = h * np.exp(1j * m.frequency * m.sample_time * (m.delay_samples + 0.5))
            return m.frequency, h
    return None


def visible_spectrum(measurements: Sequence[Measurement], n: int) -> tuple[np.ndarray, np.ndarray]:
    """The (antiresonances, resonances) of an ``n``-mass chain that the driving-point data show."""
    dp = _driving_point(measurements)
    return (np.zeros(0), np.zeros(0)) if dp is None else read_spectrum(dp[0], dp[1], n - 1)


def other_peaks(measurements: Sequence[Measurement], known: np.ndarray) -> np.ndarray:
    """Resonance peaks of the non-driving-point measurements (handle, gauge, clamped) that are
    not within 10 % of a ``known`` resonance, most prominent first.  A mode hidden from the
    actuator (pole and zero nearly cancel) usually shows as a peak there."""
    found: list[tuple[float, float]] = []
    for m in measurements:
        if m.quantity == "actuator" and m.boundary == "free":
            continue
        scale = m.frequency ** 2 if m.quantity != "gauge" and m.boundary == "free" else 1.0
        y = np.log(np.abs(m.response) * scale)
        pk, pp = signal.find_peaks(y, prominence=0.05)
        for i, v in zip(pk, pp["prominences"]):
            f = float(m.frequency[i])
            if m.boundary == "free" and not np.any(np.abs(np.log(f / np.maximum(known, 1e-300))) < 0.1):
                found.append((float(v), f))
    found.sort(reverse=True)
    return np.array([f for _, f in found])


def _spectra(measurements: Sequence[Measurement], n: int, count: int, seed: int,
             hints: np.ndarray | None) -> tuple[float, float, list[tuple[np.ndarray, np.ndarray]]]:
    """Total mass, ground damping and candidate (zeros, poles) lists."""
    lo = min(float(m.frequency[0]) for m in measurements)
    hi = max(float(m.frequency[-1]) for m in measurements)
    dp = _driving_point(measurements)
    if dp is None:
        free = [m for m in measurements if m.boundary == "free" and m.quantity != "gauge"]
        M, g = mass_line(free[0].frequency, free[0].response, 3 * lo) if free else (1.0, 0.0)
        z, p = np.zeros(0), np.zeros(0)
    else:
        w, h = dp
        z, p = read_spectrum(w, h, n - 1)
        M, g = mass_line(w, h, (z[0] if z.size else hi) / 3.0)
    M = abs(M) if np.isfinite(M) and M != 0 else 1.0
    missing = n - 1 - z.size
    if missing <= 0:
        return M, g, [(z, p)]
    return M, g, hidden_pair_starts(z, p, missing, (lo, hi), count, seed, hints)


def start_chains(measurements: Sequence[Measurement], n: int, ground: Sequence[int],
                 fixed: Mapping[str, float], count: int = 6, seed: int = 0,
                 hints: np.ndarray | None = None) -> ChainParameters:
    """Seeded start chains (one row each) for an ``n``-mass fit (module doc); ``hints`` are
    frequencies of resonance pairs the data hide (see :func:`hidden_pair_starts`)."""
    M, g, cands = _spectra(measurements, n, count, seed, hints)
    lo = min(float(m.frequency[0]) for m in measurements)
    rows = []
    for z, p in cands:
        try:
            masses, k = chain_from_spectrum(p, z, M)
        except (ValueError, FloatingPointError):
            continue
        if not (np.all(np.isfinite(masses)) and np.all(masses > 0) and np.all(np.isfinite(k)) and np.all(k > 0)):
            continue
        mu = masses[:-1] * masses[1:] / (masses[:-1] + masses[1:])
        b = 2.0 * START_RATIO * np.sqrt(k * mu)
        gd = np.zeros(n)
        for i in ground:
            gd[i] = max(g, 0.05 * M * lo) if i == n - 1 else 0.01 * 2.0 * M * lo
        rows.append((masses, k, b, gd))
    if not rows:
        masses = np.full(n, M / n)
        ws = np.geomspace(lo * 3, lo * 300, max(n - 1, 1))[: n - 1]
        k = masses[:-1] * ws ** 2
        rows.append((masses, k, 2 * START_RATIO * np.sqrt(k * masses[:-1] / 2), np.zeros(n)))
    params = ChainParameters(*(np.array([r[j] for r in rows]) for j in range(4)))
    for key, v in fixed.items():
        name, i = parse_key(key, n)
        getattr(params, name)[:, i] = float(v)
    return params
