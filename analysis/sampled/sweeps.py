"""Exact stability sweeps of the sampled loop: worst case, critical couplings, stability maps.

Everything here reduces to spectral radii of the closed-loop matrices of
:mod:`analysis.sampled.loop`, computed in batches (one ``expm`` per distinct grasp, one stacked
``np.linalg.eigvals`` per causality).  A linear loop is stable exactly when the spectral radius
is at most 1 (rigid-body modes of free motion sit at z = 1 and count as 1).

Critical couplings
------------------
The spectral radius is not monotone in the coupling gains: it can dip below 1 again above a
first unstable k_c (stable windows), and it can touch 1 from below without crossing.  The
critical value reported is the *first* crossing: a geometric scan from the safe end (small
k_c, large m_c) with 24 points per decade, in one batch, and then bisection (60 halvings)
between the last stable and the first unstable scan point.  An unstable window narrower than
one scan step (10 % in the parameter) can be missed; :func:`stability_map` shows the whole
picture.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from analysis.chain.device import Device
from analysis.chain.limits import MAX_MAP_POINTS, check_count
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import nonnegative, positive
from analysis.errors import ValidationError
from analysis.sampled.controllers import display_loop
from analysis.sampled.loop import LoopSpec, closed_loop_matrices, discretize_zoh, plant_matrices, spectral_radius
from analysis.sampled.results import CriticalChart, CriticalMassChart, StabilityMap, WorstCase
from analysis.sampled.terminations import (
    CAUSALITIES,
    HANDS_OFF,
    RIGID_GRASP,
    Environment,
    Grasp,
    Termination,
    default_terminations,
    free_motion,
    god_object_wall,
)

__all__ = [
    "radii",
    "worst_case",
    "critical_stiffness",
    "critical_stiffness_chart",
    "critical_mass",
    "critical_mass_chart",
    "stability_map",
    "MAP_PARAMETERS",
]

_UNSTABLE = 1.0 + 1e-12
_PER_DECADE = 24


def radii(device: Device, spec: LoopSpec, terminations: Sequence[Termination],
          overrides: dict[str, np.ndarray] | None = None) -> np.ndarray:
    """Spectral radius of the closed loop for each termination (batched)."""
    terms = list(terminations)
    out = np.empty(len(terms))
    if not terms:
        return out
    grasps: dict[Grasp, int] = {}
    gidx = np.array([grasps.setdefault(t.grasp, len(grasps)) for t in terms])
    plants = discretize_zoh(*plant_matrices(device, list(grasps)), device.sample_time)
    for caus in CAUSALITIES:  # one batch of closed-loop matrices per environment causality
        sel = np.array([i for i, t in enumerate(terms) if t.environment.causality == caus], dtype=int)
        if sel.size == 0:
            continue
        ov = None if overrides is None else {k: np.asarray(v, float).reshape(-1)[sel] for k, v in overrides.items()}
        Phi = closed_loop_matrices(device, spec, [terms[i] for i in sel], plants, gidx[sel], ov)
        out[sel] = spectral_radius(Phi)
    return out


def worst_case(device: Device, display: str = "impedance", coupling: tuple[float, float] = (50e3, 100.0),
               terminations: Sequence[Termination] | None = None, *, pd: tuple[float, float] = (50e3, 100.0),
               delay_samples: int = 0, implementation_delay: bool = False,
               velocity_filter: VelocityFilter | None = None) -> WorstCase:
    """Worst spectral radius over human grasps x environments, and the termination attaining it.

    Default sweep (:func:`analysis.sampled.terminations.default_terminations`): hands-off to a rigid
    grasp (64 grasps) times free motion to rigid wall in both environment causalities (13).
    ``velocity_filter`` filters the damping term's velocity (default the backward difference).
    """
    spec = LoopSpec(display, coupling, pd, delay_samples, implementation_delay, velocity_filter)
    terms = tuple(default_terminations() if terminations is None else terminations)
    if not terms:
        raise ValidationError("terminations", "at least one termination", [])
    r = radii(device, spec, terms)
    i = int(np.argmax(r))
    return WorstCase(spectral_radius=float(r[i]), termination=terms[i], index=i, stable=bool(r[i] <= _UNSTABLE),
                     radii=r, terminations=terms)


def _first_crossing(f, lo: float, hi: float, increasing: bool) -> float:
    """First parameter value (scanning from the safe end) where ``f`` (batched) exceeds 1."""
    n = max(int(math.ceil(_PER_DECADE * math.log10(hi / lo))), 2) + 1
    grid = np.geomspace(lo, hi, n)
    if not increasing:
        grid = grid[::-1]
    bad = f(grid) > _UNSTABLE
    if not bad.any():
        return math.inf if increasing else 0.0
    j = int(np.argmax(bad))
    if j == 0:
        return 0.0 if increasing else math.inf
    safe, unsafe = float(grid[j - 1]), float(grid[j])
    for _ in range(60):
        mid = math.sqrt(safe * unsafe)
        if f(np.array([mid]))[0] > _UNSTABLE:
            unsafe = mid
        else:
            safe = mid
        if abs(unsafe - safe) <= 1e-12 * safe:
            break
    return safe


def critical_stiffness(device: Device, bc: float, delay_samples: int = 0, *, environment: Environment | None = None,
                       grasp: Grasp = HANDS_OFF, implementation_delay: bool = False,
                       k_range: tuple[float, float] = (1.0, 1e9),
                       velocity_filter: VelocityFilter | None = None) -> float:
    """Largest stable coupling stiffness k_c (N/m) of an impedance display, exactly.

    Default termination: hands-off against a rigid wall -- the god-object wall, which holds the
    coupling's far end fixed (the limit of an infinitely stiff penalty wall) -- the paper's
    worst case for impedance displays.  ``delay_samples`` is a computation delay between
    sampling and the force output.  Returns the first crossing of spectral radius 1 (see the
    module docstring), ``inf`` if none below ``k_range[1]``, ``0.0`` if already unstable at
    ``k_range[0]``.  ``velocity_filter`` filters the coupling's damping term
    (:mod:`analysis.sampled.filtered`; default ``None``, the backward difference).
    """
    nonnegative("bc", bc, "N s/m")
    env = god_object_wall() if environment is None else environment
    term = (Termination(grasp, env),)

    def f(ks: np.ndarray) -> np.ndarray:
        spec = LoopSpec("impedance", (1.0, float(bc)), delay_samples=delay_samples,
                        implementation_delay=implementation_delay, velocity_filter=velocity_filter)
        return radii(device, spec, term * ks.size, {"kc": ks})

    return _first_crossing(f, k_range[0], k_range[1], increasing=True)


def _each(values: np.ndarray, func: Callable[[float], float], progress: Callable[[int, int], None] | None,
          cancelled: Callable[[], bool] | None) -> np.ndarray | None:
    """``func`` at each value, reporting ``progress(done, total)``; ``None`` once ``cancelled()``."""
    out = np.empty(values.size)
    for i, v in enumerate(values):
        if cancelled is not None and cancelled():
            return None
        out[i] = func(float(v))
        if progress is not None:
            progress(i + 1, values.size)
    return out


def critical_stiffness_chart(device: Device, bc_values, delay_samples: int = 0, *,
                             progress: Callable[[int, int], None] | None = None,
                             cancelled: Callable[[], bool] | None = None, **kwargs) -> CriticalChart | None:
    """:func:`critical_stiffness` over a list of b_c (overlay for the two-port design chart).

    ``progress(done, total)`` after each b_c; ``None`` when ``cancelled()`` turns true."""
    bcs = np.asarray(bc_values, float).reshape(-1)
    kcs = _each(bcs, lambda b: critical_stiffness(device, b, delay_samples, **kwargs), progress, cancelled)
    return None if kcs is None else CriticalChart(bc=bcs, kc=kcs, delay_samples=int(delay_samples))


def critical_mass(device: Device, bc: float, pd: tuple[float, float] = (50e3, 100.0), delay_samples: int = 0, *,
                  environment: Environment | None = None, grasp: Grasp = RIGID_GRASP,
                  implementation_delay: bool = False, m_range: tuple[float, float] = (1e-3, 1e4),
                  velocity_filter: VelocityFilter | None = None) -> float:
    """Smallest stable coupling mass m_c (kg) of an admittance display, exactly.

    Default termination: the paper's worst case for admittance displays, a rigid grasp
    (:data:`analysis.sampled.terminations.RIGID_GRASP`) in free motion (penalty causality, ``F_e = 0``).
    Scans m_c downward from ``m_range[1]``; returns ``0.0`` if nothing down to ``m_range[0]`` is
    unstable and ``inf`` if ``m_range[1]`` already is.  ``velocity_filter`` filters the PD
    loop's derivative term (default ``None``, the backward difference).
    """
    positive("bc", bc, "N s/m")
    env = free_motion("impedance") if environment is None else environment
    term = (Termination(grasp, env),)

    def f(ms: np.ndarray) -> np.ndarray:
        spec = LoopSpec("admittance", (1.0, float(bc)), pd, delay_samples, implementation_delay, velocity_filter)
        return radii(device, spec, term * ms.size, {"mc": ms})

    return _first_crossing(f, m_range[0], m_range[1], increasing=False)


def critical_mass_chart(device: Device, bc_values, pd: tuple[float, float] = (50e3, 100.0), delay_samples: int = 0,
                        *, progress: Callable[[int, int], None] | None = None,
                        cancelled: Callable[[], bool] | None = None, **kwargs) -> CriticalMassChart | None:
    """:func:`critical_mass` over a list of b_c (overlay for the admittance design chart).

    ``progress(done, total)`` after each b_c; ``None`` when ``cancelled()`` turns true."""
    bcs = np.asarray(bc_values, float).reshape(-1)
    mcs = _each(bcs, lambda b: critical_mass(device, b, pd, delay_samples, **kwargs), progress, cancelled)
    return None if mcs is None else CriticalMassChart(bc=bcs, mc=mcs, delay_samples=int(delay_samples))


#: Parameters a stability map can sweep, and where they act.
MAP_PARAMETERS = {
    "kc": "coupling", "bc": "coupling", "mc": "coupling", "kp": "coupling", "kd": "coupling",
    "kobj": "environment", "bobj": "environment", "me": "environment",
    "grasp_mass": "grasp", "grasp_damping": "grasp", "grasp_stiffness": "grasp",
}


def stability_map(device: Device, x: tuple[str, Sequence[float]], y: tuple[str, Sequence[float]], *,
                  display: str = "impedance", coupling: tuple[float, float] = (50e3, 100.0),
                  pd: tuple[float, float] = (50e3, 100.0), termination: Termination | None = None,
                  delay_samples: int = 0, implementation_delay: bool = False,
                  velocity_filter: VelocityFilter | None = None) -> StabilityMap:
    """Spectral radius over a grid of two parameters, in one batched sweep.

    ``x`` and ``y`` are ``(name, values)`` with names from :data:`MAP_PARAMETERS`, e.g.
    ``("kc", ...)`` and ``("kobj", ...)``.  The other parameters come from ``coupling``, ``pd``
    and ``termination`` (default: hands-off and the paper's penalty wall for an impedance
    display; rigid grasp and free motion for an admittance display).
    """
    (xn, xv), (yn, yv) = x, y
    for name in (xn, yn):
        if name not in MAP_PARAMETERS:
            raise ValidationError("map parameter", ", ".join(MAP_PARAMETERS), name)
    if xn == yn:
        raise ValidationError("map parameter", "two different parameters", yn)
    xv = np.asarray(xv, float).reshape(-1)
    yv = np.asarray(yv, float).reshape(-1)
    check_count("map points", xv.size * yv.size, MAX_MAP_POINTS, f"{xv.size} × {yv.size}")
    if termination is None:
        termination = display_loop(display).default_termination()
    spec = LoopSpec(display, coupling, pd, delay_samples, implementation_delay, velocity_filter)
    X, Y = np.meshgrid(xv, yv)
    values = {xn: X.ravel(), yn: Y.ravel()}
    terms = []
    g0 = termination.grasp
    for i in range(X.size):
        g = g0
        gk = {k[6:]: values[k][i] for k in values if MAP_PARAMETERS[k] == "grasp"}
        if gk:
            g = Grasp(**{**g0.to_dict(), **gk})
        terms.append(Termination(g, termination.environment))
    overrides = {k: v for k, v in values.items() if MAP_PARAMETERS[k] != "grasp"}
    r = radii(device, spec, terms, overrides or None)
    return StabilityMap(x_name=xn, x=xv, y_name=yn, y=yv, spectral_radius=r.reshape(X.shape))
