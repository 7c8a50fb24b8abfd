"""50-digit reference implementation of the two-port formulas (Adams et al.), naive forms.

Independent of the production code: the chain is solved as a dense n x n system in mpmath,
the discrete two-port is formed literally as eq. (2), (14), and the bounds literally as the
right-hand sides of eq. (9) and (21).  With 50 digits the cancellations that ruin a
double-precision evaluation of these same formulas are harmless.
"""

from __future__ import annotations

import mpmath as mp

DPS = 50


def _chain_matrix(dev, s):
    n = dev.n
    A = mp.matrix(n, n)
    for i in range(n):
        A[i, i] = mp.mpf(float(dev.masses[i])) * s + mp.mpf(float(dev.ground_dampings[i]))
    for i in range(n - 1):
        z = mp.mpf(float(dev.dampings[i])) + mp.mpf(float(dev.stiffnesses[i])) / s
        A[i, i] += z
        A[i + 1, i + 1] += z
        A[i, i + 1] -= z
        A[i + 1, i] -= z
    return A


def _z_theta(w, T):
    w = mp.mpf(float(w))
    T = mp.mpf(float(T))
    z = mp.exp(1j * w * T)
    s = (2 / T) * (z - 1) / (z + 1)
    return z, s, T


def device_y(dev, w):
    """Discrete Y(z) of eq. (2) plus the gauge row, naive, at 50 digits."""
    with mp.workdps(DPS):
        z, s, T = _z_theta(w, dev.sample_time)
        A = _chain_matrix(dev, s)
        n = dev.n
        e0 = mp.matrix(n, 1)
        e0[0] = 1
        en = mp.matrix(n, 1)
        en[n - 1] = -1  # force -F_d on the last mass
        v = mp.lu_solve(A, e0)
        u = mp.lu_solve(A, en)
        h = (2 / T) * (z - 1) / (z + 1)
        hold = (1 / h) * (z - 1) / (T * z)
        y11 = v[0]
        y21 = -v[n - 1]
        y12 = u[0] * hold
        y22 = -u[n - 1] * hold
        se = dev.sensor_element
        if n > 1:
            zs = mp.mpf(float(dev.dampings[se])) + mp.mpf(float(dev.stiffnesses[se])) / s
            f1 = zs * (v[se] - v[se + 1])
            f2 = zs * (u[se] - u[se + 1]) * hold
        else:
            f1, f2 = mp.mpf(1), mp.mpf(0)
        return (y11, y12, y21, y22, f1, f2, z, T)


def impedance_bound(dev, w):
    """Right side of eq. (9), naive, 50 digits."""
    with mp.workdps(DPS):
        y11, y12, y21, y22, *_ = device_y(dev, w)
        p = y12 * y21
        return (abs(p) + mp.re(p)) / (2 * mp.re(y11)) - mp.re(y22)


def re_inv_zc(w, T, kc, bc):
    with mp.workdps(DPS):
        z, _, T = _z_theta(w, T)
        zc = mp.mpf(bc) + mp.mpf(kc) * T * z / (z - 1)
        return mp.re(1 / zc)


def admittance_g(dev, w, kp, kd):
    """G(z) of eq. (14) from eq. (2), (27), (30), naive, 50 digits."""
    with mp.workdps(DPS):
        y11, y12, y21, y22, f1, f2, z, T = device_y(dev, w)
        Kd = mp.mpf(kp) * T * z / (z - 1) + mp.mpf(kd)
        d = 1 + Kd * y22
        g11 = y11 - y12 * Kd * y21 / d
        g12 = y12 * Kd / d
        g21 = f1 - f2 * Kd * y21 / d
        g22 = f2 * Kd / d
        return g11, g12, g21, g22, z, T


def admittance_bound(dev, w, kp, kd):
    """Right side of eq. (21), naive, 50 digits."""
    with mp.workdps(DPS):
        g11, g12, g21, g22, _, _ = admittance_g(dev, w, kp, kd)
        p = g12 * g21
        return (abs(p) + mp.re(p)) / (2 * mp.re(g11)) - mp.re(g22)


def re_zca(w, T, mc, bc):
    with mp.workdps(DPS):
        z, _, T = _z_theta(w, T)
        s = (z - 1) / (T * z)
        y = 1 / mp.mpf(bc) + 1 / (mp.mpf(mc) * s)
        return mp.re(1 / y)
