"""Disturbance observer of Eom, Suh & Yi, section 2 (Fig. 1, eq. 3-5), one and two axes.

Structure (Fig. 1, per axis): the plant input is ``u_p = u - d_hat`` and the observer estimates
``d_hat = Q (P_n^{-1} v - u_p)`` with the nominal plant ``P_n = 1/(M s + B)`` (``M``, ``B`` the
"bar" values of eq. 3) and ``Q = (w_Q/(s + w_Q))^r`` (binomial low-pass, ``r >= 1`` so that
``Q P_n^{-1}`` is proper).  With an input disturbance ``d`` (``v = P (u_p + d)``):

* effective plant ``v/u = P P_n / (P_n (1 - Q) + P Q)`` -> ``P_n`` where ``Q ~ 1``;
* disturbance to velocity ``v/d = (1 - Q) P P_n / (P_n (1 - Q) + P Q)`` (without observer: ``P``).

The real plant may differ from the nominal one: ``P~`` of eq. (13) (``alpha``, ``beta``,
``Delta``) or a device chain's handle admittance.

Two axes (eq. 2-5): ``v = (M_x s + B_x)^{-1} F`` with coupled 2x2 ``M_x``, ``B_x``; one observer
per axis with the nominal values measured with the other axis locked, i.e. the diagonal entries.
With ``Z = M_x s + B_x``, ``Z_n = diag(Z)`` and the same ``Q`` on both axes the effective plant is
``[(1 - Q) Z + Q Z_n]^{-1}``, so the cross-axis coupling ``v_y/F_x`` is divided by

    ``ratio = (1 - Q) det Z / (z11 z22 - (1 - Q)^2 z12 z21)``

(``~ r s / w_Q`` below ``w_Q``).  :meth:`TwoAxisObserver.coupling` evaluates the observer loop from
its state-space realization (not from this formula), and the tests compare the two.  The commanded
force ``u`` is the actuator force; the observer also rejects forces applied at the handle (``d``),
which is why the paper closes the wall loop around the observer-compensated device.
The observer is modelled in continuous time; time responses use the exact (matrix-exponential)
discretization of the whole loop for a step input.  Its settings record :class:`ObserverSettings`
(a profile section) lives in the light :mod:`analysis.transparency.settings` and is re-exported here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import linalg

from analysis.chain.continued_fraction import handle_admittance
from analysis.chain.device import Device
from analysis.checks import Real, frequencies, integer, positive
from analysis.errors import ValidationError
from analysis.transparency.five_bar import five_bar_preset
from analysis.transparency.settings import OBSERVER_PRESETS, ObserverSettings

__all__ = [
    "PRESETS",
    "ObserverSettings",
    "DisturbanceObserver",
    "ObserverResponse",
    "TwoAxisObserver",
    "CouplingResponse",
    "TwoAxisStep",
]

#: The two-axis devices an :class:`ObserverSettings` may name.
PRESETS = OBSERVER_PRESETS
_FORCE = Real(unit="N")
_DURATION = Real(lo=0.0, lo_open=True, hi=100.0, allowed="in (0, 100] s")


@dataclass(frozen=True)
class ObserverResponse:
    """Single-axis frequency responses at ``w`` (rad/s): the real plant ``plant``, the nominal
    ``nominal``, the ``effective`` plant through the observer, and disturbance-to-velocity with
    and without the observer.

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    plant : numpy.ndarray
        The real plant ``P(jw)`` [m/(N s)], complex, shape (N,).
    nominal : numpy.ndarray
        The nominal plant ``P_n(jw)`` [m/(N s)], complex, shape (N,).
    effective : numpy.ndarray
        The effective plant through the observer ``v/u`` [m/(N s)], complex, shape (N,).
    q : numpy.ndarray
        The low-pass ``Q(jw)`` (dimensionless), complex, shape (N,).
    disturbance_with : numpy.ndarray
        Disturbance to velocity ``v/d`` with the observer [m/(N s)], complex, shape (N,).
    disturbance_without : numpy.ndarray
        Disturbance to velocity without the observer (``P``) [m/(N s)], complex, shape (N,).
    """

    w: np.ndarray
    plant: np.ndarray
    nominal: np.ndarray
    effective: np.ndarray
    q: np.ndarray
    disturbance_with: np.ndarray
    disturbance_without: np.ndarray


@dataclass(frozen=True)
class CouplingResponse:
    """Two-axis responses at ``w``: ``v_y/F_x`` (coupling) and ``v_x/F_x`` (direct), without and
    with the observers; ``ratio = with/without`` and its closed form (module doc).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    coupling_without : numpy.ndarray
        ``v_y/F_x`` without the observers [m/(N s)], complex, shape (N,).
    coupling_with : numpy.ndarray
        ``v_y/F_x`` with the observers [m/(N s)], complex, shape (N,).
    direct_without : numpy.ndarray
        ``v_x/F_x`` without the observers [m/(N s)], complex, shape (N,).
    direct_with : numpy.ndarray
        ``v_x/F_x`` with the observers [m/(N s)], complex, shape (N,).
    ratio : numpy.ndarray
        ``coupling_with / coupling_without`` from the state space, complex, shape (N,).
    ratio_closed_form : numpy.ndarray
        The same ratio by the closed form of the module doc, complex, shape (N,).
    """

    w: np.ndarray
    coupling_without: np.ndarray
    coupling_with: np.ndarray
    direct_without: np.ndarray
    direct_with: np.ndarray
    ratio: np.ndarray
    ratio_closed_form: np.ndarray


@dataclass(frozen=True)
class TwoAxisStep:
    """Commanded force step on x (``force`` N at ``t = 0``): positions and velocities of both
    axes without and with the observers (exact discretization).

    Parameters
    ----------
    t : numpy.ndarray
        Times [s], equally spaced from 0, shape (N,).
    force : float
        The commanded force step on x [N].
    x_without : numpy.ndarray
        Position on x without the observers [m], shape (N,).
    y_without : numpy.ndarray
        Position on y without the observers [m], shape (N,).
    vy_without : numpy.ndarray
        Velocity on y without the observers [m/s], shape (N,).
    x_with : numpy.ndarray
        Position on x with the observers [m], shape (N,).
    y_with : numpy.ndarray
        Position on y with the observers [m], shape (N,).
    vy_with : numpy.ndarray
        Velocity on y with the observers [m/s], shape (N,).
    """

    t: np.ndarray
    force: float
    x_without: np.ndarray
    y_without: np.ndarray
    vy_without: np.ndarray
    x_with: np.ndarray
    y_with: np.ndarray
    vy_with: np.ndarray


class DisturbanceObserver:
    """One axis: ``P_n = 1/(M s + B)``, ``Q = (w_Q/(s + w_Q))^r``.

    Parameters
    ----------
    nominal_mass : float, optional
        Nominal mass ``M`` [kg].
    nominal_damping : float, optional
        Nominal damping ``B`` [N s/m].
    order : int, optional
        Order ``r`` of ``Q``, 1 .. 8.
    cutoff : float, optional
        Cut-off ``w_Q`` of ``Q`` [rad/s], > 0.

    Raises
    ------
    ValidationError
        When a parameter is out of its range (as :class:`ObserverSettings` checks it).
    """

    def __init__(self, nominal_mass: float = 0.01, nominal_damping: float = 0.022, order: int = 2,
                 cutoff: float = 200.0):
        st = ObserverSettings(nominal_mass=nominal_mass, nominal_damping=nominal_damping, order=order,
                              cutoff=cutoff)
        self.settings = st

    @classmethod
    def from_settings(cls, st: ObserverSettings) -> DisturbanceObserver:
        """The single-axis observer of a settings record (its nominal plant and ``Q``).

        Parameters
        ----------
        st : ObserverSettings
            The observer settings (profile section).

        Returns
        -------
        DisturbanceObserver
            The observer with ``st``'s nominal mass, damping, order and cut-off.
        """
        return cls(st.nominal_mass, st.nominal_damping, st.order, st.cutoff)

    def q(self, s: np.ndarray) -> np.ndarray:
        """The binomial low-pass ``Q(s) = (w_Q/(s + w_Q))^r``.

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.

        Returns
        -------
        numpy.ndarray
            ``Q(s)`` (dimensionless), complex, the shape of ``s``.
        """
        st = self.settings
        return (st.cutoff / (np.asarray(s, dtype=complex) + st.cutoff)) ** st.order

    def nominal(self, s: np.ndarray) -> np.ndarray:
        """The nominal plant ``P_n(s) = 1/(M s + B)`` (eq. 3).

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.

        Returns
        -------
        numpy.ndarray
            ``P_n(s)`` [m/(N s)], complex, the shape of ``s``.
        """
        st = self.settings
        return 1.0 / (st.nominal_mass * np.asarray(s, dtype=complex) + st.nominal_damping)

    def perturbed_plant(self, s: np.ndarray, alpha: float, beta: float, delta: float) -> np.ndarray:
        """``P~`` of eq. (13) around the nominal values.

        ``P~(s) = 1/(M (1 + alpha Delta) s + B (1 + beta Delta))``.

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.
        alpha : float
            Mass uncertainty.
        beta : float
            Damping uncertainty.
        delta : float
            The perturbation ``Delta``, in [-1, 1].

        Returns
        -------
        numpy.ndarray
            ``P~(s)`` [m/(N s)], complex, the shape of ``s``.
        """
        st = self.settings
        return 1.0 / (st.nominal_mass * (1 + alpha * delta) * np.asarray(s, dtype=complex)
                      + st.nominal_damping * (1 + beta * delta))

    def response(self, w, plant: np.ndarray | Device | None = None, alpha: float = 0.0, beta: float = 0.0,
                 delta: float = 0.0) -> ObserverResponse:
        """Responses at ``w`` for a real plant given as values ``P(jw)``, a :class:`Device` (handle
        admittance), or ``None`` (eq. 13 with ``alpha``, ``beta``, ``delta``).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], positive and finite, shape (N,).
        plant : numpy.ndarray or Device or None, optional
            The real plant: its values ``P(jw)`` [m/(N s)] (shape (N,)), a device chain (its
            handle admittance), or ``None`` for ``P~`` of eq. (13).
        alpha : float, optional
            Mass uncertainty of ``P~`` (only when ``plant`` is None).
        beta : float, optional
            Damping uncertainty of ``P~`` (only when ``plant`` is None).
        delta : float, optional
            The perturbation ``Delta`` of ``P~`` (only when ``plant`` is None).

        Returns
        -------
        ObserverResponse
            The plant, nominal, effective and disturbance responses at ``w``.

        Raises
        ------
        ValidationError
            When a frequency is not finite and positive.
        """
        w = frequencies(w)
        s = 1j * w
        if plant is None:
            P = self.perturbed_plant(s, alpha, beta, delta)
        elif isinstance(plant, Device):
            P = handle_admittance(plant, s)
        else:
            P = np.asarray(plant, dtype=complex)
        Pn, Q = self.nominal(s), self.q(s)
        den = Pn * (1 - Q) + P * Q
        eff = P * Pn / den
        return ObserverResponse(w, P, Pn, eff, Q, (1 - Q) * eff, P)


class TwoAxisObserver:
    """Two coupled Cartesian axes ``(M_x s + B_x) v = F`` with one observer per axis.

    ``nominal_mass``/``nominal_damping`` default to the diagonals of ``M_x``/``B_x`` (each axis
    identified with the other locked, as in the paper).

    Parameters
    ----------
    inertia : array_like
        Cartesian inertia ``M_x`` [kg], symmetric positive definite, shape (2, 2).
    damping : array_like
        Cartesian damping ``B_x`` [N s/m], symmetric positive semidefinite, shape (2, 2).
    order : int, optional
        Order ``r`` of ``Q``, 1 .. 8.
    cutoff : float, optional
        Cut-off ``w_Q`` of ``Q`` [rad/s], > 0.
    nominal_mass : array_like or None, optional
        Nominal masses of the two axes [kg], shape (2,); ``None`` for the diagonal of ``M_x``.
    nominal_damping : array_like or None, optional
        Nominal dampings of the two axes [N s/m], shape (2,); ``None`` for the diagonal of
        ``B_x``.

    Raises
    ------
    ValidationError
        When ``inertia`` or ``damping`` is not a finite symmetric 2x2 matrix, ``inertia`` is not
        positive definite, ``damping`` not positive semidefinite, or ``order``/``cutoff`` is out
        of range.
    """

    def __init__(self, inertia, damping, order: int = 2, cutoff: float = 200.0, nominal_mass=None,
                 nominal_damping=None):
        M = np.asarray(inertia, dtype=float)
        B = np.asarray(damping, dtype=float)
        for name, X in (("inertia", M), ("damping", B)):
            if X.shape != (2, 2) or not np.all(np.isfinite(X)) or not np.allclose(X, X.T, rtol=1e-12, atol=0):
                raise ValidationError(name, "a finite symmetric 2x2 matrix", X.tolist())
        if np.min(np.linalg.eigvalsh(M)) <= 0:
            raise ValidationError("inertia", "positive definite", M.tolist())
        if np.min(np.linalg.eigvalsh(B)) < -1e-12 * max(1.0, np.abs(B).max()):
            raise ValidationError("damping", "positive semidefinite", B.tolist())
        self.M, self.B = M, B
        self.order = integer("order", order, 1, 8)
        self.cutoff = positive("cutoff", cutoff, "rad/s")
        self.Mn = np.diag(M).copy() if nominal_mass is None else np.asarray(nominal_mass, float).reshape(2)
        self.Bn = np.diag(B).copy() if nominal_damping is None else np.asarray(nominal_damping, float).reshape(2)

    @classmethod
    def from_settings(cls, st: ObserverSettings) -> TwoAxisObserver:
        """The two-axis observer of a settings record, on its five-bar preset.

        Parameters
        ----------
        st : ObserverSettings
            The observer settings; ``preset`` names the device
            (:func:`~analysis.transparency.five_bar.five_bar_preset`).

        Returns
        -------
        TwoAxisObserver
            The preset's ``M_x``, ``B_x`` with ``st``'s order and cut-off (nominal values: the
            diagonals).
        """
        M, B, _, _ = five_bar_preset(st.preset)
        return cls(M, B, st.order, st.cutoff)

    # -- realizations ------------------------------------------------------------------------
    def state_space(self, observer: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(A, Bu, C)``: input the commanded forces (2), outputs ``[x, y, v_x, v_y]``.

        States: positions (2), velocities (2) and, with the observers, per axis a chain of ``r``
        lags on ``v`` (``xi``) and one on ``u_p`` (``zeta``):
        ``Q Z_n v = M_n w_Q (xi_{r-1} - xi_r) + B_n xi_r`` (``xi_0 = v``), ``Q u_p = zeta_r``,
        ``d_hat = Q Z_n v - Q u_p`` and ``u_p = u - d_hat``.

        Parameters
        ----------
        observer : bool
            Whether the loop includes the observers.

        Returns
        -------
        A : numpy.ndarray
            State matrix, shape (n, n) with n = 4 (4 + 4 r with the observers).
        Bu : numpy.ndarray
            Input matrix of the commanded forces ``(F_x, F_y)`` [N], shape (n, 2).
        C : numpy.ndarray
            Output matrix of ``[x, y, v_x, v_y]`` [m, m/s], shape (4, n).
        """
        r, wq = self.order, self.cutoff
        Minv = np.linalg.inv(self.M)
        nx = 4 + (4 * r if observer else 0)
        A = np.zeros((nx, nx))
        Bu = np.zeros((nx, 2))
        C = np.zeros((4, nx))
        C[:, :4] = np.eye(4)
        A[0:2, 2:4] = np.eye(2)
        A[2:4, 2:4] = -Minv @ self.B
        if not observer:
            Bu[2:4] = Minv
            return A, Bu, C
        xi = lambda i, j: 4 + i * r + (j - 1)  # noqa: E731  xi_{i,j}, j = 1..r
        ze = lambda i, j: 4 + 2 * r + i * r + (j - 1)  # noqa: E731
        # u_p = u - d_hat as a row over the states (Up) plus u
        Up = np.zeros((2, nx))
        for i in range(2):
            prev = 2 + i if r == 1 else xi(i, r - 1)  # xi_{r-1} (xi_0 = v_i)
            Up[i, prev] -= self.Mn[i] * wq
            Up[i, xi(i, r)] -= -self.Mn[i] * wq + self.Bn[i]
            Up[i, ze(i, r)] += 1.0
        A[2:4] += Minv @ Up
        Bu[2:4] = Minv
        for i in range(2):
            for j in range(1, r + 1):
                src = 2 + i if j == 1 else xi(i, j - 1)
                A[xi(i, j), src] += wq
                A[xi(i, j), xi(i, j)] -= wq
                if j == 1:
                    A[ze(i, 1)] += wq * Up[i]
                    Bu[ze(i, 1), i] += wq
                else:
                    A[ze(i, j), ze(i, j - 1)] += wq
                A[ze(i, j), ze(i, j)] -= wq
        return A, Bu, C

    # -- views --------------------------------------------------------------------------------
    def coupling(self, w) -> CouplingResponse:
        """``v_y/F_x`` and ``v_x/F_x`` with and without the observers at ``w`` (rad/s).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], positive and finite, shape (N,).

        Returns
        -------
        CouplingResponse
            The coupling and direct responses, their ratio and its closed form.

        Raises
        ------
        ValidationError
            When a frequency is not finite and positive.
        """
        w = frequencies(w)
        s = 1j * w
        out = {}
        for obs in (False, True):
            A, Bu, C = self.state_space(obs)
            n = A.shape[0]
            X = np.linalg.solve(s[:, None, None] * np.eye(n)[None] - A[None], np.broadcast_to(Bu[:, :1], (w.size, n, 1)))
            G = (C[None] @ X)[:, :, 0]  # N x 4
            out[obs] = (G[:, 3], G[:, 2])
        Z = self.M[None] * s[:, None, None] + self.B[None]
        q = (self.cutoff / (s + self.cutoff)) ** self.order
        detZ = Z[:, 0, 0] * Z[:, 1, 1] - Z[:, 0, 1] * Z[:, 1, 0]
        ratio_cf = (1 - q) * detZ / (Z[:, 0, 0] * Z[:, 1, 1] - (1 - q) ** 2 * Z[:, 0, 1] * Z[:, 1, 0])
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = out[True][0] / out[False][0]
        return CouplingResponse(w, out[False][0], out[True][0], out[False][1], out[True][1], ratio, ratio_cf)

    def step_response(self, force: float = 1.0, duration: float = 0.2, points: int = 2001) -> TwoAxisStep:
        """Commanded force step on x: exact discretization ``x_{k+1} = e^{A h} x_k + Gamma F``.

        Parameters
        ----------
        force : float, optional
            The force step on x [N], finite.
        duration : float, optional
            Duration [s], in (0, 100].
        points : int, optional
            Number of equally spaced times from 0 to ``duration``, 2 .. 10^6.

        Returns
        -------
        TwoAxisStep
            Positions and velocities of both axes without and with the observers.

        Raises
        ------
        ValidationError
            When an argument is out of its range.
        """
        force = _FORCE("force", force)
        duration = _DURATION("duration", duration)
        points = integer("points", points, 2, 10**6)
        t = np.linspace(0.0, duration, points)
        h = t[1] - t[0]
        res = {}
        for obs in (False, True):
            A, Bu, C = self.state_space(obs)
            n = A.shape[0]
            Mx = np.zeros((n + 1, n + 1))
            Mx[:n, :n] = A * h
            Mx[:n, n] = Bu[:, 0] * force * h
            E = linalg.expm(Mx)
            Phi, gam = E[:n, :n], E[:n, n]
            X = np.zeros((points, n))
            for k in range(points - 1):
                X[k + 1] = Phi @ X[k] + gam
            Y = X @ C.T
            res[obs] = Y
        a, b = res[False], res[True]
        return TwoAxisStep(t, force, a[:, 0], a[:, 1], a[:, 3], b[:, 0], b[:, 1], b[:, 3])
