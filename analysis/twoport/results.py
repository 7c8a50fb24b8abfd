"""Result objects: frozen dataclasses of numpy arrays and floats (nothing here draws)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.progress import Cancelled, Progress  # the one protocol, re-exported here (issue 21)

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
    """A 2x2 immittance array sampled at frequencies ``w`` (rad/s).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    p11, p12, p21, p22 : numpy.ndarray
        The four entries at ``w``, complex, shape (N,); their units follow the form (Y(z) of
        eq. 2 for the impedance display, G(z) of eq. 14 for the admittance display).
    """

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

    All arrays have shape (N,).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s].
    bound : numpy.ndarray
        The bound: on ``Re(1/Z_c)`` [m/(N s)] (impedance display, eq. 9) or on ``Re(Z_cA)``
        [N s/m] (admittance display, eq. 21).
    p11 : numpy.ndarray
        The two-port's ``p11`` (``Y11`` or ``G11``), complex.
    re_p11 : numpy.ndarray
        Its real part, computed without cancellation.
    abs_p : numpy.ndarray
        ``|p12 p21|``.
    re_p : numpy.ndarray
        ``Re(p12 p21)``.
    singular : numpy.ndarray
        Booleans: ``Re p11 = 0`` exactly, or an exact pole (the bound is then infinite).
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

    The arrays have shape (N,), one value per frequency of ``w``.  The coupling term, bound
    and margin are in m/(N s) for the impedance display and N s/m for the admittance display.

    Parameters
    ----------
    display : str
        ``"impedance"`` or ``"admittance"``.
    w : numpy.ndarray
        Angular frequencies [rad/s].
    bound : numpy.ndarray
        Right-hand side of eq. (9) or (21).
    coupling_term : numpy.ndarray
        ``Re(1/Z_c)`` or ``Re(Z_cA)``.
    margin : numpy.ndarray
        ``coupling_term - bound`` (>= 0 everywhere means unconditionally stable).
    eta : numpy.ndarray
        Llewellyn's factor of the coupled interface (dimensionless).
    zmin, zmax : numpy.ndarray
        The impedance range of eq. (11)-(12) or (22) [N s/m], complex.
    singular : numpy.ndarray
        Booleans: frequencies where the bound is infinite (lossless device, exact poles).
    worst_margin : float
        The smallest margin over the band (after refinement).
    worst_frequency : float
        Where it occurs [rad/s].
    min_eta : float
        The smallest finite ``eta`` on the grid (``inf`` if none is finite).
    stable : bool
        ``worst_margin >= 0``.
    k_max : float
        Low-frequency stiffness of Z_max [N/m].
    b_min : float
        Low-frequency damping of Z_min [N s/m].
    apparent_mass : float
        Free-motion mass read off Z_min at :data:`~analysis.twoport.APPARENT_FREQUENCY` [kg].
    apparent_damping : float
        Free-motion damping read there [N s/m].
    relative_margin : float, optional
        The smallest ``margin / coupling_term`` (at most 1; dimensionless), after refinement.
    binding_frequency : float, optional
        Where the relative margin is smallest [rad/s].
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

    Parameters
    ----------
    bc : float
        Coupling damping b_c [N s/m].
    kc : float or None
        Largest coupling stiffness k_c [N/m], ``None`` or ``inf`` as above.
    frequency : float
        Where the bound binds [rad/s] (NaN when every k_c works).
    margin : float
        Worst margin of eq. (9) at ``kc`` [m/(N s)].
    evaluations : int
        Frequencies at which the bound was evaluated for this design.
    """

    bc: float
    kc: float | None
    frequency: float
    margin: float
    evaluations: int


@dataclass(frozen=True)
class StiffnessChart:
    """Largest k_c against b_c (design chart of the impedance display).

    Parameters
    ----------
    bc : numpy.ndarray
        Coupling dampings b_c [N s/m], shape (M,).
    kc : numpy.ndarray
        Largest k_c for each [N/m], shape (M,); NaN where infeasible.
    frequency : numpy.ndarray
        Where the bound binds for each [rad/s], shape (M,).
    """

    bc: np.ndarray
    kc: np.ndarray  # NaN where infeasible
    frequency: np.ndarray


@dataclass(frozen=True)
class DampingInterval:
    """Feasible coupling damping interval [low, high] for a given m_c (eq. 21).

    ``low``/``high`` are ``None`` when no b_c works; ``high`` may be ``inf``.
    ``low_frequency`` and ``high_frequency`` are where each edge binds.

    Parameters
    ----------
    mc : float
        Coupling mass m_c [kg].
    low : float or None
        Smallest feasible b_c [N s/m].
    high : float or None
        Largest feasible b_c [N s/m] (may be ``inf``).
    low_frequency : float
        Where the lower edge binds [rad/s].
    high_frequency : float
        Where the upper edge binds [rad/s].
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
    """Smallest coupling mass m_c for which some b_c satisfies eq. (21).

    Parameters
    ----------
    mc : float
        Smallest coupling mass m_c [kg].
    bc : float
        A coupling damping b_c that works at ``mc`` [N s/m].
    frequency : float
        Where the bound binds [rad/s].
    interval : DampingInterval
        The feasible b_c interval at ``mc``.
    """

    mc: float
    bc: float
    frequency: float
    interval: DampingInterval


@dataclass(frozen=True)
class MassChart:
    """Feasible b_c interval against m_c (design chart of the admittance display).

    Parameters
    ----------
    mc : numpy.ndarray
        Coupling masses m_c [kg], shape (M,).
    low : numpy.ndarray
        Smallest feasible b_c for each [N s/m], shape (M,); NaN where infeasible.
    high : numpy.ndarray
        Largest feasible b_c for each [N s/m], shape (M,); NaN where infeasible, inf where
        unbounded.
    """

    mc: np.ndarray
    low: np.ndarray  # NaN where infeasible
    high: np.ndarray  # NaN where infeasible, inf where unbounded
