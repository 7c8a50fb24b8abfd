"""Loop realisations of the wall controller (Eom, Suh & Yi, eq. 9, 12): the transmitted
admittance ``Y_t = P/(1 + H P C)`` in every form the analysis needs.

* the frequency-domain parts ``a = 1/P + H K_c/s`` and ``h = H``, so that
  ``Y_t = 1/(a + B_c h)`` for many ``B_c`` on one grid;
* the state space of the closed loop with a rational hold, affine in ``B_c``
  (:class:`RationalLoop`), and its poles;
* the exact sampled loop (:class:`analysis.transparency.discrete_loop.DiscreteLoop`);
* the singularities that guide the frequency grids and quadrature panels.

See :mod:`analysis.transparency.design` for the reading of the paper.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from analysis.errors import ValidationError
from analysis.transparency.discrete_loop import DiscreteLoop, DiscreteModal
from analysis.transparency.holds import hold_response, hold_state_space
from analysis.transparency.plant import WallPlant
from analysis.transparency.settings import WallSettings

__all__ = ["check_bc", "RationalLoop", "LoopRealizations"]

_SINGULARITY_CACHE = 64  # distinct B_c vectors whose singularities are kept


def check_bc(bc) -> np.ndarray:
    """Controller dampings ``B_c`` as a 1-d float array; every value finite.

    Parameters
    ----------
    bc : float or array_like
        One controller damping ``B_c`` or several [N s/m].

    Returns
    -------
    numpy.ndarray
        The dampings [N s/m], float, shape (N,) (N = 1 for a scalar).

    Raises
    ------
    ValidationError
        When a value is not finite (names the first one and its index).
    """
    arr = np.atleast_1d(np.asarray(bc, dtype=float))
    bad = ~np.isfinite(arr)
    if bad.any():
        raise ValidationError("bc", "finite (N s/m)", float(arr[bad][0]), int(np.flatnonzero(bad)[0]))
    return arr


@dataclass(frozen=True)
class RationalLoop:
    """``A_cl(B_c) = a0 + B_c a1``, ``b`` (human force in), ``c`` (velocity out) of eq. (9) with a
    rational hold.  States: plant, ``xi = int v`` (only when ``K_c != 0``), hold.

    Parameters
    ----------
    a0 : numpy.ndarray
        The part of ``A_cl`` independent of ``B_c``, shape (N, N).
    a1 : numpy.ndarray
        The part of ``A_cl`` per unit ``B_c``, shape (N, N).
    b : numpy.ndarray
        Input column of the human force [N], shape (N, 1).
    c : numpy.ndarray
        Output row of the handle velocity [m/s], shape (1, N).
    """

    a0: np.ndarray
    a1: np.ndarray
    b: np.ndarray
    c: np.ndarray


class LoopRealizations:
    """The closed loop of one design in its frequency-domain, rational and sampled forms.

    Parameters
    ----------
    settings : WallSettings
        The design.
    plant : WallPlant
        Its plant ``P(s)``.
    """

    def __init__(self, settings: WallSettings, plant: WallPlant):
        self.settings = settings
        self.plant = plant
        self.discrete = DiscreteLoop(settings, plant)
        self._rational: dict[str, RationalLoop] = {}
        self._singularities: dict[bytes, np.ndarray] = {}

    def continuous_parts(self, w: np.ndarray, oscillating: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``a = 1/P + H K_c/s`` and ``h = H`` at ``s = j w``: ``Y_t = 1/(a + B_c h)``.

        Parameters
        ----------
        w : numpy.ndarray
            Angular frequencies [rad/s], nonzero, shape (P,).
        oscillating : bool, optional
            False drops the ``e^{-sT}`` term of the ``zoh`` hold (see
            :func:`~analysis.transparency.holds.hold_response`).

        Returns
        -------
        a : numpy.ndarray
            ``1/P + H K_c/s`` [N s/m], complex, shape (P,).
        h : numpy.ndarray
            The hold response ``H`` (dimensionless), complex, shape (P,).
        """
        st = self.settings
        s = 1j * np.asarray(w, dtype=float)
        H = hold_response(st.hold, s, st.sample_time, st.lowpass_damping, oscillating)
        return self.plant.impedance(s) + H * (st.kc / s), H

    def rational(self, hold: str) -> RationalLoop:
        """The closed loop of eq. (9) with the rational ``hold`` (cached).

        Parameters
        ----------
        hold : str
            A rational hold model: ``"none"``, ``"pade"`` or ``"lowpass2"``.

        Returns
        -------
        RationalLoop
            The state space, affine in ``B_c``.
        """
        loop = self._rational.get(hold)
        if loop is None:
            loop = self._rational[hold] = self._build_rational(hold)
        return loop

    def _build_rational(self, hold: str) -> RationalLoop:
        st, p = self.settings, self.plant
        Ah, Bh, Ch, Dh = hold_state_space(hold, st.sample_time, st.lowpass_damping)
        kc = st.kc
        npl, nh = p.order, Ah.shape[0]
        nx = 1 if kc != 0 else 0
        N = npl + nx + nh
        A0 = np.zeros((N, N))
        A1 = np.zeros((N, N))
        P, X, Hs = slice(0, npl), slice(npl, npl + nx), slice(npl + nx, N)
        dh = float(Dh[0, 0])
        A0[P, P] = p.A
        A0[P, Hs] = -p.B @ Ch
        A1[P, P] = -dh * (p.B @ p.Cv)
        A1[Hs, P] = Bh @ p.Cv
        if nx:
            A0[P, X] = -dh * kc * p.B
            A0[X, P] = p.Cv
            A0[Hs, X] = Bh * kc
        A0[Hs, Hs] = Ah
        Bcl = np.zeros((N, 1))
        Bcl[P] = p.B
        Ccl = np.zeros((1, N))
        Ccl[0, P] = p.Cv[0]
        return RationalLoop(A0, A1, Bcl, Ccl)

    def poles_many(self, bcs: np.ndarray, hold: str) -> np.ndarray:
        """Closed-loop poles (rows = ``bcs``), batched; ``log(z)/T`` for ``discrete``.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        hold : str
            A rational hold model or ``"discrete"``.

        Returns
        -------
        numpy.ndarray
            Poles [rad/s], complex, shape (R, N) (N the loop's order).
        """
        if hold == "discrete":
            return self.discrete.poles(bcs)
        loop = self.rational(hold)
        return np.linalg.eigvals(loop.a0[None] + bcs[:, None, None] * loop.a1[None])

    def singularities(self, bcs: np.ndarray) -> np.ndarray:
        """Complex ``w0 + j sigma`` of the integrand's poles for all ``bcs`` (panel/grid guides).

        Includes the plant's poles, the weight's cut-off and the wall's corner ``K/B``; near
        duplicates (0.1 % on a log scale) are merged.  Cached per ``bcs``.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).

        Returns
        -------
        numpy.ndarray
            ``|Im p| + j |Re p|`` of each distinct pole ``p`` [rad/s], finite and nonzero, complex,
            shape (M,).
        """
        key = bcs.tobytes()
        c = self._singularities.get(key)
        if c is None:
            c = self._find_singularities(bcs)
            if len(self._singularities) > _SINGULARITY_CACHE:
                self._singularities.clear()
            self._singularities[key] = c
        return c

    def _find_singularities(self, bcs: np.ndarray) -> np.ndarray:
        st = self.settings
        sur = ("pade", "lowpass2") if st.hold == "zoh" else (st.hold,)
        poles = [self.plant.poles()] + [self.poles_many(bcs, h).ravel() for h in sur]
        p = np.concatenate(poles)
        c = np.abs(p.imag) + 1j * np.abs(p.real)
        extra = [1j * st.weight_cutoff]
        if st.wall_damping > 0 and st.wall_stiffness > 0:
            extra.append(1j * st.wall_stiffness / st.wall_damping)
        c = np.concatenate([c, extra])
        c = c[np.isfinite(c) & (np.abs(c) > 0)]
        # merge near-duplicates (many B_c give nearby poles): 0.1 % on a log scale
        key2 = np.round(np.log(np.abs(c)) * 1000.0) + 1j * np.round(np.angle(c) * 1000.0)
        _, first = np.unique(key2, return_index=True)
        return c[np.sort(first)]

    def admittance_rows(self, bcs: np.ndarray, w: np.ndarray, oscillating: bool = True,
                        modal: DiscreteModal | None = None) -> np.ndarray:
        """``Y_t`` (rows = ``bcs``) at ``w``; ``Y_t(e^{jwT})`` for the ``discrete`` hold.

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        w : numpy.ndarray
            Angular frequencies [rad/s], shape (P,) (below ``pi/T`` for ``discrete``).
        oscillating : bool, optional
            False drops the ``e^{-sT}`` term of the ``zoh`` hold.
        modal : DiscreteModal or None, optional
            The modal form of ``bcs`` for the ``discrete`` hold, if already computed; ``None``
            computes it.

        Returns
        -------
        numpy.ndarray
            The transmitted admittance ``Y_t`` [m/(N s)], complex, shape (R, P).
        """
        if self.settings.hold == "discrete":
            md = modal if modal is not None else self.discrete.modal(bcs)
            return md.admittance(np.arange(bcs.size), np.exp(1j * w * self.settings.sample_time))
        a, h = self.continuous_parts(w, oscillating)
        return 1.0 / (a[None, :] + bcs[:, None] * h[None, :])
