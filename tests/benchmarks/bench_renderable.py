"""Renderable-space benchmarks (issue 24): the (M, B, K) space of the HBFD and its brute-force peer.

* the renderable space of the HBFD (one sample of delay, backward difference, second-difference
  acceleration) on a 41 x 41 (M, B) grid, M -0.8 to 0.2 kg, B -5 to 100 N s/m, with every
  quality (stable, passive, accurate, quiet; a 0.1 um encoder, accurate within 20 % over
  1-10 rad/s; target 5000 ms on an unloaded core), with the eigenvalue problems it solves per grid point (the loop's stability trace,
  counted on one extra untimed run) and the volume;
* the peer: the same loop's largest stable K by a dense brute-force scan of K (200 points per
  decade from 1 N/m to 1e9 N/m, every K of the scan evaluated, the last stable one before the
  first unstable) on a 5 x 5 (M, B) grid, against the space's bisection on the same grid: the
  run-time ratio, the largest disagreement (relative; the scan's own step is 1.2 %) and the
  number of points where the scan finds an unstable K below the space's k_max (must be 0).

``quick`` (``zwidth bench --quick``, at most about 2 s): an 11 x 11 grid, and the peer on a 3 x 3
grid at 50 points per decade.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from analysis.sampled import QualitySettings, renderable_space
import analysis.sampled.zwidth as zwidth_module
from analysis.sampled.loop import is_stable
from analysis.sampled.qualities import stable_radius
from analysis.sampled.rendered import RenderingController

from tests.benchmarks.common import hbfd, timed

QUALITIES = ("stable", "passive", "accurate", "quiet")
SETTINGS = QualitySettings(encoder_resolution=1e-7, band=(1.0, 10.0), tolerance=0.2)


def _grid(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.linspace(-0.8, 0.2, n), np.linspace(-5.0, 100.0, n)


def _count_eigenproblems(fn: Callable[[], object]) -> int:
    """The closed-loop matrices whose eigenvalues the stability trace computes during ``fn()``."""
    original = zwidth_module.spectral_radius
    count = [0]

    def counting(Phi: np.ndarray, *args: object, **kwargs: object) -> np.ndarray:
        count[0] += int(np.prod(Phi.shape[:-2]))
        return original(Phi, *args, **kwargs)

    zwidth_module.spectral_radius = counting
    try:
        fn()
    finally:
        zwidth_module.spectral_radius = original
    return count[0]


def dense_stable_k(device, controller: RenderingController, mass: float, damping: float,
                   per_decade: int, k_range: tuple[float, float] = (1.0, 1e9)) -> tuple[float, float]:
    """``(k_last_stable, k_first_unstable)`` of a dense scan of K (every point evaluated)."""
    n = int(round(per_decade * np.log10(k_range[1] / k_range[0]))) + 1
    ks = np.geomspace(k_range[0], k_range[1], n)
    rho = stable_radius(device, controller, np.full(n, mass), np.full(n, damping), ks, SETTINGS.grasps)
    bad = ~np.asarray(is_stable(rho))
    if not bad.any():
        return float(ks[-1]), float("inf")
    j = int(np.argmax(bad))
    return (float(ks[j - 1]) if j else 0.0), float(ks[j])


def _peer_rows(quick: bool) -> list[dict]:
    dev = hbfd()
    ctrl = RenderingController(1)
    n, per_decade = (3, 50) if quick else (5, 200)
    M, B = _grid(n)
    t_space, space = timed(lambda: renderable_space(dev, M, B, 1, qualities=("stable",)), repeat=3, quick=quick)

    def brute() -> np.ndarray:
        return np.array([[dense_stable_k(dev, ctrl, m, b, per_decade) for b in B] for m in M])

    t_brute, dense = timed(brute, repeat=1, quick=quick)
    k = space.k_max
    last_stable, first_unstable = dense[..., 0], dense[..., 1]
    both = (k > 0) & (last_stable > 0)
    disagreement = float(np.max(np.abs(last_stable[both] / k[both] - 1.0))) if both.any() else 0.0
    return [{"name": f"renderable space vs dense K scan ({per_decade}/decade), HBFD, {n}x{n} (M, B), stable",
             "space_ms": t_space["median_ms"], "dense_ms": t_brute["median_ms"],
             "ratio": t_brute["median_ms"] / t_space["median_ms"], "max_rel_disagreement": disagreement,
             "unstable_below_k_max": int(np.count_nonzero(first_unstable <= k * (1 - 1e-12))),
             "scan_step": 10 ** (1 / per_decade) - 1}]


def run(quick: bool = False) -> list[dict]:
    """``quick``: an 11 x 11 grid and a 3 x 3 peer at 50 points per decade (module docstring)."""
    dev = hbfd()
    n = 11 if quick else 41
    M, B = _grid(n)

    def space():
        return renderable_space(dev, M, B, 1, qualities=QUALITIES, settings=SETTINGS)

    t, s = timed(space, repeat=3, quick=quick)
    eig = 0 if quick else _count_eigenproblems(space)
    row = {"name": f"renderable space of the HBFD, {n}x{n} (M, B), every quality, 1 sample delay", **t,
           **({} if quick else {"target_ms": 5000.0, "eigenproblems_per_point": eig / (n * n)}),
           "volume": s.volume, "median_k_max": float(np.median(s.k_max)),
           **{f"points_{q}": int(np.count_nonzero(s.by_quality[q] > 0)) for q in QUALITIES}}
    return [row] + _peer_rows(quick)


if __name__ == "__main__":  # pragma: no cover
    for r in run(quick=True):
        print(r)
