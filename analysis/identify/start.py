"""Automatic start of the chain fit: the undamped chain from resonances and antiresonances, and the
seeded start chains built from it.

Inverse problem (Stieltjes / Lanczos)
-------------------------------------
The driving-point compliance of an undamped free chain at the actuator is, with ``mu = w^2``,

    ``x_{n-1} / F = (1/m_a) prod_j (z_j^2 - mu) / (mu prod_i (p_i^2 - mu))``,

poles ``0 = p_0 < p_1 < ... < p_{n-1}`` (free-free modes), zeros ``z_j`` (the modes with the
actuator held), interlaced ``z_1 < p_1 < z_2 < ... < z_{n-1} < p_{n-1}``, and ``m_a`` the
actuator mass.  In mass-normalized coordinates ``J = M^{-1/2} K M^{-1/2}`` is a Jacobi
(tridiagonal) matrix and ``x_{n-1}/F = (1/m_a) e^T (J - mu)^{-1} e`` with ``e`` the actuator's
unit vector, so the partial-fraction residues give the actuator components ``q_i`` of the
normalized eigenvectors: ``q_i^2 = prod_j (z_j^2 - p_i^2) / prod_{k != i} (p_k^2 - p_i^2)``
(they sum to 1).  Lanczos on ``diag(p^2)`` from ``q`` rebuilds ``J`` (this is the Stieltjes
continued-fraction / Cauer expansion of the driving-point function, done in the numerically
stable orthogonal form).  The rigid-body mode ``p_0 = 0`` has eigenvector ``M^{1/2} 1``, so the
masses are ``m_j = m_a (u_j / u_0)^2`` with ``u`` its Lanczos coordinates, and
``k_j = beta_j sqrt(m_j m_{j+1})``.  The scale ``m_a = M q_0^2`` comes from the total mass ``M``,
read from the low-frequency mass line ``x/F -> 1/(s (M s + g))``.

Reading the spectrum off data
-----------------------------
Peaks (resonances) and troughs (antiresonances) of ``|H| w^2`` (the mass line removed) are
found with :func:`scipy.signal.find_peaks` and paired trough -> peak in frequency order; the
most prominent ``n - 1`` pairs are kept.  Pairs the data do not show (a mode that the actuator
barely sees, such as the HBFD's handle mode, whose pole and zero nearly cancel) are the job of
:func:`hidden_pair_starts`: seeded candidates for the multi-start of :func:`analysis.identify.fit_chain`.

Start chains
------------
:func:`start_chains` returns a seeded list of full parameter sets (one :class:`ChainParameters`
row each) for an ``n``-mass chain: the spectrum read off the driving-point actuator
measurement gives the undamped chain (the inverse above), the mass line gives the total
mass and the actuator's ground damping, element dampings start at a damping ratio of 5 %
(eq. 28) and other selected ground dampings at 1 % of the critical value of the total mass at the
lowest measured frequency.  Resonance pairs the data do not show are added as seeded candidates.
Without an ``actuator``/``free`` measurement, the modes are spread log-uniformly over the band.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy import signal

from analysis.identify.measurement import Measurement
from analysis.identify.params import ChainParameters, parse_key

__all__ = ["chain_from_spectrum", "spectrum_from_chain", "read_spectrum", "mass_line", "hidden_pair_starts",
           "start_chains", "visible_spectrum", "other_peaks", "START_RATIO"]

#: Damping ratio of the element dampings at the start (eq. 28 with the reduced mass).
START_RATIO = 0.05


def spectrum_from_chain(masses, stiffnesses) -> tuple[np.ndarray, np.ndarray]:
    """Undamped poles (free-free, nonzero) and zeros (actuator held) of the actuator
    driving-point compliance, rad/s, both ascending (the forward map of :func:`chain_from_spectrum`).

    Parameters
    ----------
    masses : array_like
        Masses [kg], handle first, actuator last, shape (n,).
    stiffnesses : array_like
        Element stiffnesses [N/m], shape (n - 1,).

    Returns
    -------
    poles : numpy.ndarray
        The ``n - 1`` nonzero free-free resonances [rad/s], ascending.
    zeros : numpy.ndarray
        The ``n - 1`` antiresonances (actuator held) [rad/s], ascending.
    """
    m = np.asarray(masses, float)
    k = np.asarray(stiffnesses, float)
    n = m.size
    K = np.zeros((n, n))
    for i in range(n - 1):
        K[i:i + 2, i:i + 2] += k[i] * np.array([[1.0, -1.0], [-1.0, 1.0]])
    r = 1.0 / np.sqrt(m)
    J = K * r[:, None] * r[None, :]
    ev = np.linalg.eigvalsh(J)
    poles = np.sqrt(np.maximum(np.sort(ev)[1:], 0.0))
    zeros = np.sqrt(np.maximum(np.linalg.eigvalsh(J[:-1, :-1]), 0.0)) if n > 1 else np.zeros(0)
    return poles, zeros


def chain_from_spectrum(poles, zeros, total_mass: float) -> tuple[np.ndarray, np.ndarray]:
    """Masses (handle first) and stiffnesses of the undamped chain with these poles and zeros
    (module doc).  ``poles`` and ``zeros`` are the ``n - 1`` nonzero resonances and the
    ``n - 1`` antiresonances (rad/s), strictly interlaced ``z_1 < p_1 < z_2 < ...``.

    Parameters
    ----------
    poles : array_like
        The ``n - 1`` nonzero resonances [rad/s] (sorted here).
    zeros : array_like
        The ``n - 1`` antiresonances [rad/s] (sorted here).
    total_mass : float
        Total mass ``M`` of the chain [kg].

    Returns
    -------
    masses : numpy.ndarray
        Masses [kg], handle first, shape (n,).
    stiffnesses : numpy.ndarray
        Element stiffnesses [N/m], shape (n - 1,).

    Raises
    ------
    ValueError
        When the numbers of poles and zeros differ, or they do not interlace.
    """
    p = np.sort(np.asarray(poles, float))
    z = np.sort(np.asarray(zeros, float))
    if p.size != z.size:
        raise ValueError("as many antiresonances as resonances are needed")
    if p.size == 0:
        return np.array([float(total_mass)]), np.zeros(0)
    lam = np.r_[0.0, p * p]
    zz = z * z
    n = lam.size
    q2 = np.empty(n)
    for i in range(n):
        others = np.delete(lam, i)
        q2[i] = np.prod(zz - lam[i]) / np.prod(others - lam[i])
    if np.any(q2 <= 0):
        raise ValueError("resonances and antiresonances do not interlace")
    q2 /= q2.sum()
    alpha, beta, V = _lanczos(lam, np.sqrt(q2))
    u = V[0, :]  # rigid-body eigenvector in the Lanczos basis (actuator first)
    m_a = total_mass * q2[0]
    m = m_a * (u / u[0]) ** 2
    k = beta * np.sqrt(m[:-1] * m[1:])
    return m[::-1].copy(), k[::-1].copy()


def _lanczos(lam: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lanczos tridiagonalization of ``diag(lam)`` from ``q`` with full reorthogonalization."""
    n = lam.size
    V = np.zeros((n, n))
    alpha = np.zeros(n)
    beta = np.zeros(n - 1)
    V[:, 0] = q / np.linalg.norm(q)
    for j in range(n):
        w = lam * V[:, j]
        alpha[j] = V[:, j] @ w
        w = w - V[:, : j + 1] @ (V[:, : j + 1].T @ w)
        w = w - V[:, : j + 1] @ (V[:, : j + 1].T @ w)
        if j < n - 1:
            beta[j] = np.linalg.norm(w)
            V[:, j + 1] = w / beta[j]
    return alpha, beta, V


def mass_line(w: np.ndarray, h: np.ndarray, upto: float) -> tuple[float, float]:
    """Total mass ``M`` and ground damping ``g`` from ``1/(j w H) = M j w + g`` at ``w < upto``
    (medians over the low-frequency points; at least the 5 lowest are used)."""
    sel = w < upto
    if np.count_nonzero(sel) < 5:
        sel = np.zeros(w.size, bool)
        sel[: min(5, w.size)] = True
    imp = 1.0 / (1j * w[sel] * h[sel])
    return float(np.median(imp.imag / w[sel])), float(np.median(imp.real))


def read_spectrum(w: np.ndarray, h: np.ndarray, pairs: int) -> tuple[np.ndarray, np.ndarray]:
    """Up to ``pairs`` (antiresonance, resonance) pairs read off ``|h| w^2`` (module doc)."""
    y = np.log(np.abs(h) * w * w)
    pk, pp = signal.find_peaks(y, prominence=0.05)
    tr, tp = signal.find_peaks(-y, prominence=0.05)
    events = sorted([(int(i), +1, float(v)) for i, v in zip(pk, pp["prominences"])]
                    + [(int(i), -1, float(v)) for i, v in zip(tr, tp["prominences"])])
    found = []
    for (i0, k0, v0), (i1, k1, v1) in zip(events[:-1], events[1:]):
        if k0 == -1 and k1 == +1:
            found.append((v0 + v1, w[i0], w[i1]))
    found.sort(reverse=True)
    found = sorted(found[:pairs], key=lambda f: f[1])
    return np.array([f[1] for f in found]), np.array([f[2] for f in found])


def hidden_pair_starts(zeros: np.ndarray, poles: np.ndarray, missing: int, band: tuple[float, float],
                       count: int, seed: int = 0,
                       hints: np.ndarray | None = None) -> list[tuple[np.ndarray, np.ndarray]]:
    """Candidate spectra with ``missing`` nearly cancelled (zero, pole) pairs added.

    ``hints`` are frequencies where the data suggest a hidden pair (the largest misfit of a
    fit without it, see :func:`analysis.identify.fit.fit_chain`); the first candidates put the
    pairs there and at +-3 % (seeded jitter), the rest at log-spaced frequencies across the band.
    The pair is 0.2 % wide; :func:`_interlace` restores the interlacing of poles and zeros.
    """
    rng = np.random.default_rng(seed)
    lo, hi = band
    spread = list(np.geomspace(lo * 3.0, hi * 1.5, max(count, 1)))
    hint = [] if hints is None else [float(h) for h in np.atleast_1d(hints)]
    out = []
    for c in range(count):
        z, p = list(zeros), list(poles)
        for h in range(missing):
            if h < len(hint):
                f = hint[h] * (1.0 if c == 0 else float(np.exp(rng.normal(0.0, 0.03))))
            else:
                f = spread[(c + 3 * h) % len(spread)] * float(np.exp(rng.normal(0.0, 0.05)))
            z.append(f * 0.998)
            p.append(f)
        out.append(_interlace(np.array(z), np.array(p)))
    return out


def _interlace(z: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sort and nudge so that ``z_1 < p_1 < z_2 < p_2 < ...`` holds strictly."""
    allv = np.sort(np.r_[z, p])
    return allv[0::2] * (1 - 1e-6), allv[1::2] * (1 + 1e-6)


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
