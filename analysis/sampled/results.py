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

    Parameters
    ----------
    spectral_radius : float
        The worst (largest) spectral radius.
    termination : Termination
        The termination attaining it.
    index : int
        Its index in ``terminations``.
    stable : bool
        Whether the worst case, hence every termination, is stable.
    radii : numpy.ndarray
        Spectral radius of each termination, shape (M,).
    terminations : tuple of Termination
        The M terminations of the sweep.
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

    Parameters
    ----------
    bc : numpy.ndarray
        Coupling dampings b_c [N s/m], shape (N,).
    kc : numpy.ndarray
        Largest stable coupling stiffness k_c [N/m] at each b_c, shape (N,).
    delay_samples : int
        Computation delay in samples.
    """

    bc: np.ndarray
    kc: np.ndarray
    delay_samples: int


@dataclass(frozen=True)
class CriticalMassChart:
    """Exact smallest stable m_c against b_c (admittance display).

    ``mc`` is ``0`` where every scanned m_c is stable and ``inf`` where none is.

    Parameters
    ----------
    bc : numpy.ndarray
        Coupling dampings b_c [N s/m], shape (N,).
    mc : numpy.ndarray
        Smallest stable coupling mass m_c [kg] at each b_c, shape (N,).
    delay_samples : int
        Computation delay in samples.
    """

    bc: np.ndarray
    mc: np.ndarray
    delay_samples: int


@dataclass(frozen=True)
class StabilityMap:
    """Spectral radius over a grid of two parameters: ``spectral_radius[j, i]`` at ``(x[i], y[j])``.

    Parameters
    ----------
    x_name : str
        The parameter along ``x`` (a key of :data:`~analysis.sampled.sweeps.MAP_PARAMETERS`).
    x : numpy.ndarray
        Its values, shape (NX,), in its unit.
    y_name : str
        The parameter along ``y``.
    y : numpy.ndarray
        Its values, shape (NY,).
    spectral_radius : numpy.ndarray
        Spectral radii, shape (NY, NX).
    """

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

    Parameters
    ----------
    kind : str
        ``"stable"``, ``"sustained oscillation"`` or ``"divergent"``.
    amplitude_previous : float
        RMS of the detrended actuator position in the second-last window [m] (NaN for a
        non-finite run).
    amplitude_last : float
        The same in the last window [m].
    threshold : float
        Rest threshold [m]: ``max(2 encoder counts, 1 um)``.
    reason : str
        Why, in words.
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

    Parameters
    ----------
    t : numpy.ndarray
        Sample instants [s], shape (K,).
    positions : numpy.ndarray
        Positions of the n masses [m], shape (K, n); handle first, actuator last.
    velocities : numpy.ndarray
        Velocities of the masses [m/s], shape (K, n).
    encoder : numpy.ndarray
        Encoder reading [m], shape (K,).
    f_meas : numpy.ndarray
        Force-gauge reading [N], shape (K,).
    f_h : numpy.ndarray
        Force of the human on the handle [N], shape (K,).
    f_d : numpy.ndarray
        Actuator force held from each sample [N], shape (K,).
    f_e : numpy.ndarray
        Environment force [N], shape (K,).
    x_e : numpy.ndarray
        Environment object (or x_com) position [m], shape (K,).
    energy : numpy.ndarray
        Energy absorbed by the digital side through the actuator port [J], cumulative, shape (K,).
    energy_observed : numpy.ndarray
        The same from encoder readings [J], shape (K,).
    energy_human : numpy.ndarray
        Work of the human on the handle [J], cumulative, shape (K,).
    contact : numpy.ndarray
        Whether the environment is on the wall, bool, shape (K,).
    verdict : Verdict
        The detector's verdict (:func:`~analysis.sampled.simulator.detect`).
    substeps : int
        Sub-steps per sample (1 without friction).
    events : int
        Dyadic splits of sub-steps at friction regime changes.
    passivity_energy : numpy.ndarray or None, optional
        The passivity observer's energy [J], shape (K,); ``None`` without the observer.
    pc_damping : numpy.ndarray or None, optional
        The passivity controller's damping ``alpha`` [N s/m], shape (K,); ``None`` without the
        observer.

    Notes
    -----
    After a divergence with friction the signals are NaN.
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
