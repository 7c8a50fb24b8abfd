"""Dense-grid references for the design searches (independent grids and optimizers).

They use the production bound (checked against 50-digit mpmath in test_accuracy.py) but
neither the resonance grid nor :func:`analysis.grids.refine_minima`.  The coupling side of
each inequality is written here from its closed form.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar


def band(device, points: int) -> np.ndarray:
    return np.geomspace(device.band_min, device.nyquist * (1.0 - 1e-9), points)


def re_inv_zc(w, T, kc, bc):
    """Re(1/Z_c), Z_c = b_c + k_c T z/(z-1) = (b_c + k_c T/2) - j (k_c T/2) cot(wT/2)."""
    beta = bc + 0.5 * kc * T
    gam = 0.5 * kc * T / np.tan(0.5 * np.asarray(w) * T)
    return beta / (beta * beta + gam * gam)


def re_zca(w, T, mc, bc):
    """Re(Z_cA), 1/Z_cA = 1/b_c + T z/(m_c (z-1)) = (1/b_c + T/(2m_c)) - j T cot(wT/2)/(2 m_c)."""
    a = 0.5 * T / mc
    re = 1.0 / bc + a
    im = a / np.tan(0.5 * np.asarray(w) * T)
    return re / (re * re + im * im)


def refined_min(f, w, v, candidates: int = 6, xatol: float = 1e-13):
    """Global minimum of a sampled function ``v = f(w)``: the dense minimum, then scipy's bounded
    Brent search (in log w) between the neighbours of the ``candidates`` best local minima."""
    v = np.where(np.isnan(v), np.inf, v)
    j = int(np.argmin(v))
    best, wbest = float(v[j]), float(w[j])
    if not math.isfinite(best):
        return best, wbest
    inner = np.flatnonzero((v[1:-1] <= v[:-2]) & (v[1:-1] <= v[2:])) + 1
    idx = list(inner[np.argsort(v[inner])][:candidates])
    for i in idx:
        lo, hi = math.log(w[max(i - 1, 0)]), math.log(w[min(i + 1, w.size - 1)])
        r = minimize_scalar(lambda x: float(f(np.array([math.exp(x)]))[0]), bounds=(lo, hi),
                            method="bounded", options=dict(xatol=xatol))
        if r.fun < best:
            best, wbest = float(r.fun), math.exp(r.x)
    return best, wbest


def dense_max_stiffness(imp, bc: float, points: int = 300_000, candidates: int = 6):
    """Largest k_c of eq. (9): minimum over frequency of the closed-form per-frequency limit."""
    from analysis.twoport.impedance import kc_upper

    T = imp.device.sample_time
    w = band(imp.device, points)

    def f(x):
        return kc_upper(imp.bound_parts(x).bound, x, T, bc)

    return refined_min(f, w, f(w), candidates)


def u_limits(B, w, T, mc):
    """Interval [L, U] of u = 1/b_c for which Re Z_cA >= B at each w (independent algebra).

    With t = u + a, a = T/(2 m_c), g = a cot(wT/2): Re Z_cA = t/(t^2+g^2) >= B, i.e.
    B t^2 - t + B g^2 <= 0 for B > 0 (every t >= a works where B <= 0).
    """
    L = np.full(w.shape, -np.inf)
    U = np.full(w.shape, np.inf)
    pos = B > 0
    L[pos], U[pos] = _u_limits_pos(B[pos], np.tan(0.5 * w[pos] * T), 0.5 * T / mc)
    return L, U


def _u_limits_pos(Bp, tan_half, a):
    """:func:`u_limits` where B > 0 (``Bp``), with ``tan(wT/2)`` there and ``a = T/(2 m_c)``."""
    g2 = (a / tan_half) ** 2
    d = 1.0 - 4.0 * Bp ** 2 * g2
    ok = d >= 0
    sq = np.sqrt(np.where(ok, d, 0.0))
    tlo = 2.0 * Bp * g2 / (1.0 + sq)  # = (1 - sq)/(2B), stable
    thi = (1.0 + sq) / (2.0 * Bp)
    return np.where(ok, tlo - a, np.inf), np.where(ok, thi - a, -np.inf)


def dense_interval(adm, mc: float, points: int = 400_000):
    """Feasible b_c interval of eq. (21) on a dense log grid (optimistic by construction)."""
    w = band(adm.device, points)
    B = adm.bound_parts(w).bound
    L, U = u_limits(B, w, adm.device.sample_time, mc)
    u_lo, u_hi = max(float(L.max()), 0.0), float(U.min())
    if not u_hi > u_lo:
        return None
    return 1.0 / u_hi, (math.inf if u_lo == 0 else 1.0 / u_lo), w, B


def dense_min_mass(adm, w, B, rtol: float = 1e-12):
    """Smallest m_c with a non-empty interval on the sampled (w, B): bisection in log m_c."""
    T = adm.device.sample_time
    pos = B > 0  # u_limits' algebra on the points with B > 0 (elsewhere L = -inf, U = inf),
    Bp, tan_half = B[pos], np.tan(0.5 * w[pos] * T)  # their mass-independent parts computed once

    def feasible(mc):
        if Bp.size == 0:
            return True
        L, U = _u_limits_pos(Bp, tan_half, 0.5 * T / mc)
        return max(float(L.max()), 0.0) < float(U.min())

    lo, hi = 1e-6, 1.0
    while not feasible(hi):
        hi *= 2.0
    while hi / lo - 1.0 > rtol:
        mid = math.sqrt(lo * hi)
        if feasible(mid):
            hi = mid
        else:
            lo = mid
    return hi
