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
difference of encoder positions, as in the paper; every controller below is written in
position form, where ``Tz/(z-1)`` applied to a backward difference is the position itself.

Controllers (one step, from the samples at ``kT`` to the force held on ``[kT, (k+1)T)``)
--------------------------------------------------------------------------------------
``delta = y - x_e`` is the deflection of the coupling; ``p`` a penetration into the wall at
``x_w``; ``L`` the optional one-sample implementation delay between coupling and environment
(the paper's explicit integration).  Without it, coupling and environment are solved together
(implicit); both are linear, so that is one division.

* impedance display, impedance environment (eq. 4, 5): ``F = k_c delta + b_c (delta -
  delta[k-1])/T`` and ``F = k_obj p + b_obj (p - p[k-1])/T``; ``F_d = F_e``.  With ``L``
  the coupling uses ``F_e[k-1]``.
* impedance display, admittance environment (eq. 4, 6): ``F_d = F_e = Z_c (v_d - v_e)``;
  the object ``m_e v_e' = F_e - b_e v_e`` by backward Euler (with ``L``: driven by
  ``F_e[k-1]``); the god-object wall holds ``x_e = x_w``.
* admittance display (eq. 13, 30): ``F_d = k_p e + k_d (e - e[k-1])/T``, ``e = y - x_com``,
  and the coupling ``Y_cA = 1/b_c + T z/(m_c (z-1))`` (eq. 16): ``v_com = G/b_c + w``,
  ``w[k] = w[k-1] + T G/m_c``, ``x_com[k] = x_com[k-1] + T v_com``, where ``G`` is the force
  through the coupling.  Impedance environment (eq. 17): ``G = F_meas - F_e(x_com)``.
  Admittance environment (eq. 18): ``v_com = v_e`` and ``F_e = F_meas - G``.

A computation delay of ``d`` samples holds the force computed at step ``k`` on
``[(k+d)T, (k+d+1)T)``.

The same step functions serve the linear analysis (arguments are coefficient rows, the wall
is assumed engaged or free as the environment says) and the nonlinear simulator (arguments are
floats and the wall is unilateral), so both use one implementation of the architectures.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
from scipy import linalg

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.sampled.terminations import Environment, Grasp, Termination

__all__ = [
    "LoopSpec",
    "plant_matrices",
    "discretize_zoh",
    "sensor_rows",
    "memory_names",
    "controller_step",
    "controller_params",
    "closed_loop_matrices",
    "spectral_radius",
    "RIGID_TOL",
]

#: Eigenvalues closer than this to z = 1 are rigid-body (translation) or integrator modes of free
#: motion (a free mass has a double pole at z = 1 in position coordinates); they count as |z| = 1.
RIGID_TOL = 1e-6

_DISPLAYS = ("impedance", "admittance")


def _real(name: str, value: object, positive: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValidationError(name, "a real number", value)
    x = float(value)
    if not math.isfinite(x) or x < 0 or (positive and x == 0):
        raise ValidationError(name, "> 0 and finite" if positive else ">= 0 and finite", value)
    return x


@dataclass(frozen=True)
class LoopSpec:
    """Everything in the loop except the device and the terminations.

    ``coupling`` is ``(k_c, b_c)`` for an impedance display and ``(m_c, b_c)`` for an
    admittance display; ``pd = (k_p, k_d)`` is the position loop of an admittance display
    (default the paper's 50 kN/m, 100 N s/m).
    """

    display: str = "impedance"
    coupling: tuple[float, float] = (50e3, 100.0)
    pd: tuple[float, float] = (50e3, 100.0)
    delay_samples: int = 0
    implementation_delay: bool = False

    def __post_init__(self) -> None:
        if self.display not in _DISPLAYS:
            raise ValidationError("display", "impedance or admittance", self.display)
        try:
            a, b = self.coupling
        except (TypeError, ValueError) as exc:
            raise ValidationError("coupling", "a pair of real numbers", self.coupling) from exc
        if self.display == "impedance":
            a = _real("kc", a)
            b = _real("bc", b)
            if a + b <= 0:
                raise ValidationError("coupling", "k_c + b_c > 0", self.coupling)
        else:
            a = _real("mc", a, positive=True)
            b = _real("bc", b, positive=True)
        object.__setattr__(self, "coupling", (a, b))
        try:
            kp, kd = self.pd
        except (TypeError, ValueError) as exc:
            raise ValidationError("pd", "a pair (kp, kd)", self.pd) from exc
        object.__setattr__(self, "pd", (_real("kp", kp), _real("kd", kd)))
        d = self.delay_samples
        if isinstance(d, bool) or not isinstance(d, (int, np.integer)) or d < 0 or d > 1000:
            raise ValidationError("delay_samples", "an integer in [0, 1000]", d)
        object.__setattr__(self, "delay_samples", int(d))
        if not isinstance(self.implementation_delay, (bool, np.bool_)):
            raise ValidationError("implementation_delay", "true or false", self.implementation_delay)
        object.__setattr__(self, "implementation_delay", bool(self.implementation_delay))


# -- plant ----------------------------------------------------------------------------------
def plant_matrices(device: Device, grasps: Sequence[Grasp] | None = None,
                   friction_damping: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Continuous ``A`` (G, 2n, 2n) and ``B`` (G, 2n, 2) for each grasp; inputs ``(F_d, F_ext)``.

    ``friction_damping`` (length n) adds dampers to ground (the simulator's stick regime).
    """
    grasps = list(grasps) if grasps is not None else [Grasp()]
    n = device.n
    M, Bm, K = device.matrices()
    G = len(grasps)
    mh = np.array([g.mass for g in grasps])
    bh = np.array([g.damping for g in grasps])
    kh = np.array([g.stiffness for g in grasps])
    Ms = np.broadcast_to(np.diag(M), (G, n)).copy()
    Ms[:, 0] += mh
    Bs = np.broadcast_to(Bm, (G, n, n)).copy()
    Bs[:, 0, 0] += bh
    if friction_damping is not None:
        Bs[:, np.arange(n), np.arange(n)] += np.asarray(friction_damping, float)
    Ks = np.broadcast_to(K, (G, n, n)).copy()
    Ks[:, 0, 0] += kh
    inv = 1.0 / Ms[:, :, None]
    A = np.zeros((G, 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -Ks * inv
    A[:, n:, n:] = -Bs * inv
    Bu = np.zeros((G, 2 * n, 2))
    Bu[:, 2 * n - 1, 0] = -1.0 / Ms[:, n - 1]
    Bu[:, n, 1] = 1.0 / Ms[:, 0]
    return A, Bu


def discretize_zoh(A: np.ndarray, Bu: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """Exact zero-order-hold discretization by one batched ``expm`` of ``[[A, B], [0, 0]] h``."""
    N, m = A.shape[-1], Bu.shape[-1]
    aug = np.zeros(A.shape[:-2] + (N + m, N + m))
    aug[..., :N, :N] = A * h
    aug[..., :N, N:] = Bu * h
    E = linalg.expm(aug)
    return E[..., :N, :N], E[..., :N, N:]


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
def memory_names(display: str, causality: str, lag: bool) -> tuple[str, ...]:
    """Names of the controller memory of one architecture (the values at the last sample)."""
    if display == "impedance":
        base = ("delta", "xe") if causality == "impedance" else ("delta", "xe", "ve")
    else:
        base = ("yp", "xc", "w") if causality == "impedance" else ("yp", "xc", "ve", "w")
    return base + (("fe",) if lag else ())


def _pick(cond, a, b):
    if isinstance(cond, (bool, np.bool_)):
        return a if cond else b
    return np.where(cond, a, b)


def controller_params(spec: LoopSpec, T: float, envs: Sequence[Environment], wall_position: float = 0.0,
                      batch: bool = True) -> SimpleNamespace:
    """Controller constants; arrays of shape (E, 1) for a batch of environments, else floats."""

    def col(values):
        a = np.array(values, dtype=float)
        return a[:, None] if batch else float(a[0])

    p = SimpleNamespace(T=float(T), lag=spec.implementation_delay, xw=float(wall_position))
    if spec.display == "impedance":
        p.kc, p.bc = spec.coupling
    else:
        p.mc, p.bc = spec.coupling
        p.kp, p.kd = spec.pd
    p.kobj = col([e.stiffness for e in envs])
    p.bobj = col([e.damping for e in envs])
    p.me = col([e.mass for e in envs])
    walls = np.array([e.wall for e in envs], dtype=bool)
    p.wall = walls[:, None] if batch else bool(walls[0])
    return p


Engaged = Callable[[object, object], object]


def linear_engaged(pen, flag):
    """Linear analysis: the wall is engaged exactly when the environment says so."""
    return flag


def controller_step(display: str, causality: str, p: SimpleNamespace, y, f, mem: dict,
                    engaged: Engaged = linear_engaged):
    """One controller step: returns ``(F_d, new_memory, F_e, x_e)``.

    ``y``, ``f`` and the memory are floats (simulation) or coefficient rows (linear
    analysis); ``engaged(penetration, flag)`` decides wall contact (see module docstring).
    """
    T, lag = p.T, p.lag
    new: dict = {}
    if display == "impedance":
        kcp = p.kc + p.bc / T
        g = p.bc / T
        dprev = mem["delta"]
        if causality == "impedance":
            kop = p.kobj + p.bobj / T
            if lag:
                fin = mem["fe"]
                delta = (fin + g * dprev) / kcp
                xe = y - delta
                fe_c = p.kobj * (xe - p.xw) + (p.bobj / T) * (xe - mem["xe"])
                fe = _pick(engaged(xe - p.xw, True), fe_c, 0.0 * fe_c)
                u = fin
                new["fe"] = fe
            else:
                xe_c = (kcp * y - g * dprev + p.kobj * p.xw + (p.bobj / T) * mem["xe"]) / (kcp + kop)
                delta_f = g * dprev / kcp
                xe_f = y - delta_f
                on = engaged(xe_c - p.xw, True)
                xe = _pick(on, xe_c, xe_f)
                delta = y - xe
                u = kcp * delta - g * dprev
                fe = u
            new["delta"], new["xe"] = delta, xe
            return u, new, fe, xe
        # admittance (constraint) environment, eq. (6)
        me, be = p.me, p.bobj
        xprev, vprev = mem["xe"], mem["ve"]
        if lag:
            v_f = (vprev + (T / me) * mem["fe"]) / (1.0 + T * be / me)
            x_f = xprev + T * v_f
        else:
            a = me / (T * T)
            x_f = (a * (xprev + T * vprev) + kcp * y - g * dprev + (be / T) * xprev) / (a + kcp + be / T)
            v_f = (x_f - xprev) / T
        on = engaged(x_f - p.xw, p.wall)
        xe = _pick(on, 0.0 * x_f + p.xw, x_f)
        ve = _pick(on, 0.0 * v_f, v_f)
        delta = y - xe
        u = kcp * delta - g * dprev
        new["delta"], new["xe"], new["ve"] = delta, xe, ve
        if lag:
            new["fe"] = u
        return u, new, u, xe
    # admittance display
    mc, bc = p.mc, p.bc
    xcp, w = mem["xc"], mem["w"]
    if causality == "impedance":
        c = T / bc + T * T / mc
        if lag:
            G = f - mem["fe"]
            xc = xcp + T * w + c * G
            fe_c = p.kobj * (xc - p.xw) + (p.bobj / T) * (xc - xcp)
            fe = _pick(engaged(xc - p.xw, True), fe_c, 0.0 * fe_c)
            new["fe"] = fe
        else:
            cb = c * p.bobj / T
            x_c = (xcp + T * w + c * f + c * p.kobj * p.xw + cb * xcp) / (1.0 + c * p.kobj + cb)
            x_f = xcp + T * w + c * f
            on = engaged(x_c - p.xw, True)
            xc = _pick(on, x_c, x_f)
            fe_c = p.kobj * (x_c - p.xw) + (p.bobj / T) * (x_c - xcp)
            fe = _pick(on, fe_c, 0.0 * fe_c)
            G = f - fe
        new["w"] = w + (T / mc) * G
    else:
        me, be = p.me, p.bobj
        c1 = 1.0 / bc + T / mc
        vprev = mem["ve"]
        if lag:
            v_f = (vprev + (T / me) * mem["fe"]) / (1.0 + T * be / me)
        else:
            v_f = (vprev + (T / me) * (f + w / c1)) / (1.0 + T / (me * c1) + T * be / me)
        x_f = xcp + T * v_f
        on = engaged(x_f - p.xw, p.wall)
        xc = _pick(on, 0.0 * x_f + p.xw, x_f)
        ve = _pick(on, 0.0 * v_f, v_f)
        G = (ve - w) / c1
        fe = f - G
        new["ve"] = ve
        new["w"] = w + (T / mc) * G
        if lag:
            new["fe"] = fe
    e = y - xc
    u = p.kp * e + (p.kd / T) * (e - (mem["yp"] - xcp))
    new["yp"], new["xc"] = y, xc
    return u, new, fe, xc


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
    """
    terms = list(terminations)
    if not terms:
        return np.zeros((0, 0, 0))
    caus = {t.environment.causality for t in terms}
    if len(caus) != 1:
        raise ValidationError("terminations", "environments of one causality per call", sorted(caus))
    causality = caus.pop()
    T = device.sample_time
    if plants is None:
        grasps = [t.grasp for t in terms]
        Ad, Bd = discretize_zoh(*plant_matrices(device, grasps), T)
        plant_index = np.arange(len(terms))
    else:
        Ad, Bd = plants
    Ad, Bd = Ad[plant_index], Bd[plant_index, :, 0]
    n2 = 2 * device.n
    names = memory_names(spec.display, causality, spec.implementation_delay)
    d = spec.delay_samples
    N = n2 + len(names) + d
    B = len(terms)
    eye = np.eye(N)
    cy, cf = sensor_rows(device)
    y = np.broadcast_to(cy @ eye[:n2], (B, N))
    f = np.broadcast_to(cf @ eye[:n2], (B, N))
    mem = {nm: np.broadcast_to(eye[n2 + i], (B, N)) for i, nm in enumerate(names)}
    p = controller_params(spec, T, [t.environment for t in terms])
    for key, val in (overrides or {}).items():
        if not hasattr(p, key) or key in ("T", "lag", "xw", "wall"):
            raise ValidationError("overrides", "kc, bc, mc, kp, kd, kobj, bobj or me", key)
        arr = np.asarray(val, dtype=float).reshape(-1)
        if arr.size != B:
            raise ValidationError(key, f"{B} values (one per termination)", arr.size)
        setattr(p, key, arr[:, None])
    u, new, _, _ = controller_step(spec.display, causality, p, y, f, mem)
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
    """
    ev = np.linalg.eigvals(Phi)
    mag = np.abs(ev)
    mag = np.where(np.abs(ev - 1.0) < rigid_tol, np.minimum(mag, 1.0), mag)
    return mag.max(axis=-1)
