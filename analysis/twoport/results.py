"""Result objects: frozen dataclasses of numpy arrays and floats (nothing here draws)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: ``progress(done, total)``: called by long computations after each step
Progress = Callable[[int, int], None]
#: ``cancelled() -> bool``: polled by long computations between steps; true stops them
Cancelled = Callable[[], bool]

__all__ = [
    "Progress",
    "Cancelled",
    "TwoPort",
    "BoundResult",
    "StabilityResult",
    "StiffnessDesign",
    "StiffnessChart",
    "DampingInterval",
    "MassDesign",
    "MassChart",
]


@dataclass(frozen=True)
class TwoPort:
    """A 2x2 immittance array sampled at frequencies ``w`` (rad/s)."""

    w: np.ndarray
    p11: np.ndarray
    p12: np.ndarray
    p21: np.ndarray
    p22: np.ndarray


@dataclass(frozen=True)
class BoundResult:
    """Right-hand side of eq. (9) or (21) with the pieces that define it.

    ``singular`` marks frequencies where ``Re p11 = 0`` exactly (lossless device): there the
    bound is ``+inf`` (or ``-inf``) instead of NaN.
    """

    w: np.ndarray
    bound: np.ndarray
    p11: np.ndarray
    re_p11: np.ndarray
    abs_p: np.ndarray
    re_p: np.ndarray
    singular: np.ndarray


@dataclass(frozen=True)
class StabilityResult:
    """Everything the stability and impedance-range views show for one design.

    ``coupling_term`` is Re(1/Z_c) (impedance display, eq. 9) or Re(Z_cA) (admittance
    display, eq. 21); ``margin = coupling_term - bound``; ``eta`` is Llewellyn's factor of
    the coupled interface (>= 1 where unconditionally stable).  ``worst_*`` come from the
    grid plus local refinement, so they are not limited by the grid spacing.
    """

    display: str
    w: np.ndarray
    bound: np.ndarray
    coupling_term: np.ndarray
    margin: np.ndarray
    eta: np.ndarray
    zmin: np.ndarray
    zmax: np.ndarray
    singular: np.ndarray
    worst_margin: float
    worst_frequency: float
    min_eta: float
    stable: bool
    k_max: float
    b_min: float
    apparent_mass: float
    apparent_damping: float
    relative_margin: float = float("nan")
    binding_frequency: float = float("nan")


@dataclass(frozen=True)
class StiffnessDesign:
    """Largest coupling stiffness k_c that satisfies eq. (9) for a given b_c.

    ``kc`` is ``None`` when no k_c >= 0 works (b_c too large), ``inf`` when every k_c
    works.  ``frequency`` is where the bound binds; ``margin`` the worst margin at ``kc``.
    """

    bc: float
    kc: float | None
    frequency: float
    margin: float
    evaluations: int


@dataclass(frozen=True)
class StiffnessChart:
    """Largest k_c against b_c (design chart of the impedance display)."""

    bc: np.ndarray
    kc: np.ndarray  # NaN where infeasible
    frequency: np.ndarray


@dataclass(frozen=True)
class DampingInterval:
    """Feasible coupling damping interval [low, high] for a given m_c (eq. 21).

    ``low``/``high`` are ``None`` when no b_c works; ``high`` may be ``inf``.
    ``low_frequency`` and ``high_frequency`` are where each edge binds.
    """

    mc: float
    low: float | None
    high: float | None
    low_frequency: float
    high_frequency: float

    @property
    def feasible(self) -> bool:
        return self.low is not None


@dataclass(frozen=True)
class MassDesign:
    """Smallest coupling mass m_c for which some b_c satisfies eq. (21)."""

    mc: float
    bc: float
    frequency: float
    interval: DampingInterval


@dataclass(frozen=True)
class MassChart:
    """Feasible b_c interval against m_c (design chart of the admittance display)."""

    mc: np.ndarray
    low: np.ndarray  # NaN where infeasible
    high: np.ndarray  # NaN where infeasible, inf where unbounded
