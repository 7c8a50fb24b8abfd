"""The rendered environment ``F = M a^ + B v^ + K x`` of an impedance display (issue 24).

Colonnese & Okamura ("M-width: stability and accuracy of haptic rendering of virtual mass",
RSS 2012) render a virtual mass through the acceleration estimated from the encoder; Colonnese
& Chan ("Z-qualities and renderable mass-damping-stiffness spaces", IEEE Haptics Symposium 2016)
render the whole mass-damper-spring.  Here the impedance display's controller renders, at the
point it reads and drives (the encoder sample ``y`` of the actuator mass, where the coupling of
:mod:`analysis.sampled.controllers` acts; the handle itself for a rigid 1-DOF device)::

    F[k] = M a^[k] + B v^[k] + K x[k],      held by the zero-order hold on [(k+d)T, (k+d+1)T)

with ``d`` samples of computation delay.  ``x`` is the coupling deflection ``delta = y - x_e``
(against the god-object wall ``x_e = 0`` this is the encoder position itself).

Discretization, exactly
-----------------------
* ``v^ = V(z) x``, ``V(z) = H_f(z) (1 - z^{-1})/T``: the controller's velocity estimate, the
  :class:`~analysis.chain.velocity_filter.VelocityFilter` (backward difference by default).
* ``a^ = A(z) x`` by an :class:`AccelerationEstimate`:

  - ``"second_difference"`` (default): ``A(z) = H_a(z) (1 - z^{-1})^2/T^2``, i.e.
    ``a^[k] = (x[k] - 2 x[k-1] + x[k-2])/T^2`` without a low-pass;
  - ``"filtered_velocity"``: the backward difference of the filtered velocity,
    ``a^[k] = (v^[k] - v^[k-1])/T``, i.e. ``A(z) = H_a(z) H_f(z) (1 - z^{-1})^2/T^2``;

  either followed by the optional low-pass ``H_a``: ``"lowpass1"``, ``(1 - a)/(1 - a z^{-1})``
  with ``a = e^{-w_a T}``, or ``"butter2"``, the bilinear second-order Butterworth pre-warped
  to ``w_a`` (the same discretizations as the velocity filter's, unity gain at DC).

In the loop, ``a^ = C s + D d2`` with ``d2[k] = (x[k] - 2 x[k-1] + x[k-2])/T^2`` and ``s`` the
states of the cascade ``H_f`` (``"filtered_velocity"`` only), then ``H_a``, each in the
controllable canonical form of :meth:`VelocityFilter.realization`.  The controller memory
gains ``"dd"`` (``x[k-2]``) and the cascade's states (``"ac<i><j>"``), zero at rest; the
force keeps the form ``kcp delta - hist`` of the coupling (eq. 4), with
``kcp += M D/T^2`` and ``hist += M D (2 delta[k-1] - delta[k-2])/T^2 - M C s``, so the implicit
solve against a wall, the exact closed-loop matrices, the sweeps and the simulator all run the
one controller model with the mass term (:class:`InertialImpedanceLoop`).  ``M = 0`` without
an acceleration estimate is today's loop, unchanged.

The sampled impedance (:func:`rendered_force_response`) is the classical frequency response
through the hold: force per position ``G(jw) = e^{-j w d T} ZOH(jw) (K + B V + M A)(e^{j w T})``,
``ZOH(jw) = (1 - e^{-j w T})/(j w T)``; for the spring alone ``Re G = K sin(wT)/(wT)`` and
``Im G/w = -K (1 - cos wT)/(w^2 T)`` (-> ``-K T/2``, the hold's negative damping), the
effective stiffness and damping of Colonnese, Siu, Abbott & Okamura ("Rendered and
characterized closed-loop accuracy of impedance-type haptic displays", IEEE Trans. Haptics
8(4), 2015).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from types import SimpleNamespace
from typing import Any, ClassVar

import numpy as np

from analysis.chain.continued_fraction import handle_impedance
from analysis.chain.device import Device
from analysis.chain.limits import DAMPING, MASS
from analysis.chain.velocity_filter import BACKWARD, VelocityFilter
from analysis.checks import Real, SettingsRecord, choice, integer
from analysis.errors import ValidationError
from analysis.sampled.controllers import DisplayLoop, ImpedanceLoop
from analysis.sampled.terminations import EnvironmentCausality

__all__ = [
    "ACCELERATION_KINDS",
    "LOWPASS_KINDS",
    "AccelerationEstimate",
    "RenderedEnvironment",
    "RenderingController",
    "InertialImpedanceLoop",
    "inertial_loop",
    "rendered_force_response",
    "handle_transmission",
    "handle_force_response",
    "check_virtual_mass",
    "check_virtual_damping",
]

#: The acceleration estimates and what they are (module docstring).
ACCELERATION_KINDS = {
    "second_difference": "second backward difference of the position",
    "filtered_velocity": "backward difference of the filtered velocity",
}
#: The low-pass after the acceleration estimate: none, or a velocity filter's kinds.
LOWPASS_KINDS = {"none": "no low-pass", "lowpass1": "first-order low-pass", "butter2": "second-order Butterworth"}

#: A virtual mass (kg): either sign, within the physical range of masses (chain/limits.py).
_VIRTUAL_MASS = Real(lo=-MASS.hi, hi=MASS.hi, unit="kg", not_real="a real number")
#: A virtual damping (N s/m): either sign, within the physical range of dampings.
_VIRTUAL_DAMPING = Real(lo=-DAMPING.hi, hi=DAMPING.hi, unit="N s/m", not_real="a real number")
_STIFFNESS = Real(lo=0.0, hi=1e9, unit="N/m", not_real="a real number")
_CUTOFF = Real(lo=0.0, lo_open=True, allow_inf=True, unit="rad/s")


def check_virtual_mass(name: str, value: object, index: int | None = None) -> float:
    """A virtual mass M (kg): finite, of either sign, ``|M| <= 1e3`` (the range of masses).

    Parameters
    ----------
    name : str
        The field named in the error.
    value : object
        The value.
    index : int or None, optional
        The element index named in the error.

    Returns
    -------
    float
        The mass [kg].

    Raises
    ------
    ValidationError
        When the value is not a real number, NaN, infinite or out of range.
    """
    return _VIRTUAL_MASS(name, value, index)


def check_virtual_damping(name: str, value: object, index: int | None = None) -> float:
    """A virtual damping B (N s/m): finite, of either sign, ``|B| <= 1e8`` (the range of dampings).

    Parameters
    ----------
    name : str
        The field named in the error.
    value : object
        The value.
    index : int or None, optional
        The element index named in the error.

    Returns
    -------
    float
        The damping [N s/m].

    Raises
    ------
    ValidationError
        When the value is not a real number, NaN, infinite or out of range.
    """
    return _VIRTUAL_DAMPING(name, value, index)


@dataclass(frozen=True)
class AccelerationEstimate(SettingsRecord):
    """The controller's acceleration estimate ``a^ = A(z) x`` (module docstring).

    Parameters
    ----------
    kind : str, optional
        One of :data:`ACCELERATION_KINDS`: ``"second_difference"`` (default) or
        ``"filtered_velocity"``.
    lowpass : str, optional
        One of :data:`LOWPASS_KINDS`: ``"none"`` (default), ``"lowpass1"`` or ``"butter2"``.
    cutoff : float, optional
        The low-pass cut-off ``w_a`` [rad/s]; ``inf`` (default) without a low-pass, finite
        and below Nyquist with one.

    Raises
    ------
    ValidationError
        When ``kind`` or ``lowpass`` is unknown, or ``cutoff`` is not > 0, or not finite with a
        low-pass.
    """

    record_name: ClassVar[str] = "acceleration estimate"

    kind: str = "second_difference"
    lowpass: str = "none"
    cutoff: float = math.inf

    def __post_init__(self) -> None:
        choice("kind", self.kind, ACCELERATION_KINDS, allowed=", ".join(ACCELERATION_KINDS))
        choice("lowpass", self.lowpass, LOWPASS_KINDS, allowed=", ".join(LOWPASS_KINDS))
        c = _CUTOFF("cutoff", self.cutoff)
        if self.lowpass != "none" and not math.isfinite(c):
            raise ValidationError("cutoff", f"> 0 and finite (rad/s) for a {self.lowpass} low-pass", self.cutoff)
        object.__setattr__(self, "cutoff", c)

    @property
    def lowpass_filter(self) -> VelocityFilter:
        """``H_a`` as a :class:`VelocityFilter` record (the backward difference for none)."""
        return BACKWARD if self.lowpass == "none" else VelocityFilter(self.lowpass, self.cutoff)

    def stages(self, velocity_filter: VelocityFilter | None) -> tuple[VelocityFilter, ...]:
        """The filters of the cascade after ``d2``, in order (``H_f`` then ``H_a``; none is skipped).

        Parameters
        ----------
        velocity_filter : VelocityFilter or None
            The controller's velocity filter ``H_f`` (used by ``"filtered_velocity"`` only).

        Returns
        -------
        tuple of VelocityFilter
            The non-trivial filters of the cascade.
        """
        out = []
        if self.kind == "filtered_velocity" and velocity_filter is not None and not velocity_filter.is_backward:
            out.append(velocity_filter)
        if self.lowpass != "none":
            out.append(self.lowpass_filter)
        return tuple(out)

    def filter_response(self, w: Any, sample_time: float, velocity_filter: VelocityFilter | None = None) -> np.ndarray:
        """``H(e^{j w T})`` of the cascade (unity at DC).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].
        velocity_filter : VelocityFilter or None, optional
            The controller's velocity filter ``H_f``.

        Returns
        -------
        numpy.ndarray
            The cascade's response (dimensionless), complex, shape (N,).

        Raises
        ------
        ValidationError
            When a cut-off is not below Nyquist.
        """
        h = np.ones(np.shape(w), dtype=complex)
        for f in self.stages(velocity_filter):
            h = h * f.filter_response(w, sample_time)
        return h

    def response(self, w: Any, sample_time: float, velocity_filter: VelocityFilter | None = None) -> np.ndarray:
        """``A(e^{j w T}) = H (1 - e^{-j w T})^2/T^2`` [1/s^2]: acceleration per unit position.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].
        velocity_filter : VelocityFilter or None, optional
            The controller's velocity filter ``H_f``.

        Returns
        -------
        numpy.ndarray
            ``A`` [1/s^2], complex, shape (N,).

        Raises
        ------
        ValidationError
            When a cut-off is not below Nyquist.
        """
        w = np.asarray(w, dtype=float)
        th = 0.5 * w * sample_time
        diff = (2.0j / sample_time) * np.sin(th) * np.exp(-1j * th)
        return self.filter_response(w, sample_time, velocity_filter) * diff * diff

    def transfer_function(self, sample_time: float,
                          velocity_filter: VelocityFilter | None = None) -> tuple[np.ndarray, np.ndarray]:
        """``(num, den)`` of ``A(z)`` in powers of ``z^{-1}`` (``den[0] = 1``).

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s].
        velocity_filter : VelocityFilter or None, optional
            The controller's velocity filter ``H_f``.

        Returns
        -------
        num : numpy.ndarray
            Numerator coefficients [1/s^2].
        den : numpy.ndarray
            Denominator coefficients, ``den[0] = 1``.

        Raises
        ------
        ValidationError
            When a cut-off is not below Nyquist.
        """
        num = np.array([1.0, -2.0, 1.0]) / sample_time ** 2
        den = np.array([1.0])
        for f in self.stages(velocity_filter):
            n, d = f.coefficients(sample_time)
            num, den = np.polymul(num, n), np.polymul(den, d)
        return num, den

    def label(self) -> str:
        """Short description, e.g. ``"second backward difference of the position"``.

        Returns
        -------
        str
            The kind in words, and the low-pass and its cut-off in Hz when there is one.
        """
        text = ACCELERATION_KINDS[self.kind]
        if self.lowpass != "none":
            text += f", {LOWPASS_KINDS[self.lowpass]} at {self.cutoff / (2 * math.pi):.4g} Hz"
        return text


#: The default acceleration estimate: the second backward difference, no low-pass.
SECOND_DIFFERENCE = AccelerationEstimate()


@dataclass(frozen=True)
class RenderingController:
    """How the impedance display renders ``F = M a^ + B v^ + K x`` (module docstring).

    Parameters
    ----------
    delay_samples : int, optional
        Computation delay ``d`` in samples, 0 to 1000 (default 1).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter ``H_f``; ``None`` for the backward difference.
    acceleration : AccelerationEstimate or None, optional
        The acceleration estimate; ``None`` for the second backward difference.

    Raises
    ------
    ValidationError
        When the delay is out of range or a record is of the wrong type.
    """

    delay_samples: int = 1
    velocity_filter: VelocityFilter | None = None
    acceleration: AccelerationEstimate | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "delay_samples", integer("delay_samples", self.delay_samples, 0, 1000))
        vf = self.velocity_filter
        if vf is not None and not isinstance(vf, VelocityFilter):
            raise ValidationError("velocity_filter", "a VelocityFilter or None", vf)
        acc = self.acceleration
        if acc is not None and not isinstance(acc, AccelerationEstimate):
            raise ValidationError("acceleration", "an AccelerationEstimate or None", acc)
        object.__setattr__(self, "acceleration", SECOND_DIFFERENCE if acc is None else acc)

    def check(self, sample_time: float) -> None:
        """Check the filters' cut-offs against the Nyquist frequency ``pi/T``.

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s].

        Raises
        ------
        ValidationError
            When a cut-off is not below Nyquist.
        """
        if self.velocity_filter is not None:
            self.velocity_filter.check(sample_time)
        if self.acceleration.lowpass != "none":
            self.acceleration.lowpass_filter.check(sample_time)

    def velocity_response(self, w: Any, sample_time: float) -> np.ndarray:
        """``V(e^{j w T})`` [1/s] of the velocity estimate.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].

        Returns
        -------
        numpy.ndarray
            ``V``, complex, shape (N,).
        """
        return (self.velocity_filter or BACKWARD).response(w, sample_time)

    def acceleration_response(self, w: Any, sample_time: float) -> np.ndarray:
        """``A(e^{j w T})`` [1/s^2] of the acceleration estimate.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].

        Returns
        -------
        numpy.ndarray
            ``A``, complex, shape (N,).
        """
        return self.acceleration.response(w, sample_time, self.velocity_filter)


@dataclass(frozen=True)
class RenderedEnvironment:
    """A mass-damper-spring ``F = M a^ + B v^ + K x`` to render.

    Parameters
    ----------
    mass : float, optional
        Virtual mass ``M`` [kg], either sign (negative: inertia compensation), ``|M| <= 1e3``.
    damping : float, optional
        Virtual damping ``B`` [N s/m], either sign, ``|B| <= 1e8``.
    stiffness : float, optional
        Virtual stiffness ``K`` [N/m], 0 to 1e9.

    Raises
    ------
    ValidationError
        When a value is not finite or out of range.
    """

    mass: float = 0.0
    damping: float = 0.0
    stiffness: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "mass", check_virtual_mass("mass", self.mass))
        object.__setattr__(self, "damping", check_virtual_damping("damping", self.damping))
        object.__setattr__(self, "stiffness", _STIFFNESS("stiffness", self.stiffness))

    def target(self, w: Any) -> np.ndarray:
        """The ideal force per position ``K + j w B - w^2 M`` [N/m] (``M s + B + K/s`` times ``s``).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).

        Returns
        -------
        numpy.ndarray
            Complex, shape (N,).
        """
        w = np.asarray(w, dtype=float)
        return self.stiffness + 1j * w * self.damping - w * w * self.mass


def rendered_force_response(w: Any, sample_time: float, controller: RenderingController,
                            environment: RenderedEnvironment) -> np.ndarray:
    """The sampled force per position ``G(jw) = e^{-j w d T} ZOH(jw) (K + B V + M A)`` [N/m].

    The rendered impedance is ``G/(jw)``; ``Re G`` is the effective stiffness and ``Im G/w``
    the effective damping (module docstring; Colonnese et al. 2015).

    Parameters
    ----------
    w : array_like
        Angular frequencies [rad/s], shape (N,), below Nyquist ``pi/T``.
    sample_time : float
        Sample period ``T`` [s].
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    environment : RenderedEnvironment
        ``(M, B, K)``.

    Returns
    -------
    numpy.ndarray
        ``G`` [N/m], complex, shape (N,).
    """
    w = np.asarray(w, dtype=float)
    T = float(sample_time)
    th = w * T
    hold = np.exp(-0.5j * th) * np.sinc(th / (2.0 * math.pi))  # (1 - e^{-j wT})/(j wT)
    ctrl = (environment.stiffness + environment.damping * controller.velocity_response(w, T)
            + environment.mass * controller.acceleration_response(w, T))
    return np.exp(-1j * controller.delay_samples * th) * hold * ctrl


def handle_transmission(device: Device, w: Any) -> tuple[np.ndarray, np.ndarray]:
    """``(alpha, beta)`` per frequency: an impedance ``Z`` at the actuator is ``Z/(alpha + beta Z)`` at the handle.

    The handle impedance of the chain with ``Z`` from the actuator mass to ground is a Moebius
    function of ``Z`` (the one continued fraction,
    :func:`~analysis.chain.continued_fraction.handle_impedance`), so what ``Z`` adds at the
    handle, ``R_0(Z) - R_0(0)``, is ``Z/(alpha + beta Z)``: ``1/alpha`` is the squared velocity
    ratio actuator/handle of the free chain, ``1/beta = R_0(inf) - R_0(0)`` (the actuator
    clamped).  Both follow from ``R_0`` at the terminations ``tau`` and ``2 tau``,
    ``tau = |R_0(0)|`` (real and positive, so never resonant with a passive chain):
    ``1/Delta(t) = alpha/t + beta``.  A rigid device (one mass: handle = actuator) is
    ``(1, 0)`` exactly.

    Parameters
    ----------
    device : Device
        The chain.
    w : array_like
        Angular frequencies [rad/s], shape (N,), > 0.

    Returns
    -------
    alpha : numpy.ndarray
        Dimensionless, complex, shape (N,).
    beta : numpy.ndarray
        [m/(N s)], complex, shape (N,).
    """
    w = np.asarray(w, dtype=float).reshape(-1)
    if device.masses.size == 1:
        return np.ones(w.size, dtype=complex), np.zeros(w.size, dtype=complex)
    s = 1j * w
    r0 = handle_impedance(device, s)
    tau = np.maximum(np.abs(r0), 1e-300)
    inv1 = 1.0 / (handle_impedance(device, s, termination=tau) - r0)
    inv2 = 1.0 / (handle_impedance(device, s, termination=2.0 * tau) - r0)
    return 2.0 * tau * (inv1 - inv2), 2.0 * inv2 - inv1


def handle_force_response(device: Device, w: Any, controller: RenderingController,
                          environment: RenderedEnvironment) -> np.ndarray:
    """The rendered force per handle position ``G_h(jw) = jw [R_0(Z_c) - R_0(0)]`` [N/m].

    The controller renders ``Z_c = G/(jw)`` (:func:`rendered_force_response`) at the actuator
    (the point it reads and drives); the user holds the handle, which sees the chain between
    them terminated by ``Z_c``.  ``R_0(Z_c)`` is that handle impedance (the one continued
    fraction), and ``R_0(0)``, the free device's own (its mass and damping, felt with the
    controller off), is taken away: ``G_h = G/(alpha + beta G/(jw))``
    (:func:`handle_transmission`), the rendered impedance at the handle of issue 24's
    *accurate*.  For a rigid device ``G_h = G``; at low frequencies, where the chain is rigid,
    ``G_h -> G`` and the whole handle impedance ``R_0(Z_c) -> Z_c + sum m_i jw + sum g_i``.

    Parameters
    ----------
    device : Device
        The chain and its sample time.
    w : array_like
        Angular frequencies [rad/s], shape (N,), > 0 and below Nyquist ``pi/T``.
    controller : RenderingController
        Delay, velocity filter and acceleration estimate.
    environment : RenderedEnvironment
        ``(M, B, K)``.

    Returns
    -------
    numpy.ndarray
        ``G_h`` [N/m], complex, shape (N,).
    """
    w = np.asarray(w, dtype=float).reshape(-1)
    G = rendered_force_response(w, device.sample_time, controller, environment)
    if device.masses.size == 1:
        return G
    alpha, beta = handle_transmission(device, w)
    return G / (alpha + beta * G / (1j * w))


# -- the mass term in the one controller model ------------------------------------------------
def _stage_names(stages: tuple[VelocityFilter, ...]) -> tuple[str, ...]:
    return tuple(f"ac{i}{j}" for i, f in enumerate(stages) for j in range(f.order))


def _cascade(p: SimpleNamespace, d2: Any, mem: dict, new: dict | None) -> Any:
    """``a^`` of the cascade ``p.acc`` driven by ``d2`` (its states in ``mem``); updates into ``new``."""
    u = d2
    for i, r in enumerate(p.acc):
        y = r.D * u
        for j in range(r.order):
            y = y + r.C[j] * mem[f"ac{i}{j}"]
        if new is not None:
            for j in range(r.order):
                acc = r.B[j] * u
                for m in range(r.order):
                    if r.A[j, m] != 0.0:
                        acc = acc + r.A[j, m] * mem[f"ac{i}{m}"]
                new[f"ac{i}{j}"] = acc
        u = y
    return u


class InertialImpedanceLoop:
    """Mixin of the mass term ``M a^`` on an impedance loop (module docstring).

    Built by :func:`inertial_loop` on the plain or the filtered impedance loop; the virtual mass
    is the controller constant ``mv`` (overridable per termination like ``kc``, ``bc``).
    """

    acceleration: AccelerationEstimate
    mass: float
    stages: tuple[VelocityFilter, ...]

    def memory_names(self, causality: EnvironmentCausality, lag: bool) -> tuple[str, ...]:
        """The impedance loop's memory, then ``"dd"`` and the acceleration cascade's states.

        Parameters
        ----------
        causality : EnvironmentCausality
            The environment's causality.
        lag : bool
            Whether the one-sample implementation delay is modelled.

        Returns
        -------
        tuple of str
            The memory names.
        """
        return super().memory_names(causality, lag) + ("dd",) + _stage_names(self.stages)  # type: ignore[misc]

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        """Write the coupling, the virtual mass ``mv`` and the cascade's realizations into ``p``.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants, written in place.
        coupling : tuple of (float, float)
            ``(k_c [N/m], b_c [N s/m])``.
        pd : tuple of (float, float)
            Unused (admittance display only).
        """
        super().set_gains(p, coupling, pd)  # type: ignore[misc]
        p.mv = self.mass
        p.acc = tuple(f.realization(p.T) for f in self.stages)

    def damper(self, p: SimpleNamespace, mem: dict) -> tuple[Any, Any]:
        """The coupling's ``(kcp, hist)`` with the mass term added (module docstring).

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants (``kc``, ``bc``, ``mv``, ``T``, the cascade ``acc``).
        mem : dict
            Controller memory at the last sample.

        Returns
        -------
        tuple
            ``(kcp [N/m], hist [N])``: the force is ``kcp delta - hist``.
        """
        kcp, hist = super().damper(p, mem)  # type: ignore[misc]
        dtot = 1.0
        for r in p.acc:
            dtot *= r.D
        g = p.mv * (dtot / (p.T * p.T))
        past = _cascade(p, 0.0, mem, None)  # the states' part of a^
        return kcp + g, hist + g * (2.0 * mem["delta"] - mem["dd"]) - p.mv * past

    def filter_memory(self, p: SimpleNamespace, delta: Any, mem: dict, new: dict) -> None:
        """Update the velocity filter's and the acceleration cascade's states, and ``dd``.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants.
        delta : float or numpy.ndarray
            Coupling deflection at this sample [m].
        mem : dict
            Controller memory at the last sample.
        new : dict
            Controller memory at this sample, updated in place.
        """
        super().filter_memory(p, delta, mem, new)  # type: ignore[misc]
        d2 = (delta - 2.0 * mem["delta"] + mem["dd"]) / (p.T * p.T)
        _cascade(p, d2, mem, new)
        new["dd"] = mem["delta"]

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        """Memory at rest: the impedance loop's, with ``x[k-2]`` at rest too (``dd = delta``).

        Parameters
        ----------
        names : tuple of str
            Names of the memory.
        x0 : float
            Rest position of the device [m].
        wall : bool
            Whether a wall holds the environment.
        xw : float
            Wall position [m].

        Returns
        -------
        dict
            The memory, keyed by ``names``.
        """
        mem = super().rest_memory(names, x0, wall, xw)  # type: ignore[misc]
        mem["dd"] = mem["delta"]
        return mem

    def __repr__(self) -> str:
        return f"<impedance display loop with M = {self.mass:g} kg, {self.acceleration.label()}>"


@lru_cache(maxsize=None)
def _inertial_class(base: type) -> type:
    return type(f"Inertial{base.__name__}", (InertialImpedanceLoop, base), {})


def inertial_loop(base: DisplayLoop, acceleration: AccelerationEstimate | None, mass: float,
                  velocity_filter: VelocityFilter | None) -> DisplayLoop:
    """The impedance loop ``base`` (plain or filtered) with the mass term ``M a^``.

    Parameters
    ----------
    base : DisplayLoop
        The impedance display's loop (:func:`~analysis.sampled.filtered.filtered_loop`).
    acceleration : AccelerationEstimate or None
        The acceleration estimate; ``None`` for the second backward difference.
    mass : float
        The virtual mass ``M`` [kg] (the constant ``mv``).
    velocity_filter : VelocityFilter or None
        The controller's velocity filter (the ``"filtered_velocity"`` estimate uses it).

    Returns
    -------
    DisplayLoop
        A loop of the class of ``base`` with :class:`InertialImpedanceLoop` mixed in.

    Raises
    ------
    ValidationError
        When ``base`` is not an impedance display's loop.
    """
    if not isinstance(base, ImpedanceLoop):
        raise ValidationError("mass", "0 without an acceleration estimate for an admittance display", mass)
    cls = _inertial_class(type(base))
    loop = cls.__new__(cls)
    loop.__dict__.update(base.__dict__)
    loop.acceleration = SECOND_DIFFERENCE if acceleration is None else acceleration
    loop.mass = float(mass)
    loop.stages = loop.acceleration.stages(velocity_filter)
    return loop
