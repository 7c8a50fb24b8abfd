"""Nonlinear time-domain simulator of the sampled haptic loop.

The controller is the same step as the linear analysis (the display loop objects of
:mod:`analysis.sampled.controllers`), called with floats and a unilateral wall (contact only
while the solution penetrates).  Sensors are sampled and optionally quantized;
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
exact step.  A run stops at divergence (``|x_1| > 1e6`` m or not finite) and the signals after
it are NaN (without friction it used to run on into overflow).

Each sample: the human's grasp and push (:meth:`Simulator.hand`), the sensors
(:meth:`Simulator.sample`), the controller step, the actuator (delay, peak clip and I^2 t
fold-back; :mod:`analysis.sampled.actuation`, with the optional passivity observer and controller
of Hannaford & Ryu), the record with the energy integrals, then the exact propagation to the next
sample.

Verdict (``detect``)
--------------------
The actuator position over the last 40 % of the run is split into two windows; each is
detrended by a quadratic fit and its RMS taken (``a_prev``, ``a_last``).  Divergent: non-finite
values, |x| > 1 m, or ``a_last > 1.5 a_prev`` with ``a_last`` above the rest threshold.
Sustained oscillation: ``a_last`` above the threshold and ``a_last >= 0.7 a_prev``.  Stable
otherwise (at rest or decaying).  Rest threshold: ``max(2 encoder counts, 1 um)`` RMS.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from analysis.chain.device import Device
from analysis.chain.discretize import discretize_zoh
from analysis.chain.limits import check_simulation_size
from analysis.checks import positive
from analysis.errors import ValidationError
from analysis.chain.velocity_filter import VelocityFilter
from analysis.sampled.actuation import Actuator
from analysis.sampled.controllers import display_loop
from analysis.sampled.loop import LoopSpec, controller_params, plant_matrices, sensor_rows
from analysis.sampled.results import SimulationResult, Verdict
from analysis.sampled.scenarios import Scenario, SimulationOptions
from analysis.sampled.terminations import HANDS_OFF, Environment, Grasp, causality_kind

__all__ = ["Simulator", "simulate", "detect"]

_LEVELS = 10  # dyadic event resolution: sub-step / 2**10
_FAR = 1e30  # wall position meaning "no wall"


def _sim_engaged(pen: float, flag: bool) -> bool:
    """Simulation: the wall is a one-sided contact, engaged while penetrated."""
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
        Phi, Gam = discretize_zoh(A, B3, hs)
        return np.concatenate([Phi, Gam], axis=-1)  # (levels+1, 2n, 2n+3)

    def regime(self, z: np.ndarray) -> tuple[int, ...]:
        vs = self.v_stick
        return tuple([0 if -vs <= v <= vs else (1 if v > 0 else -1) for v in z[self.vidx].tolist()])

    def friction_force0(self, z: np.ndarray) -> float:
        """Friction force on the handle mass at state ``z``."""
        fc = float(self.friction[0])
        if fc == 0:
            return 0.0
        return -min(max(float(z[self.n]) * fc / self.v_stick, -fc), fc)

    def hand_force(self, z: np.ndarray, push: float) -> float:
        """Force of the hand on the handle: the push less the grasp's spring, damper and mass."""
        n, g = self.n, self.grasp
        fr0 = self.friction_force0(z)
        a0 = float(self.A[n] @ z[:2 * n] + self.Bu[n] @ z[2 * n:2 * n + 2]) + fr0 / self.m0
        return push - g.stiffness * z[0] - g.damping * z[n] - g.mass * a0

    def advance(self, z: np.ndarray, substeps: int) -> int:
        """Propagate ``z`` over one sample, in place; returns the number of dyadic splits.

        Without friction one exact step; with it ``substeps`` sub-steps, each split in halves
        while a mass changes regime (see the module docstring).
        """
        n2 = 2 * self.n
        if not self.idx:
            z[:n2] = self.get(())[0] @ z
            return 0
        N = 1 << self.levels
        regime, cache = self.regime, self.cache
        events = 0
        for _ in range(substeps):
            tick = 0
            r = regime(z)
            while tick < N:
                size = N if tick == 0 else min(tick & -tick, N - tick)
                Ps = cache.get(r)
                if Ps is None:
                    Ps = self.get(r)
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
        return events


class _Trace:
    """The signals of one run, sample by sample, and their energy integrals."""

    def __init__(self, size: int, n: int) -> None:
        self.size, self.n = size, n
        self.pos, self.vel = np.empty((size, n)), np.empty((size, n))
        self.enc, self.fm, self.fh, self.fd, self.fe, self.xe = (np.empty(size) for _ in range(6))
        self.contact = np.zeros(size, dtype=bool)
        self.energy, self.energy_obs, self.energy_h = np.zeros(size), np.zeros(size), np.zeros(size)
        self.sums = (0.0, 0.0, 0.0)
        self.prev: tuple | None = None

    def record(self, k: int, z: np.ndarray, y: float, f: float, u: float, fe: float, xe: float,
               contact: bool, fh: float) -> None:
        """Sample ``k``; the energies integrate ``F_d dx_n``, ``F_d dy`` and ``F_h dx_1`` (trapezoid)."""
        n = self.n
        self.pos[k] = z[:n]
        self.vel[k] = z[n:2 * n]
        self.enc[k], self.fm[k], self.fd[k], self.fe[k], self.xe[k] = y, f, u, fe, xe
        self.contact[k] = contact
        self.fh[k] = fh
        if self.prev is not None:
            xn_prev, y_prev, x1_prev, fh_prev, u_prev = self.prev
            e, eo, eh = self.sums
            e += u_prev * (z[n - 1] - xn_prev)
            eo += u_prev * (y - y_prev)
            eh += 0.5 * (fh_prev + self.fh[k]) * (z[0] - x1_prev)
            self.sums = (e, eo, eh)
            self.energy[k], self.energy_obs[k], self.energy_h[k] = e, eo, eh
        self.prev = (z[n - 1], y, z[0], self.fh[k], u)

    def diverged(self, k: int) -> None:
        """Blank every signal after sample ``k``."""
        for arr in (self.pos, self.vel, self.enc, self.fm, self.fh, self.fd, self.fe, self.xe, self.energy,
                    self.energy_obs, self.energy_h):
            arr[k + 1:] = np.nan

    def result(self, t: np.ndarray, verdict: Verdict, substeps: int, events: int) -> SimulationResult:
        return SimulationResult(t=t, positions=self.pos, velocities=self.vel, encoder=self.enc, f_meas=self.fm,
                                f_h=self.fh, f_d=self.fd, f_e=self.fe, x_e=self.xe, energy=self.energy,
                                energy_observed=self.energy_obs, energy_human=self.energy_h,
                                contact=self.contact, verdict=verdict, substeps=substeps, events=events)


class Simulator:
    """Precomputed simulator of one device, loop and scenario (see module docstring).

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses and its sample time.
    spec : LoopSpec
        Display, gains, delays and velocity filter.
    scenario : Scenario
        What the human and the virtual world do.
    options : SimulationOptions or None, optional
        Nonlinear effects and numerics (all off by default).

    Raises
    ------
    ValidationError
        When ``options.friction`` is given but not one value per mass.
    """

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
        self.loop, self.kind = spec.loop, causality_kind(sc.causality)
        self.env = Environment(sc.causality, stiffness=sc.wall_stiffness if sc.wall else 0.0,
                               damping=sc.wall_damping if sc.wall else 0.0, mass=sc.object_mass,
                               wall=self.kind.constrains(sc.wall))
        self.params = controller_params(spec, T, [self.env], sc.wall_position if sc.wall else _FAR, batch=False)
        self.names = self.loop.memory_names(self.kind, spec.implementation_delay)
        self.cy, self.cf = sensor_rows(device)

    def run(self, duration: float | None = None) -> SimulationResult:
        """Simulate ``duration`` s (default the scenario's) and classify the run (:func:`detect`).

        Parameters
        ----------
        duration : float or None, optional
            Simulated time [s], greater than 0; ``None`` for the scenario's.

        Returns
        -------
        SimulationResult
            The signals at the sample instants and the verdict.
        """
        sc, T = self.scenario, self.device.sample_time
        D = sc.duration if duration is None else positive("duration", duration, "s")
        trace = _Trace(check_simulation_size(D, T, self.substeps, self.device.n), self.device.n)
        mem = self.loop.rest_memory(self.names, sc.initial_position, sc.wall, self.params.xw)
        actuator = Actuator(self.options, T, self.spec.delay_samples, trace.size)
        events = self._steps(self.initial_state(), mem, trace, actuator)
        t = np.arange(trace.size) * T
        verdict = detect(t, trace.pos[:, -1], self.options.encoder_resolution)
        res = trace.result(t, verdict, self.substeps, events)
        if actuator.energy is None:
            return res
        return dataclasses.replace(res, passivity_energy=actuator.energy, pc_damping=actuator.damping)

    def initial_state(self) -> np.ndarray:
        """``(X, F_d, F_ext, 1)`` with every mass at the scenario's initial position and velocity.

        Returns
        -------
        numpy.ndarray
            The augmented state, shape (2n + 3,): positions [m], velocities [m/s], ``F_d = 0``,
            ``F_ext = 0`` [N] and the constant 1.
        """
        n, sc = self.device.n, self.scenario
        z = np.zeros(2 * n + 3)
        z[:n] = sc.initial_position
        z[n:2 * n] = sc.initial_velocity
        z[2 * n + 2] = 1.0
        return z

    def hand(self, tk: float) -> tuple[Grasp, float]:
        """The human's grasp and push force at time ``tk`` (see :class:`Scenario`).

        Parameters
        ----------
        tk : float
            Time [s].

        Returns
        -------
        tuple of (Grasp, float)
            The grasp (hands-off after the release) and the push [N] (0 outside the push).
        """
        sc = self.scenario
        released = tk >= sc.release_time
        grasp = HANDS_OFF if released else sc.grasp
        push = sc.push_force if (sc.push_start <= tk < sc.push_end and not released) else 0.0
        return grasp, push

    def sample(self, z: np.ndarray) -> tuple[float, float]:
        """Encoder and force gauge at state ``z``, quantized as the options say.

        Parameters
        ----------
        z : numpy.ndarray
            Augmented state ``(X, F_d, F_ext, 1)``, shape (2n + 3,).

        Returns
        -------
        tuple of (float, float)
            Encoder reading [m] (truncated toward minus infinity) and gauge reading [N]
            (rounded).
        """
        X = z[:2 * self.device.n]
        res_x, res_f = self.options.encoder_resolution, self.options.force_resolution
        y = float(self.cy @ X)
        if res_x > 0:
            y = math.floor(y / res_x) * res_x
        f = float(self.cf @ X)
        if res_f > 0:
            f = round(f / res_f) * res_f
        return y, f

    def _steps(self, z: np.ndarray, mem: dict, trace: _Trace, actuator: Actuator) -> int:
        """The run, sample after sample (module docstring); returns the number of dyadic splits."""
        sc, p, n2 = self.scenario, self.params, 2 * self.device.n
        T, last, sub = self.device.sample_time, trace.size - 1, self.substeps
        step, touches = self.loop.step_for(self.kind), self.kind.contact
        actuate = actuator.apply
        events = 0
        for k in range(trace.size):
            grasp, push = self.hand(k * T)
            pr = self.props[grasp]
            y, f = self.sample(z)
            u, mem, fe, xe = step(p, y, f, mem, _sim_engaged)
            u = actuate(u, y)
            z[n2] = u
            z[n2 + 1] = push
            trace.record(k, z, y, f, u, fe, xe, sc.wall and touches(xe, p.xw), pr.hand_force(z, push))
            if k == last:
                break
            events += pr.advance(z, sub)
            if not np.isfinite(z[0]) or abs(z[0]) > 1e6:
                trace.diverged(k)
                break
        return events


def detect(t: np.ndarray, x: np.ndarray, encoder_resolution: float = 0.0) -> Verdict:
    """Classify a run from the actuator position (see module docstring).

    Parameters
    ----------
    t : numpy.ndarray
        Sample instants [s], shape (K,).
    x : numpy.ndarray
        Actuator position [m], shape (K,).
    encoder_resolution : float, optional
        Encoder quantum [m] (sets the rest threshold); 0 = ideal encoder.

    Returns
    -------
    Verdict
        ``"stable"``, ``"sustained oscillation"`` or ``"divergent"``, with its numbers.
    """
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
             pd: tuple[float, float] | None = None, options: SimulationOptions | None = None,
             velocity_filter: VelocityFilter | None = None) -> SimulationResult:
    """Simulate a scenario (a :class:`Scenario` or a preset name from :data:`analysis.sampled.scenarios.SCENARIOS`).

    ``profile_or_device``: a :class:`analysis.profiles.Profile` (device, display and couplings
    taken from it) or a :class:`Device`.  ``display``, ``coupling`` (``(k_c, b_c)`` or
    ``(m_c, b_c)``) and ``pd`` override the profile; for a bare device they default to an
    impedance display with the paper's experimental coupling (50 kN/m, 100 N s/m) and, for an
    admittance display, (8 kg, 400 N s/m) with ``k_p, k_d = 50 kN/m, 100 N s/m``.
    Delays and the passivity observer/controller come from ``options``; ``velocity_filter``
    filters the controller's damping term (:mod:`analysis.sampled.filtered`).

    Parameters
    ----------
    profile_or_device : Profile or Device
        A profile (device, display and couplings taken from it) or a bare device.
    scenario : Scenario or str
        A scenario or a key of :data:`~analysis.sampled.scenarios.SCENARIOS`.
    duration : float or None, optional
        Simulated time [s]; ``None`` for the scenario's.
    display : str or None, optional
        ``"impedance"`` or ``"admittance"``; ``None`` for the profile's (impedance for a device).
    coupling : tuple of (float, float) or None, optional
        ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``; ``None`` for the default.
    pd : tuple of (float, float) or None, optional
        ``(k_p [N/m], k_d [N s/m])`` of the admittance display; ``None`` for the default.
    options : SimulationOptions or None, optional
        Nonlinear effects, delays and passivity control (all off by default).
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.

    Returns
    -------
    SimulationResult
        The signals at the sample instants and the verdict.

    Raises
    ------
    ValidationError
        When ``scenario`` is neither a Scenario nor a preset name, ``profile_or_device`` is
        neither a profile nor a device, or a setting is out of range.
    """
    from analysis.sampled.scenarios import scenario as preset

    sc = preset(scenario) if isinstance(scenario, str) else scenario
    if not isinstance(sc, Scenario):
        raise ValidationError("scenario", "a Scenario or a preset name", scenario)
    opt = options or SimulationOptions()
    if isinstance(profile_or_device, Device):
        dev = profile_or_device
        loop = display_loop(display or "impedance")
        if coupling is None:
            coupling = loop.default_coupling
        pd = pd or (50e3, 100.0)
    elif hasattr(profile_or_device, "device"):
        prof = profile_or_device
        dev = prof.device
        loop = display_loop(display or prof.display)
        if coupling is None:
            coupling = loop.profile_coupling(prof)
        pd = pd or (prof.kp, prof.kd)
    else:
        raise ValidationError("profile_or_device", "a Profile or a Device", type(profile_or_device).__name__)
    spec = LoopSpec(loop.name, coupling, pd, opt.delay_samples, opt.implementation_delay, velocity_filter)
    return Simulator(dev, spec, sc, opt).run(duration)
