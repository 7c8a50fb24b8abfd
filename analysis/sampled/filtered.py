"""Display loops whose damping term uses a filtered velocity estimate (issue 15).

The controllers of :mod:`analysis.sampled.controllers` differentiate by the backward difference.
Here the damping term goes through a :class:`~analysis.chain.velocity_filter.VelocityFilter`
``V(z) = H_f(z)(1 - z^{-1})/T`` instead; the filter's states are extra controller memory
(``"vf0"``, ``"vf1"``; zero at rest), so the exact closed-loop matrices, the sweeps and the
simulator all run the filter the controller really applies.

* Impedance display (eq. 4): the coupling force is ``k_c delta + b_c V(z) delta`` with
  ``delta = y - x_e`` the coupling deflection, i.e. ``Z_c(z) = k_c T z/(z-1) + b_c H_f(z)`` --
  the filter acts on the coupling's relative velocity, which keeps the coupling a one-port
  (against the god-object wall, ``x_e`` is fixed and this is the filtered device velocity).
  With ``v = C s + D d`` and ``d = (delta - delta[k-1])/T`` the force is
  ``(k_c + b_c D/T) delta - (b_c D delta[k-1]/T - b_c C s)``, so the implicit solve with the
  wall keeps its form.
* Admittance display (eq. 30): the PD loop's derivative term is ``k_d V(z) e``, ``e = y - x_com``
  (the coupling of eq. 16 has no velocity estimate).
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

from analysis.chain.velocity_filter import VelocityFilter
from analysis.sampled.controllers import AdmittanceLoop, DisplayLoop, ImpedanceLoop, StepResult, display_loop
from analysis.sampled.terminations import EnvironmentCausality

__all__ = ["FilteredImpedanceLoop", "FilteredAdmittanceLoop", "filtered_loop", "filter_state_names"]


def filter_state_names(order: int) -> tuple[str, ...]:
    """Memory names of the filter states."""
    return tuple(f"vf{i}" for i in range(order))


def _filter_output(p: SimpleNamespace, d: Any, mem: dict) -> Any:
    """``v = C s + D d`` of the filter realization ``p.vf`` (floats or coefficient rows)."""
    r = p.vf
    v = r.D * d
    for i in range(r.order):
        v = v + r.C[i] * mem[f"vf{i}"]
    return v


def _filter_update(p: SimpleNamespace, d: Any, mem: dict, new: dict) -> None:
    """``s' = A s + B d`` into ``new``."""
    r = p.vf
    for i in range(r.order):
        acc = r.B[i] * d
        for j in range(r.order):
            if r.A[i, j] != 0.0:
                acc = acc + r.A[i, j] * mem[f"vf{j}"]
        new[f"vf{i}"] = acc


class _Filtered:
    """Mixin: the filter record, its realization in the controller constants, its memory."""

    velocity_filter: VelocityFilter

    def memory_names(self, causality: EnvironmentCausality, lag: bool) -> tuple[str, ...]:
        return super().memory_names(causality, lag) + filter_state_names(self.velocity_filter.order)  # type: ignore[misc]

    def set_gains(self, p: SimpleNamespace, coupling: tuple[float, float], pd: tuple[float, float]) -> None:
        super().set_gains(p, coupling, pd)  # type: ignore[misc]
        p.vf = self.velocity_filter.realization(p.T)

    def __repr__(self) -> str:
        return f"<{self.name} display loop, {self.velocity_filter.label()}>"  # type: ignore[attr-defined]


class FilteredImpedanceLoop(_Filtered, ImpedanceLoop):
    """Impedance display with ``Z_c(z) = k_c T z/(z-1) + b_c H_f(z)`` (module docstring)."""

    def __init__(self, velocity_filter: VelocityFilter) -> None:
        self.velocity_filter = velocity_filter

    def damper(self, p: SimpleNamespace, mem: dict) -> tuple[Any, Any]:
        r, T = p.vf, p.T
        g = p.bc * r.D / T
        hist = g * mem["delta"]
        for i in range(r.order):
            hist = hist - (p.bc * r.C[i]) * mem[f"vf{i}"]
        return p.kc + g, hist

    def filter_memory(self, p: SimpleNamespace, delta: Any, mem: dict, new: dict) -> None:
        _filter_update(p, (delta - mem["delta"]) / p.T, mem, new)


class FilteredAdmittanceLoop(_Filtered, AdmittanceLoop):
    """Admittance display whose PD derivative term is ``k_d V(z) e`` (module docstring)."""

    def __init__(self, velocity_filter: VelocityFilter) -> None:
        self.velocity_filter = velocity_filter

    def position_loop(self, p: SimpleNamespace, y: Any, mem: dict, new: dict, xc: Any, fe: Any) -> StepResult:
        """Eq. (30) with the filtered derivative: ``F_d = k_p e + k_d V(z) e``."""
        e = y - xc
        d = (e - (mem["yp"] - mem["xc"])) / p.T
        u = p.kp * e + p.kd * _filter_output(p, d, mem)
        _filter_update(p, d, mem, new)
        new["yp"], new["xc"] = y, xc
        return u, new, fe, xc


def filtered_loop(display: str | DisplayLoop, velocity_filter: VelocityFilter | None) -> DisplayLoop:
    """The loop of ``display`` with ``velocity_filter``; the plain loop for ``None``/backward."""
    base = display_loop(display)
    if velocity_filter is None or velocity_filter.is_backward:
        return base
    if isinstance(base, ImpedanceLoop):
        return FilteredImpedanceLoop(velocity_filter)
    return FilteredAdmittanceLoop(velocity_filter)
