"""The controllers of the two display loops: one object per display (Adams et al., section III).

One controller step goes from the samples at ``kT`` (encoder ``y``, force gauge ``f``) to the
force held on ``[kT, (k+1)T)``.  ``delta = y - x_e`` is the deflection of the coupling; ``p`` a
penetration into the wall at ``x_w``; ``L`` the optional one-sample implementation delay between
coupling and environment (the paper's explicit integration).  Without it, coupling and
environment are solved together (implicit); both are linear, so that is one division.

* impedance display, impedance environment (eq. 4, 5): ``F = k_c delta + b_c (delta -
  delta[k-1])/T`` and ``F = k_obj p + b_obj (p - p[k-1])/T``; ``F_d = F_e``.  With ``L``
  the coupling uses ``F_e[k-1]``.
* impedance display, admittance environment (eq. 4, 6): ``F_d = F_e = Z_c (v_d - v_e)``;
  the object ``m_e v_e' = F_e - b_e v_e`` by backward Euler (with ``L``: driven by
  ``F_e[k-1]``); the god-object wall holds ``x_e = x_w``.  The free object's implicit step
  divides by ``m_e/T^2 + b_e/T`` plus the coupling's direct feedthrough; a rendered negative
  mass can cancel it exactly, and then only the held object is defined (the free step is NaN).
* admittance display (eq. 13, 30): ``F_d = k_p e + k_d (e - e[k-1])/T``, ``e = y - x_com``,
  and the coupling ``Y_cA = 1/b_c + T z/(m_c (z-1))`` (eq. 16): ``v_com = G/b_c + w``,
  ``w[k] = w[k-1] + T G/m_c``, ``x_com[k] = x_com[k-1] + T v_com``, where ``G`` is the force
  through the coupling.  Impedance environment (eq. 17): ``G = F_meas - F_e(x_com)``.
  Admittance environment (eq. 18): ``v_com = v_e`` and ``F_e = F_meas - G``.

Every controller is written in position form, where ``Tz/(z-1)`` applied to a backward
difference is the position itself.  The same steps serve the linear analysis (arguments are
coefficient rows, the wall is assumed engaged or free as the environment says) and the nonlinear
simulator (arguments are floats and the wall is unilateral), so both use one implementation of
the architectures.

A display is an object here (:class:`DisplayLoop`: :data:`IMPEDANCE_LOOP`,
:data:`ADMITTANCE_LOOP`) that validates its gains, names its controller memory and steps its
controller; the environment's causality object
(:class:`~analysis.sampled.terminations.EnvironmentCausality`) selects the penalty or the
constraint form.  :data:`DISPLAY_LOOPS` is the one mapping from the name a profile or a
:class:`~analysis.sampled.loop.LoopSpec` holds (``"impedance"``/``"admittance"``) to the object.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any, ClassVar

import numpy as np

from analysis.checks import Real, choice
from analysis.errors import ValidationError
from analysis.sampled.terminations import (
    HANDS_OFF,
    RIGID_GRASP,
    EnvironmentCausality,
    Termination,
    free_motion,
    penalty_wall,
)

__all__ = [
    "DisplayLoop",
    "ImpedanceLoop",
    "AdmittanceLoop",
    "IMPEDANCE_LOOP",
    "ADMITTANCE_LOOP",
    "DISPLAY_LOOPS",
    "display_loop",
    "Engaged",
    "Step",
    "StepResult",
    "linear_engaged",
    "pick",
]

# "> 0 and finite" / ">= 0 and finite", and "a real number" for a value that is not one.
_POS = Real(lo=0.0, lo_open=True, not_real="a real number")
_NONNEG = Real(lo=0.0, not_real="a real number")

#: ``engaged(penetration, flag)``: whether the wall is in contact (see the module docstring).
Engaged = Callable[[Any, Any], Any]
#: What a controller step returns: ``(F_d, new_memory, F_e, x_e)``.
StepResult = tuple[Any, dict, Any, Any]
#: ``step(p, y, f, memory, engaged) -> StepResult``: one controller step.
Step = Callable[[SimpleNamespace, Any, Any, dict, Engaged], StepResult]


def linear_engaged(pen: Any, flag: Any) -> Any:
    """Linear analysis: the wall is engaged exactly when the environment says so."""
    return flag


def pick(cond: Any, a: Any, b: Any) -> Any:
    """``a`` where ``cond`` holds, else ``b``: a plain choice for floats, ``np.where`` for rows."""
    if isinstance(cond, (bool, np.bool_)):
        return a if cond else b
    return np.where(cond, a, b)


class DisplayLoop:
    """The controller of one display, in both environment causalities (module docstring).

    ``coupling_fields`` are the names of ``LoopSpec.coupling`` in the controller constants and
    the profile (``kc``/``bc`` or ``mc``/``bc``); ``default_coupling`` is the paper's
    experimental coupling used for a bare device; ``penalty_memory``/``constraint_memory`` name
    the controller memory of the two architectures (the values at the last sample).
    """

    name: ClassVar[str]
    coupling_fields: ClassVar[tuple[str, str]]
    default_coupling: ClassVar[tuple[float, float]]
    penalty_memory: ClassVar[tuple[str, ...]]
    constraint_memory: ClassVar[tuple[str, ...]]

    def check_gains(self, coupling: object, pd: object) -> tuple[tuple[float, float], tuple[float, float]]:
        """The validated ``coupling`` and PD pair ``(k_p, k_d)`` of a :class:`LoopSpec`.

        Parameters
        ----------
        coupling : object
            The coupling gains: ``(k_c [N/m], b_c [N s/m])`` for the impedance display,
            ``(m_c [kg], b_c [N s/m])`` for the admittance display.
        pd : object
            The PD gains ``(k_p [N/m], k_d [N s/m])`` of the admittance display's position loop.

        Returns
        -------
        tuple of (tuple of (float, float), tuple of (float, float))
            ``(coupling, (k_p, k_d))``, validated.

        Raises
        ------
        ValidationError
            When ``coupling`` or ``pd`` is not a pair, or a gain is out of range.
        """
        try:
            a, b = coupling
        except (TypeError, ValueError) as exc:
            raise ValidationError("coupling", "a pair of real numbers", coupling) from exc
        checked = self.check_coupling(a, b, coupling)
        try:
            kp, kd = pd
        except (TypeError, ValueError) as exc:
            raise ValidationError("pd", "a pair (kp, kd)", pd) from exc
        return checked, (_NONNEG("kp", kp), _NONNEG("kd", kd))

    def check_coupling(self, a: object, b: object, coupling: object) -> tuple[float, float]:
        """The validated coupling gains of this display.

        Parameters
        ----------
        a : object
            First coupling gain: ``k_c`` [N/m] or ``m_c`` [kg].
        b : object
            Coupling damping ``b_c`` [N s/m].
        coupling : object
            The whole coupling, named in the error.

        Returns
        -------
        tuple of (float, float)
            The validated ``(a, b)``.

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        """Write the coupling (and PD) gains into the controller constants ``p``.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants, written in place.
        coupling : tuple of (float, float)
            The validated coupling (:meth:`check_gains`): ``(k_c [N/m], b_c [N s/m])`` or
            ``(m_c [kg], b_c [N s/m])``.
        pd : tuple of (float, float)
            The validated PD gains ``(k_p [N/m], k_d [N s/m])`` (admittance display only).

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        """The coupling of this display in a profile.

        Parameters
        ----------
        profile : Profile
            A device profile (:class:`~analysis.profiles.model.Profile`).

        Returns
        -------
        tuple of (float, float)
            ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``.

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def default_termination(self) -> Termination:
        """The paper's worst-case termination for this display (section III).

        Returns
        -------
        Termination
            The grasp and the environment.

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def memory_names(self, causality: EnvironmentCausality, lag: bool) -> tuple[str, ...]:
        """Names of the controller memory; ``lag`` adds the delayed environment force.

        Parameters
        ----------
        causality : EnvironmentCausality
            The environment's causality (penalty or constraint architecture).
        lag : bool
            Whether the one-sample implementation delay is modelled (adds ``"fe"``).

        Returns
        -------
        tuple of str
            The memory names.
        """
        return causality.select(self.penalty_memory, self.constraint_memory) + (("fe",) if lag else ())

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        """Controller memory consistent with rest at position ``x0`` (wall at ``xw`` if ``wall``).

        Parameters
        ----------
        names : tuple of str
            Names of the memory (:meth:`memory_names`).
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

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def step_for(self, causality: EnvironmentCausality) -> Step:
        """The controller step of this display against an environment of ``causality``.

        Parameters
        ----------
        causality : EnvironmentCausality
            The environment's causality.

        Returns
        -------
        Step
            :meth:`penalty_step` or :meth:`constraint_step`.
        """
        return causality.select(self.penalty_step, self.constraint_step)

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        """One controller step against a penalty (impedance-causality) environment.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def constraint_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                        engaged: Engaged = linear_engaged) -> StepResult:
        """One controller step against a constraint (admittance-causality) environment.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].

        Raises
        ------
        NotImplementedError
            Always: each display overrides it.
        """
        raise NotImplementedError

    def __repr__(self) -> str:
        return f"<{self.name} display loop>"


class ImpedanceLoop(DisplayLoop):
    """Impedance display: the coupling ``Z_c = k_c + b_c (z-1)/(T z)`` drives the device (eq. 4)."""

    name = "impedance"
    coupling_fields = ("kc", "bc")
    default_coupling = (50e3, 100.0)
    penalty_memory = ("delta", "xe")
    constraint_memory = ("delta", "xe", "ve")

    def check_coupling(self, a: object, b: object, coupling: object) -> tuple[float, float]:
        """The validated ``(k_c, b_c)``: both at least 0, not both 0.

        Parameters
        ----------
        a : object
            First coupling gain: ``k_c`` [N/m] or ``m_c`` [kg].
        b : object
            Coupling damping ``b_c`` [N s/m].
        coupling : object
            The whole coupling, named in the error.

        Returns
        -------
        tuple of (float, float)
            The validated ``(a, b)``.

        Raises
        ------
        ValidationError
            When a gain is negative or not a real number, or ``k_c + b_c <= 0``.
        """
        kc, bc = _NONNEG("kc", a), _NONNEG("bc", b)
        if kc + bc <= 0:
            raise ValidationError("coupling", "k_c + b_c > 0", coupling)
        return kc, bc

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        """Write ``k_c`` and ``b_c`` into the controller constants ``p`` (``pd`` is unused).

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants, written in place.
        coupling : tuple of (float, float)
            The validated coupling (:meth:`check_gains`): ``(k_c [N/m], b_c [N s/m])`` or
            ``(m_c [kg], b_c [N s/m])``.
        pd : tuple of (float, float)
            The validated PD gains ``(k_p [N/m], k_d [N s/m])`` (admittance display only).
        """
        p.kc, p.bc = coupling

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        """The profile's impedance coupling ``(kc, bc)``.

        Parameters
        ----------
        profile : Profile
            A device profile (:class:`~analysis.profiles.model.Profile`).

        Returns
        -------
        tuple of (float, float)
            ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``.
        """
        return (profile.kc, profile.bc)

    def default_termination(self) -> Termination:
        """Hands off against a rigid penalty wall (section III).

        Returns
        -------
        Termination
            The grasp and the environment.
        """
        return Termination(HANDS_OFF, penalty_wall())

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        """Memory at rest: the environment at ``x0`` (or on the wall), the deflection ``x0 - x_e``.

        Parameters
        ----------
        names : tuple of str
            Names of the memory (:meth:`memory_names`).
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
        mem = dict.fromkeys(names, 0.0)
        mem["xe"] = x0 if not (wall and x0 > xw) else xw
        mem["delta"] = x0 - mem["xe"]
        return mem

    def damper(self, p: SimpleNamespace, mem: dict) -> tuple[Any, Any]:
        """``(k_c + b_c/T, b_c delta[k-1]/T)``: the coupling force is ``kcp delta - hist`` (eq. 4).

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants (``kc`` [N/m], ``bc`` [N s/m], ``T`` [s]).
        mem : dict
            Controller memory at the last sample (``delta`` [m]).

        Returns
        -------
        tuple
            ``(kcp [N/m], hist [N])``, floats or coefficient rows like ``mem["delta"]``.
        """
        return p.kc + p.bc / p.T, (p.bc / p.T) * mem["delta"]

    def filter_memory(self, p: SimpleNamespace, delta: Any, mem: dict, new: dict) -> None:
        """Update velocity-filter states in ``new`` (none for the backward difference).

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

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (4, 5): coupling and penalty wall, solved together (or the wall a sample late).

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].
        """
        T = p.T
        kcp, hist = self.damper(p, mem)
        new: dict = {}
        if p.lag:
            fin = mem["fe"]
            delta = (fin + hist) / kcp
            xe = y - delta
            fe_c = p.kobj * (xe - p.xw) + (p.bobj / T) * (xe - mem["xe"])
            fe = pick(engaged(xe - p.xw, True), fe_c, 0.0 * fe_c)
            u = fin
            new["fe"] = fe
        else:
            kop = p.kobj + p.bobj / T
            xe_c = (kcp * y - hist + p.kobj * p.xw + (p.bobj / T) * mem["xe"]) / (kcp + kop)
            xe_f = y - hist / kcp
            xe = pick(engaged(xe_c - p.xw, True), xe_c, xe_f)
            delta = y - xe
            u = kcp * delta - hist
            fe = u
        new["delta"], new["xe"] = delta, xe
        self.filter_memory(p, delta, mem, new)
        return u, new, fe, xe

    def constraint_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                        engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (4, 6): the coupling drives an object of mass ``m_e``, held by a god-object wall.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].
        """
        T, lag = p.T, p.lag
        kcp, hist = self.damper(p, mem)
        me, be = p.me, p.bobj
        xprev, vprev = mem["xe"], mem["ve"]
        if lag:
            v_f = (vprev + (T / me) * mem["fe"]) / (1.0 + T * be / me)
            x_f = xprev + T * v_f
        else:
            # the free object's implicit step: its inertia and damping (a + b_e/T) plus the
            # coupling's direct feedthrough kcp (the weight of delta[k] in F[k]; with a rendered
            # environment K + B/T + M D/T^2).  A negative virtual mass can cancel them exactly:
            # then the free object's step has no solution (NaN here), and only an object the
            # wall holds (x_e = x_w, which never reads the free step) is defined
            a = me / (T * T)
            den = a + kcp + be / T
            x_f = (a * (xprev + T * vprev) + kcp * y - hist + (be / T) * xprev) / pick(den == 0.0, math.nan, den)
            v_f = (x_f - xprev) / T
        on = engaged(x_f - p.xw, p.wall)
        xe = pick(on, 0.0 * y + p.xw, x_f)
        ve = pick(on, 0.0 * y, v_f)
        delta = y - xe
        u = kcp * delta - hist
        new = {"delta": delta, "xe": xe, "ve": ve}
        if lag:
            new["fe"] = u
        self.filter_memory(p, delta, mem, new)
        return u, new, u, xe


class AdmittanceLoop(DisplayLoop):
    """Admittance display: the coupling ``Y_cA`` (eq. 16) sets the commanded position of a PD loop."""

    name = "admittance"
    coupling_fields = ("mc", "bc")
    default_coupling = (8.0, 400.0)
    penalty_memory = ("yp", "xc", "w")
    constraint_memory = ("yp", "xc", "ve", "w")

    def check_coupling(self, a: object, b: object, coupling: object) -> tuple[float, float]:
        """The validated ``(m_c, b_c)``: both greater than 0.

        Parameters
        ----------
        a : object
            First coupling gain: ``k_c`` [N/m] or ``m_c`` [kg].
        b : object
            Coupling damping ``b_c`` [N s/m].
        coupling : object
            The whole coupling, named in the error.

        Returns
        -------
        tuple of (float, float)
            The validated ``(a, b)``.

        Raises
        ------
        ValidationError
            When a gain is not greater than 0 or not a real number.
        """
        return _POS("mc", a), _POS("bc", b)

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        """Write ``m_c``, ``b_c``, ``k_p`` and ``k_d`` into the controller constants ``p``.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants, written in place.
        coupling : tuple of (float, float)
            The validated coupling (:meth:`check_gains`): ``(k_c [N/m], b_c [N s/m])`` or
            ``(m_c [kg], b_c [N s/m])``.
        pd : tuple of (float, float)
            The validated PD gains ``(k_p [N/m], k_d [N s/m])`` (admittance display only).
        """
        p.mc, p.bc = coupling
        p.kp, p.kd = pd

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        """The profile's admittance coupling ``(mc, bc_adm)``.

        Parameters
        ----------
        profile : Profile
            A device profile (:class:`~analysis.profiles.model.Profile`).

        Returns
        -------
        tuple of (float, float)
            ``(k_c [N/m], b_c [N s/m])`` or ``(m_c [kg], b_c [N s/m])``.
        """
        return (profile.mc, profile.bc_adm)

    def default_termination(self) -> Termination:
        """A rigid grasp in free motion (section III).

        Returns
        -------
        Termination
            The grasp and the environment.
        """
        return Termination(RIGID_GRASP, free_motion("impedance"))

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        """Memory at rest: the encoder and the commanded position at ``x0``, no coupling velocity.

        Parameters
        ----------
        names : tuple of str
            Names of the memory (:meth:`memory_names`).
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
        mem = dict.fromkeys(names, 0.0)
        mem["yp"], mem["xc"] = x0, x0
        return mem

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (16, 17): the coupling is driven by ``F_meas - F_e(x_com)`` of the penalty wall.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].
        """
        T, mc, bc = p.T, p.mc, p.bc
        xcp, w = mem["xc"], mem["w"]
        c = T / bc + T * T / mc
        new: dict = {}
        if p.lag:
            G = f - mem["fe"]
            xc = xcp + T * w + c * G
            fe_c = p.kobj * (xc - p.xw) + (p.bobj / T) * (xc - xcp)
            fe = pick(engaged(xc - p.xw, True), fe_c, 0.0 * fe_c)
            new["fe"] = fe
        else:
            cb = c * p.bobj / T
            x_c = (xcp + T * w + c * f + c * p.kobj * p.xw + cb * xcp) / (1.0 + c * p.kobj + cb)
            x_f = xcp + T * w + c * f
            on = engaged(x_c - p.xw, True)
            xc = pick(on, x_c, x_f)
            fe_c = p.kobj * (x_c - p.xw) + (p.bobj / T) * (x_c - xcp)
            fe = pick(on, fe_c, 0.0 * fe_c)
            G = f - fe
        new["w"] = w + (T / mc) * G
        return self.position_loop(p, y, mem, new, xc, fe)

    def constraint_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                        engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (16, 18): the coupling moves with the object (``v_com = v_e``), held by the wall.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants: sample period ``T`` [s], ``lag`` (the one-sample implementation
            delay), the coupling and PD gains (:meth:`set_gains`) and the environment (``kobj``
            [N/m], ``bobj`` [N s/m], ``me`` [kg], wall position ``xw`` [m], ``wall``).
        y : float or numpy.ndarray
            Encoder sample ``y[k]`` [m]: a float (simulator) or a coefficient row (linear analysis).
        f : float or numpy.ndarray
            Force-gauge sample ``F_meas[k]`` [N], like ``y``.
        mem : dict
            Controller memory at the last sample, keyed by :meth:`memory_names`.
        engaged : Engaged, optional
            ``engaged(penetration, flag)``: whether the wall is in contact; by default (linear
            analysis) exactly when the environment says so.

        Returns
        -------
        StepResult
            ``(F_d, new_memory, F_e, x_e)``: the device force [N] held on ``[kT, (k+1)T)``, the
            controller memory at this sample, the environment force [N] and position [m].
        """
        T, mc, bc = p.T, p.mc, p.bc
        xcp, w = mem["xc"], mem["w"]
        me, be = p.me, p.bobj
        c1 = 1.0 / bc + T / mc
        vprev = mem["ve"]
        if p.lag:
            v_f = (vprev + (T / me) * mem["fe"]) / (1.0 + T * be / me)
        else:
            v_f = (vprev + (T / me) * (f + w / c1)) / (1.0 + T / (me * c1) + T * be / me)
        x_f = xcp + T * v_f
        on = engaged(x_f - p.xw, p.wall)
        xc = pick(on, 0.0 * x_f + p.xw, x_f)
        ve = pick(on, 0.0 * v_f, v_f)
        G = (ve - w) / c1
        fe = f - G
        new = {"ve": ve, "w": w + (T / mc) * G}
        if p.lag:
            new["fe"] = fe
        return self.position_loop(p, y, mem, new, xc, fe)

    @staticmethod
    def position_loop(p: SimpleNamespace, y: Any, mem: dict, new: dict, xc: Any, fe: Any) -> StepResult:
        """Eq. (30): the PD position loop ``F_d = k_p e + k_d (e - e[k-1])/T`` on ``e = y - x_com``.

        Parameters
        ----------
        p : types.SimpleNamespace
            Controller constants (``kp`` [N/m], ``kd`` [N s/m], ``T`` [s]).
        y : float or numpy.ndarray
            Encoder sample [m].
        mem : dict
            Controller memory at the last sample (``yp``, ``xc`` [m]).
        new : dict
            Controller memory at this sample, completed in place (``yp``, ``xc``).
        xc : float or numpy.ndarray
            Commanded position ``x_com`` at this sample [m].
        fe : float or numpy.ndarray
            Environment force at this sample [N], passed through.

        Returns
        -------
        StepResult
            ``(F_d, new, F_e, x_com)``.
        """
        e = y - xc
        u = p.kp * e + (p.kd / p.T) * (e - (mem["yp"] - mem["xc"]))
        new["yp"], new["xc"] = y, xc
        return u, new, fe, xc


IMPEDANCE_LOOP = ImpedanceLoop()
ADMITTANCE_LOOP = AdmittanceLoop()
#: The one mapping from a display name (profiles, :class:`LoopSpec`) to its loop object.
DISPLAY_LOOPS: dict[str, DisplayLoop] = {IMPEDANCE_LOOP.name: IMPEDANCE_LOOP,
                                          ADMITTANCE_LOOP.name: ADMITTANCE_LOOP}


def display_loop(display: str | DisplayLoop) -> DisplayLoop:
    """The loop object of a display name (``ValidationError`` on ``display`` for an unknown one).

    Parameters
    ----------
    display : str or DisplayLoop
        ``"impedance"`` or ``"admittance"``, or a loop object (returned as is).

    Returns
    -------
    DisplayLoop
        :data:`IMPEDANCE_LOOP` or :data:`ADMITTANCE_LOOP`.
    """
    if isinstance(display, DisplayLoop):
        return display
    return DISPLAY_LOOPS[choice("display", display, DISPLAY_LOOPS, allowed="impedance or admittance")]
