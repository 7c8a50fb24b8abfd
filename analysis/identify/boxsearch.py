"""Worst case of a scalar design limit over a box of device parameters.

The limits (largest k_c by eq. 9, the edges of the feasible b_c interval by eq. 21, the exact
sampled-data critical k_c) are minima over frequency of smooth functions of the parameters, so
as functions of the parameters they are continuous and piecewise smooth, with kinks where the
binding frequency jumps from one resonance to another.  They are usually monotone in each
parameter over a modest box, which puts the worst case at a corner -- but not always: a kink
(two resonances binding at once) can sit inside the box, and stiffnesses move resonances
across the band.  The search therefore combines

1. the nominal point and a one-at-a-time screening of each parameter at both ends (2p points);
2. corners: all ``2^p`` for ``p <= corner_limit``; otherwise the screening corner (every
   parameter at the end that lowered the limit) and its ``p`` single-parameter flips;
3. a seeded random sample (uniform in the box coordinates);
4. bounded local minimization (L-BFGS-B with forward-difference gradients) in the box
   coordinates from the best points found so far, which finds interior minima and kinks;

and keeps the smallest value.  Box coordinates are ``u in [0, 1]^p``, logarithmic in a
parameter whose lower bound is positive, linear otherwise.  No finite search is a proof; the
tests check the result against dense random samples of the box (and all corners of small
boxes), and the design functions back off the final value.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.identify.params import device_value, device_with, parse_key, physical_range

__all__ = ["ParameterBox", "SearchTrace", "box_search", "open_intervals", "parameter_box"]


@dataclass(frozen=True, eq=False)
class ParameterBox:
    """Intervals on some parameters of ``device``; ``u`` in ``[0, 1]^p`` maps into it.

    Parameters
    ----------
    device : Device
        The nominal device, with the point intervals' values already set.
    keys : tuple of str
        The boxed parameter keys (``p`` of them, :mod:`analysis.identify.params`).
    low : numpy.ndarray
        Lower ends [kg, N/m or N s/m], shape (p,).
    high : numpy.ndarray
        Upper ends, shape (p,), ``high > low``.
    log : numpy.ndarray
        Whether each coordinate is logarithmic (``low > 0``) or linear, bool, shape (p,).
    """

    device: Device
    keys: tuple[str, ...]
    low: np.ndarray
    high: np.ndarray
    log: np.ndarray

    @property
    def dim(self) -> int:
        return len(self.keys)

    def values(self, u: np.ndarray) -> np.ndarray:
        """Parameter values of box points (the inverse of :meth:`coordinates`).

        Parameters
        ----------
        u : numpy.ndarray
            Box coordinates in ``[0, 1]`` (clipped), shape (E, p) or (p,).

        Returns
        -------
        numpy.ndarray
            Values of :attr:`keys` [kg, N/m or N s/m], shape (E, p).
        """
        u = np.clip(np.atleast_2d(u), 0.0, 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            lg = self.low * (self.high / np.where(self.log, self.low, 1.0)) ** u
        return np.where(self.log, lg, self.low + u * (self.high - self.low))

    def coordinates(self, values: np.ndarray) -> np.ndarray:
        """Box coordinates of parameter values (the inverse of :meth:`values`).

        Parameters
        ----------
        values : numpy.ndarray
            Values of :attr:`keys`, shape (..., p).

        Returns
        -------
        numpy.ndarray
            Coordinates clipped to ``[0, 1]``, the shape of ``values``.
        """
        v = np.asarray(values, float)
        with np.errstate(divide="ignore", invalid="ignore"):
            lg = np.log(v / self.low) / np.log(self.high / self.low)
            lin = (v - self.low) / (self.high - self.low)
        return np.clip(np.where(self.log, lg, lin), 0.0, 1.0)

    def device_at(self, u: np.ndarray) -> Device:
        """The device at one box point.

        Parameters
        ----------
        u : numpy.ndarray
            Box coordinates, shape (p,) (or (1, p)).

        Returns
        -------
        Device
            :attr:`device` with :attr:`keys` set to the point's values.

        Raises
        ------
        ValidationError
            When a value is outside the range :class:`~analysis.Device` accepts.
        """
        return device_with(self.device, dict(zip(self.keys, self.values(u)[0])))

    def binding(self, u: np.ndarray) -> dict[str, float]:
        """The boxed parameters' values at one box point.

        Parameters
        ----------
        u : numpy.ndarray
            Box coordinates, shape (p,) (or (1, p)).

        Returns
        -------
        dict of str to float
            ``{key: value}`` for every key of :attr:`keys`.
        """
        return {k: float(v) for k, v in zip(self.keys, self.values(u)[0])}


#: Fields whose values are positive: an interval of theirs reaching 0 is not a box edge.
_POSITIVE = ("masses", "stiffnesses")


def open_intervals(intervals: Mapping[str, tuple[float, float]], n: int) -> tuple[str, ...]:
    """Keys of ``intervals`` (an ``n``-mass chain) that the data leave open, so that they bound no
    box: a high end that is not finite, or a low end of 0 for a mass or stiffness (a fit's
    unbounded ``(0, inf)``).  :func:`parameter_box` refuses them; a caller that wants to say why
    rather than fail asks here first.

    Parameters
    ----------
    intervals : mapping of str to tuple of (float, float)
        ``{key: (low, high)}`` in the parameters' units, e.g. :attr:`ChainFit.intervals
        <analysis.identify.ChainFit.intervals>`.
    n : int
        Number of masses of the chain.

    Returns
    -------
    tuple of str
        The open keys, in the order of ``intervals``; empty when every interval bounds a box.

    Raises
    ------
    ParameterKeyError
        When a key with a low end of 0 does not name a parameter of an ``n``-mass chain.
    """
    return tuple(k for k, (lo, hi) in intervals.items()
                 if not math.isfinite(hi) or (lo <= 0 and parse_key(k, n)[0] in _POSITIVE))


def parameter_box(device: Device, intervals: Mapping[str, tuple[float, float]]) -> ParameterBox:
    """Validate ``intervals`` (``{key: (low, high)}``) against ``device``; point intervals are
    dropped (they fix the parameter at that value), and every interval is clipped to the physical
    range :class:`~analysis.Device` accepts (a fit's interval may reach beyond it).

    Parameters
    ----------
    device : Device
        The nominal device.
    intervals : mapping of str to tuple of (float, float)
        ``{key: (low, high)}`` in the parameters' units (kg, N/m, N s/m), finite with
        ``0 <= low <= high``; ``low > 0`` for masses and stiffnesses.

    Returns
    -------
    ParameterBox
        The box of the intervals that are not points, on ``device`` with the point intervals'
        values set.

    Raises
    ------
    ValidationError
        For an interval that is not finite, has ``low > high`` or a negative end, or starts at 0
        for a mass or stiffness (or a fixed value that :class:`~analysis.Device` refuses).
    ParameterKeyError
        When a key does not name a parameter of ``device``'s chain.
    """
    keys, lo, hi = [], [], []
    fixed = {}
    for key, iv in intervals.items():
        name, _ = parse_key(key, device.n)
        a, b = (float(x) for x in iv)
        if not (np.isfinite(a) and np.isfinite(b) and 0 <= a <= b):
            raise ValidationError(key, "an interval (low, high) with 0 <= low <= high, finite", iv)
        if a == 0 and name in _POSITIVE:
            raise ValidationError(key, "low > 0 (masses and stiffnesses are positive)", iv)
        plo, phi = physical_range(key, device.n)
        a, b = min(max(a, plo if a > 0 else 0.0), phi), min(max(b, plo), phi)  # clip to the physical range
        if a == b:
            fixed[key] = a
            continue
        keys.append(key)
        lo.append(a)
        hi.append(b)
    base = device_with(device, fixed) if fixed else device
    low, high = np.array(lo, float), np.array(hi, float)
    return ParameterBox(base, tuple(keys), low, high, low > 0)


@dataclass(frozen=True)
class SearchTrace:
    """Every point evaluated (box coordinates), its value, and the index of the smallest.

    Parameters
    ----------
    points : numpy.ndarray
        Box coordinates of every evaluated point, in evaluation order, shape (E, p).
    values : numpy.ndarray
        The value at each point (``-inf`` where it could not be evaluated), shape (E,).
    best : int
        Index of the smallest value.
    corner : bool
        Whether the smallest value is at a corner of the box (every coordinate 0 or 1).
    """

    points: np.ndarray
    values: np.ndarray
    best: int
    corner: bool


class _Recorder:
    """Evaluates batches of box points and records them."""

    def __init__(self, evaluate: Callable[[np.ndarray], np.ndarray]):
        self.evaluate = evaluate
        self.points: list[np.ndarray] = []
        self.values: list[float] = []

    def __call__(self, u: np.ndarray) -> np.ndarray:
        u = np.clip(np.atleast_2d(np.asarray(u, float)), 0.0, 1.0)
        v = np.asarray(self.evaluate(u), float).reshape(-1)
        v = np.where(np.isnan(v), -np.inf, v)  # an unevaluable device counts as the worst
        self.points.extend(u)
        self.values.extend(v.tolist())
        return v

    def best(self, k: int) -> np.ndarray:
        order = np.argsort(np.array(self.values), kind="stable")
        out: list[np.ndarray] = []
        for j in order:
            if all(np.max(np.abs(self.points[j] - o)) > 1e-3 for o in out):
                out.append(self.points[j])
            if len(out) == k:
                break
        return np.array(out)


def _corners(rec: _Recorder, nominal: np.ndarray, corner_limit: int) -> None:
    """Screening (both ends of each parameter) and corners (module doc, steps 1-2)."""
    p = nominal.size
    rec(nominal)
    ends = np.repeat(nominal[None, :], 2 * p, axis=0)
    for j in range(p):
        ends[2 * j, j], ends[2 * j + 1, j] = 0.0, 1.0
    v = rec(ends)
    if p <= corner_limit:
        rec(np.array(list(itertools.product((0.0, 1.0), repeat=p))))
        return
    worse = (v[1::2] < v[0::2]).astype(float)
    flips = np.repeat(worse[None, :], p + 1, axis=0)
    flips[np.arange(1, p + 1), np.arange(p)] = 1.0 - worse
    rec(flips)


def box_search(evaluate: Callable[[np.ndarray], np.ndarray], box: ParameterBox, *, corner_limit: int = 8,
               random: int = 64, local_starts: int = 2, local_iterations: int = 12,
               seed: int = 0) -> SearchTrace:
    """Smallest value of ``evaluate`` (a batch of box points -> values) over the box (module doc).

    Parameters
    ----------
    evaluate : callable
        ``evaluate(u) -> values``: box coordinates of shape (E, p) to values of shape (E,); a
        ``nan`` counts as ``-inf`` (an unevaluable device is the worst).
    box : ParameterBox
        The box searched.
    corner_limit : int, optional
        Largest ``p`` for which all ``2^p`` corners are evaluated; above it, the screening
        corner and its ``p`` single flips.
    random : int, optional
        Number of seeded uniform random points.
    local_starts : int, optional
        Number of distinct best points the local minimization starts from.
    local_iterations : int, optional
        L-BFGS-B iterations per start (at most twice as many function evaluations).
    seed : int, optional
        Seed of the random sample.

    Returns
    -------
    SearchTrace
        Every evaluated point (the nominal one first), its value and the smallest.
    """
    p = box.dim
    rec = _Recorder(evaluate)
    nominal = box.coordinates(np.array([device_value(box.device, k) for k in box.keys]))
    if p == 0:
        rec(np.zeros((1, 0)))
        return SearchTrace(np.zeros((1, 0)), np.array(rec.values), 0, True)
    _corners(rec, nominal, corner_limit)
    if random:
        rec(np.random.default_rng(seed).random((random, p)))
    h = 1e-4

    def fun_grad(u: np.ndarray) -> tuple[float, np.ndarray]:
        pts = np.repeat(u[None, :], p + 1, axis=0)
        step = np.where(u[None, :] + h <= 1.0, h, -h)[0]
        pts[np.arange(1, p + 1), np.arange(p)] += step
        v = rec(pts)
        if not np.all(np.isfinite(v)):
            return float(v[0]), np.zeros(p)
        return float(v[0]), (v[1:] - v[0]) / step

    for start in rec.best(local_starts):
        if not np.isfinite(min(rec.values)):
            break
        optimize.minimize(fun_grad, start, jac=True, method="L-BFGS-B", bounds=[(0.0, 1.0)] * p,
                          options={"maxiter": local_iterations, "maxfun": 2 * local_iterations})
    pts, vals = np.array(rec.points), np.array(rec.values)
    best = int(np.argmin(vals))
    corner = bool(np.all((pts[best] == 0.0) | (pts[best] == 1.0)))
    return SearchTrace(pts, vals, best, corner)
