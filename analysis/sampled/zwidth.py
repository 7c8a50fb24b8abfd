"""The classic Z-width picture: the stable region of a virtual wall in the (B, K) plane.

Colgate & Brown ("Factors affecting the Z-width of a haptic display", IEEE ICRA 1994,
pp. 3205-3210) read a display's Z-width as the set of virtual walls ``K + B V(z)`` it renders
stably, drawn in the (B, K) plane and often measured point by point on hardware.  Here the
region is computed exactly from the sampled loop of :mod:`analysis.sampled.loop`: the wall is
the impedance display's coupling ``(k_c, b_c) = (K, B)`` against the default termination,
hands-off and the god-object wall (the same worst case as
:func:`~analysis.sampled.sweeps.critical_stiffness`), with the controller's velocity estimate
(:class:`~analysis.chain.velocity_filter.VelocityFilter`) and computation delay.

For each B the largest stable K is the *first* crossing of spectral radius 1 going up in K:
a geometric scan of K from ``k_range[0]`` (``per_decade/3`` points per decade, a decade at a
time for the B still stable, every B in one batch of eigenvalue problems sharing one plant
discretization), the first unstable coarse step rescanned at ``per_decade`` points per decade
(24 by default: 10 % steps, as :func:`~analysis.sampled.sweeps.critical_stiffness`), then a
vectorized bracketing (false position alternating with halving, in log K) between the last
stable and the first unstable point, keeping the stable end (conservative).  Stable islands
above the first crossing are never reported; an unstable window narrower than a coarse step
(10^(1/8), 33 %) below it can be missed.  Where ``k_range[0]`` itself is unstable the row is 0,
even when a window of K above it is stable (conservative; e.g. a 0.05 kg, 2 N s/m rigid device
with a 1 Hz ``butter2`` at B = 50 N s/m and one sample of delay is stable for K in about
[35, 1300] N/m only).  On a rigid device with the backward difference the region ends at the
damping limit ``B_max = (2m/T) tan(pi/(4(d+1)))`` (ideal mass, d samples of delay), where the
K -> 0 loop ``z^(d+1)(z - 1) + (BT/2m)(z + 1)`` reaches the unit circle.  States whose rows vanish in every closed-loop matrix
(the god-object's held ``x_e``, ``v_e``) are dropped before the eigenvalues: they only add
eigenvalues at 0.

The region also carries the passive region of the device taken as a rigid body (total mass,
total damping to ground, no grasp; Colgate & Schenkel,
:func:`~analysis.sampled.passivity.passivity_limits`)
and, when the caller provides it, the two-port limit of eq. (9) (``twoport_limit``: the sampled
layer may not import :mod:`analysis.twoport`; pass e.g.
``lambda b: ImpedanceDisplay(device, velocity_filter=f).stiffness_chart(b).kc``).

Scalar Z-width (:func:`region_area`): the area of the stable region over the B range,
``area_linear = int K_max dB`` (N^2 s/m^2) and ``area_log = int log10(K_max/K_floor)
d log10 B`` (decades^2, ``K_floor = k_range[0]``), both by the trapezoid rule on the given
B grid, with ``K_max`` capped at ``k_range[1]``.  :func:`~analysis.sampled.trials.optimal_filter`
maximizes ``area_linear`` by default (:data:`OPTIMIZER_AREA`), the area of Colgate & Brown's and
Chawda et al.'s linear plots.

Noise criterion (optional, off by default): with ``encoder_resolution`` (m) the damping's force
noise ``B sigma_v`` of the filtered estimate (:mod:`analysis.sampled.velocity_noise`: white
quantization noise ``q^2/12`` through ``H_f(z)(1 - z^{-1})/T``) must stay within ``force_noise``
(N rms, default 0.1): every B above ``b_noise = F_noise/sigma_v`` gets ``K_max = 0`` (not
renderable).  This is the noise side of Chawda et al.'s trade-off; it makes the area fall at high
cut-offs (noise) as the lag makes it fall at low ones.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import BACKWARD, VelocityFilter
from analysis.checks import Real, integer
from analysis.errors import ValidationError
from analysis.sampled.loop import STABILITY_TOLERANCE, LoopSpec, closed_loop_matrices, discrete_plants, spectral_radius
from analysis.sampled.passivity import passivity_limits
from analysis.sampled.rendered import AccelerationEstimate
from analysis.sampled.terminations import HANDS_OFF, Termination, god_object_wall
from analysis.sampled.velocity_noise import DEFAULT_FORCE_NOISE, noise_limited_damping

__all__ = ["ZWidthRegion", "zwidth_region", "stiffness_limits", "noise_limited_stiffness", "region_area", "check_b_values", "OPTIMIZER_AREA",
           "DEFAULT_B"]

_UNSTABLE = 1.0 + STABILITY_TOLERANCE
_B = Real(lo=0.0, unit="N s/m")
#: The area the filter optimizer maximizes (a :class:`ZWidthRegion` attribute name).
OPTIMIZER_AREA = "area_linear"
#: The default B range: 100 values from 0.1 to 100 N s/m.
DEFAULT_B = np.geomspace(0.1, 100.0, 100)


@dataclass(frozen=True)
class ZWidthRegion:
    """The (B, K) stable region of a virtual wall (module docstring).

    ``k_max[i]``: exact largest stable K at ``b[i]`` (``k_ceiling`` where nothing up to it is
    unstable, 0 where ``k_floor`` already is); ``k_passive[i]``: Colgate-Schenkel's largest
    passive K of the rigid-body device (NaN where none); ``k_twoport[i]``: the eq. (9) limit at
    ``b_c = b[i]`` (NaN when not computed or infeasible).  ``area_linear`` and ``area_log``:
    :func:`region_area` (the optimizer uses :data:`OPTIMIZER_AREA`).  ``b_noise``: the
    noise-limited damping of the noise criterion (N s/m; ``inf`` when it is off), above which
    ``k_max`` is 0; ``force_noise``: its tolerance (N rms; ``None`` when off).

    Parameters
    ----------
    b : numpy.ndarray
        Wall dampings B [N s/m], strictly increasing, shape (N,).
    k_max : numpy.ndarray
        Largest stable K [N/m] at each B, shape (N,).
    k_passive : numpy.ndarray
        Largest passive K [N/m] of the rigid-body device, shape (N,); NaN where none or not
        computed.
    k_twoport : numpy.ndarray
        The eq. (9) limit [N/m], shape (N,); NaN when not computed or infeasible.
    area_linear : float
        ``int K_max dB`` [N^2 s/m^2].
    area_log : float
        ``int log10(K_max/K_floor) d log10 B`` [decades^2].
    delay_samples : int
        Computation delay in samples.
    velocity_filter : VelocityFilter
        The velocity estimate's filter (the backward difference for none).
    k_floor : float
        Lowest scanned K [N/m] (``k_range[0]``).
    k_ceiling : float
        Highest scanned K [N/m] (``k_range[1]``).
    b_noise : float, optional
        Noise-limited damping [N s/m]; ``inf`` when the criterion is off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` when the criterion is off.
    """

    b: np.ndarray
    k_max: np.ndarray
    k_passive: np.ndarray
    k_twoport: np.ndarray
    area_linear: float
    area_log: float
    delay_samples: int
    velocity_filter: VelocityFilter
    k_floor: float
    k_ceiling: float
    b_noise: float = math.inf
    force_noise: float | None = None

    def stable(self, b: float, k: float) -> bool:
        """Whether ``(b, k)`` lies in the region (K_max interpolated linearly in log B).

        Parameters
        ----------
        b : float
            Wall damping B [N s/m].
        k : float
            Wall stiffness K [N/m].

        Returns
        -------
        bool
            True when ``k <= K_max(b)``; False outside the computed B range.
        """
        return bool(k <= self.k_limit(np.array([b]))[0])

    def k_limit(self, b: np.ndarray) -> np.ndarray:
        """``K_max`` at ``b`` (linear interpolation in log B; NaN outside the computed range).

        Parameters
        ----------
        b : numpy.ndarray
            Wall dampings B [N s/m], any shape.

        Returns
        -------
        numpy.ndarray
            ``K_max`` [N/m], the shape of ``b``.
        """
        b = np.asarray(b, float)
        lb, grid = np.log(np.maximum(b, 1e-300)), np.log(np.maximum(self.b, 1e-300))
        out = np.interp(lb, grid, self.k_max)
        return np.where((b < self.b.min()) | (b > self.b.max()), np.nan, out)


def check_b_values(b: object) -> np.ndarray:
    """The B values of a region: at least two, >= 0, finite, strictly increasing (default :data:`DEFAULT_B`)."""
    arr = np.asarray(DEFAULT_B if b is None else b, dtype=float).reshape(-1)
    if arr.size < 2:
        raise ValidationError("b", "at least two values of B (N s/m)", b)
    for i, x in enumerate(arr.tolist()):
        _B("b", x, i)
    if np.any(np.diff(arr) <= 0):
        raise ValidationError("b", "strictly increasing values (N s/m)", b)
    return arr


def stiffness_limits(device: Device, b: np.ndarray, delay_samples: int = 0,
                     velocity_filter: VelocityFilter | None = None, *, termination: Termination | None = None,
                     implementation_delay: bool = False, k_range: tuple[float, float] = (1.0, 1e9),
                     per_decade: int = 24, rtol: float = 1e-10, mass: np.ndarray | None = None,
                     acceleration: AccelerationEstimate | None = None) -> np.ndarray:
    """Largest stable wall stiffness K for each damping ``b`` (first crossing; module docstring).

    Numerical kernel: the scan and the bisection are batched over every B at once (one plant
    discretization, one stacked eigenvalue problem per step), which is what makes 100 values of
    B for the HBFD take a fraction of a second; it is kept in one piece for that reason.
    ``rtol`` is the relative width of the final bracket (the stable end is returned).
    ``mass`` (one virtual mass per B, kg) adds the rendered environment's mass term with the
    estimate ``acceleration`` (:mod:`analysis.sampled.rendered`); ``None``: no mass term.
    """
    b = np.asarray(b, float).reshape(-1)
    lo, hi = float(k_range[0]), float(k_range[1])
    if not (0 < lo < hi and math.isfinite(hi)):
        raise ValidationError("k_range", "0 < low < high, finite (N/m)", k_range)
    term = Termination(HANDS_OFF, god_object_wall()) if termination is None else termination
    masses = None if mass is None else np.broadcast_to(np.asarray(mass, float).reshape(-1), b.shape)
    spec = LoopSpec("impedance", (1.0, 1.0), delay_samples=integer("delay_samples", delay_samples, 0, 1000),
                    implementation_delay=implementation_delay, velocity_filter=velocity_filter,
                    acceleration=None if masses is None else (acceleration or AccelerationEstimate()))
    if velocity_filter is not None:
        velocity_filter.check(device.sample_time)
    plants = discrete_plants(device, (term.grasp,))

    def radius(idx: np.ndarray, ks: np.ndarray) -> np.ndarray:
        ov = {"kc": ks, "bc": b[idx]} if masses is None else {"kc": ks, "bc": b[idx], "mv": masses[idx]}
        Phi = closed_loop_matrices(device, spec, [term] * idx.size, plants, np.zeros(idx.size, dtype=int), ov)
        # a state whose row is zero in every matrix (the god-object's held x_e, v_e) only adds an
        # eigenvalue 0: expanding det(zI - Phi) along that row leaves z det(minor)
        keep = np.flatnonzero(np.any(Phi != 0.0, axis=(0, 2)))
        return spectral_radius(Phi[:, keep][:, :, keep])

    def scan(grid: np.ndarray, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per row of ``b[rows]``: index of the first unstable K of ``grid``, whether any is, radii."""
        n = grid.shape[-1]
        g = np.broadcast_to(grid, (rows.size, n))
        rho = radius(np.repeat(rows, n), g.reshape(-1)).reshape(rows.size, n)
        bad = rho > _UNSTABLE
        return np.argmax(bad, axis=1), bad.any(axis=1), rho

    # coarse scan at per_decade/3, a decade at a time for the rows still stable (a row stops at
    # its first unstable point); the first coarse unstable step is rescanned at per_decade
    n = max(int(math.ceil(per_decade / 3 * math.log10(hi / lo))), 2) + 1
    grid = np.geomspace(lo, hi, n)
    first, anybad = np.zeros(b.size, dtype=int), np.zeros(b.size, dtype=bool)
    rho = np.zeros((b.size, n))
    step = max(per_decade // 3, 1)
    for start in range(0, n, step):
        rows = np.flatnonzero(~anybad)
        if rows.size == 0:
            break
        j, hit, r = scan(grid[start:start + step], rows)
        rho[rows, start:start + step] = r
        first[rows] = np.where(hit, start + j, first[rows])
        anybad[rows] = hit
    out = np.where(anybad, 0.0, hi)
    todo = np.flatnonzero(anybad & (first > 0))
    if todo.size:
        f = first[todo]
        fine = np.exp(np.linspace(np.log(grid[f - 1]), np.log(grid[f]), 4, axis=-1))
        j, _, rfine = scan(fine[:, 1:3], todo)
        j = np.where((rfine > _UNSTABLE).any(axis=1), j + 1, 3)
        rows = np.arange(todo.size)
        rvals = np.concatenate([rho[todo, f - 1][:, None], rfine, rho[todo, f][:, None]], axis=1)
        safe = np.log(fine[rows, j - 1]), rvals[rows, j - 1] - _UNSTABLE
        unsafe = np.log(fine[rows, j]), rvals[rows, j] - _UNSTABLE
        out[todo] = np.exp(_bracket(lambda x: radius(todo, np.exp(x)) - _UNSTABLE, safe, unsafe, rtol))
    return out


def noise_limited_stiffness(device: Device, b: np.ndarray, b_noise: float, delay_samples: int = 0,
                            velocity_filter: VelocityFilter | None = None, **options) -> np.ndarray:
    """:func:`stiffness_limits` with ``K_max = 0`` for every B above ``b_noise`` (not computed there).

    ``b_noise = inf`` is exactly :func:`stiffness_limits` over all of ``b``.
    """
    b = np.asarray(b, float).reshape(-1)
    if not math.isfinite(b_noise):
        return stiffness_limits(device, b, delay_samples, velocity_filter, **options)
    out, ok = np.zeros(b.size), b <= b_noise
    if ok.any():
        out[ok] = stiffness_limits(device, b[ok], delay_samples, velocity_filter, **options)
    return out


def _bracket(g: Callable[[np.ndarray], np.ndarray], safe: tuple[np.ndarray, np.ndarray],
             unsafe: tuple[np.ndarray, np.ndarray], tol: float = 1e-10) -> np.ndarray:
    """The safe end of ``[x_s, x_u]`` (``g <= 0`` at ``x_s``, ``> 0`` at ``x_u``) shrunk below ``tol``.

    False-position steps (kept 5 % inside the bracket) alternate with halvings, so the bracket
    at least halves every two steps and shrinks fast where ``g`` is smooth; the stable end is
    returned (conservative).
    """
    (xs, gs), (xu, gu) = safe, unsafe
    for it in range(120):
        w = xu - xs
        if np.all(w <= tol):
            break
        if it % 2 == 0:
            with np.errstate(divide="ignore", invalid="ignore"):
                t = np.where(gu - gs > 0, -gs / (gu - gs), 0.5)
            x = xs + np.clip(t, 0.05, 0.95) * w
        else:
            x = xs + 0.5 * w
        gx = g(x)
        up = gx > 0
        xu, gu = np.where(up, x, xu), np.where(up, gx, gu)
        xs, gs = np.where(up, xs, x), np.where(up, gs, gx)
    return xs


def region_area(b: np.ndarray, k: np.ndarray, k_floor: float, k_ceiling: float) -> tuple[float, float]:
    """``(area_linear, area_log)`` of the region under ``k`` over ``b`` (module docstring)."""
    b, k = np.asarray(b, float), np.minimum(np.asarray(k, float), k_ceiling)
    k = np.where(np.isfinite(k), k, 0.0)
    lin = float(np.trapezoid(k, b))
    lb = np.log10(np.maximum(b, 1e-300))
    heights = np.log10(np.maximum(k, k_floor) / k_floor)
    ok = b > 0  # B = 0 is at minus infinity on a log axis
    log = float(np.trapezoid(heights[ok], lb[ok])) if np.count_nonzero(ok) > 1 else 0.0
    return lin, log


def zwidth_region(device: Device, b: np.ndarray | None = None, delay_samples: int = 0,
                  velocity_filter: VelocityFilter | None = None, *, termination: Termination | None = None,
                  implementation_delay: bool = False, k_range: tuple[float, float] = (1.0, 1e9),
                  passive: bool = True, twoport_limit: Callable[[np.ndarray], np.ndarray] | None = None,
                  encoder_resolution: float | None = None, force_noise: float | None = None) -> ZWidthRegion:
    """The (B, K) region of the wall ``K + B V(z)`` (module docstring), default B 0.1-100 N s/m.

    ``passive``: also compute the Colgate-Schenkel region of the rigid-body device;
    ``twoport_limit(b) -> k`` supplies eq. (9)'s limit (NaN otherwise).  ``encoder_resolution``
    (m) turns on the noise criterion with tolerance ``force_noise`` (N rms, default 0.1).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    b : numpy.ndarray or None, optional
        Wall dampings B [N s/m], at least two, at least 0, strictly increasing, shape (N,);
        ``None`` for :data:`DEFAULT_B`.
    delay_samples : int, optional
        Computation delay in samples, 0 to 1000.
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter; ``None`` for the backward difference.
    termination : Termination or None, optional
        The grasp and environment; ``None`` for hands-off against the god-object wall.
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    k_range : tuple of (float, float), optional
        The scanned K [N/m], ``(low, high)`` with ``0 < low < high``, finite.
    passive : bool, optional
        Also compute the Colgate-Schenkel passive region of the rigid-body device.
    twoport_limit : callable or None, optional
        ``twoport_limit(b) -> k``: eq. (9)'s limit [N/m] at each B, shape (N,).
    encoder_resolution : float or None, optional
        Encoder resolution [m] of the noise criterion; ``None`` turns it off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` for 0.1 (only with ``encoder_resolution``).

    Returns
    -------
    ZWidthRegion
        The region, its limits and areas.
    """
    bs = check_b_values(b)
    vf = BACKWARD if velocity_filter is None else velocity_filter
    bn = noise_limited_damping(vf, device.sample_time, encoder_resolution, force_noise)
    kmax = noise_limited_stiffness(device, bs, bn, delay_samples, velocity_filter, termination=termination,
                                   implementation_delay=implementation_delay, k_range=k_range)
    kpas = np.full(bs.size, np.nan)
    if passive:
        kpas = passivity_limits(device.total_mass, device.total_ground_damping, device.sample_time, bs,
                                delay_samples, 2001, velocity_filter=vf)
    k2 = np.full(bs.size, np.nan) if twoport_limit is None else np.asarray(twoport_limit(bs), float).reshape(-1)
    lin, log = region_area(bs, kmax, float(k_range[0]), float(k_range[1]))
    return ZWidthRegion(b=bs, k_max=kmax, k_passive=kpas, k_twoport=k2, area_linear=lin, area_log=log,
                        delay_samples=int(delay_samples), velocity_filter=vf, k_floor=float(k_range[0]),
                        k_ceiling=float(k_range[1]), b_noise=bn,
                        force_noise=None if encoder_resolution is None else
                        (DEFAULT_FORCE_NOISE if force_noise is None else float(force_noise)))
