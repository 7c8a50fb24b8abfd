"""The exact sampled-data loop of the four haptic architectures (Adams et al., section III).

Plant
-----
The continuous chain of eq. (25), with the human grasp added to the handle (mass ``m_h``
added to mass 0, damper ``b_h`` and spring ``k_h`` from mass 0 to ground), has the state
``X = (q, q')`` and two inputs: ``F_d`` (applied as ``-F_d`` to the actuator mass, eq. 25)
and an external force on the handle.  ``F_d`` is held by a zero-order hold; the plant is
discretized exactly with the matrix exponential of the augmented matrix
``[[A, B], [0, 0]] T`` (Van Loan), so ``X[k+1] = Ad X[k] + Bd u[k]`` holds exactly.

Sensors (sampled at ``kT``): the encoder position of the actuator mass ``y = q[n-1]`` and the
force gauge on element ``s = device.sensor_element``,
``F_meas = k_s (q_s - q_{s+1}) + b_s (q_s' - q_{s+1}')``.  The device velocity is the backward
difference of encoder positions, as in the paper; every controller is written in position
form, where ``Tz/(z-1)`` applied to a backward difference is the position itself.

Controllers
-----------
The controllers of the four architectures (impedance or admittance display, eq. 4-6, 13-18 and
30, against an impedance or admittance environment) are the display loop objects of
:mod:`analysis.sampled.controllers`; the environment's causality
(:mod:`analysis.sampled.terminations`) selects the form.  A :class:`LoopSpec` names its display
by string (``"impedance"``/``"admittance"``, as profiles do) and :attr:`LoopSpec.loop` is the
object.

A computation delay of ``d`` samples holds the force computed at step ``k`` on
``[(k+d)T, (k+d+1)T)``.

The discretized plant depends on the device (its parameters and sample time) and the grasps
only, not on the controller, its gains, delay or velocity filter, nor the environment:
:func:`discrete_plants` computes it once for a device and a tuple of grasps and keeps the last
:data:`PLANT_CACHE_SIZE` results (keyed by value: every device parameter and every grasp; sets of
plants over :data:`PLANT_CACHE_BYTES` are not kept), so a sweep over gains needs one ``expm``.

Stability: a loop is stable when its spectral radius is at most ``1 +``
:data:`STABILITY_TOLERANCE` (:func:`is_stable`), the one rule of every sweep, result and view.

The same controller steps serve the closed-loop matrices below (coefficient rows) and the
nonlinear simulator (floats), so both use one implementation of the architectures.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from types import SimpleNamespace
from typing import Any

import numpy as np

from analysis.chain.device import Device
from analysis.chain.discretize import discretize_zoh
from analysis.chain.state_space import chain_state_space
from analysis.chain.velocity_filter import VelocityFilter
from analysis.checks import boolean, integer
from analysis.errors import ValidationError
from analysis.sampled.controllers import DisplayLoop, Engaged, StepResult, display_loop, linear_engaged
from analysis.sampled.filtered import filtered_loop
from analysis.sampled.rendered import AccelerationEstimate, check_virtual_mass, inertial_loop
from analysis.sampled.terminations import (
    Environment,
    EnvironmentCausality,
    Grasp,
    Termination,
    causality_kind,
)

__all__ = [
    "LoopSpec",
    "plant_matrices",
    "discretize_zoh",
    "sensor_rows",
    "memory_names",
    "controller_step",
    "controller_params",
    "override_params",
    "closed_loop_matrices",
    "spectral_radius",
    "RIGID_TOL",
    "STABILITY_TOLERANCE",
    "is_stable",
    "discrete_plants",
    "PLANT_CACHE_SIZE",
    "PLANT_CACHE_BYTES",
]

#: Eigenvalues closer than this to z = 1 are rigid-body (translation) or integrator modes of free
#: motion (a free mass has a double pole at z = 1 in position coordinates); they count as |z| = 1.
RIGID_TOL = 1e-6
#: A loop is stable when its spectral radius is at most ``1 + STABILITY_TOLERANCE`` (round-off of
#: the eigenvalues of a marginally stable loop, e.g. an undamped mode, may put it just above 1).
STABILITY_TOLERANCE = 1e-12
#: How many sets of discretized plants :func:`discrete_plants` keeps (least recently used first out).
PLANT_CACHE_SIZE = 16
#: The largest set of discretized plants (bytes of ``Ad`` and ``Bd``) that is kept: 16 entries of
#: at most 2 MiB bound the cache at 32 MiB (one grasp of a 100-mass chain is 0.3 MiB).
PLANT_CACHE_BYTES = 2 << 20


def is_stable(rho: np.ndarray | float) -> np.ndarray | bool:
    """Whether spectral radii are stable: ``rho <= 1 + STABILITY_TOLERANCE`` (NaN is not).

    Parameters
    ----------
    rho : float or numpy.ndarray
        Spectral radii of closed-loop matrices (:func:`spectral_radius`).

    Returns
    -------
    bool or numpy.ndarray
        A bool for a scalar, a boolean array of the shape of ``rho`` otherwise.
    """
    ok = np.asarray(rho, dtype=float) <= 1.0 + STABILITY_TOLERANCE
    return bool(ok) if ok.ndim == 0 else ok


@dataclass(frozen=True)
class LoopSpec:
    """Everything in the loop except the device and the terminations.

    ``coupling`` is ``(k_c, b_c)`` for an impedance display and ``(m_c, b_c)`` for an
    admittance display; ``pd = (k_p, k_d)`` is the position loop of an admittance display
    (default the paper's 50 kN/m, 100 N s/m).  :attr:`loop` is the display's loop object.
    ``velocity_filter`` (``None`` = the backward difference) filters the damping term's
    velocity estimate (:mod:`analysis.sampled.filtered`).

    Parameters
    ----------
    display : str, optional
        ``"impedance"`` or ``"admittance"``.
    coupling : tuple of (float, float), optional
        ``(k_c [N/m], b_c [N s/m])`` (impedance display, both at least 0, not both 0) or
        ``(m_c [kg], b_c [N s/m])`` (admittance display, both greater than 0).
    pd : tuple of (float, float), optional
        ``(k_p [N/m], k_d [N s/m])`` of the admittance display's position loop, at least 0.
    delay_samples : int, optional
        Computation delay ``d`` in samples, 0 to 1000.
    implementation_delay : bool, optional
        The one-sample delay between coupling and environment (the paper's explicit
        integration); without it they are solved together.
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.
    mass : float, optional
        Virtual mass ``M`` [kg] of the impedance display's rendered environment
        ``M a^ + b_c v^ + k_c delta`` (:mod:`analysis.sampled.rendered`), either sign; 0 by default.
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate of the mass term; ``None`` for the second backward difference.
        With ``mass == 0`` and ``acceleration is None`` the loop has no mass term (today's loop,
        unchanged); with an estimate it has one whose mass (``mv``) sweeps may override.

    Raises
    ------
    ValidationError
        When a gain, the delay, the filter, the mass or the estimate is out of range or of the
        wrong type, or a mass term is asked of an admittance display.
    """

    display: str = "impedance"
    coupling: tuple[float, float] = (50e3, 100.0)
    pd: tuple[float, float] = (50e3, 100.0)
    delay_samples: int = 0
    implementation_delay: bool = False
    velocity_filter: VelocityFilter | None = None
    mass: float = 0.0
    acceleration: AccelerationEstimate | None = None

    def __post_init__(self) -> None:
        coupling, pd = display_loop(self.display).check_gains(self.coupling, self.pd)
        object.__setattr__(self, "coupling", coupling)
        object.__setattr__(self, "pd", pd)
        object.__setattr__(self, "delay_samples", integer("delay_samples", self.delay_samples, 0, 1000))
        object.__setattr__(self, "implementation_delay", boolean("implementation_delay", self.implementation_delay))
        vf = self.velocity_filter
        if vf is not None and not isinstance(vf, VelocityFilter):
            raise ValidationError("velocity_filter", "a VelocityFilter or None", vf)
        object.__setattr__(self, "mass", check_virtual_mass("mass", self.mass))
        acc = self.acceleration
        if acc is not None and not isinstance(acc, AccelerationEstimate):
            raise ValidationError("acceleration", "an AccelerationEstimate or None", acc)
        if self.has_mass_term and self.display != "impedance":
            raise ValidationError("mass", "0 without an acceleration estimate for an admittance display", self.mass)

    @property
    def has_mass_term(self) -> bool:
        """Whether the loop renders a mass term (a nonzero mass or an acceleration estimate)."""
        return self.mass != 0.0 or self.acceleration is not None

    @property
    def loop(self) -> DisplayLoop:
        """The display's loop object (:mod:`analysis.sampled.controllers`), with the velocity
        filter of :mod:`analysis.sampled.filtered` when one is set (not the backward difference),
        and the mass term of :mod:`analysis.sampled.rendered` when there is one."""
        base = filtered_loop(self.display, self.velocity_filter)
        if not self.has_mass_term:
            return base
        return inertial_loop(base, self.acceleration, self.mass, self.velocity_filter)


# -- plant ----------------------------------------------------------------------------------
def plant_matrices(device: Device, grasps: Sequence[Grasp] | None = None,
                   friction_damping: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Continuous ``A`` (G, 2n, 2n) and ``B`` (G, 2n, 2) for each grasp; inputs ``(F_d, F_ext)``.

    The chain's one state space (:func:`analysis.chain.state_space.chain_state_space`) with the
    grasps added to the handle; ``friction_damping`` (length n) adds dampers to ground (the
    simulator's stick regime).

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    grasps : sequence of Grasp, optional
        The grasps on the handle, ``G`` of them (default: hands-off only).
    friction_damping : numpy.ndarray, optional
        Dampers to ground [N s/m], shape (n,).

    Returns
    -------
    tuple of numpy.ndarray
        ``(A, B)``, shapes (G, 2n, 2n) and (G, 2n, 2), state ``X = (q, q')``, inputs
        ``(F_d, F_ext)``.
    """
    grasps = list(grasps) if grasps is not None else [Grasp()]
    return chain_state_space(device, [g.mass for g in grasps], [g.damping for g in grasps],
                             [g.stiffness for g in grasps], friction_damping)


def _zoh_plants(device: Device, grasps: tuple[Grasp, ...]) -> tuple[np.ndarray, np.ndarray]:
    Ad, Bd = discretize_zoh(*plant_matrices(device, grasps), device.sample_time)
    Ad.flags.writeable = False
    Bd.flags.writeable = False
    return Ad, Bd


_cached_zoh_plants = lru_cache(maxsize=PLANT_CACHE_SIZE)(_zoh_plants)


def discrete_plants(device: Device, grasps: Sequence[Grasp] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The exact ZOH plants of :func:`plant_matrices`, one per grasp, read-only.

    One batched ``expm`` (:func:`analysis.chain.discretize.discretize_zoh`) for all grasps.  The
    result depends on nothing else, so it is cached by value (the device's every parameter,
    sample time included, and the grasps; module docstring): the sweeps over gains, delays or
    filters of one device reuse it, and a changed device or grasp is a different key.  Sets
    larger than :data:`PLANT_CACHE_BYTES` are computed and not kept.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    grasps : sequence of Grasp, optional
        The grasps on the handle (default: hands-off only).

    Returns
    -------
    tuple of numpy.ndarray
        ``(Ad, Bd)``, shapes (G, 2n, 2n) and (G, 2n, 2), inputs ``(F_d, F_ext)``; not writeable.
    """
    gs = (Grasp(),) if grasps is None else tuple(grasps)
    N = 2 * device.n
    if len(gs) * N * (N + 2) * 8 > PLANT_CACHE_BYTES:
        return _zoh_plants(device, gs)
    return _cached_zoh_plants(device, gs)


def sensor_rows(device: Device) -> tuple[np.ndarray, np.ndarray]:
    """Rows ``c_y`` (encoder on the actuator mass) and ``c_f`` (force gauge) on ``X = (q, q')``."""
    n = device.n
    cy = np.zeros(2 * n)
    cy[n - 1] = 1.0
    cf = np.zeros(2 * n)
    if n >= 2:
        s = device.sensor_element
        ks, bs = device.stiffnesses[s], device.dampings[s]
        cf[s], cf[s + 1] = ks, -ks
        cf[n + s], cf[n + s + 1] = bs, -bs
    return cy, cf


# -- controllers ----------------------------------------------------------------------------
def memory_names(display: str | DisplayLoop, causality: str | EnvironmentCausality,
                 lag: bool) -> tuple[str, ...]:
    """Names of the controller memory of one architecture (the values at the last sample)."""
    return display_loop(display).memory_names(causality_kind(causality), lag)


def controller_params(spec: LoopSpec, T: float, envs: Sequence[Environment], wall_position: float = 0.0,
                      batch: bool = True) -> SimpleNamespace:
    """Controller constants; arrays of shape (E, 1) for a batch of environments, else floats."""

    def col(values: list[float]) -> Any:
        a = np.array(values, dtype=float)
        return a[:, None] if batch else float(a[0])

    p = SimpleNamespace(T=float(T), lag=spec.implementation_delay, xw=float(wall_position))
    spec.loop.set_gains(p, spec.coupling, spec.pd)
    p.kobj = col([e.stiffness for e in envs])
    p.bobj = col([e.damping for e in envs])
    p.me = col([e.mass for e in envs])
    walls = np.array([e.wall for e in envs], dtype=bool)
    p.wall = walls[:, None] if batch else bool(walls[0])
    return p


def controller_step(display: str | DisplayLoop, causality: str | EnvironmentCausality, p: SimpleNamespace,
                    y: Any, f: Any, mem: dict, engaged: Engaged = linear_engaged) -> StepResult:
    """One controller step of an architecture: returns ``(F_d, new_memory, F_e, x_e)``.

    ``y``, ``f`` and the memory are floats (simulation) or coefficient rows (linear
    analysis); ``engaged(penetration, flag)`` decides wall contact (see
    :mod:`analysis.sampled.controllers`, whose loop objects this calls).
    """
    return display_loop(display).step_for(causality_kind(causality))(p, y, f, mem, engaged)


def override_params(p: SimpleNamespace, overrides: dict[str, np.ndarray], count: int) -> None:
    """Replace controller constants of ``p`` by columns of ``count`` values (one per termination)."""
    for key, val in overrides.items():
        if not hasattr(p, key) or key in ("T", "lag", "xw", "wall"):
            raise ValidationError("overrides", "kc, bc, mc, kp, kd, kobj, bobj, me or mv (with a mass term)", key)
        arr = np.asarray(val, dtype=float).reshape(-1)
        if arr.size != count:
            raise ValidationError(key, f"{count} values (one per termination)", arr.size)
        setattr(p, key, arr[:, None])


# -- closed loop ----------------------------------------------------------------------------
def closed_loop_matrices(device: Device, spec: LoopSpec, terminations: Sequence[Termination],
                         plants: tuple[np.ndarray, np.ndarray] | None = None,
                         plant_index: np.ndarray | None = None,
                         overrides: dict[str, np.ndarray] | None = None) -> np.ndarray:
    """Closed-loop state matrices ``Phi`` (B, N, N) for terminations of one causality.

    State: ``X`` (2n) | controller memory (:func:`memory_names`) | ``d`` delayed forces.
    ``plants`` = ``(Ad, Bd)`` for a list of grasps and ``plant_index`` mapping each termination
    to its plant may be passed to share the matrix exponentials across environments.
    ``overrides`` replaces controller constants per termination (``"kc"``, ``"bc"``, ``"mc"``,
    ``"kp"``, ``"kd"``, ``"kobj"``, ``"bobj"``, ``"me"``; arrays of length B), which is how
    sweeps over coupling parameters stay one batched eigenvalue computation.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    spec : LoopSpec
        Display, gains, delays and velocity filter.
    terminations : sequence of Termination
        ``B`` terminations whose environments share one causality.
    plants : tuple of numpy.ndarray, optional
        ``(Ad, Bd)`` of :func:`discrete_plants` for a list of grasps (computed here by default).
    plant_index : numpy.ndarray, optional
        Index of each termination's plant in ``plants``, shape (B,) (required with ``plants``).
    overrides : dict of str to numpy.ndarray, optional
        Controller constants per termination, each of length B.

    Returns
    -------
    numpy.ndarray
        ``Phi``, shape (B, N, N) with ``N = 2n + len(memory) + d``; shape (0, 0, 0) without
        terminations.

    Raises
    ------
    ValidationError
        When the environments have more than one causality, or an override is unknown or of
        the wrong length.
    """
    terms = list(terminations)
    if not terms:
        return np.zeros((0, 0, 0))
    caus = {t.environment.causality for t in terms}
    if len(caus) != 1:
        raise ValidationError("terminations", "environments of one causality per call", sorted(caus))
    kind = causality_kind(caus.pop())
    loop = spec.loop
    T = device.sample_time
    if plants is None:
        grasps: dict[Grasp, int] = {}
        plant_index = np.array([grasps.setdefault(t.grasp, len(grasps)) for t in terms])
        Ad, Bd = discrete_plants(device, tuple(grasps))
    else:
        Ad, Bd = plants
    Ad, Bd = Ad[plant_index], Bd[plant_index, :, 0]
    n2 = 2 * device.n
    names = loop.memory_names(kind, spec.implementation_delay)
    d = spec.delay_samples
    N = n2 + len(names) + d
    B = len(terms)
    eye = np.eye(N)
    cy, cf = sensor_rows(device)
    y = np.broadcast_to(cy @ eye[:n2], (B, N))
    f = np.broadcast_to(cf @ eye[:n2], (B, N))
    mem = {nm: np.broadcast_to(eye[n2 + i], (B, N)) for i, nm in enumerate(names)}
    p = controller_params(spec, T, [t.environment for t in terms])
    override_params(p, overrides or {}, B)
    u, new, _, _ = loop.step_for(kind)(p, y, f, mem, linear_engaged)
    u = np.broadcast_to(u, (B, N))
    applied = np.broadcast_to(eye[n2 + len(names)], (B, N)) if d else u
    Phi = np.zeros((B, N, N))
    Phi[:, :n2, :n2] = Ad
    Phi[:, :n2, :] += Bd[:, :, None] * applied[:, None, :]
    for i, nm in enumerate(names):
        Phi[:, n2 + i, :] = new[nm]
    if d:
        base = n2 + len(names)
        for j in range(d - 1):
            Phi[:, base + j, base + j + 1] = 1.0
        Phi[:, base + d - 1, :] = u
    return Phi


def spectral_radius(Phi: np.ndarray, rigid_tol: float = RIGID_TOL) -> np.ndarray:
    """Largest eigenvalue magnitude of each matrix, with rigid-body modes at z = 1 counted as 1.

    Free motion leaves translation (and, for a free coupling mass, constant-velocity) modes at
    z = 1; in double precision a 2x2 Jordan block there splits by ~1e-8, so eigenvalues within
    ``rigid_tol`` of 1 are clamped to magnitude 1.  A true real divergence slower than
    ``rigid_tol`` per sample (e-folding time > 1e6 samples) is not reported.

    Parameters
    ----------
    Phi : numpy.ndarray
        Closed-loop state matrices, shape (..., N, N).
    rigid_tol : float, optional
        Distance from z = 1 within which an eigenvalue counts as a rigid-body mode.

    Returns
    -------
    numpy.ndarray
        Spectral radii, shape (...,) (a numpy float for one matrix).
    """
    ev = np.linalg.eigvals(Phi)
    mag = np.abs(ev)
    mag = np.where(np.abs(ev - 1.0) < rigid_tol, np.minimum(mag, 1.0), mag)
    return mag.max(axis=-1)
