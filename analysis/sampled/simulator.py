"""Nonlinear time-domain simulator of the sampled haptic loop.

The controller is the same step function as the linear analysis
(:func:`analysis.sampled_loop.controller_step`), called with floats and a unilateral wall
(contact only while the solution penetrates).  Sensors are sampled and optionally quantized;
the actuator force is held (ZOH), optionally delayed and saturated.

Continuous part
---------------
Between samples the chain is linear except for Coulomb friction.  Friction on mass ``i`` is
``-sat(v_i F_i / v_s, F_i)``: a stiff viscous band ``|v| <= v_s`` (stick) and a constant force
outside (slip).  In each *regime* (which masses stick, which slide in which direction) the
dynamics are linear with constant inputs, so they are propagated exactly with precomputed
matrix exponentials.  Each sub-step ``h = T / substeps`` is tried whole; if a mass changes
regime during it, the sub-step is split in halves recursively (dyadic event location, down to
``h / 2^10``) so the regime switch happens at the right time.  The result is therefore
independent of ``substeps`` up to the event resolution (the tests check that halving the
sub-step changes it by less than 1e-6 relative).  Without friction the whole sample is one
exact step.

Verdict (``detect``)
--------------------
The actuator position over the last 40 % of the run is split into two windows; each is
detrended by a quadratic fit and its RMS taken (``a_prev``, ``a_last``).  Divergent: non-finite
values, |x| > 1 m, or ``a_last > 1.5 a_prev`` with ``a_last`` above the rest threshold.
Sustained oscillation: ``a_last`` above the threshold and ``a_last >= 0.7 a_prev``.  Stable
otherwise (at rest or decaying).  Rest threshold: ``max(2 encoder counts, 1 um)`` RMS.
"""

from __future__ import annotations

import math

import numpy as np

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.sampled.loop import LoopSpec, controller_params, controller_step, memory_names, plant_matrices, sensor_rows
from analysis.sampled.results import SimulationResult, Verdict
from analysis.sampled.scenarios import Scenario, SimulationOptions
from analysis.sampled.terminations import HANDS_OFF, Environment, Grasp

__all__ = ["Simulator", "simulate", "detect"]

_LEVELS = 10  # dyadic event resolution: sub-step / 2**10
_FAR = 1e30  # wall position meaning "no wall"


def _sim_engaged(pen, flag):
    return pen > 0.0


class _Propagators:
    """Exact propagators ``X' = P @ (X, F_d, F_ext, 1)`` per friction regime and dyadic level."""

    def __init__(self, device: Device, grasp: Grasp, friction: np.ndarray, v_stick: float, h: float, levels: int):
        self.device, self.grasp, self.h, self.levels = device, grasp, h, levels
        self.friction, self.v_stick = friction, v_stick
        self.idx = [int(i) for i in np.flatnonzero(friction > 0)]
        self.cache: dict[tuple[int, ...], np.ndarray] = {}
        n = device.n
        A, Bu = plant_matrices(device, [grasp])
        self.A, self.Bu = A[0], Bu[0]
        self.m0 = device.masses[0] + grasp.mass
        self.n = n
        self.vidx = np.array([n + i for i in self.idx], dtype=int)

    def get(self, regime: tuple[int, ...]) -> np.ndarray:
        P = self.cache.get(regime)
        if P is None:
            P = self._build(regime)
            self.cache[regime] = P
        return P

    def _build(self, regime: tuple[int, ...]) -> np.ndarray:
        from scipy import linalg

        n, n2 = self.n, 2 * self.n
        extra = np.zeros(n)
        const = np.zeros(n)
        for i, r in zip(self.idx, regime):
            if r == 0:
                extra[i] = self.friction[i] / self.v_stick
            else:
                const[i] = -r * self.friction[i]
        A, Bu = plant_matrices(self.device, [self.grasp], friction_damping=extra)
        A, Bu = A[0], Bu[0]
        masses = self.device.masses.copy()
        masses[0] += self.grasp.mass
        B3 = np.zeros((n2, 3))
        B3[:, :2] = Bu
        B3[n:, 2] = const / masses
        hs = self.h / 2.0 ** np.arange(self.levels + 1)
        aug = np.zeros((hs.size, n2 + 3, n2 + 3))
        aug[:, :n2, :n2] = A[None] * hs[:, None, None]
        aug[:, :n2, n2:] = B3[None] * hs[:, None, None]
        E = linalg.expm(aug)
        return np.ascontiguousarray(E[:, :n2, :])  # (levels+1, 2n, 2n+3)

    def regime(self, z: np.ndarray) -> tuple[int, ...]:
        vs = self.v_stick
        return tuple([0 if -vs <= v <= vs else (1 if v > 0 else -1) for v in z[self.vidx].tolist()])

    def friction_force0(self, z: np.ndarray) -> float:
        """Friction force on the handle mass at state ``z``."""
        fc = float(self.friction[0])
        if fc == 0:
            return 0.0
        return -min(max(float(z[self.n]) * fc / self.v_stick, -fc), fc)


class Simulator:
    """Precomputed simulator of one device, loop and scenario (see module docstring)."""

    def __init__(self, device: Device, spec: LoopSpec, scenario: Scenario, options: SimulationOptions | None = None):
        self.device, self.spec, self.scenario = device, spec, scenario
        self.options = options or SimulationOptions()
        opt = self.options
        n = device.n
        fr = np.zeros(n)
        if opt.friction:
            if len(opt.friction) != n:
                raise ValidationError("friction", f"exactly {n} values (one per mass)", list(opt.friction))
            fr = np.array(opt.friction, float)
        self.friction = fr
        T = device.sample_time
        self.has_friction = bool(np.any(fr > 0))
        self.substeps = opt.substeps if self.has_friction else 1
        h = T / self.substeps
        levels = _LEVELS if self.has_friction else 0
        self.props = {g: _Propagators(device, g, fr, opt.stick_velocity, h, levels)
                      for g in {scenario.grasp, HANDS_OFF}}
        sc = scenario
        self.env = Environment(sc.causality, stiffness=sc.wall_stiffness if sc.wall else 0.0,
                               damping=sc.wall_damping if sc.wall else 0.0, mass=sc.object_mass,
                               wall=sc.wall and sc.causality == "admittance")
        self.params = controller_params(spec, T, [self.env], sc.wall_position if sc.wall else _FAR, batch=False)
        self.cy, self.cf = sensor_rows(device)

    def run(self, duration: float | None = None) -> SimulationResult:
        dev, spec, sc, opt = self.device, self.spec, self.scenario, self.options
        T = dev.sample_time
        D = sc.duration if duration is None else float(duration)
        if not (math.isfinite(D) and D > 0):
            raise ValidationError("duration", "> 0 and finite (s)", duration)
        K = int(round(D / T)) + 1
        n, n2 = dev.n, 2 * dev.n
        display, caus = spec.display, sc.causality
        p = self.params
        names = memory_names(display, caus, spec.implementation_delay)
        z = np.zeros(n2 + 3)
        z[:n] = sc.initial_position
        z[n:n2] = sc.initial_velocity
        z[n2 + 2] = 1.0
        # controller memory consistent with rest at the initial position
        mem = {nm: 0.0 for nm in names}
        x0 = sc.initial_position
        if display == "impedance":
            mem["xe"] = x0 if not (sc.wall and x0 > p.xw) else p.xw
            mem["delta"] = x0 - mem["xe"]
        else:
            mem["yp"], mem["xc"] = x0, x0
            if "ve" in mem:
                mem["ve"] = 0.0
        res_x, res_f = opt.encoder_resolution, opt.force_resolution
        fpk, fcont = opt.force_peak, opt.force_continuous
        thermal = fcont < math.inf
        alpha = T / opt.thermal_time_constant
        msq = 0.0
        d = spec.delay_samples
        buf = [0.0] * d
        cy, cf = self.cy, self.cf

        t = np.arange(K) * T
        pos = np.empty((K, n))
        vel = np.empty((K, n))
        enc = np.empty(K)
        fm = np.empty(K)
        fh = np.empty(K)
        fd = np.empty(K)
        fe_out = np.empty(K)
        xe_out = np.empty(K)
        contact = np.zeros(K, dtype=bool)
        energy = np.zeros(K)
        energy_obs = np.zeros(K)
        energy_h = np.zeros(K)
        events = 0
        sub = self.substeps
        N = 1 << (self.props[sc.grasp].levels)
        e_acc = eo_acc = eh_acc = 0.0
        prev = None
        for k in range(K):
            tk = k * T
            released = tk >= sc.release_time
            grasp = HANDS_OFF if released else sc.grasp
            pr = self.props[grasp]
            push = sc.push_force if (sc.push_start <= tk < sc.push_end and not released) else 0.0
            X = z[:n2]
            y = float(cy @ X)
            if res_x > 0:
                y = math.floor(y / res_x) * res_x
            f = float(cf @ X)
            if res_f > 0:
                f = round(f / res_f) * res_f
            u, mem, fe, xe = controller_step(display, caus, p, y, f, mem, _sim_engaged)
            if d:
                buf.append(u)
                u = buf.pop(0)
            if u > fpk:
                u = fpk
            elif u < -fpk:
                u = -fpk
            if thermal and msq > fcont * fcont:
                u = min(max(u, -fcont), fcont)
            msq += alpha * (u * u - msq)
            z[n2] = u
            z[n2 + 1] = push
            # record at the sample
            pos[k] = z[:n]
            vel[k] = z[n:n2]
            enc[k] = y
            fm[k] = f
            fd[k] = u
            fe_out[k] = fe
            xe_out[k] = xe
            contact[k] = sc.wall and (xe >= p.xw if caus == "admittance" else xe > p.xw)
            g = grasp
            fr0 = pr.friction_force0(z)
            a0 = float(pr.A[n] @ z[:n2] + pr.Bu[n] @ z[n2:n2 + 2]) + fr0 / pr.m0
            fh[k] = push - g.stiffness * z[0] - g.damping * z[n] - g.mass * a0
            if prev is not None:
                xn_prev, y_prev, x1_prev, fh_prev, u_prev = prev
                e_acc += u_prev * (z[n - 1] - xn_prev)
                eo_acc += u_prev * (y - y_prev)
                eh_acc += 0.5 * (fh_prev + fh[k]) * (z[0] - x1_prev)
                energy[k], energy_obs[k], energy_h[k] = e_acc, eo_acc, eh_acc
            prev = (z[n - 1], y, z[0], fh[k], u)
            if k == K - 1:
                break
            if not pr.idx:
                P = pr.get(())[0]
                z[:n2] = P @ z
                continue
            regime, cache = pr.regime, pr.cache
            for _ in range(sub):
                tick = 0
                r = regime(z)
                while tick < N:
                    size = N if tick == 0 else min(tick & -tick, N - tick)
                    Ps = cache.get(r)
                    if Ps is None:
                        Ps = pr.get(r)
                    while True:
                        znew = Ps[_LEVELS + 1 - size.bit_length()] @ z
                        rn = regime(znew)
                        if size == 1 or rn == r:
                            break
                        size >>= 1
                        events += 1
                    z[:n2] = znew
                    r = rn
                    tick += size
            if not np.isfinite(z[0]) or abs(z[0]) > 1e6:
                pos[k + 1:] = np.nan
                vel[k + 1:] = np.nan
                for arr in (enc, fm, fh, fd, fe_out, xe_out, energy, energy_obs, energy_h):
                    arr[k + 1:] = np.nan
                break
        verdict = detect(t, pos[:, -1], opt.encoder_resolution)
        return SimulationResult(t=t, positions=pos, velocities=vel, encoder=enc, f_meas=fm, f_h=fh, f_d=fd, f_e=fe_out,
                                x_e=xe_out, energy=energy, energy_observed=energy_obs, energy_human=energy_h,
                                contact=contact, verdict=verdict, substeps=self.substeps, events=events)


def detect(t: np.ndarray, x: np.ndarray, encoder_resolution: float = 0.0) -> Verdict:
    """Classify a run from the actuator position (see module docstring)."""
    thr = max(2.0 * encoder_resolution, 1e-6)
    if not np.all(np.isfinite(x)) or np.max(np.abs(x)) > 1.0:
        return Verdict("divergent", math.nan, math.nan, thr, "non-finite or |x| > 1 m")
    K = x.size
    a, b, c = int(0.6 * K), int(0.8 * K), K
    amps = []
    for lo, hi in ((a, b), (b, c)):
        tt, xx = t[lo:hi], x[lo:hi]
        if xx.size < 4:
            amps.append(0.0)
            continue
        tc = tt - tt.mean()
        coef = np.polyfit(tc, xx, 2)
        amps.append(float(np.sqrt(np.mean((xx - np.polyval(coef, tc)) ** 2))))
    prev, last = amps
    if last > thr and last > 1.5 * prev:
        return Verdict("divergent", prev, last, thr, "oscillation growing by > 1.5x between the last two windows")
    if last > thr and last >= 0.7 * prev:
        return Verdict("sustained oscillation", prev, last, thr, "oscillation above the rest threshold, not decaying")
    return Verdict("stable", prev, last, thr, "at rest or decaying")


def simulate(profile_or_device, scenario: Scenario | str, duration: float | None = None, *,
             display: str | None = None, coupling: tuple[float, float] | None = None,
             pd: tuple[float, float] | None = None, options: SimulationOptions | None = None) -> SimulationResult:
    """Simulate a scenario (a :class:`Scenario` or a preset name from :data:`analysis.scenarios.SCENARIOS`).

    ``profile_or_device``: a :class:`analysis.profiles.Profile` (device, display and couplings
    taken from it) or a :class:`Device`.  ``display``, ``coupling`` (``(k_c, b_c)`` or
    ``(m_c, b_c)``) and ``pd`` override the profile; for a bare device they default to an
    impedance display with the paper's experimental coupling (50 kN/m, 100 N s/m) and, for an
    admittance display, (8 kg, 400 N s/m) with ``k_p, k_d = 50 kN/m, 100 N s/m``.
    Delays come from ``options``.
    """
    from analysis.sampled.scenarios import scenario as preset

    sc = preset(scenario) if isinstance(scenario, str) else scenario
    if not isinstance(sc, Scenario):
        raise ValidationError("scenario", "a Scenario or a preset name", scenario)
    opt = options or SimulationOptions()
    if isinstance(profile_or_device, Device):
        dev = profile_or_device
        disp = display or "impedance"
        if coupling is None:
            coupling = (50e3, 100.0) if disp == "impedance" else (8.0, 400.0)
        pd = pd or (50e3, 100.0)
    elif hasattr(profile_or_device, "device"):
        prof = profile_or_device
        dev = prof.device
        disp = display or prof.display
        if coupling is None:
            coupling = (prof.kc, prof.bc) if disp == "impedance" else (prof.mc, prof.bc_adm)
        pd = pd or (prof.kp, prof.kd)
    else:
        raise ValidationError("profile_or_device", "a Profile or a Device", type(profile_or_device).__name__)
    spec = LoopSpec(disp, coupling, pd, opt.delay_samples, opt.implementation_delay)
    return Simulator(dev, spec, sc, opt).run(duration)
