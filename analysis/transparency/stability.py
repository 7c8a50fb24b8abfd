"""Closed-loop stability of the wall controller for many ``B_c`` at once (Eom, Suh & Yi, eq. 9).

``J`` (eq. 11) is finite only for an asymptotically stable loop.  Rational holds: the poles of
:class:`analysis.transparency.loops.RationalLoop`; ``discrete``: the sampled loop's
eigenvalues inside the unit circle; ``zoh``: the argument principle on the quadrature nodes.
"""

from __future__ import annotations

import math

import numpy as np

from analysis.transparency.holds import hold_response
from analysis.transparency.loops import LoopRealizations

__all__ = ["ClosedLoopStability", "unstable_reason"]

#: Quadrature nodes ``(w, wt, w_tail, wt_tail)`` (see ``TransparencyIndex.quadrature_nodes``).
Nodes = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


def unstable_reason(ev: np.ndarray) -> str:
    """Why a continuous loop with poles ``ev`` is unstable."""
    return f"closed loop unstable (pole at {ev[np.argmax(ev.real)]:.6g} rad/s)"


class ClosedLoopStability:
    """Stability per ``B_c`` of the loop of one design, with the reason when unstable.

    Parameters
    ----------
    loops : LoopRealizations
        The loop realisations of the design.
    """

    def __init__(self, loops: LoopRealizations):
        self.loops = loops

    def stable_many(self, bcs: np.ndarray, nodes: Nodes) -> tuple[np.ndarray, list[str]]:
        """Closed-loop stability per ``B_c`` and the reason when unstable; ``nodes`` are the
        quadrature nodes of ``J`` (used by the ``zoh`` test).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        nodes : tuple of numpy.ndarray
            ``(w, wt, w_tail, wt_tail)`` of
            :meth:`~analysis.transparency.index.TransparencyIndex.quadrature_nodes` [rad/s].

        Returns
        -------
        stable : numpy.ndarray
            Whether each loop is asymptotically stable, bool, shape (R,).
        reasons : list of str
            Why each loop is unstable; ``""`` where stable (R entries).
        """
        st = self.loops.settings
        if st.hold == "zoh":
            return self.zoh_stable_many(bcs, nodes)
        if st.hold == "discrete":
            rad = np.max(np.abs(np.exp(self.loops.poles_many(bcs, "discrete") * st.sample_time)), axis=1)
            ok = rad < 1
            return ok, ["" if o else f"sampled loop unstable (|z| = {x:.6g})" for o, x in zip(ok, rad)]
        ev = self.loops.poles_many(bcs, st.hold)
        ok = np.max(ev.real, axis=1) < 0
        return ok, ["" if o else unstable_reason(e) for o, e in zip(ok, ev)]

    def zoh_stable_many(self, bcs: np.ndarray, nodes: Nodes) -> tuple[np.ndarray, list[str]]:
        """Argument principle for ``g(s) = s (1/P + H C)`` (``s`` dropped when ``K_c = 0``).

        ``g`` is analytic in the right half plane (``H`` is entire, ``1/P`` has no RHP poles for
        a passive device) and ``~ m_0 s^d`` on a large arc, ``d = 2`` (1 if ``K_c = 0``), so the
        number of RHP closed-loop poles is ``d/2 - Delta arg g(j w)|_{0+}^{inf} / pi``; the phase
        is tracked on the quadrature nodes (panels resolve every surrogate resonance).
        A loop whose phase steps by a quarter turn or more between nodes, or where ``g`` vanishes,
        counts as unresolved (not stable).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m], shape (R,).
        nodes : tuple of numpy.ndarray
            ``(w, wt, w_tail, wt_tail)`` of
            :meth:`~analysis.transparency.index.TransparencyIndex.quadrature_nodes` [rad/s].

        Returns
        -------
        stable : numpy.ndarray
            Whether each loop is resolved and has no right-half-plane pole, bool, shape (R,).
        reasons : list of str
            Why each loop is not stable; ``""`` where stable (R entries).
        """
        w0, _, w1, _ = nodes
        st = self.loops.settings
        T, kc = st.sample_time, st.kc
        w0 = w0[w0 > 0]
        w1 = np.sort(w1)
        w = np.concatenate([w0, w1])
        s = 1j * w
        H = np.concatenate([hold_response("zoh", 1j * w0, T), hold_response("zoh", 1j * w1, T, oscillating=False)])
        Z = self.loops.plant.impedance(s)
        if kc != 0:
            g, d = (s * Z)[None, :] + H[None, :] * (bcs[:, None] * s[None, :] + kc), 2
        else:
            g, d = Z[None, :] + H[None, :] * bcs[:, None], 1
        ph = np.unwrap(np.angle(g), axis=1)
        step = np.max(np.abs(np.diff(ph, axis=1)), axis=1)
        end = ph[:, -1] + np.angle(np.exp(1j * (d * math.pi / 2 - ph[:, -1])))
        n_rhp = np.rint(d / 2 - (end - ph[:, 0]) / math.pi).astype(int)
        resolved = (step < 0.5 * math.pi) & (np.min(np.abs(g), axis=1) > 0)
        ok = resolved & (n_rhp == 0)
        reasons = []
        for o, rsv, n in zip(ok, resolved, n_rhp):
            reasons.append("" if o else ("stability of the zoh model could not be resolved on the grid" if not rsv
                                         else f"closed loop (zoh model) unstable: {n} poles in the right half plane"))
        return ok, reasons
