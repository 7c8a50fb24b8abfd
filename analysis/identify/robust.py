"""Designs that hold for every device in a box of parameters (issue 14).

Given a device and intervals on any of its parameters (``{"ground_dampings[3]": (1.2, 5.0)}``,
or a fit's :attr:`~analysis.identify.ChainFit.intervals`):

* :func:`robust_max_stiffness` -- the largest k_c that satisfies eq. (9) of Adams, Moreyra &
  Hannaford for *every* device in the box (impedance display, coupling ``b_c + k_c Tz/(z-1)``);
* :func:`robust_feasible_damping` -- the b_c interval for a coupling mass m_c that satisfies
  eq. (21) for every device (admittance display with PD gains ``k_p``, ``k_d``);
* :func:`robust_critical_stiffness` -- the smallest exact sampled-data critical k_c over the box
  (:func:`analysis.sampled.critical_stiffness`).

Each is the worst case of a per-device limit, found by :func:`analysis.identify.boxsearch.box_search`
(screening, corners, seeded random sample, bounded local minimization; see there why corners
alone are not enough).  The search runs on a cheap evaluation (the limit on the device's own
resonance-aware grid, no refinement between grid points); the best few points are then
re-evaluated with the refined design functions (:meth:`analysis.ImpedanceDisplay.max_stiffness`,
:meth:`analysis.AdmittanceDisplay.feasible_damping`), whose results are already backed off by
1e-9 relative, and the smallest is reported together with the binding device.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.identify.boxsearch import ParameterBox, SearchTrace, box_search, parameter_box
from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.impedance import ImpedanceDisplay, kc_upper

__all__ = ["RobustStiffness", "RobustDamping", "robust_max_stiffness", "robust_feasible_damping",
           "robust_critical_stiffness"]

_REFINE = 4  # best search points re-evaluated with the refined design functions


@dataclass(frozen=True, eq=False)
class RobustStiffness:
    """Robust largest k_c (eq. 9) or exact critical k_c over a parameter box.

    ``kc`` is ``None`` when some device in the box admits no k_c >= 0; ``device`` and
    ``binding`` (the boxed parameters' values) are where the limit binds, ``frequency`` the
    binding frequency (``nan`` for the sampled-data limit).  ``points`` (E, p) and ``values`` are
    every device evaluated by the search (parameter values of ``keys``, cheap limits).

    Parameters
    ----------
    bc : float
        The coupling damping b_c [N s/m] the limit is for.
    kc : float or None
        The robust k_c [N/m]; ``None`` when some device in the box admits no k_c >= 0.
    device : Device
        The device where the limit binds.
    binding : dict of str to float
        The boxed parameters' values at ``device``.
    frequency : float
        The binding frequency [rad/s]; ``nan`` for the sampled-data limit.
    nominal_kc : float or None
        The same limit for the nominal device [N/m]; ``None`` when it admits no k_c >= 0.
    corner : bool
        Whether the binding device is at a corner of the box.
    evaluations : int
        Number of devices evaluated by the search.
    keys : tuple of str
        The boxed parameter keys (``p`` of them).
    points : numpy.ndarray
        Parameter values of ``keys`` of every evaluated device [kg, N/m or N s/m], shape (E, p).
    values : numpy.ndarray
        The search's (cheap) limit of each evaluated device [N/m], shape (E,).
    """

    bc: float
    kc: float | None
    device: Device
    binding: dict
    frequency: float
    nominal_kc: float | None
    corner: bool
    evaluations: int
    keys: tuple[str, ...]
    points: np.ndarray
    values: np.ndarray


@dataclass(frozen=True, eq=False)
class RobustDamping:
    """Robust feasible b_c interval ``[low, high]`` for ``mc`` (eq. 21); ``None`` when empty.

    ``low_device`` / ``high_device`` are the devices where each edge binds (``*_binding`` their
    boxed parameter values).

    Parameters
    ----------
    mc : float
        The coupling mass m_c [kg] the interval is for.
    low : float or None
        Lower edge of the robust b_c interval [N s/m]; ``None`` when the interval is empty.
    high : float or None
        Upper edge [N s/m] (may be ``inf``); ``None`` when the interval is empty.
    low_device : Device
        The device where the lower edge binds.
    high_device : Device
        The device where the upper edge binds.
    low_binding : dict of str to float
        The boxed parameters' values at ``low_device``.
    high_binding : dict of str to float
        The boxed parameters' values at ``high_device``.
    nominal : tuple of (float or None, float or None)
        The nominal device's feasible ``(low, high)`` [N s/m]; ``(None, None)`` when empty.
    evaluations : int
        Number of devices evaluated by the two searches.
    """

    mc: float
    low: float | None
    high: float | None
    low_device: Device
    high_device: Device
    low_binding: dict
    high_binding: dict
    nominal: tuple[float | None, float | None]
    evaluations: int

    @property
    def feasible(self) -> bool:
        return self.low is not None


def _kc_on_grid(device: Device, bc: float) -> float:
    """Largest k_c by eq. (9) on the device's own grid, without refinement (the search's cheap
    evaluation; ``-inf`` when no k_c works)."""
    disp = ImpedanceDisplay(device)
    w = disp.frequencies()
    return float(np.min(kc_upper(disp.bound(w), w, device.sample_time, bc)))


def _kc_refined(device: Device, bc: float) -> tuple[float, float]:
    d = ImpedanceDisplay(device).max_stiffness(bc)
    return (-math.inf if d.kc is None else float(d.kc)), float(d.frequency)


def _each(box: ParameterBox, fn: Callable[[Device], float]) -> Callable[[np.ndarray], np.ndarray]:
    def evaluate(u: np.ndarray) -> np.ndarray:
        return np.array([fn(box.device_at(row)) for row in u])
    return evaluate


def _finish(box: ParameterBox, trace: SearchTrace, exact: Callable[[Device], tuple[float, float]],
            k: int = _REFINE) -> tuple[float, float, np.ndarray]:
    """Re-evaluate the ``k`` best distinct search points with ``exact`` (device -> (value, freq));
    returns (value, frequency, u) of the smallest."""
    order = np.argsort(trace.values, kind="stable")
    seen: list[np.ndarray] = []
    best = (math.inf, math.nan, trace.points[trace.best])
    for j in order:
        u = trace.points[j]
        if any(np.max(np.abs(u - s)) <= 1e-9 for s in seen):
            continue
        seen.append(u)
        v, f = exact(box.device_at(u))
        if v < best[0]:
            best = (v, f, u)
        if len(seen) == k:
            break
    return best


def robust_max_stiffness(device: Device, bc: float, intervals: Mapping[str, tuple[float, float]], *,
                         seed: int = 0, random: int = 64, corner_limit: int = 8) -> RobustStiffness:
    """Largest k_c satisfying eq. (9) for every device in the box (module doc).

    Example (Adams et al., section VI): the HBFD with ``ground_dampings[3]`` (their b4) in
    ``[1.2, 5]`` N s/m and ``b_c = 100`` N s/m gives 49.15 kN/m, the b4 = 1.2 value, against
    117.1 kN/m for the nominal b4 = 5.

    Parameters
    ----------
    device : Device
        The nominal device (impedance display).
    bc : float
        The coupling damping b_c [N s/m].
    intervals : mapping of str to tuple of (float, float)
        ``{key: (low, high)}`` in the parameters' units (kg, N/m, N s/m), e.g. a fit's
        :attr:`~analysis.identify.ChainFit.intervals`.
    seed : int, optional
        Seed of the random sample of the search.
    random : int, optional
        Number of random points of the search.
    corner_limit : int, optional
        Largest number of boxed parameters for which every corner is evaluated.

    Returns
    -------
    RobustStiffness
        The robust k_c [N/m] with its binding device and frequency, the nominal k_c and the
        search's points.

    Raises
    ------
    ValidationError
        For an interval that :func:`~analysis.identify.parameter_box` refuses (not finite,
        ``low > high``, or a mass or stiffness interval starting at 0).
    ParameterKeyError
        When a key does not name a parameter of ``device``'s chain.
    """
    box = parameter_box(device, intervals)
    trace = box_search(_each(box, lambda d: _kc_on_grid(d, bc)), box, seed=seed, random=random,
                       corner_limit=corner_limit)
    kc, freq, u = _finish(box, trace, lambda d: _kc_refined(d, bc))
    nominal = _kc_refined(device, bc)[0]
    return RobustStiffness(bc=float(bc), kc=None if kc == -math.inf else kc, device=box.device_at(u),
                           binding=box.binding(u), frequency=freq, nominal_kc=None if nominal == -math.inf else nominal,
                           corner=bool(np.all((u == 0) | (u == 1))), evaluations=len(trace.values),
                           keys=box.keys, points=box.values(trace.points), values=trace.values)


def _damping_edges(device: Device, mc: float, kp: float, kd: float) -> tuple[float, float]:
    """(low, high) of the feasible b_c on the device's own grid (eq. 21), no refinement;
    ``(inf, 0)`` when empty."""
    disp = AdmittanceDisplay(device, kp, kd)
    w = disp.frequencies()
    L, U = disp.inverse_damping_limits(disp.bound(w), w, mc)
    u_hi, u_lo = float(np.min(U)), max(float(np.max(L)), 0.0)
    if not u_hi > u_lo:
        return math.inf, 0.0
    return (1.0 / u_hi if math.isfinite(u_hi) else 0.0), (math.inf if u_lo == 0 else 1.0 / u_lo)


def robust_feasible_damping(device: Device, mc: float, kp: float, kd: float,
                            intervals: Mapping[str, tuple[float, float]], *, seed: int = 0,
                            random: int = 64, corner_limit: int = 8) -> RobustDamping:
    """b_c interval satisfying eq. (21) for every device in the box: ``[max low, min high]``
    (each device's feasible set is an interval, so the robust set is their intersection).

    Parameters
    ----------
    device : Device
        The nominal device (admittance display).
    mc : float
        The coupling mass m_c [kg].
    kp : float
        Proportional gain k_p of the admittance display's PD controller [N/m].
    kd : float
        Derivative gain k_d [N s/m].
    intervals : mapping of str to tuple of (float, float)
        ``{key: (low, high)}`` in the parameters' units (kg, N/m, N s/m).
    seed : int, optional
        Seed of the random sample (the upper edge's search uses ``seed + 1``).
    random : int, optional
        Number of random points of each search.
    corner_limit : int, optional
        Largest number of boxed parameters for which every corner is evaluated.

    Returns
    -------
    RobustDamping
        The robust b_c interval [N s/m] (``None`` edges when empty) with the binding devices.

    Raises
    ------
    ValidationError
        For an interval that :func:`~analysis.identify.parameter_box` refuses (not finite,
        ``low > high``, or a mass or stiffness interval starting at 0), or for ``kp`` or ``kd``
        outside its physical range.
    ParameterKeyError
        When a key does not name a parameter of ``device``'s chain.
    """
    box = parameter_box(device, intervals)

    def refined(d: Device) -> tuple[float, float]:
        r = AdmittanceDisplay(d, kp, kd).feasible_damping(mc)
        return (math.inf, 0.0) if r.low is None else (r.low, r.high)

    tl = box_search(_each(box, lambda d: -_damping_edges(d, mc, kp, kd)[0]), box, seed=seed, random=random,
                    corner_limit=corner_limit)
    th = box_search(_each(box, lambda d: _damping_edges(d, mc, kp, kd)[1]), box, seed=seed + 1, random=random,
                    corner_limit=corner_limit)
    neg_low, _, ul = _finish(box, tl, lambda d: (-refined(d)[0], math.nan))
    high, _, uh = _finish(box, th, lambda d: (refined(d)[1], math.nan))
    low = -neg_low
    nom = refined(device)
    ok = math.isfinite(low) and low < high
    return RobustDamping(mc=float(mc), low=low if ok else None, high=high if ok else None,
                         low_device=box.device_at(ul), high_device=box.device_at(uh), low_binding=box.binding(ul),
                         high_binding=box.binding(uh),
                         nominal=(None, None) if not math.isfinite(nom[0]) else nom,
                         evaluations=len(tl.values) + len(th.values))


def robust_critical_stiffness(device: Device, bc: float, intervals: Mapping[str, tuple[float, float]],
                              delay_samples: int = 0, *, seed: int = 0, random: int = 8,
                              corner_limit: int = 4, **kwargs) -> RobustStiffness:
    """Smallest exact sampled-data critical k_c (:func:`analysis.sampled.critical_stiffness`,
    ``kwargs`` passed on) over the box.

    Each evaluation is an exact scan and bisection of the closed-loop spectral radius (about
    0.5 s for the HBFD), so the search is lighter than for eq. (9): screening, corners up to
    ``corner_limit`` parameters, ``random`` seeded samples and one short local minimization.

    Parameters
    ----------
    device : Device
        The nominal device.
    bc : float
        The coupling damping b_c [N s/m].
    intervals : mapping of str to tuple of (float, float)
        ``{key: (low, high)}`` in the parameters' units (kg, N/m, N s/m).
    delay_samples : int, optional
        Computation delay [samples].
    seed : int, optional
        Seed of the random sample of the search.
    random : int, optional
        Number of random points of the search.
    corner_limit : int, optional
        Largest number of boxed parameters for which every corner is evaluated.
    **kwargs
        Keyword arguments of :func:`analysis.sampled.critical_stiffness`.

    Returns
    -------
    RobustStiffness
        The smallest critical k_c [N/m] (``None`` when not positive), its binding device, the
        nominal critical k_c and the search's points; ``frequency`` is ``nan``.

    Raises
    ------
    ValidationError
        For an interval that :func:`~analysis.identify.parameter_box` refuses (not finite,
        ``low > high``, or a mass or stiffness interval starting at 0).
    ParameterKeyError
        When a key does not name a parameter of ``device``'s chain.
    """
    from analysis.sampled import critical_stiffness

    box = parameter_box(device, intervals)

    def crit(d: Device) -> float:
        return float(critical_stiffness(d, bc, delay_samples, **kwargs))

    trace = box_search(_each(box, crit), box, seed=seed, random=random, corner_limit=corner_limit,
                       local_starts=1, local_iterations=3)
    u = trace.points[trace.best]
    kc = float(trace.values[trace.best])
    nominal = crit(device)
    return RobustStiffness(bc=float(bc), kc=kc if kc > 0 else None, device=box.device_at(u), binding=box.binding(u),
                           frequency=math.nan, nominal_kc=nominal, corner=trace.corner,
                           evaluations=len(trace.values), keys=box.keys, points=box.values(trace.points),
                           values=trace.values)
