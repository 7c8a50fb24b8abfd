"""Automatic start of the chain fit: the undamped chain from resonances and antiresonances.

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
"""

from __future__ import annotations

import numpy as np
from scipy import signal

__all__ = ["chain_from_spectrum", "spectrum_from_chain", "read_spectrum", "mass_line", "hidden_pair_starts"]


def spectrum_from_chain(masses, stiffnesses) -> tuple[np.ndarray, np.ndarray]:
    """Undamped poles (free-free, nonzero) and zeros (actuator held) of the actuator
    driving-point compliance, rad/s, both ascending (the forward map of :func:`chain_from_spectrum`)."""
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
