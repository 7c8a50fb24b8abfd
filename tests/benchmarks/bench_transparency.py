"""Transparency benchmarks (Eom, Suh & Yi): run time against error for J and ||L||_inf, Fig. 8 timing.

* J (eq. 11) at B_c = 15 for the ``zoh`` hold: Gauss-Legendre panel density (panels per decade,
  nodes per panel) against error, next to scipy quad at tight tolerance (the reference);
* J for ``lowpass2``: Lyapunov (the reference), the batched modal H2 formula and the quadrature;
* ||L||_inf at B_c = 1 and 15 (``zoh``): fixed log grids of 10^2 .. 10^6 points without refinement
  against the grid-with-resonances-plus-zoom route; reference = 10^6-point grid plus Brent;
* the full Fig. 8 curves (100 values of B_c, J and ||L||_inf) for every hold model, target 100 ms.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, optimize

from analysis.transparency.holds import hold_response
from analysis.transparency.design import WallDesign

from tests.benchmarks.common import timed, timeit

PAPER = dict(mass=0.01, damping=0.022, wall_stiffness=1000.0, wall_damping=1.0, sample_time=1e-3,
             weight_cutoff=100.0)


def _quad_J(bc: float, hold: str, half_periods: int = 636) -> float:
    """scipy quad over ``half_periods`` half periods beyond Nyquist (636: up to 2e6 rad/s), then the
    ``w = X/u`` tail.  ``zwidth bench --quick`` takes 10: the same route, a crash check, not a reference."""
    T, m, b, K, B = 1e-3, 0.01, 0.022, 1000.0, 1.0

    def f(w: float, osc: bool = True) -> float:
        s = 1j * w
        H = hold_response(hold, np.array([s]), T, 0.7071, osc)[0]
        P = 1 / (m * s + b)
        e = 100 / (s + 100) * (s / (K + B * s) - P / (1 + H * P * (bc + K / s)))
        return abs(e) ** 2

    edges = np.concatenate([[0.0], np.geomspace(1e-2, math.pi / T, 60), np.arange(2, half_periods + 1) * math.pi / T])
    tot = sum(integrate.quad(f, a, c, epsabs=0, epsrel=1e-13, limit=200)[0] for a, c in zip(edges[:-1], edges[1:]))
    X = edges[-1]
    tot += integrate.quad(lambda u: f(X / u, False) * X / u**2, 0.0, 1.0, epsabs=0, epsrel=1e-13)[0]
    return tot / math.pi


def _brute_peak(d: WallDesign, bc: float, n: int, refine: bool) -> float:
    w = np.geomspace(1e-1, 1e6, n)

    def mag(x):
        _, yt = d.admittances(np.atleast_1d(x), bc)
        return np.abs((0.5 * 0.01 * 1j * np.atleast_1d(x) + 0.5 * 0.022) * yt)

    v = np.concatenate([mag(c) for c in np.array_split(w, max(1, n // 50_000))])
    i = int(np.argmax(v))
    best = float(v[i])
    if refine:
        res = optimize.minimize_scalar(lambda x: -mag(x)[0], bounds=(w[max(i - 1, 0)], w[min(i + 1, n - 1)]),
                                       method="bounded", options={"xatol": 1e-12 * w[i]})
        best = max(best, -float(res.fun))
    return max(best, 0.5)


#: Half periods of the quad reference in ``zwidth bench --quick`` (70 pieces with the tail): the
#: quick run's errors against it are a crash check, not the accuracy the full run reports.
QUICK_HALF_PERIODS = 10


def run(quick: bool = False) -> list[dict]:
    """``quick``: one call of each, 2 x 2 quadrature densities, 10 B_c, a 10^5-point peak reference,
    the quad reference on :data:`QUICK_HALF_PERIODS` half periods."""
    rows: list[dict] = []
    rep = 20

    # -- J, zoh --------------------------------------------------------------------------------
    d = WallDesign(**PAPER, hold="zoh")
    halves = QUICK_HALF_PERIODS if quick else 636
    t, ref = timed(lambda: _quad_J(15.0, "zoh", halves), repeat=3, quick=quick)
    label = f"{halves + 60} pieces (quick: a crash check)" if quick else "1300 pieces (reference)"
    rows.append({"name": f"J zoh B_c=15: scipy quad, {label}", **t, "J": ref})
    for per_decade in (2, 8) if quick else (1, 2, 4, 8, 16):
        for order in (4, 16) if quick else (4, 6, 8, 12, 16, 24):
            r = d.index_result(15.0, method="quadrature", per_decade=per_decade, order=order)
            t = timeit(lambda: WallDesign(**PAPER, hold="zoh").index_result(15.0, per_decade=per_decade,
                                                                           order=order), repeat=rep, quick=quick)
            rows.append({"name": f"J zoh B_c=15: Gauss {order} nodes x {per_decade} panels/decade", **t,
                         "nodes": r.nodes, "rel_err_vs_quad": abs(r.index - ref) / ref})

    # -- J, lowpass2 ------------------------------------------------------------------------------
    d2 = WallDesign(**PAPER, hold="lowpass2")
    t, lyap_result = timed(lambda: WallDesign(**PAPER, hold="lowpass2").index_result(15.0), repeat=rep, quick=quick)
    lyap = lyap_result.index
    rows.append({"name": "J lowpass2 B_c=15: Lyapunov (reference)", **t, "J": lyap,
                 "rel_err_vs_quad": abs(lyap - _quad_J(15.0, "lowpass2", halves)) / lyap})
    t, r = timed(lambda: WallDesign(**PAPER, hold="lowpass2").index_result(15.0, method="quadrature"), repeat=rep,
                 quick=quick)
    rows.append({"name": "J lowpass2 B_c=15: Gauss quadrature (16 x 8/decade)", **t, "nodes": r.nodes,
                 "rel_err_vs_lyapunov": abs(r.index - lyap) / lyap})
    bcs = np.linspace(0.5, 40, 10 if quick else 100)
    t, many = timed(lambda: WallDesign(**PAPER, hold="lowpass2").index.h2_modal_many(bcs, "lowpass2"), repeat=rep,
                    quick=quick)
    exact = np.array([d2.index_result(x).index for x in bcs])
    rows.append({"name": f"J lowpass2, {bcs.size} B_c: batched modal H2", **t,
                 "max_rel_err_vs_lyapunov": float(np.max(np.abs(many - exact) / exact))})

    # -- ||L||_inf, zoh --------------------------------------------------------------------------
    dense, dense_label = (100_000, "1e5") if quick else (1_000_000, "1e6")
    for bc in (1.0, 15.0):
        t, refp = timed(lambda: _brute_peak(d, bc, dense, refine=True), repeat=3, quick=quick)
        rows.append({"name": f"||L|| zoh B_c={bc:g}: {dense_label} grid + Brent (reference)", **t, "gain": refp})
        for n in (100, 10_000) if quick else (100, 1000, 10_000, 100_000):
            t, g = timed(lambda: _brute_peak(d, bc, n, refine=False), repeat=rep, quick=quick)
            rows.append({"name": f"||L|| zoh B_c={bc:g}: fixed log grid, {n} points", **t,
                         "rel_err": abs(g - refp) / refp})
        t, p = timed(lambda: WallDesign(**PAPER, hold="zoh").robustness_peak(bc), repeat=rep, quick=quick)
        rows.append({"name": f"||L|| zoh B_c={bc:g}: resonance grid + zoom (ours)", **t,
                     "rel_err": abs(p.gain - refp) / refp, "certified": p.certified})

    # -- Fig. 8 ------------------------------------------------------------------------------------
    for hold in ("none", "pade", "lowpass2", "zoh", "discrete"):
        t = timeit(lambda: WallDesign(**PAPER, hold=hold).tradeoff(bcs), repeat=rep, quick=quick)
        rows.append({"name": f"Fig. 8 curves, {bcs.size} B_c, hold={hold} (cold)", **t,
                     **({} if quick else {"target_ms": 100.0})})
    return rows


if __name__ == "__main__":
    for row in run(quick=False):
        print(row)
