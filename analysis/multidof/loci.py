"""Critical wall stiffnesses from the wall-free loop's frequency response, certified by eigenvalues.

The wall is the only part of the loop of :mod:`analysis.multidof.loop` that depends on ``k``:
``Phi(k) = Phi_0 + G (-(k S Y + b S V))``.  With ``T_y(z) = Y (zI - Phi_0)^{-1} G`` and
``T_v(z) = V (zI - Phi_0)^{-1} G`` (``m x m``, the wall-free loop seen by the wall) and the shape
factored as ``S = U U^T`` (``U`` of rank ``r``: ``n`` for a plane wall, ``I`` for the isotropic
one),

    ``det(zI - Phi(k)) = det(zI - Phi_0) det(I_r + U^T (k T_y + b T_v) U)``,

so a closed-loop root sits on the unit circle at ``z = e^{jw}`` exactly when ``k`` is a real
eigenvalue of ``Q(w) = -(U^T T_y U)^{-1} (I + b U^T T_v U)`` (the Nyquist / characteristic-locus
condition: a scalar for a plane wall, the 2 x 2 loci of a planar isotropic wall).  ``T_y`` and
``T_v`` are computed once per device at :data:`FREQUENCIES` frequencies; every wall shape is then
a projection.  A crossing is a sign change over the grid of the continuous function whose zeros
are exactly the real eigenvalues (``Im k |U^T T_y U|^2`` for ``r = 1``; for ``r = 2`` the
quadratic ``k^2 - tr Q k + det Q``'s resultant form), refined by regula falsi in ``w``; ``z = -1``
(``w = pi``, where ``Q`` is real) adds its real eigenvalues.

The rigid modes at ``z = 1`` never enter: the grid starts above ``w = 0`` and ``det(zI - Phi_0)``
(the free directions of a plane wall) is factored out; the plant's response is a sum over its
modes (``(zI - A_d)^{-1}`` by the plant's eigenvectors; the whole loop solved where they are ill
conditioned, e.g. an undamped free mass's Jordan block).  The result is then certified on the
exact loop, as :func:`analysis.multidof.limits.first_crossings` states it, with the one stability
rule (:func:`analysis.sampled.loop.is_stable` of :func:`~analysis.sampled.loop.spectral_radius`),
by four eigenvalue computations a wall:

* the first crossing ``k_c`` above ``k_range[0]``: ``k_c (1 + w)`` and ``k_c (1 + 2 w)``
  (:data:`CERTIFY_WIDTH`) must have radii above 1 and growing; their radii (the crossing pair's
  modulus, analytic in ``k``) extrapolate to the rule's own crossing ``rho = 1 + 1e-12``, and two
  more checks bracket it to ``rtol`` (else the points evaluated are bisected,
  :func:`~analysis.multidof.limits.narrow_brackets`).  The bracket's stable end also certifies
  every ``k`` below it: the loci found no other crossing above ``k_range[0]``, so a root outside
  the circle below ``k_c`` would still be outside there;
* no crossing up to ``k_range[1]``: ``k_range[1]`` must be stable (``inf``).

A wall that fails its certificate gets ``0.0`` if ``k_range[0]`` is unstable and is otherwise
handed to the scan of :func:`~analysis.multidof.limits.first_crossings`, as is a wall whose shape
has rank above 2, so every result is the stable end of a bracket of relative width ``rtol`` of the
exact loop whichever route found it.  Between ``k_range[0]`` and the result the frequency grid
found no crossing: an unstable window narrower than the grid resolves (the scan's own blind spot
too, at its 24 points a decade) is the only way to miss one.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analysis.chain.discretize import discretize_zoh
from analysis.chain.velocity_filter import VelocityFilter
from analysis.errors import ValidationError
from analysis.multidof.limits import check_k_range, first_crossings, narrow_brackets
from analysis.multidof.loop import loop_parts, plant_matrices
from analysis.multidof.model import DeviceLike, structural_model
from analysis.sampled.loop import STABILITY_TOLERANCE, is_stable, spectral_radius
from analysis.sampled.sweeps import CROSSING_RTOL
from analysis.sampled.terminations import HANDS_OFF, Grasp

__all__ = ["FREQUENCIES", "CERTIFY_WIDTH", "frequency_grid", "loop_responses", "certified_crossings",
           "frequency_first_crossings"]

#: Frequencies of the grid on which the loci are scanned (:func:`frequency_grid`).
FREQUENCIES = 384
#: Relative step ``w`` above the loci's crossing ``k_c`` of the certificate's points ``k_c (1 + w)``, ``k_c (1 + 2 w)``.
CERTIFY_WIDTH = 1e-8
_REFINE_STEPS = 8  # regula falsi steps in w per crossing
_GRID_CHUNK = 1 << 15  # (device, frequency, wall) triples per batch of the loci
_RADII_CHUNK = 4096  # closed loops per batch of eigenvalue computations
_QUANTUM = 2.0 ** -25  # the mantissa step of the certificate's points (relative 3e-8 to 6e-8)
_MODAL_COND = 1e6  # largest condition number of the plant's eigenvectors for the modal responses
_CHUNK = 1 << 15  # frequency responses per batch (memory)


def frequency_grid(count: int = FREQUENCIES) -> np.ndarray:
    """Normalized frequencies ``w = omega T`` in ``(0, pi]``: a quarter geometric from 1e-5, the rest linear.

    Parameters
    ----------
    count : int, optional
        Number of frequencies, at least 8.

    Returns
    -------
    numpy.ndarray
        Increasing frequencies [rad/sample], the last exactly ``pi``.
    """
    low = count // 4
    split = 0.05 * math.pi
    return np.concatenate([np.geomspace(1e-5, split, low, endpoint=False),
                           np.linspace(split, math.pi, count - low)])


def loop_responses(Phi0: np.ndarray, G: np.ndarray, Y: np.ndarray, V: np.ndarray,
                   w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``T_y`` and ``T_v`` of wall-free loops at frequencies (module docstring).

    Parameters
    ----------
    Phi0, G, Y, V : numpy.ndarray
        The loops of :func:`~analysis.multidof.loop.loop_parts`, stacked: shapes (P, N, N),
        (P, N, m), (P, m, N), (P, m, N).
    w : numpy.ndarray
        Frequencies [rad/sample], shape (F,) (the same for every loop) or (P, F).

    Returns
    -------
    numpy.ndarray
        ``T_y`` and ``T_v``, shapes (P, F, m, m), complex.
    """
    P, N = Phi0.shape[:2]
    z = np.exp(1j * np.broadcast_to(w, (P,) + np.shape(w)[-1:]))
    Ty = np.empty(z.shape + (G.shape[2],) * 2, dtype=complex)
    Tv = np.empty_like(Ty)
    step = max(1, _CHUNK // z.shape[1])
    for s in range(0, P, step):
        sl = slice(s, s + step)
        A = z[sl, :, None, None] * np.eye(N) - Phi0[sl, None]
        R = np.linalg.solve(A, np.broadcast_to(G[sl, None], A.shape[:2] + G.shape[1:]))
        Ty[sl] = Y[sl, None] @ R
        Tv[sl] = V[sl, None] @ R
    return Ty, Tv


@dataclass(frozen=True)
class WallFreeLoops:
    """Wall-free loops of P devices, stacked, with the modal form of their plants.

    ``T_y = z^{-d} C_s (zI - A_d)^{-1} B_d`` (the held command reaches the plant after the delay)
    and ``T_v = h(z) T_y`` with ``h`` the velocity estimate
    (:meth:`~analysis.chain.velocity_filter.VelocityFilter.response`): the loop of
    :func:`~analysis.multidof.loop.loop_parts` seen by the wall.  Where the plant's eigenvectors
    are well conditioned ``(zI - A_d)^{-1}`` is a sum of residues over its modes; elsewhere (a
    defective plant, e.g. an undamped free mass) :func:`loop_responses` solves the whole loop.
    """

    Phi0: np.ndarray
    G: np.ndarray
    Y: np.ndarray
    V: np.ndarray
    lam: np.ndarray
    residues: np.ndarray
    modal: np.ndarray
    delay: int
    sample_time: float
    vf: VelocityFilter

    @classmethod
    def build(cls, devices: Sequence[DeviceLike], delay_samples: int, grasp: Grasp,
              velocity_filter: VelocityFilter | None) -> "WallFreeLoops":
        models = [structural_model(d) for d in devices]
        m, n = models[0].axes, models[0].n
        odd = [i for i, mo in enumerate(models) if (mo.n, mo.axes, mo.sample_time) != (n, m, models[0].sample_time)]
        if odd:
            raise ValidationError("devices", f"devices of one size and sample time (device {odd[0]} differs from "
                                             f"device 0)", len(models))
        A, B = (np.concatenate(a) for a in zip(*(plant_matrices(mo, (grasp,)) for mo in models)))
        Ad, Bd = discretize_zoh(A, B, models[0].sample_time)  # one batched expm (the ZOH of discrete_plant)
        parts = [loop_parts(mo, delay_samples, grasp, velocity_filter, plant=(Ad[i], Bd[i]))
                 for i, mo in enumerate(models)]
        Phi0, G, Y, V = (np.stack(a) for a in zip(*parts))
        Bu = Bd[:, :, :m]
        lam, vec = np.linalg.eig(Ad)
        modal = np.linalg.cond(vec) < _MODAL_COND
        vec[~modal] = np.eye(2 * n)
        right = np.linalg.solve(vec, Bu.astype(complex))  # (P, 2n, m)
        left = np.stack([mo.sensing for mo in models]) @ vec[:, :n]  # (P, m, 2n)
        residues = (left.transpose(0, 2, 1)[:, :, :, None] * right[:, :, None, :]).reshape(lam.shape + (m * m,))
        vf = VelocityFilter() if velocity_filter is None else velocity_filter
        return cls(Phi0, G, Y, V, lam, residues, modal, int(delay_samples), models[0].sample_time, vf)

    def responses(self, idx: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``T_y``, ``T_v`` of loops ``idx`` (C,) at ``w`` (F,) or (C, 1): shapes (C, F, m, m)."""
        z = np.exp(1j * np.broadcast_to(w, (idx.size,) + np.shape(w)[-1:]))
        inv = 1.0 / (z[:, :, None] - self.lam[idx, None, :])
        m = self.G.shape[2]
        Ty = (inv @ self.residues[idx]).reshape(z.shape + (m, m)) * (z ** -self.delay)[..., None, None]
        h = self.vf.response(np.broadcast_to(w, z.shape) / self.sample_time, self.sample_time)
        Tv = h[..., None, None] * Ty
        slow = np.flatnonzero(~self.modal[idx])
        if slow.size:
            j = idx[slow]
            Ty[slow], Tv[slow] = loop_responses(self.Phi0[j], self.G[j], self.Y[j], self.V[j],
                                                np.broadcast_to(w, z.shape)[slow])
        return Ty, Tv


def _real_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a @ b`` for complex ``a`` (n, p) and real ``b`` (p, q) with small ``p`` (no batched tiny matmuls)."""
    out = a[:, :1] * b[0]
    for i in range(1, b.shape[0]):  # p is m^2, a handful: a sum of broadcast products
        out += a[:, i:i + 1] * b[i]
    return out


def _projected(Ty: np.ndarray, Tv: np.ndarray, U: np.ndarray, damping: float) -> tuple[np.ndarray, np.ndarray]:
    """``A = U^T T_y U`` and ``C = I + b U^T T_v U`` for wall factors ``U`` (W, m, r): (..., W, r, r)."""
    W, m, r = U.shape
    kron = np.einsum("wia,wjb->ijwab", U, U).reshape(m * m, W * r * r)  # vec(U^T T U) = vec(T) @ kron
    shape = Ty.shape[:-2] + (W, r, r)
    A = _real_product(Ty.reshape(-1, m * m), kron).reshape(shape)
    C = damping * _real_product(Tv.reshape(-1, m * m), kron).reshape(shape) + np.eye(r)
    return A, C


def _loci(A: np.ndarray, C: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The sign function whose zeros are the real eigenvalues of ``Q = -A^{-1} C``, and those eigenvalues.

    Returns ``g`` (...,) real and ``k`` (..., r) complex.
    """
    if A.shape[-1] == 1:
        a, c = A[..., 0, 0], C[..., 0, 0]
        return -(c * a.conj()).imag, (-c / a)[..., None]
    det_a = A[..., 0, 0] * A[..., 1, 1] - A[..., 0, 1] * A[..., 1, 0]
    det = (C[..., 0, 0] * C[..., 1, 1] - C[..., 0, 1] * C[..., 1, 0]) / det_a
    adj_c = A[..., 1, 1] * C[..., 0, 0] - A[..., 0, 1] * C[..., 1, 0] - A[..., 1, 0] * C[..., 0, 1] + \
        A[..., 0, 0] * C[..., 1, 1]
    tr = -adj_c / det_a
    g = det.imag ** 2 - tr.real * det.imag * tr.imag + det.real * tr.imag ** 2
    root = np.sqrt(tr * tr / 4.0 - det)
    return g, np.stack([tr / 2.0 + root, tr / 2.0 - root], axis=-1)


def _groups(shapes: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """The walls of each rank 1 and 2, with ``U`` (S = U U^T): ``[(indices, U (w, m, r)), ...]``."""
    lam, vec = np.linalg.eigh(shapes)
    ranks = (lam > 1e-12 * np.maximum(lam[:, -1:], 1e-300)).sum(axis=1)
    out = []
    for r in (1, 2):
        sel = np.flatnonzero(ranks == r)
        if sel.size:
            out.append((sel, vec[sel][:, :, -r:] * np.sqrt(lam[sel][:, None, -r:])))
    return out


def _locus_crossings(loops: WallFreeLoops, shapes: np.ndarray, damping: float, low: float,
                     count: int = FREQUENCIES) -> np.ndarray:
    """The smallest ``k > low`` at which each loop and wall shape has a root on the unit circle.

    Parameters
    ----------
    loops : WallFreeLoops
        The wall-free loops, P of them.
    shapes : numpy.ndarray
        Wall shapes ``S`` (W, m, m).
    damping : float
        Wall damping ``b`` [N s/m].
    low : float
        Crossings at or below ``low`` [N/m] are ignored.
    count : int, optional
        Frequencies of the grid.

    Returns
    -------
    numpy.ndarray
        Shape (P, W): the first crossing [N/m], ``inf`` where none was found, ``nan`` where a
        shape's rank is not 1 or 2.
    """
    P, W = loops.Phi0.shape[0], shapes.shape[0]
    best = np.full((P, W), math.nan)
    groups = _groups(shapes)
    w = frequency_grid(count)
    found: list[tuple[np.ndarray, ...]] = []
    step = max(1, _GRID_CHUNK // (w.size * W))
    for s in range(0, P, step):  # a few devices at a time: the (devices, F, W) arrays stay in cache
        idx = np.arange(s, min(s + step, P))
        Ty, Tv = loops.responses(idx, w)
        for sel, U in groups:
            g, ks = _loci(*_projected(Ty, Tv, U, damping))  # (c, F, w), (c, F, w, r)
            end = ks[:, -1]  # z = -1: Q is real, its real eigenvalues are crossings
            real_end = np.where(np.abs(end.imag) <= 1e-9 * np.abs(end), end.real, math.inf)
            best[idx[:, None], sel] = np.where(real_end > low, real_end, math.inf).min(axis=-1)
            c, f, j = np.nonzero(np.signbit(g[:, :-2]) != np.signbit(g[:, 1:-1]))  # interior sign changes
            found.append((idx[c], f, sel[j], g[c, f, j], g[c, f + 1, j]))
    for sel, U in groups:
        refined = _refine(loops, U, sel, damping, low, w, *(np.concatenate(a) for a in zip(*found)))
        best[:, sel] = np.minimum(best[:, sel], refined)
    return best


def _refine(loops: WallFreeLoops, U: np.ndarray, sel: np.ndarray, damping: float, low: float, w: np.ndarray,
            p: np.ndarray, f: np.ndarray, wall: np.ndarray, ga: np.ndarray, gb: np.ndarray) -> np.ndarray:
    """The crossings of the sign changes of walls ``sel`` refined in ``w``: the smallest above ``low`` (P, len(sel))."""
    best = np.full((loops.Phi0.shape[0], sel.size), math.inf)
    pos = np.searchsorted(sel, wall)
    mine = (pos < sel.size) & (sel[np.minimum(pos, sel.size - 1)] == wall)
    p, f, wi, ga, gb = p[mine], f[mine], pos[mine], ga[mine], gb[mine]
    if p.size == 0:
        return best
    wa, wb = w[f], w[f + 1]
    wm = wa
    side = np.zeros(p.size, dtype=int)  # the end kept by the last step: 1 for a, -1 for b
    for _ in range(_REFINE_STEPS):  # Illinois regula falsi in w
        den = gb - ga
        wm = np.where(den != 0, (wa * gb - wb * ga) / np.where(den != 0, den, 1.0), 0.5 * (wa + wb))
        wm = np.clip(wm, wa, wb)
        gm, _ = _candidate_loci(loops, U, damping, p, wi, wm)
        move_a = np.signbit(gm) == np.signbit(ga)
        wa, wb = np.where(move_a, wm, wa), np.where(move_a, wb, wm)
        ga, gb = np.where(move_a, gm, ga), np.where(move_a, gb, gm)
        gb = np.where(move_a & (side == -1), 0.5 * gb, gb)  # b kept twice: halve it (Illinois)
        ga = np.where(~move_a & (side == 1), 0.5 * ga, ga)
        side = np.where(move_a, -1, 1)
    _, km = _candidate_loci(loops, U, damping, p, wi, wm)
    pick = np.argmin(np.abs(km.imag) / np.maximum(np.abs(km), 1e-300), axis=-1)
    k = np.take_along_axis(km, pick[:, None], axis=-1)[:, 0].real
    k = np.where(k > low, k, math.inf)
    np.minimum.at(best, (p, wi), k)
    return best


def _congruence(U: np.ndarray, T: np.ndarray) -> np.ndarray:
    """``U^T T U`` of each (U (C, m, r), T (C, m, m)) by explicit sums: each one's digits do not
    depend on the batch (a batched einsum's may), so a point's result is the same in any grid."""
    TU = (T[:, :, :, None] * U[:, None, :, :]).sum(axis=2)  # (C, m, r)
    return (U[:, :, :, None] * TU[:, :, None, :]).sum(axis=1)  # (C, r, r)


def _candidate_loci(loops: WallFreeLoops, U: np.ndarray, damping: float, p: np.ndarray, wi: np.ndarray,
                    w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_loci` of loop ``p[i]`` and wall ``wi[i]`` at frequency ``w[i]`` (one each)."""
    Ty, Tv = loops.responses(p, w[:, None])
    Ui = U[wi]
    A, C = _congruence(Ui, Ty[:, 0]), damping * _congruence(Ui, Tv[:, 0]) + np.eye(U.shape[2])
    return _loci(A, C)


def _radii(P0: np.ndarray, P1: np.ndarray, idx: np.ndarray, ks: np.ndarray) -> np.ndarray:
    """Spectral radii of pencils ``idx`` at ``ks`` (n, j), a few thousand matrices at a time: (n, j)."""
    out = np.empty(ks.shape)
    step = max(1, _RADII_CHUNK // ks.shape[1])
    for s in range(0, idx.size, step):
        i = idx[s:s + step]
        out[s:s + step] = spectral_radius(P0[i, None] + ks[s:s + step, :, None, None] * P1[i, None])
    return out


def _canonical(k: np.ndarray, steps: Sequence[int]) -> np.ndarray:
    """Points ``steps`` quanta from ``k`` rounded up on a fixed grid of relative step ~4e-8 (exact arithmetic).

    The certificate evaluates the loop there, not at ``k`` itself: a crossing that the loci found
    within round-off of another batch's (a point computed in another grid, a band of rows) gives
    the same points, hence the same eigenvalues and the same result, bit for bit (unless it
    straddles a grid point, about 1e-5 of the walls).
    """
    m, e = np.frexp(k)
    q = np.ceil(m / _QUANTUM) * _QUANTUM
    return np.ldexp(q[:, None] + np.asarray(steps, dtype=float) * _QUANTUM, e[:, None])


def certified_crossings(P0: np.ndarray, P1: np.ndarray, guess: np.ndarray, k_range: tuple[float, float] = (1.0, 1e9),
                        rtol: float = CROSSING_RTOL) -> tuple[np.ndarray, np.ndarray]:
    """Certify first crossings ``guess`` of pencils ``P0 + k P1`` on the exact loop (module docstring).

    Parameters
    ----------
    P0, P1 : numpy.ndarray
        Pencils, shapes (W, N, N).
    guess : numpy.ndarray
        The first crossing above ``k_range[0]`` of each pencil, ``inf`` for none (W,).
    k_range : tuple of (float, float), optional
        The ``k`` range [N/m].
    rtol : float, optional
        Relative width of the final brackets.

    Returns
    -------
    k : numpy.ndarray
        The largest stable ``k`` as :func:`~analysis.multidof.limits.first_crossings` states it
        (W,), ``nan`` where the certificate failed.
    eigenproblems : numpy.ndarray
        Eigenvalue computations spent on each pencil (W,).
    """
    lo, hi = check_k_range(k_range)
    W = P0.shape[0]
    out = np.full(W, math.nan)
    cost = np.zeros(W, dtype=int)
    idx = np.flatnonzero((guess > hi) | np.isposinf(guess))
    if idx.size:  # no crossing up to hi: hi must be stable
        ok = np.asarray(is_stable(_radii(P0, P1, idx, np.full((idx.size, 1), hi))[:, 0]), dtype=bool)
        out[idx[ok]] = math.inf
        cost[idx] += 1
    idx = np.flatnonzero((guess <= hi) & (guess * (1 - CERTIFY_WIDTH) > lo))
    if idx.size == 0:
        return out, cost
    # two unstable points just above the crossing: their radii (the crossing pair's modulus,
    # analytic in k) extrapolate to the rule's own crossing rho = 1 + STABILITY_TOLERANCE
    ks = _canonical(guess[idx] * (1.0 + CERTIFY_WIDTH), [0, 1, -8])  # above, above, below the crossing
    floor, ks = ks[:, 2], ks[:, :2]
    rho = _radii(P0, P1, idx, ks)
    cost[idx] += 2
    good = (rho[:, 0] > 1.0) & (rho[:, 1] > rho[:, 0])
    idx, ks, rho, floor = idx[good], ks[good], rho[good], floor[good]
    if idx.size == 0:
        return out, cost
    slope = (rho[:, 1] - rho[:, 0]) / (ks[:, 1] - ks[:, 0])
    ke = ks[:, 0] + (1.0 + STABILITY_TOLERANCE - rho[:, 0]) / slope
    ke = np.clip(ke, floor, ks[:, 1])
    half = 0.4 * rtol
    # the final bracket; its stable end also certifies everything below it, since the loci found
    # no other crossing above k_range[0]: a root outside the circle there would still be outside
    pair = ke[:, None] * np.array([1.0 - half, 1.0 + half])
    rho2 = _radii(P0, P1, idx, pair)
    cost[idx] += 2
    below, above = np.asarray(is_stable(rho2[:, 0]), dtype=bool), ~np.asarray(is_stable(rho2[:, 1]), dtype=bool)
    fine = below & above
    out[idx[fine]] = pair[fine, 0]
    rest = np.flatnonzero(~fine)
    if rest.size:  # the rule is not linear enough there: bisect a bracket of the points evaluated
        j = idx[rest]
        low = floor[rest]
        low_ok = np.where(below[rest], True, np.asarray(is_stable(_radii(P0, P1, j, low[:, None])[:, 0]), dtype=bool))
        cost[j[~below[rest]]] += 1
        low = np.where(below[rest], pair[rest, 0], low)
        cands = np.column_stack([pair[rest, 1], ks[rest]])  # increasing; the first unstable one is the top
        bad = np.column_stack([above[rest], ~np.asarray(is_stable(rho[rest]), dtype=bool)])
        ok = low_ok & bad.any(axis=1)
        top = cands[np.arange(rest.size), np.argmax(bad, axis=1)]
        j, low, top = j[ok], low[ok], top[ok]
        out[j] = narrow_brackets(P0[j], P1[j], low, top, rtol)
        cost[j] += int(math.ceil(math.log2(max(math.log1p(20 * _QUANTUM) / math.log1p(rtol), 1.0))))
    return out, cost


def frequency_first_crossings(devices: Sequence[DeviceLike], shapes: np.ndarray, damping: float,
                              delay_samples: int = 0, grasp: Grasp = HANDS_OFF,
                              velocity_filter: VelocityFilter | None = None, k_range: tuple[float, float] = (1.0, 1e9),
                              rtol: float = CROSSING_RTOL, count: int = FREQUENCIES) -> tuple[np.ndarray, dict[str, int]]:
    """First crossings of every device with every wall shape, by the loci and certified (module docstring).

    The result is that of :func:`~analysis.multidof.limits.first_crossings` on the pencils of
    :func:`~analysis.multidof.loop.wall_pencil` within ``rtol``: the stable end of a bracket of
    relative width ``rtol`` of the exact loop.

    Parameters
    ----------
    devices : sequence of StructuralModel, RigidCartesianDevice or Device
        The devices, P of them, all of one size and sample time.
    shapes : numpy.ndarray
        Wall shapes ``S`` (W, m, m) (:func:`~analysis.multidof.loop.wall_shape`).
    damping : float
        Wall damping ``b`` [N s/m].
    delay_samples : int, optional
        Computation delay in samples.
    grasp : Grasp, optional
        The human grasp at the handle.
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate; ``None`` for the backward difference.
    k_range : tuple of (float, float), optional
        The ``k`` range [N/m].
    rtol : float, optional
        Relative width of the final brackets.
    count : int, optional
        Frequencies of the loci's grid.

    Returns
    -------
    k : numpy.ndarray
        Shape (P, W) [N/m]: ``inf`` when nothing up to ``k_range[1]`` is unstable, ``0.0`` when
        ``k_range[0]`` already is.
    stats : dict
        ``"walls"``, ``"certified"`` (walls the loci and their certificate settled),
        ``"eigenproblems"`` (eigenvalue computations of the certificates) and ``"fallback"``
        (walls handed to the scan).

    Raises
    ------
    ValidationError
        When the devices differ in size or sample time, the range is not ``0 < low < high <
        inf``, or a setting of the loop is out of range (as
        :func:`~analysis.multidof.loop.loop_parts`).
    """
    lo, _ = check_k_range(k_range)
    loops = WallFreeLoops.build(devices, delay_samples, grasp, velocity_filter)
    b = float(damping)
    shapes = np.asarray(shapes, dtype=float).reshape((-1,) + loops.G.shape[2:3] * 2)
    P, W = loops.Phi0.shape[0], shapes.shape[0]
    guess = _locus_crossings(loops, shapes, b, lo, count)
    Phi0, G, Y, V = loops.Phi0, loops.G, loops.Y, loops.V
    P0 = (Phi0[:, None] + G[:, None] @ -(b * shapes[None] @ V[:, None])).reshape((P * W,) + Phi0.shape[1:])
    P1 = (G[:, None] @ -(shapes[None] @ Y[:, None])).reshape(P0.shape)
    k, cost = certified_crossings(P0, P1, guess.reshape(-1), k_range, rtol)
    bad = np.flatnonzero(np.isnan(k))
    if bad.size:  # k_range[0] unstable gives 0.0 as the scan would; the rest is scanned
        low_ok = np.asarray(is_stable(_radii(P0, P1, bad, np.full((bad.size, 1), lo))[:, 0]), dtype=bool)
        cost[bad] += 1
        k[bad[~low_ok]] = 0.0
        bad = bad[low_ok]
        k[bad] = first_crossings(P0[bad], P1[bad], k_range, rtol)
    stats = {"walls": P * W, "certified": int(P * W - bad.size), "eigenproblems": int(cost.sum()),
             "fallback": int(bad.size)}
    return k.reshape(P, W), stats
