"""Side-by-side runs: a too-stiff wall with and without passivity control, and behind a coupling.

Issue 15 compares the two ways of rendering a wall stiffer than the exact critical k_c of the
hands-off, god-object-wall loop (:func:`~analysis.sampled.sweeps.critical_stiffness`):

* ``"wall"``: the wall ``K + B V(z)`` rendered directly (the impedance display's coupling *is*
  the wall, against the god-object constraint), without passivity control -- it diverges once
  the hand lets go, since ``K > k_c``;
* ``"wall + PC"``: the same with Hannaford & Ryu's passivity observer and controller
  (:mod:`analysis.sampled.actuation`), which adds damping whenever the observed energy would go
  negative -- stable at the price of force spikes;
* ``"coupled wall"``: the same wall as a penalty wall ``k_obj = K, b_obj = B`` behind the virtual
  coupling designed by eq. (9) (``coupling``; the sampled layer may not import the two-port
  layer, so pass e.g. ``(ImpedanceDisplay(device).max_stiffness(b_c).kc, b_c)``).

Each run is the loop of the exact analysis in contact: no grasp impedance (hands-off) and a
constant push ``push_force`` holding the handle against the wall, from 0.1 mm in front of it --
so the linearization in contact is exactly the loop whose critical stiffness is ``k_c`` (a
released handle would bounce off a unilateral wall and come to rest in free space).  :class:`ComparisonRun` reports the verdict, the peak force, the
largest sample-to-sample force jump and the number of spikes (jumps above ``spike_fraction`` of
the peak force), the penetration (largest encoder reading past the wall) and the energy traces.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.device import Device
from analysis.chain.velocity_filter import VelocityFilter
from analysis.sampled.results import SimulationResult
from analysis.sampled.scenarios import Scenario, SimulationOptions
from analysis.sampled.simulator import simulate
from analysis.sampled.sweeps import critical_stiffness
from analysis.sampled.terminations import HANDS_OFF

__all__ = ["ComparisonRun", "PassivityComparison", "passivity_comparison", "run_metrics"]


@dataclass(frozen=True)
class ComparisonRun:
    """One run of the comparison and its numbers (module docstring); energies in J, force in N.

    Parameters
    ----------
    name : str
        ``"wall"``, ``"wall + PC"`` or ``"coupled wall"``.
    result : SimulationResult
        The simulation.
    verdict : str
        The verdict's kind (:class:`~analysis.sampled.results.Verdict`).
    peak_force : float
        Largest ``|F_d|`` [N] (NaN samples ignored).
    max_jump : float
        Largest sample-to-sample jump of ``F_d`` [N].
    spikes : int
        Jumps above ``spike_fraction`` of the peak force.
    penetration : float
        Largest encoder reading past the wall [m], at least 0.
    final_energy : float
        Last finite energy absorbed by the digital side (``SimulationResult.energy``) [J]; NaN
        when no sample is finite.
    min_observed_energy : float
        Least finite energy from encoder readings (``SimulationResult.energy_observed``) [J];
        NaN when no sample is finite.
    """

    name: str
    result: SimulationResult
    verdict: str
    peak_force: float
    max_jump: float
    spikes: int
    penetration: float
    final_energy: float
    min_observed_energy: float


@dataclass(frozen=True)
class PassivityComparison:
    """The runs, the wall ``(K, B)``, the exact critical stiffness ``k_critical`` and the coupling.

    Parameters
    ----------
    runs : tuple of ComparisonRun
        ``"wall"``, ``"wall + PC"`` and ``"coupled wall"``, in this order.
    wall : tuple of (float, float)
        The wall's ``(K [N/m], B [N s/m])``.
    k_critical : float
        Exact critical stiffness ``k_c`` [N/m] of the hands-off god-object-wall loop.
    coupling : tuple of (float, float)
        The coupled wall's ``(k_c [N/m], b_c [N s/m])``.
    """

    runs: tuple[ComparisonRun, ...]
    wall: tuple[float, float]
    k_critical: float
    coupling: tuple[float, float]

    def run(self, name: str) -> ComparisonRun:
        """The run of a name.

        Parameters
        ----------
        name : str
            ``"wall"``, ``"wall + PC"`` or ``"coupled wall"``.

        Returns
        -------
        ComparisonRun
            The run (``StopIteration`` for an unknown name).
        """
        return next(r for r in self.runs if r.name == name)


def run_metrics(name: str, r: SimulationResult, wall_position: float = 0.0,
                spike_fraction: float = 0.25) -> ComparisonRun:
    """The numbers of one run (module docstring); NaN samples (a diverged run) are ignored."""
    f = np.nan_to_num(r.f_d, nan=0.0, posinf=0.0, neginf=0.0)
    peak = float(np.max(np.abs(f))) if f.size else 0.0
    jumps = np.abs(np.diff(f))
    pen = np.nan_to_num(r.encoder - wall_position, nan=0.0, posinf=0.0, neginf=0.0)
    e = r.energy[np.isfinite(r.energy)]
    eo = r.energy_observed[np.isfinite(r.energy_observed)]
    return ComparisonRun(name=name, result=r, verdict=r.verdict.kind, peak_force=peak,
                         max_jump=float(jumps.max()) if jumps.size else 0.0,
                         spikes=int(np.count_nonzero(jumps > spike_fraction * peak)) if peak > 0 else 0,
                         penetration=float(max(pen.max(), 0.0)), final_energy=float(e[-1]) if e.size else math.nan,
                         min_observed_energy=float(eo.min()) if eo.size else math.nan)


def passivity_comparison(device: Device, b: float = 10.0, factor: float = 1.5,
                         coupling: tuple[float, float] = (50e3, 100.0), *, delay_samples: int = 0,
                         velocity_filter: VelocityFilter | None = None, push_force: float = 10.0,
                         duration: float = 1.0,
                         options: SimulationOptions | None = None) -> PassivityComparison:
    """The three runs of the module docstring for the wall ``K = factor k_c(b)``, damping ``b``.

    Parameters
    ----------
    device : Device
        The device.
    b : float, optional
        The wall's damping ``B`` [N s/m]; ``k_c(b)`` is the critical stiffness with it.
    factor : float, optional
        The wall stiffness as a multiple of ``k_c(b)``.
    coupling : tuple of (float, float), optional
        ``(k_c [N/m], b_c [N s/m])`` of the coupled wall, e.g. designed by eq. (9).
    delay_samples : int, optional
        Computation delay in samples (critical stiffness and simulations).
    velocity_filter : VelocityFilter or None, optional
        Filter of the damping term's velocity estimate; ``None`` for the backward difference.
    push_force : float, optional
        Constant push holding the handle against the wall [N].
    duration : float, optional
        Simulated time of each run [s].
    options : SimulationOptions or None, optional
        Simulator options (``delay_samples`` replaced; passivity control set on the second run).

    Returns
    -------
    PassivityComparison
        The three runs, the wall and ``k_c(b)``.
    """
    kcrit = critical_stiffness(device, b, delay_samples, velocity_filter=velocity_filter)
    K = factor * kcrit
    base = dataclasses.replace(options or SimulationOptions(), delay_samples=delay_samples)
    god = Scenario(name="wall", causality="admittance", wall=True, grasp=HANDS_OFF, push_force=push_force,
                   initial_position=-1e-4, duration=duration)
    pen = god.replace(name="coupled wall", causality="impedance", wall_stiffness=K, wall_damping=b)
    runs = []
    for name, sc, opt, cpl in (
            ("wall", god, base, (K, b)),
            ("wall + PC", god, dataclasses.replace(base, passivity_control=True), (K, b)),
            ("coupled wall", pen, base, coupling)):
        r = simulate(device, sc, display="impedance", coupling=cpl, options=opt, velocity_filter=velocity_filter)
        runs.append(run_metrics(name, r))
    return PassivityComparison(runs=tuple(runs), wall=(K, b), k_critical=kcrit, coupling=tuple(coupling))
