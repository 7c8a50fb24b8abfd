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
  ``F_e[k-1]``); the god-object wall holds ``x_e = x_w``.
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
        """The validated ``coupling`` and PD pair ``(k_p, k_d)`` of a :class:`LoopSpec`."""
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
        raise NotImplementedError

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        """Write the coupling (and PD) gains into the controller constants ``p``."""
        raise NotImplementedError

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        """The coupling of this display in a profile."""
        raise NotImplementedError

    def default_termination(self) -> Termination:
        """The paper's worst-case termination for this display (section III)."""
        raise NotImplementedError

    def memory_names(self, causality: EnvironmentCausality, lag: bool) -> tuple[str, ...]:
        """Names of the controller memory; ``lag`` adds the delayed environment force."""
        return causality.select(self.penalty_memory, self.constraint_memory) + (("fe",) if lag else ())

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        """Controller memory consistent with rest at position ``x0`` (wall at ``xw`` if ``wall``)."""
        raise NotImplementedError

    def step_for(self, causality: EnvironmentCausality) -> Step:
        """The controller step of this display against an environment of ``causality``."""
        return causality.select(self.penalty_step, self.constraint_step)

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        raise NotImplementedError

    def constraint_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                        engaged: Engaged = linear_engaged) -> StepResult:
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
        kc, bc = _NONNEG("kc", a), _NONNEG("bc", b)
        if kc + bc <= 0:
            raise ValidationError("coupling", "k_c + b_c > 0", coupling)
        return kc, bc

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        p.kc, p.bc = coupling

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        return (profile.kc, profile.bc)

    def default_termination(self) -> Termination:
        return Termination(HANDS_OFF, penalty_wall())

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        mem = dict.fromkeys(names, 0.0)
        mem["xe"] = x0 if not (wall and x0 > xw) else xw
        mem["delta"] = x0 - mem["xe"]
        return mem

    def damper(self, p: SimpleNamespace, mem: dict) -> tuple[Any, Any]:
        """``(k_c + b_c/T, b_c delta[k-1]/T)``: the coupling force is ``kcp delta - hist`` (eq. 4)."""
        return p.kc + p.bc / p.T, (p.bc / p.T) * mem["delta"]

    def filter_memory(self, p: SimpleNamespace, delta: Any, mem: dict, new: dict) -> None:
        """Update velocity-filter states in ``new`` (none for the backward difference)."""

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (4, 5): coupling and penalty wall, solved together (or the wall a sample late)."""
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
        """Eq. (4, 6): the coupling drives an object of mass ``m_e``, held by a god-object wall."""
        T, lag = p.T, p.lag
        kcp, hist = self.damper(p, mem)
        me, be = p.me, p.bobj
        xprev, vprev = mem["xe"], mem["ve"]
        if lag:
            v_f = (vprev + (T / me) * mem["fe"]) / (1.0 + T * be / me)
            x_f = xprev + T * v_f
        else:
            a = me / (T * T)
            x_f = (a * (xprev + T * vprev) + kcp * y - hist + (be / T) * xprev) / (a + kcp + be / T)
            v_f = (x_f - xprev) / T
        on = engaged(x_f - p.xw, p.wall)
        xe = pick(on, 0.0 * x_f + p.xw, x_f)
        ve = pick(on, 0.0 * v_f, v_f)
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
        return _POS("mc", a), _POS("bc", b)

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        p.mc, p.bc = coupling
        p.kp, p.kd = pd

    def profile_coupling(self, profile: Any) -> tuple[float, float]:
        return (profile.mc, profile.bc_adm)

    def default_termination(self) -> Termination:
        return Termination(RIGID_GRASP, free_motion("impedance"))

    def rest_memory(self, names: tuple[str, ...], x0: float, wall: bool, xw: float) -> dict:
        mem = dict.fromkeys(names, 0.0)
        mem["yp"], mem["xc"] = x0, x0
        return mem

    def penalty_step(self, p: SimpleNamespace, y: Any, f: Any, mem: dict,
                     engaged: Engaged = linear_engaged) -> StepResult:
        """Eq. (16, 17): the coupling is driven by ``F_meas - F_e(x_com)`` of the penalty wall."""
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
        """Eq. (16, 18): the coupling moves with the object (``v_com = v_e``), held by the wall."""
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
        """Eq. (30): the PD position loop ``F_d = k_p e + k_d (e - e[k-1])/T`` on ``e = y - x_com``."""
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
    """The loop object of a display name (``ValidationError`` on ``display`` for an unknown one)."""
    if isinstance(display, DisplayLoop):
        return display
    return DISPLAY_LOOPS[choice("display", display, DISPLAY_LOOPS, allowed="impedance or admittance")]
