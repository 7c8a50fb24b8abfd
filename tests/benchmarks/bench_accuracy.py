"""Run time against error for the design figures and the bound (issue: fast and accurate).

For the HBFD with damping ratio 0.1, 1e-2, 1e-3 and 1e-4 in every flexible element:

* largest k_c (b_c = 50 N s/m): plain log grids of several sizes (minimum of the closed-form
  per-frequency limit on the grid, as one would do by hand), the same grids with zwidth's
  refinement, and zwidth's resonance-aware design (``max_stiffness``); the reference is a
  dense 300 000-point grid with scipy's bounded Brent refinement of its best minima;
* smallest feasible b_c for m_c = 31 kg (admittance display, k_p = 50 kN/m, k_d = 100 N s/m),
  the same way;
* the bound itself: zwidth, the literal formula in double precision, python-control and a
  plain numpy n x n solve per frequency, against 50-digit mpmath.

Writes ``docs/bench_kc_error.png`` and ``docs/bench_bc_error.png`` (error against time).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

from analysis import AdmittanceDisplay, ImpedanceDisplay
from analysis.chain import grids
from analysis.twoport.impedance import kc_upper

from tests.benchmarks.common import hbfd, timed

RATIOS = (0.1, 1e-2, 1e-3, 1e-4)
GRIDS = (100, 300, 1000, 3000, 10000)
BC = 50.0  # N s/m: with 100, no k_c is feasible for damping ratios <= 1e-3 (B b_c > 1 at the peaks)
#: ``zwidth bench --quick``: the lightest and the least damped device, a 20 000-point reference
QUICK_RATIOS = (0.1, 1e-4)
QUICK_DENSE = 20_000


def _dense_min(f, lo, hi, points):
    w = np.geomspace(lo, hi, points)
    v = f(w)
    order = np.argsort(v)[:6]
    best = float(v[order[0]])
    for j in order:
        a, b = w[max(j - 1, 0)], w[min(j + 1, w.size - 1)]
        r = minimize_scalar(lambda lx: float(f(np.array([np.exp(lx)]))[0]), bounds=(np.log(a), np.log(b)),
                            method="bounded", options={"xatol": 1e-12})
        best = min(best, float(r.fun))
    return best


def _kc_rows(quick: bool) -> tuple[list[dict], dict]:
    rows, series = [], {}
    dense_points = QUICK_DENSE if quick else 300_000
    for z in QUICK_RATIOS if quick else RATIOS:
        dev = hbfd(ratio=z)
        imp = ImpedanceDisplay(dev)
        T = dev.sample_time
        lo, hi = grids.band_edges(dev)

        def f(x, imp=imp, T=T):
            return kc_upper(imp.bound_parts(x).bound, x, T, BC)

        ref = _dense_min(f, lo, hi, dense_points)
        pts = []
        for n in GRIDS[:2] if quick else GRIDS:
            w = np.geomspace(lo, hi, n)
            t, val = timed(lambda w=w: float(np.min(f(w))), repeat=10, quick=quick)
            pts.append(("log grid", n, t["median_ms"], (val - ref) / ref))
            t2, (rw, rv) = timed(lambda w=w: grids.refine_minima(f, w, f(w), lo, hi, candidates=8), repeat=10,
                                 quick=quick)
            val2 = min(val, float(rv[0]) if rv.size else np.inf)
            pts.append(("log grid + refinement", n, t2["median_ms"], (val2 - ref) / ref))
        t3, d = timed(lambda dev=dev: ImpedanceDisplay(dev).max_stiffness(BC), repeat=20, quick=quick)
        pts.append(("zwidth resonance grid", d.evaluations, t3["median_ms"], (d.kc - ref) / ref))
        # signed error: k_c above the dense reference is on the unsafe side
        series[z] = [(name, n, ms, abs(e), e > 1e-12) for name, n, ms, e in pts]
        for name, n, ms, err in pts:
            rows.append({"name": f"largest k_c, zeta={z:g}, {name}", "points": n, "median_ms": ms,
                         "rel_err": abs(err), "unsafe": bool(err > 1e-12)})
        rows.append({"name": f"largest k_c, zeta={z:g}, dense reference", "points": dense_points,
                     "kc": ref})
    return rows, series


def _bc_rows(quick: bool) -> tuple[list[dict], dict]:
    rows, series = [], {}
    dense_points = QUICK_DENSE if quick else 300_000
    mc = 31.0
    for z in QUICK_RATIOS if quick else RATIOS:
        dev = hbfd(ratio=z)
        adm = AdmittanceDisplay(dev, 50e3, 100.0)
        lo, hi = grids.band_edges(dev)

        def upper(x, adm=adm):
            return adm.inverse_damping_limits(adm.bound_parts(x).bound, x, mc)[1]

        ref_u = _dense_min(upper, lo, hi, dense_points)
        ref = 1.0 / ref_u
        pts = []
        for n in GRIDS[:2] if quick else GRIDS:
            w = np.geomspace(lo, hi, n)
            t, low = timed(lambda w=w: float(np.min(upper(w))), repeat=10, quick=quick)
            val = 1.0 / low
            pts.append(("log grid", n, t["median_ms"], (val - ref) / ref))
        t3, d = timed(lambda dev=dev: AdmittanceDisplay(dev, 50e3, 100.0).feasible_damping(mc), repeat=10,
                      quick=quick)
        err = (d.low - ref) / ref if d.low is not None else float("nan")
        pts.append(("zwidth resonance grid", len(adm.frequencies()), t3["median_ms"], err))
        # signed error: a smallest b_c below the dense reference is on the unsafe side
        series[z] = [(name, n, ms, abs(e), e < -1e-12) for name, n, ms, e in pts]
        for name, n, ms, e in pts:
            rows.append({"name": f"smallest b_c at m_c=31, zeta={z:g}, {name}", "points": n,
                         "median_ms": ms, "rel_err": abs(e), "unsafe": bool(e < -1e-12)})
    return rows, series


def _bound_rows(quick: bool) -> list[dict]:
    from tests import reference as ref

    from tests.benchmarks.bench_core import control_route

    dev = hbfd()
    w = np.geomspace(1e-4, dev.nyquist * 0.999, 6 if quick else 40)
    exact = np.array([float(ref.impedance_bound(dev, x)) for x in w])
    band = w >= 1.0
    M, B, K = dev.matrices()
    T = dev.sample_time

    def dense_solve(w=w):
        s = 1j * (2 / T) * np.tan(0.5 * w * T)
        out = np.empty(w.size)
        h = np.cos(0.5 * w * T) * np.exp(-0.5j * w * T)
        for i, si in enumerate(s):
            A = M * si + B + K / si
            rhs = np.zeros((dev.n, 2), complex)
            rhs[0, 0] = 1.0
            rhs[-1, 1] = -1.0
            x = np.linalg.solve(A, rhs)
            y11, y21, y12, y22 = x[0, 0], -x[-1, 0], x[0, 1] * h[i], -x[-1, 1] * h[i]
            p = y12 * y21
            out[i] = (abs(p) + p.real) / (2 * y11.real) - y22.real
        return out

    routes = {
        "zwidth (cancellation-free)": lambda: ImpedanceDisplay(dev).bound_parts(w).bound,
        "python-control (ss, c2d tustin) + literal eq. 9": lambda: control_route(dev, w)[1],
        "numpy n x n solve per frequency + literal eq. 9": dense_solve,
    }
    rows = []
    for name, fn in routes.items():
        t, val = timed(fn, repeat=20, quick=quick)
        err = np.abs(val - exact) / np.abs(exact)
        rows.append({"name": f"impedance bound, {name}, {w.size} frequencies", "median_ms": t["median_ms"],
                     "max_rel_err_1rad_to_nyq": float(err[band].max()),
                     "max_rel_err_1e-4_to_nyq": float(err.max())})
    return rows


def _plot(series: dict, title: str, path: Path) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover - plots are optional
        return
    from matplotlib.ticker import LogLocator, NullFormatter

    fig, axes = plt.subplots(1, len(series), figsize=(4.2 * len(series), 3.8), sharey=True)
    styles = (("log grid", "o", "C0"), ("log grid + refinement", "s", "C1"), ("zwidth resonance grid", "*", "C2"))
    for ax, (z, pts) in zip(np.atleast_1d(axes), series.items()):
        for method, marker, colour in styles:
            sel = [(ms, max(err, 1e-17), n, bad) for name, n, ms, err, bad in pts if name == method]
            if not sel:
                continue
            x, y, n, bad = zip(*sel)
            ax.loglog(x, y, color=colour, lw=1, label=method)
            size = 11 if marker == "*" else 6
            for xi, yi, bi in zip(x, y, bad):  # filled: conservative; hollow: on the unsafe side
                ax.plot([xi], [yi], marker=marker, ms=size, color=colour,
                        markerfacecolor="white" if bi else colour)
            labelled = range(len(x)) if method != "log grid + refinement" else (0, len(x) - 1)
            for i in labelled:
                ax.annotate(str(n[i]), (x[i], y[i]), textcoords="offset points",
                            xytext=(4, -10 if method == "log grid + refinement" else 4), fontsize=7)
        ax.axhline(1e-6, color="grey", lw=0.8, ls="--")
        ax.set_title(f"damping ratio {z:g}")
        ax.set_xlabel("run time (ms)")
        ax.xaxis.set_major_locator(LogLocator(base=10))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="major", alpha=0.3)
    np.atleast_1d(axes)[-1].text(0.98, 0.02, "hollow marker: result on the unsafe side", ha="right",
                                 va="bottom", fontsize=7, transform=np.atleast_1d(axes)[-1].transAxes)
    np.atleast_1d(axes)[0].set_ylabel("relative error against dense reference")
    np.atleast_1d(axes)[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(quick: bool = False) -> list[dict]:
    start = time.perf_counter()
    rows, kc_series = _kc_rows(quick)
    bc_rows, bc_series = _bc_rows(quick)
    rows += bc_rows
    rows += _bound_rows(quick)
    if not quick:
        docs = Path(__file__).resolve().parents[2] / "docs"
        _plot(kc_series, "Largest k_c (HBFD, b_c = 50 N s/m): error against run time (labels: points)",
              docs / "bench_kc_error.png")
        _plot(bc_series, "Smallest b_c at m_c = 31 kg (HBFD admittance display): error against run time",
              docs / "bench_bc_error.png")
    rows.append({"name": "bench_accuracy total", "seconds": time.perf_counter() - start})
    return rows


if __name__ == "__main__":
    for r in run(quick=False):
        print(r)
