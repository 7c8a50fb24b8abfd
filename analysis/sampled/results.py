"""Result objects of the sampled-data analysis and the simulator (frozen, numpy arrays)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.sampled.loop import is_stable
from analysis.sampled.terminations import Termination

__all__ = ["WorstCase", "CriticalChart", "CriticalMassChart", "StabilityMap", "Verdict", "SimulationResult"]


@dataclass(frozen=True)
class WorstCase:
    """Worst spectral radius over a sweep of terminations and the termination attaining it.

    ``radii[i]`` belongs to ``terminations[i]``; ``stable`` is
    :func:`~analysis.sampled.loop.is_stable` of ``spectral_radius`` (at most 1 up to the
    stability tolerance; rigid-body modes at z = 1 count as 1, see
    :func:`analysis.sampled.loop.spectral_radius`).
    """

    spectral_radius: float
    termination: Termination
    index: int
    stable: bool
    radii: np.ndarray
    terminations: tuple[Termination, ...]


@dataclass(frozen=True)
class CriticalChart:
    """Exact largest stable k_c against b_c (impedance display), to overlay on the design chart.

    ``kc`` is ``inf`` where no k_c up to the scan limit is unstable and ``0`` where the
    smallest scanned k_c is already unstable.
    """

    bc: np.ndarray
    kc: np.ndarray
    delay_samples: int


@dataclass(frozen=True)
class CriticalMassChart:
    """Exact smallest stable m_c against b_c (admittance display).

    ``mc`` is ``0`` where every scanned m_c is stable and ``inf`` where none is.
    """

    bc: np.ndarray
    mc: np.ndarray
    delay_samples: int


@dataclass(frozen=True)
class StabilityMap:
    """Spectral radius over a grid of two parameters: ``spectral_radius[j, i]`` at ``(x[i], y[j])``."""

    x_name: str
    x: np.ndarray
    y_name: str
    y: np.ndarray
    spectral_radius: np.ndarray

    @property
    def stable(self) -> np.ndarray:
        """Where the loop is stable (:func:`~analysis.sampled.loop.is_stable`)."""
        return np.asarray(is_stable(self.spectral_radius))


@dataclass(frozen=True)
class Verdict:
    """The detector's verdict on a simulation and the numbers it was based on.

    ``kind`` is ``"stable"``, ``"sustained oscillation"`` or ``"divergent"``; ``amplitude``
    the RMS of the detrended actuator position in the last two windows (m), ``threshold`` the
    amplitude below which motion counts as at rest.
    """

    kind: str
    amplitude_previous: float
    amplitude_last: float
    threshold: float
    reason: str


@dataclass(frozen=True)
class SimulationResult:
    """Time series at the sample instants ``t`` (s) of a simulation.

    ``positions``/``velocities`` (K, n) of the masses; ``encoder`` the (quantized) encoder
    reading; ``f_meas`` the (quantized) gauge reading; ``f_h`` the force of the human on the
    handle; ``f_d`` the actuator force held from each sample (after delay and saturation);
    ``f_e`` the environment force; ``x_e`` the environment object (or x_com) position.
    ``energy`` is the energy absorbed by the digital side through the actuator port,
    ``sum F_d (x_n[k+1] - x_n[k])`` (exact for a held force; negative means the display
    generated energy); ``energy_observed`` is the same with encoder readings (what a
    passivity observer on the hardware would compute); ``energy_human`` the work of the human
    on the handle (trapezoidal).  With the passivity observer on
    (:class:`~analysis.sampled.scenarios.SimulationOptions`), ``passivity_energy`` is the
    observer's energy after each sample's update (equal to ``energy_observed``) and
    ``pc_damping`` the controller's added damping ``alpha`` (N s/m; zeros without control);
    both are ``None`` otherwise (see :mod:`analysis.sampled.actuation`).
    """

    t: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    encoder: np.ndarray
    f_meas: np.ndarray
    f_h: np.ndarray
    f_d: np.ndarray
    f_e: np.ndarray
    x_e: np.ndarray
    energy: np.ndarray
    energy_observed: np.ndarray
    energy_human: np.ndarray
    contact: np.ndarray
    verdict: Verdict
    substeps: int
    events: int
    passivity_energy: np.ndarray | None = None
    pc_damping: np.ndarray | None = None

    @property
    def handle_position(self) -> np.ndarray:
        return self.positions[:, 0]

    @property
    def actuator_position(self) -> np.ndarray:
        return self.positions[:, -1]
