"""Numerical kernels of the transparency analysis: peak refinement and Gauss-Legendre panels.

* :func:`refine_peaks` polishes the local maxima of ``|G(jw)|`` found on a grid, for many
  transfer functions at once (one per row, e.g. one per ``B_c``).  Each bracket
  ``[w_{i-1}, w_{i+1}]`` around a grid maximum is zoomed in log-frequency: seven equally spaced
  points, keep the best and its two neighbours, repeat (the bracket shrinks by 3 per step).  Forty
  steps reach the rounding level, so the peak gain is exact to rounding provided the grid resolves
  the peak (the callers place grid points on the closed-loop resonances, see
  :mod:`analysis.transparency`), never a fixed coarse grid.
* :func:`panel_breakpoints` builds quadrature panels whose width is at most a fraction of the
  distance to the nearest singularity of the integrand, so that Gauss-Legendre converges
  geometrically on every panel; :func:`gauss_nodes` turns panels into nodes and weights.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["refine_peaks", "panel_breakpoints", "gauss_nodes", "local_maxima"]

_GL_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    if n not in _GL_CACHE:
        _GL_CACHE[n] = np.polynomial.legendre.leggauss(n)
    return _GL_CACHE[n]


def gauss_nodes(breaks: np.ndarray, order: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """Nodes and weights of composite ``order``-point Gauss-Legendre on the panels ``breaks``."""
    x, wts = _legendre(order)
    a, b = breaks[:-1, None], breaks[1:, None]
    half = 0.5 * (b - a)
    nodes = (0.5 * (a + b) + half * x[None, :]).ravel()
    weights = (half * wts[None, :]).ravel()
    return nodes, weights


#: the narrowest panel, relative to its left end (:func:`panel_breakpoints`)
MIN_PANEL = 1e-9


def panel_breakpoints(lo: float, hi: float, singularities: np.ndarray, per_decade: float = 8.0,
                      fraction: float = 0.5, max_width: float = np.inf) -> np.ndarray:
    """Breakpoints from ``lo`` to ``hi`` (both > 0).

    Panel ``[a, a + h]`` has ``h <= a (10^{1/per_decade} - 1)`` (log spacing),
    ``h <= fraction * min_k |a - c_k|`` over the complex singularities ``c_k`` of the
    integrand (as ``w0 + j sigma``), and ``h <= max_width``.  With ``fraction = 1/2`` the
    nearest singularity is at least three panel half-widths from the panel centre (Bernstein
    ellipse parameter >= 3 + sqrt 8), so 16-point Gauss-Legendre errs by ~1e-24 relative.
    A panel is never narrower than ``MIN_PANEL * a``: a singularity closer to the real axis than
    that (``|sigma| < 2e-9 w0``, e.g. an undamped plant mode) costs about 60 panels instead of
    an endless approach.
    """
    sing = np.asarray(singularities, dtype=complex).ravel()
    step = 10.0 ** (1.0 / per_decade) - 1.0
    out = [lo]
    a = lo
    while a < hi:
        h = a * step
        if sing.size:
            d = float(np.min(np.abs(a - sing)))
            h = min(h, fraction * d)
        # never narrower than MIN_PANEL * a: a singularity on the real axis (an undamped plant
        # mode, sigma = 0) would otherwise be approached in ever smaller steps and, once a step
        # fell below the spacing of doubles, never passed (the loop ran until memory ran out)
        h = min(max(h, MIN_PANEL * a), max_width)
        a = min(a + h, hi)
        if hi - a < 1e-9 * hi:
            a = hi
        out.append(a)
    return np.asarray(out)


def local_maxima(values: np.ndarray, count: int) -> np.ndarray:
    """Indices (rows x count) of up to ``count`` largest interior local maxima per row.

    Rows with fewer maxima repeat their best one; the first and last grid points count as
    maxima when they beat their single neighbour (the bracket is clipped there).
    """
    v = values
    n = v.shape[1]
    left = np.concatenate([np.full((v.shape[0], 1), -np.inf), v[:, :-1]], axis=1)
    right = np.concatenate([v[:, 1:], np.full((v.shape[0], 1), -np.inf)], axis=1)
    is_max = (v >= left) & (v >= right)
    score = np.where(is_max, v, -np.inf)
    k = min(count, n)
    idx = np.argpartition(-score, k - 1, axis=1)[:, :k]
    best = np.argmax(score, axis=1)
    bad = ~np.isfinite(np.take_along_axis(score, idx, axis=1))
    idx = np.where(bad, best[:, None], idx)
    return idx


def refine_peaks(evaluate: Callable[[np.ndarray, np.ndarray], np.ndarray], rows: np.ndarray,
                 lo: np.ndarray, hi: np.ndarray, steps: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Zoom each bracket ``[lo, hi]`` (rad/s, > 0) onto the maximum of ``evaluate``.

    Each step evaluates 13 points and keeps a sixth of the bracket (two of its twelve intervals):
    half the calls of 7 points and a third, which matters for one bracket (the live value during
    a drag), where a call's overhead outweighs its points.  It stops when every bracket is narrower
    than 1e-9 in ln(w): the peak value is then exact to about ``Q**2 * 1e-18`` relative (``Q`` the peak's
    quality factor), far below the 1e-12 the tests ask, in about half the steps of a bracket
    shrunk to round-off.

    ``evaluate(rows, w)`` returns ``|G|^2`` for row indices ``rows`` (shape K) at frequencies
    ``w`` (shape K x P).  Returns ``(w_peak, value)`` per bracket.
    """
    a = np.log(lo)
    b = np.log(hi)
    pts = np.linspace(0.0, 1.0, 13)
    best_x = 0.5 * (a + b)
    best_v = evaluate(rows, np.exp(best_x)[:, None])[:, 0]
    for _ in range(steps):
        x = a[:, None] + (b - a)[:, None] * pts[None, :]
        v = evaluate(rows, np.exp(x))
        i = np.argmax(v, axis=1)
        vi = v[np.arange(v.shape[0]), i]
        better = vi >= best_v
        best_v = np.where(better, vi, best_v)
        best_x = np.where(better, x[np.arange(x.shape[0]), i], best_x)
        il = np.maximum(i - 1, 0)
        ir = np.minimum(i + 1, 12)
        a, b = x[np.arange(x.shape[0]), il], x[np.arange(x.shape[0]), ir]
        if np.all(b - a <= 1e-9):
            break
    return np.exp(best_x), best_v
