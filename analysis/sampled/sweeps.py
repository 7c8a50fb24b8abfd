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
k_c, large m_c) with 24 points per decade, in one batch, and then the crossing between the last
stable and the first unstable scan point by Brent's method (``scipy.optimize.brentq`` on
``rho - 1 - STABILITY_TOLERANCE``, :func:`stable_end`) to a relative bracket of
:data:`CROSSING_RTOL` (1e-12).  The value reported is the *stable* end of the final bracket, a
gain whose spectral radius was computed and found stable, below every gain found unstable
(conservative).  An unstable window narrower than one scan step (10 % in the parameter) can be
missed; :func:`stability_map` shows the whole picture.  The plant is discretized once per device
and grasp (:func:`analysis.sampled.loop.discrete_plants`), not once per gain.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from scipy import optimize

from analysis.chain.device import Device
from analysis.chain.limits import MAX_MAP_POINTS, check_count
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import nonnegative, positive
from analysis.errors import ValidationError
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.sampled.controllers import display_loop
from analysis.sampled.loop import (
    STABILITY_TOLERANCE,
    LoopSpec,
    closed_loop_matrices,
    discrete_plants,
    is_stable,
    spectral_radius,
)
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
    "CROSSING_RTOL",
    "stable_end",
    "first_crossing",
]

_PER_DECADE = 24
#: Relative width of the final bracket of a stability crossing (Brent's ``xtol``/``rtol``).
CROSSING_RTOL = 1e-12


def radii(device: Device, spec: LoopSpec, terminations: Sequence[Termination],
          overrides: dict[str, np.ndarray] | None = None) -> np.ndarray:
    """Spectral radius of the closed loop for each termination (batched).

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    spec : LoopSpec
        Display, gains, delays and velocity filter.
    terminations : sequence of Termination
        The M terminations, of either causality.
    overrides : dict of str to numpy.ndarray, optional
        Controller constants per termination (``"kc"``, ``"bc"``, ``"mc"``, ``"kp"``, ``"kd"``,
        ``"kobj"``, ``"bobj"``, ``"me"``), each of length M.

    Returns
    -------
    numpy.ndarray
        Spectral radii, shape (M,).
    """
    terms = list(terminations)
    out = np.empty(len(terms))
    if not terms:
        return out
    grasps: dict[Grasp, int] = {}
    gidx = np.array([grasps.setdefault(t.grasp, len(grasps)) for t in terms])
    plants = discrete_plants(device, tuple(grasps))
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

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    display : str, optional
        ``"impedance"`` or ``"admittance"``.
    coupling : tuple of (float, float), optional
        ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``.
    terminations : sequence of Termination or None, optional
        The sweep; ``None`` for the default 832.
    pd : tuple of (float, float), optional
        ``(k_p [N/m], k_d [N s/m])`` of the admittance display's position loop.
    delay_samples : int, optional
        Computation delay in samples.
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    WorstCase
        The worst spectral radius, its termination and every radius.

    Raises
    ------
    ValidationError
        When ``terminations`` is empty, or a setting of the loop is out of range.
    """
    spec = LoopSpec(display, coupling, pd, delay_samples, implementation_delay, velocity_filter)
    terms = tuple(default_terminations() if terminations is None else terminations)
    if not terms:
        raise ValidationError("terminations", "at least one termination", [])
    r = radii(device, spec, terms)
    i = int(np.argmax(r))
    return WorstCase(spectral_radius=float(r[i]), termination=terms[i], index=i, stable=bool(is_stable(r[i])),
                     radii=r, terminations=terms)


def stable_end(g: Callable[[float], float], safe: float, unsafe: float, rtol: float = CROSSING_RTOL,
               g_safe: float | None = None, g_unsafe: float | None = None) -> float:
    """The stable end of the crossing of ``g`` in ``[safe, unsafe]`` (``g(safe) <= 0 < g(unsafe)``).

    Brent's method (``scipy.optimize.brentq``) shrinks the bracket to a relative width ``rtol``;
    every value of ``g`` is kept, and the result is the evaluated point nearest to the smallest
    (from ``safe``) point found unstable among those found stable below it: the stable end of
    the final bracket, never a point beyond one where ``g > 0`` (conservative; Brent keeps a
    sign-changing bracket and evaluates inside it only, so the points found stable all lie
    below those found unstable, whatever the sign changes of ``g`` inside).  A point where ``g``
    is exactly 0 (the spectral radius equals ``1 + STABILITY_TOLERANCE`` to the last bit; Brent
    stops there, short of ``rtol``) is stable and is the result.

    Parameters
    ----------
    g : callable
        ``g(x) -> float``, stable where ``<= 0`` (e.g. ``rho(x) - 1 - STABILITY_TOLERANCE``).
    safe, unsafe : float
        The bracket: ``g(safe) <= 0 < g(unsafe)``; ``safe`` may be above ``unsafe`` (a
        decreasing scan).  Both nonzero and of one sign.
    rtol : float, optional
        Relative width of the final bracket (default :data:`CROSSING_RTOL`, 1e-12; at least
        ``4 eps``, Brent's limit).
    g_safe, g_unsafe : float, optional
        The known values of ``g`` at the ends (not recomputed).

    Returns
    -------
    float
        A point where ``g <= 0``, within ``2 rtol`` (relative) of one where ``g > 0`` (unless
        ``g`` is 0 there), and below (from ``safe``) every point found unstable.
    """
    seen: dict[float, float] = {}
    if g_safe is not None:
        seen[float(safe)] = float(g_safe)
    if g_unsafe is not None:
        seen[float(unsafe)] = float(g_unsafe)

    def h(x: float) -> float:
        if x not in seen:
            seen[x] = float(g(x))
        return seen[x]

    d = 1.0 if unsafe > safe else -1.0  # scan direction: d x increases from safe to unsafe
    lo, hi = sorted((float(safe), float(unsafe)))
    optimize.brentq(h, lo, hi, xtol=rtol * lo, rtol=rtol)
    # Brent evaluates inside its bracket only, so the final bracket is this pair of points
    u = min((x for x, v in seen.items() if v > 0), key=lambda x: d * x)
    return max((x for x, v in seen.items() if v <= 0 and d * (u - x) > 0), key=lambda x: d * x)


def _first_crossing(f, lo: float, hi: float, increasing: bool) -> float:
    """First parameter value (scanning from the safe end) where ``f`` (batched) is unstable.

    The scan grid is evaluated a decade (:data:`_PER_DECADE` points) per batch and stops at the
    first batch with an unstable point (the same grid and first point as one batch of all)."""
    n = max(int(math.ceil(_PER_DECADE * math.log10(hi / lo))), 2) + 1
    grid = np.geomspace(lo, hi, n)
    if not increasing:
        grid = grid[::-1]
    for start in range(0, n, _PER_DECADE):
        rho = f(grid[start:start + _PER_DECADE])
        bad = ~np.asarray(is_stable(rho))
        if bad.any():
            break
    else:
        return math.inf if increasing else 0.0
    j = start + int(np.argmax(bad))
    if j == 0:
        return 0.0 if increasing else math.inf
    top = 1.0 + STABILITY_TOLERANCE
    g_safe = float(rho[j - start - 1]) - top if j > start else None
    return stable_end(lambda x: float(f(np.array([x]))[0]) - top, float(grid[j - 1]), float(grid[j]),
                      g_safe=g_safe, g_unsafe=float(rho[j - start]) - top)


#: The first crossing of a batched spectral radius from the safe end (public name of the scan above).
first_crossing = _first_crossing


def _radius_of(device: Device, spec: LoopSpec, term: Termination, gain: str) -> Callable[[np.ndarray], np.ndarray]:
    """Spectral radius of one termination as a (batched) function of one controller gain; the plant
    is discretized once (:func:`~analysis.sampled.loop.discrete_plants`)."""
    plants = discrete_plants(device, (term.grasp,))

    def f(values: np.ndarray) -> np.ndarray:
        Phi = closed_loop_matrices(device, spec, (term,) * values.size, plants, np.zeros(values.size, dtype=int),
                                   {gain: values})
        return spectral_radius(Phi)

    return f


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

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    bc : float
        Coupling damping b_c [N s/m], at least 0.
    delay_samples : int, optional
        Computation delay in samples.
    environment : Environment or None, optional
        The environment; ``None`` for the god-object wall.
    grasp : Grasp, optional
        The human grasp (hands-off by default).
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    k_range : tuple of (float, float), optional
        The scanned k_c [N/m], ``(low, high)``.
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    float
        The largest stable k_c [N/m]; ``inf`` or ``0.0`` at the ends of ``k_range``.
    """
    nonnegative("bc", bc, "N s/m")
    env = god_object_wall() if environment is None else environment
    spec = LoopSpec("impedance", (1.0, float(bc)), delay_samples=delay_samples,
                    implementation_delay=implementation_delay, velocity_filter=velocity_filter)
    f = _radius_of(device, spec, Termination(grasp, env), "kc")
    return _first_crossing(f, k_range[0], k_range[1], increasing=True)


def _each(values: np.ndarray, func: Callable[[float], float], progress: Progress | None,
          cancelled: Cancelled | None) -> np.ndarray:
    """``func`` at each value, reporting ``progress(done, total)``; raises OperationCancelled once ``cancelled()``."""
    out = np.empty(values.size)
    for i, v in enumerate(values):
        check_cancelled(cancelled)
        out[i] = func(float(v))
        report_progress(progress, i + 1, values.size)
    return out


@none_if_cancelled
def critical_stiffness_chart(device: Device, bc_values, delay_samples: int = 0, *,
                             progress: Progress | None = None,
                             cancelled: Cancelled | None = None, **kwargs) -> CriticalChart | None:
    """:func:`critical_stiffness` over a list of b_c (overlay for the two-port design chart).

    ``progress(done, total)`` after each b_c; ``None`` when ``cancelled()`` turns true.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    bc_values : array_like
        Coupling dampings b_c [N s/m], shape (N,) (flattened).
    delay_samples : int, optional
        Computation delay in samples.
    progress : callable, optional
        ``progress(done, total)``, called after each b_c.
    cancelled : callable, optional
        ``cancelled() -> bool``, asked before each b_c.
    **kwargs
        Keyword arguments of :func:`critical_stiffness` (``environment``, ``grasp``,
        ``implementation_delay``, ``k_range``, ``velocity_filter``).

    Returns
    -------
    CriticalChart or None
        The k_c [N/m] of each b_c, shape (N,); ``None`` when cancelled.
    """
    bcs = np.asarray(bc_values, float).reshape(-1)
    kcs = _each(bcs, lambda b: critical_stiffness(device, b, delay_samples, **kwargs), progress, cancelled)
    return CriticalChart(bc=bcs, kc=kcs, delay_samples=int(delay_samples))


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

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    bc : float
        Coupling damping b_c [N s/m], greater than 0.
    pd : tuple of (float, float), optional
        ``(k_p [N/m], k_d [N s/m])`` of the position loop.
    delay_samples : int, optional
        Computation delay in samples.
    environment : Environment or None, optional
        The environment; ``None`` for free motion (penalty causality).
    grasp : Grasp, optional
        The human grasp (the rigid grasp by default).
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    m_range : tuple of (float, float), optional
        The scanned m_c [kg], ``(low, high)``.
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    float
        The smallest stable m_c [kg]; ``0.0`` or ``inf`` at the ends of ``m_range``.
    """
    positive("bc", bc, "N s/m")
    env = free_motion("impedance") if environment is None else environment
    spec = LoopSpec("admittance", (1.0, float(bc)), pd, delay_samples, implementation_delay, velocity_filter)
    f = _radius_of(device, spec, Termination(grasp, env), "mc")
    return _first_crossing(f, m_range[0], m_range[1], increasing=False)


@none_if_cancelled
def critical_mass_chart(device: Device, bc_values, pd: tuple[float, float] = (50e3, 100.0), delay_samples: int = 0,
                        *, progress: Progress | None = None,
                        cancelled: Cancelled | None = None, **kwargs) -> CriticalMassChart | None:
    """:func:`critical_mass` over a list of b_c (overlay for the admittance design chart).

    ``progress(done, total)`` after each b_c; ``None`` when ``cancelled()`` turns true.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    bc_values : array_like
        Coupling dampings b_c [N s/m], shape (N,) (flattened).
    pd : tuple of (float, float), optional
        ``(k_p [N/m], k_d [N s/m])`` of the position loop.
    delay_samples : int, optional
        Computation delay in samples.
    progress : callable, optional
        ``progress(done, total)``, called after each b_c.
    cancelled : callable, optional
        ``cancelled() -> bool``, asked before each b_c.
    **kwargs
        Keyword arguments of :func:`critical_mass` (``environment``, ``grasp``,
        ``implementation_delay``, ``m_range``, ``velocity_filter``).

    Returns
    -------
    CriticalMassChart or None
        The m_c [kg] of each b_c, shape (N,); ``None`` when cancelled.
    """
    bcs = np.asarray(bc_values, float).reshape(-1)
    mcs = _each(bcs, lambda b: critical_mass(device, b, pd, delay_samples, **kwargs), progress, cancelled)
    return CriticalMassChart(bc=bcs, mc=mcs, delay_samples=int(delay_samples))


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

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    x : tuple of (str, sequence of float)
        The parameter along x and its NX values, in its unit.
    y : tuple of (str, sequence of float)
        The parameter along y and its NY values.
    display : str, optional
        ``"impedance"`` or ``"admittance"``.
    coupling : tuple of (float, float), optional
        ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``.
    pd : tuple of (float, float), optional
        ``(k_p [N/m], k_d [N s/m])`` of the admittance display's position loop.
    termination : Termination or None, optional
        The grasp and environment; ``None`` for the display's default termination.
    delay_samples : int, optional
        Computation delay in samples.
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment.
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    StabilityMap
        The spectral radii, shape (NY, NX).

    Raises
    ------
    ValidationError
        When a name is not in :data:`MAP_PARAMETERS`, both names are the same, the grid has more
        than ``MAX_MAP_POINTS`` points, or a setting of the loop is out of range.
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
