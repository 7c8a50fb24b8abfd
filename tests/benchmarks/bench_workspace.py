"""Workspace-map benchmarks (issue 25): the five-bar's map by the certified loci against the scan.

* the map of the default :class:`~analysis.multidof.FiveBar` on a 50 x 50 grid of handle
  positions (x -0.1 to 0.1 m, y 0.12 to 0.28 m), the isotropic wall and 12 plane-wall normals at
  each point, wall damping 2 N s/m, one sample of delay, by the default route (the loci of each
  point's wall-free loop, certified on the exact loop; target 5000 ms), with the eigenvalue
  problems it solves per wall and the walls its certificate left to the scan; the same at 10 x 10
  and 25 x 25 (the scaling with the number of grid points);
* the two routes in the same run on a 15 x 15 grid: the scan (24 points a decade, then bisection
  to 1e-12 for every wall: ``method="scan"``) against the loci: the run-time ratio, the
  eigenvalue problems per wall of each, and the largest disagreement (relative; both are the
  stable end of a 1e-12 bracket of the rule's crossing);
* a dense check: every K of a scan at 200 points a decade from 1 N/m up to the map's value, at 3
  points and every wall, must be stable (the count of unstable ones must be 0).

``quick`` (``zwidth bench --quick``, at most about 2 s): a 4 x 4 grid by both routes and the
dense check at one point at 50 points a decade.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

import analysis.multidof.limits as limits_module
import analysis.multidof.loci as loci_module
from analysis.multidof import (FiveBar, check_directions, five_bar_device, frequency_first_crossings, wall_pencil,
                               workspace_map)
from analysis.sampled import is_stable, spectral_radius

from tests.benchmarks.common import timed

DAMPING, DELAY, DIRECTIONS = 2.0, 1, 12


def _grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.linspace(-0.1, 0.1, n), np.linspace(0.12, 0.28, n)


def _count_eigenproblems(fn: Callable[[], object]) -> int:
    """The closed-loop matrices whose spectral radius the crossings compute during ``fn()``."""
    original = limits_module.spectral_radius
    count = [0]

    def counting(Phi: np.ndarray, *args: object, **kwargs: object) -> np.ndarray:
        count[0] += int(np.prod(Phi.shape[:-2]))
        return original(Phi, *args, **kwargs)

    limits_module.spectral_radius = loci_module.spectral_radius = counting
    try:
        fn()
    finally:
        limits_module.spectral_radius = loci_module.spectral_radius = original
    return count[0]


def _map(n: int, method: str):
    x, y = _grid(n)
    return workspace_map(FiveBar(), x=x, y=y, damping=DAMPING, delay_samples=DELAY, directions=DIRECTIONS,
                         method=method)


def _walls(m) -> int:
    return int(m.reachable.sum()) * (DIRECTIONS + 1)


def _map_rows(quick: bool) -> list[dict]:
    rows = []
    for n in (() if quick else (10, 25, 50)):  # quick: the routes row times the loci
        t, m = timed(lambda: _map(n, "loci"), repeat=3, quick=quick)
        row = {"name": f"five-bar workspace map {n}x{n}, {DIRECTIONS} normals + isotropic, 1 sample delay, loci",
               **t, "ms_per_point": t["median_ms"] / max(int(m.reachable.sum()), 1),
               "minimum_N_per_m": m.minimum.stiffness}
        if n == 50:
            row["target_ms"] = 5000.0
        if not quick:
            row["eigenproblems_per_wall"] = _count_eigenproblems(lambda: _map(n, "loci")) / _walls(m)
        rows.append(row)
    return rows


def _routes_row(quick: bool) -> dict:
    n = 4 if quick else 15
    t_scan, scan = timed(lambda: _map(n, "scan"), repeat=1, quick=quick)
    t_loci, loci = timed(lambda: _map(n, "loci"), repeat=3, quick=quick)
    r = scan.reachable
    a = np.concatenate([loci.k_max[r], loci.worst_stiffness[r]])
    b = np.concatenate([scan.k_max[r], scan.worst_stiffness[r]])
    both = np.isfinite(a) & np.isfinite(b) & (b > 0)
    row = {"name": f"workspace map {n}x{n}: scan vs loci, same run", "scan_ms": t_scan["median_ms"],
           "loci_ms": t_loci["median_ms"], "ratio": t_scan["median_ms"] / t_loci["median_ms"],
           "max_rel_disagreement": float(np.max(np.abs(a[both] / b[both] - 1.0)))}
    if not quick:
        walls = _walls(scan)
        row["scan_eigenproblems_per_wall"] = _count_eigenproblems(lambda: _map(n, "scan")) / walls
        row["loci_eigenproblems_per_wall"] = _count_eigenproblems(lambda: _map(n, "loci")) / walls
    return row


def _dense_row(quick: bool) -> dict:
    points = [(0.0, 0.2)] if quick else [(0.0, 0.2), (0.09, 0.13), (-0.05, 0.27)]
    per_decade = 50 if quick else 200
    dirs = check_directions(2, DIRECTIONS)
    shapes = np.concatenate([np.eye(2)[None], dirs[:, :, None] * dirs[:, None, :]])
    unstable = checked = 0
    for p in points:
        dev = five_bar_device(FiveBar(), p)
        k_loci, _ = frequency_first_crossings([dev], shapes, DAMPING, DELAY)  # the map's route, every wall
        P0, P1 = wall_pencil(dev, shapes, DAMPING, DELAY)
        for p0, p1, k in zip(P0, P1, k_loci[0]):
            ks = np.geomspace(1.0, k, int(per_decade * np.log10(k)) + 1)
            unstable += int(np.count_nonzero(~np.asarray(is_stable(spectral_radius(p0 + ks[:, None, None] * p1)))))
            checked += ks.size
    return {"name": f"dense K check below the loci's values ({per_decade}/decade), {len(points)} points, every wall",
            "unstable_below_k": unstable, "k_checked": checked}


def run(quick: bool = False) -> list[dict]:
    """``quick``: a 4 x 4 grid by both routes and a one-point dense check (module docstring)."""
    return _map_rows(quick) + [_routes_row(quick), _dense_row(quick)]


if __name__ == "__main__":  # pragma: no cover
    for r in run(quick=True):
        print(r)
