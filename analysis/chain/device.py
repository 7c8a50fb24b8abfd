"""The lumped-mass device chain of Adams, Moreyra & Hannaford, eq. (25)-(28).

Masses ``m[0] .. m[n-1]`` sit in a chain.  Element ``i`` (spring ``k[i]``, damper ``b[i]``)
joins mass ``i`` and mass ``i+1``.  Mass ``i`` may also have a damper ``g[i]`` to ground
(the paper's rigid-body damping ``b4`` is ``g[n-1]``).  The human grasps mass 0 (force
``F_h``); the actuator drives mass ``n-1`` with ``-F_d`` (eq. 25).  The outputs are
``v_h = x0'`` and ``-v_d = -x_{n-1}'`` (eq. 26).

The force gauge sits on element ``sensor_element`` (default 0, the element next to the
handle) and measures ``F_meas = k_s (x_s - x_{s+1}) + b_s (x_s' - x_{s+1}')``, the reading of
eq. (27) fixed by the design notes (positive and equal to ``F_h`` at DC).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg

from analysis.chain.limits import BAND_MIN, DAMPING, GROUND_DAMPING, MASS, MAX_MASSES, SAMPLE_TIME, STIFFNESS
from analysis.checks import check_elements, integer, real, vector
from analysis.errors import ValidationError

__all__ = ["Device", "damping_from_ratio", "ratio_from_damping"]


def damping_from_ratio(stiffness: float, mass_a: float, mass_b: float, ratio: float) -> float:
    """Element damping from a damping ratio, eq. (28) with the reduced mass.

    ``b = 2 * ratio * sqrt(k * mu)`` with ``mu = m_a m_b / (m_a + m_b)``.

    Parameters
    ----------
    stiffness : float
        Element stiffness ``k`` [N/m].
    mass_a, mass_b : float
        The two masses the element joins [kg].
    ratio : float
        Damping ratio (dimensionless).

    Returns
    -------
    float
        Element damping ``b`` [N s/m].
    """
    mu = mass_a * mass_b / (mass_a + mass_b)
    return 2.0 * ratio * math.sqrt(stiffness * mu)


def ratio_from_damping(stiffness: float, mass_a: float, mass_b: float, damping: float) -> float:
    """Inverse of :func:`damping_from_ratio`.

    ``ratio = b / (2 sqrt(k mu))`` with ``mu = m_a m_b / (m_a + m_b)`` (eq. 28).

    Parameters
    ----------
    stiffness : float
        Element stiffness ``k`` [N/m].
    mass_a, mass_b : float
        The two masses the element joins [kg].
    damping : float
        Element damping ``b`` [N s/m].

    Returns
    -------
    float
        Damping ratio (dimensionless).
    """
    mu = mass_a * mass_b / (mass_a + mass_b)
    return damping / (2.0 * math.sqrt(stiffness * mu))




@dataclass(frozen=True, eq=False)
class Device:
    """A validated lumped-mass chain with its sample period (eq. 25, 28).

    Every value must lie in its physical range (:mod:`analysis.chain.limits`: masses 1 mg .. 1 t,
    T 1 µs .. 1 s, ...); a value outside is refused with a ValidationError naming the range.

    Parameters
    ----------
    masses:
        ``n >= 1`` masses in kg, handle first, actuator last.
    stiffnesses, dampings:
        ``n - 1`` element stiffnesses (N/m) and dampings (N s/m); element ``i`` joins mass
        ``i`` and ``i + 1``.
    ground_dampings:
        ``n`` dampers from each mass to ground (N s/m); default all zero.
    sensor_element:
        Element carrying the force gauge (0 = next to the handle).
    sample_time:
        Sample period ``T`` in s.
    band_min:
        Lower edge of the analysis band in rad/s; the band is ``[band_min, pi/T)``.
    """

    masses: np.ndarray
    stiffnesses: np.ndarray = field(default_factory=lambda: np.zeros(0))
    dampings: np.ndarray = field(default_factory=lambda: np.zeros(0))
    ground_dampings: np.ndarray | None = None
    sensor_element: int = 0
    sample_time: float = 1e-3
    band_min: float = 1.0

    def __post_init__(self) -> None:
        m = vector("masses", self.masses, None)
        n = m.size
        if n < 1:
            raise ValidationError("masses", "at least one mass", [])
        if n > MAX_MASSES:
            raise ValidationError("masses", f"at most {MAX_MASSES} masses (the longest tested chain)", n)
        k = vector("stiffnesses", self.stiffnesses, n - 1)
        b = vector("dampings", self.dampings, n - 1)
        g = vector("ground_dampings", np.zeros(n) if self.ground_dampings is None else self.ground_dampings, n)
        check_elements("masses", m, MASS.rule)
        check_elements("stiffnesses", k, STIFFNESS.rule)
        check_elements("dampings", b, DAMPING.rule)
        check_elements("ground_dampings", g, GROUND_DAMPING.rule)
        T = SAMPLE_TIME("sample_time", self.sample_time)
        s = integer("sensor_element", self.sensor_element, 0, max(n - 2, 0))
        nyq = math.pi / T
        wmin = real("band_min", self.band_min, lo=BAND_MIN.lo, hi=nyq, hi_open=True,
                    allowed=f"> 0 and < Nyquist = {nyq:.6g} rad/s, within the physical range "
                            f"[{BAND_MIN.lo:g}, {nyq:.6g}) (rad/s)")
        object.__setattr__(self, "masses", m)
        object.__setattr__(self, "stiffnesses", k)
        object.__setattr__(self, "dampings", b)
        object.__setattr__(self, "ground_dampings", g)
        object.__setattr__(self, "sample_time", float(T))
        object.__setattr__(self, "sensor_element", int(s))
        object.__setattr__(self, "band_min", float(wmin))

    # -- identity -----------------------------------------------------------------
    def key(self) -> tuple:
        """A hashable key of every parameter (used for caching).

        Returns
        -------
        tuple
            The bytes of the four arrays, then ``sensor_element``, ``sample_time`` and
            ``band_min``; equal keys mean equal devices.
        """
        return (
            self.masses.tobytes(),
            self.stiffnesses.tobytes(),
            self.dampings.tobytes(),
            self.ground_dampings.tobytes(),
            self.sensor_element,
            self.sample_time,
            self.band_min,
        )

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Device) and self.key() == other.key()

    def __hash__(self) -> int:
        return hash(self.key())

    # -- derived quantities --------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of masses."""
        return int(self.masses.size)

    @property
    def nyquist(self) -> float:
        """Nyquist frequency pi/T in rad/s."""
        return math.pi / self.sample_time

    @property
    def total_mass(self) -> float:
        return float(self.masses.sum())

    @property
    def total_ground_damping(self) -> float:
        return float(self.ground_dampings.sum())

    @property
    def static_compliance(self) -> float:
        """Series compliance of the chain springs, sum 1/k_i (m/N)."""
        return float(np.sum(1.0 / self.stiffnesses)) if self.n > 1 else 0.0

    @property
    def damping_ratios(self) -> np.ndarray:
        """Damping ratio of each element by eq. (28) with the reduced mass."""
        m = self.masses
        mu = m[:-1] * m[1:] / (m[:-1] + m[1:])
        return self.dampings / (2.0 * np.sqrt(self.stiffnesses * mu))

    def replace(self, **changes) -> Device:
        """A copy with some parameters changed (validated again).

        Parameters
        ----------
        **changes
            New values of constructor parameters, by name (``masses``, ``sample_time``, ...).

        Returns
        -------
        Device
            The new device.

        Raises
        ------
        ValidationError
            When a changed value is outside its physical range or the shapes disagree.
        """
        data = dict(
            masses=self.masses,
            stiffnesses=self.stiffnesses,
            dampings=self.dampings,
            ground_dampings=self.ground_dampings,
            sensor_element=self.sensor_element,
            sample_time=self.sample_time,
            band_min=self.band_min,
        )
        data.update(changes)
        return Device(**data)

    @classmethod
    def from_damping_ratios(
        cls,
        masses,
        stiffnesses,
        ratios,
        ground_dampings=None,
        **kwargs,
    ) -> Device:
        """Build a chain whose element dampings follow eq. (28) from damping ratios.

        Parameters
        ----------
        masses : array_like
            ``n`` masses [kg], handle first.
        stiffnesses : array_like
            ``n - 1`` element stiffnesses [N/m].
        ratios : array_like
            Element damping ratios (dimensionless): one per element, or one for all.
        ground_dampings : array_like or None, optional
            ``n`` dampers to ground [N s/m]; ``None`` for none.
        **kwargs
            Further :class:`Device` parameters (``sensor_element``, ``sample_time``,
            ``band_min``).

        Returns
        -------
        Device
            The chain with dampings ``b_i = 2 r_i sqrt(k_i mu_i)``.

        Raises
        ------
        ValidationError
            When a value is outside its physical range.
        """
        m = np.asarray(masses, dtype=float).reshape(-1)
        k = np.asarray(stiffnesses, dtype=float).reshape(-1)
        r = np.broadcast_to(np.asarray(ratios, dtype=float), k.shape)
        mu = m[:-1] * m[1:] / (m[:-1] + m[1:]) if m.size > 1 else np.zeros(0)
        b = 2.0 * r * np.sqrt(k * mu)
        return cls(masses=m, stiffnesses=k, dampings=b, ground_dampings=ground_dampings, **kwargs)

    # -- matrices (eq. 25) ---------------------------------------------------------
    def matrices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Mass, damping and stiffness matrices of eq. (25).

        Returns
        -------
        M, B, K : numpy.ndarray
            Mass [kg], damping [N s/m] and stiffness [N/m] matrices, each of shape (n, n);
            ``B`` includes the dampers to ground.
        """
        n = self.n
        M = np.diag(self.masses)
        B = np.diag(self.ground_dampings.copy())
        K = np.zeros((n, n))
        for i in range(n - 1):
            for mat, val in ((B, self.dampings[i]), (K, self.stiffnesses[i])):
                mat[i, i] += val
                mat[i + 1, i + 1] += val
                mat[i, i + 1] -= val
                mat[i + 1, i] -= val
        return M, B, K

    def undamped_modes(self, extra_stiffness: dict[int, float] | None = None, clamp: tuple[int, ...] = ()) -> np.ndarray:
        """Undamped natural frequencies (rad/s) of the chain.

        ``extra_stiffness`` adds springs to ground at given nodes; ``clamp`` removes nodes
        (held fixed).  Rigid-body (zero) modes are dropped.  Used to place frequency grid
        points on resonances and antiresonances.

        Parameters
        ----------
        extra_stiffness : dict of int to float or None, optional
            Springs to ground [N/m] by node index.
        clamp : tuple of int, optional
            Indices of the nodes held fixed.

        Returns
        -------
        numpy.ndarray
            The nonzero undamped natural frequencies [rad/s], ascending, shape (m,) with
            ``m <= n``; empty when every node is clamped.
        """
        M, _, K = self.matrices()
        K = K.copy()
        for node, kval in (extra_stiffness or {}).items():
            K[node, node] += kval
        keep = [i for i in range(self.n) if i not in clamp]
        if not keep:
            return np.zeros(0)
        Mk = M[np.ix_(keep, keep)]
        Kk = K[np.ix_(keep, keep)]
        ev = linalg.eigh(Kk, Mk, eigvals_only=True)
        scale = max(float(np.max(np.abs(ev))), 1e-300)
        ev = ev[ev > 1e-10 * scale]
        return np.sqrt(ev)
