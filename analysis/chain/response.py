"""Frequency response of the lumped-mass chain in O(n) per frequency.

The chain's impedance matrix ``A(s) = M s + B + K/s`` (eq. 25) is tridiagonal.  Instead of
an n-by-n solve per frequency, the responses to a unit force at either end are obtained
from continued-fraction sweeps (driving-point impedance of the sub-chain to the right or
left of a node) and products of transfer ratios.  Everything is vectorized over frequency
and costs O(N n) time and memory.  The handle impedance alone (one sweep) is
:mod:`analysis.chain.continued_fraction`, whose kernel also gives ``y22`` here when the responses
to a force on the actuator are not wanted.

Accuracy
--------
Quantities are formed so that no step subtracts nearly equal numbers:

* driving-point real parts are dissipated powers ``sum b |relative velocity|^2`` (all
  terms non-negative);
* relative velocities come from transfer ratios, not differences of node velocities;
* for the Llewellyn determinant we use the identity
  ``Re y11 Re y22 - (Re y12)^2 + j (Re y11 Im y22 - Re y12 Im y12) = X`` with
  ``X = sum_e beta_e conj(nu_e) mu_e``, where ``mu_e`` are 2x2 minors of the end
  responses.  The minors follow from the Casoratian of the three-term recurrence
  (``z_i (w_i v_{i+1} - w_{i+1} v_i) = y12``) and are propagated from the actuator end
  with scaled variables, so they are exact to rounding even when the chain is nearly
  rigid (low frequency), where the direct form loses all digits.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np

from analysis.chain.continued_fraction import continued_fraction, node_element_impedances
from analysis.chain.device import Device

__all__ = ["ChainResponse", "chain_response", "KEEP_ELEMENTS", "workspace_buffers"]


@dataclass(frozen=True)
class ChainResponse:
    """Continuous responses of the chain at the complex frequencies ``s`` (shape N).

    All arrays have shape ``(N,)``.

    Attributes
    ----------
    s : numpy.ndarray
        The complex frequencies [rad/s], complex.
    y11, y22, y12 : numpy.ndarray
        Continuous two-port admittance [m/(N s)], complex, with the port convention of
        eq. (26): ``y11 = v_h/F_h``, ``y22 = (-v_d)/F_d``, ``y12 = y21 = v_h/F_d``.
    re_y11, re_y22 : numpy.ndarray
        Their real parts as dissipated powers [m/(N s)] (non-negative, cancellation-free).
    x : numpy.ndarray
        ``Re y11 Re y22 - (Re y12)^2 + j (Re y11 Im y22 - Re y12 Im y12)`` [(m/(N s))^2],
        accurate, complex; zero when :func:`chain_response` was called with ``want_x=False``.
    sensor_from_handle, sensor_from_actuator : numpy.ndarray or None
        Gauge force per unit ``F_h`` and per unit force *on* the actuator mass (N x 1),
        dimensionless, complex; ``sensor_from_actuator`` is ``None`` when
        :func:`chain_response` was called with ``want_left=False``.
    """

    s: np.ndarray
    y11: np.ndarray
    y22: np.ndarray
    y12: np.ndarray
    re_y11: np.ndarray
    re_y22: np.ndarray
    x: np.ndarray
    sensor_from_handle: np.ndarray
    sensor_from_actuator: np.ndarray


#: a work array of up to this many elements (256 KiB of complex) is kept between calls
KEEP_ELEMENTS = 1 << 14


class _Workspace(threading.local):
    """The work arrays of :func:`chain_response`, kept per thread between calls.

    One evaluation of the HBFD at 2000 frequencies needs about 0.8 MB of ``(n-1) x N`` work
    arrays.  Allocated and freed on every call, that memory returns to the top of glibc's heap,
    which (with the default trim threshold of 128 KiB) is given back to the kernel and
    page-faulted in again by the next call: 1.7x the run time of a process that tunes its
    allocator (``app/allocator.py``; issue 21).  Here each array is a flat buffer, reshaped on
    request and grown to the largest request up to :data:`KEEP_ELEMENTS` elements; a larger
    request (long chains, very fine grids) gets a fresh array that is not kept.  At most about
    4 MiB per thread are kept.  Nothing :func:`chain_response` returns is a view of them.
    """

    def __init__(self) -> None:
        self.buffers: dict[str, np.ndarray] = {}
        self.last: dict[str, tuple[tuple[int, ...], np.ndarray]] = {}  # the last shape's view

    def get(self, name: str, shape: tuple[int, ...], dtype: type = complex) -> np.ndarray:
        """A C-contiguous array of ``shape`` (contents undefined), one per ``name`` and thread."""
        hit = self.last.get(name)
        if hit is not None and hit[0] == shape:
            return hit[1]
        size = math.prod(shape)
        buf = self.buffers.get(name)
        if buf is None or buf.size < size:
            buf = np.empty(size, dtype=dtype)
            if size > KEEP_ELEMENTS:
                return buf.reshape(shape)
            self.buffers[name] = buf
        view = buf[:size].reshape(shape)
        self.last[name] = (shape, view)
        return view


_workspace = _Workspace()


def workspace_buffers() -> list[np.ndarray]:
    """The work arrays that :func:`chain_response` keeps for the calling thread.

    Returns
    -------
    list of numpy.ndarray
        The kept flat buffers (each at most :data:`KEEP_ELEMENTS` elements), for inspection: a
        result never shares memory with them.
    """
    return list(_workspace.buffers.values())


def _abs2(a: np.ndarray) -> np.ndarray:
    return a.real * a.real + a.imag * a.imag


def _wabs2(weights: np.ndarray, rows: np.ndarray, ws: _Workspace) -> np.ndarray:
    """``sum_i weights_i |rows_i|^2`` over the chain, on the contiguous float view (a work
    array of ``ws``: use it before the next call).

    (``a.real * a.real + a.imag * a.imag`` on 2-D complex arrays walks strided memory and is
    about 10x slower for long chains.)
    """
    k, N = rows.shape
    f = rows.view(np.float64)
    sq = np.multiply(f, f, out=ws.get("sq", (k, 2 * N), float))
    acc = np.einsum("i,ij->j", weights, sq, out=ws.get("acc", (2 * N,), float))
    return np.add(acc[0::2], acc[1::2], out=ws.get("racc", (N,), float))


def _rows(a: np.ndarray, index: np.ndarray, ws: _Workspace) -> np.ndarray:
    """``a[index]`` (rows), a view when ``index`` is one row, else a work array of ``ws``."""
    if index.size == 1:
        return a[index[0]:index[0] + 1]
    return np.take(a, index, axis=0, out=ws.get("take", (index.size,) + a.shape[1:], a.dtype.type))


_BLOCK_ROWS = 32  # rows per block of _damper_sums: a block of each operand stays in cache


def _damper_sums(bb: np.ndarray, v: np.ndarray, r: np.ndarray, G: np.ndarray, ws: _Workspace):
    """``nu = v[:-1] r`` (in place in ``r``), ``sum_e b_e |nu_e|^2`` and
    ``sum_e b_e conj(nu_e) v_e G_e`` in one pass over the chain, block by block of rows."""
    n1, N = r.shape
    re = ws.get("re", (2 * N,), float)
    re.fill(0.0)
    x = np.zeros(2 * N)
    rows = min(_BLOCK_ROWS, n1)
    sq = ws.get("sq", (rows, 2 * N), float)
    tmp = ws.get("tmp", (rows, N))
    acc = ws.get("acc", (2 * N,), float)
    for a in range(0, n1, rows):
        b = min(a + rows, n1)
        k = b - a
        nu = np.multiply(v[a:b], r[a:b], out=r[a:b])
        f = nu.view(np.float64)
        np.multiply(f, f, out=sq[:k])
        re += np.einsum("i,ij->j", bb[a:b], sq[:k], out=acc)
        c = np.conjugate(nu, out=tmp[:k])
        c *= v[a:b]
        c *= G[a:b]
        x += np.einsum("i,ij->j", bb[a:b], c.view(np.float64), out=acc)
    return r, re[0::2] + re[1::2], x.view(complex)


def _wsum(weights: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``weights @ rows`` without BLAS (its threads only add latency at these sizes).

    Real weights and complex rows: summed on the contiguous float view (same sums, about
    1.7x faster than complex einsum)."""
    if rows.dtype == complex and rows.flags.c_contiguous:
        return np.einsum("i,ij->j", weights, rows.view(np.float64)).view(complex)
    return np.einsum("i,ij->j", weights, rows)


def chain_response(device: Device, s: np.ndarray, termination: np.ndarray | None = None,
                   re_termination: np.ndarray | None = None, want_x: bool = True,
                   want_left: bool = True,
                   impedances: tuple[np.ndarray, np.ndarray] | None = None) -> ChainResponse:
    """Responses of the chain at complex frequencies ``s`` (see :func:`_chain_response`).

    A lossless chain has exact poles on the imaginary axis; there the responses are
    infinite.  No floating-point warning is raised: the callers map the resulting
    non-finite bounds to ``+inf`` with the ``singular`` flag.

    With ``want_left=False`` the responses to a force on the actuator are not formed (only
    ``y22``, by a continued fraction): ``re_y22`` is then ``(Re X + (Re y12)^2)/Re y11``
    (requires ``want_x``) and ``sensor_from_actuator`` is ``None``.

    ``impedances`` may pass the (node, element) arrays of :func:`analysis.chain.continued_fraction.chain_impedances` for the
    same ``s``; they are not modified.

    Every frequency is computed on its own, so a long frequency vector is taken in blocks whose
    work arrays stay in the thread's workspace (:class:`_Workspace`; the results are the same
    bits as in one block).

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    s : array_like
        Complex frequencies [rad/s], shape (N,).
    termination : numpy.ndarray or None, optional
        An impedance from the actuator mass to ground [N s/m] per frequency, shape (N,), e.g.
        the PD loop seen through the hold; ``None`` for none.
    re_termination : numpy.ndarray or None, optional
        The exact real part (dissipation) of ``termination`` [N s/m], shape (N,), given
        separately so that no cancellation enters; required with ``termination``.
    want_x : bool, optional
        Whether to form ``x`` (else it is zero).
    want_left : bool, optional
        Whether to form the responses to a force on the actuator (else ``y22`` comes from a
        continued fraction and ``sensor_from_actuator`` is ``None``).
    impedances : tuple of numpy.ndarray or None, optional
        The ``(node, elem)`` arrays of :func:`analysis.chain.continued_fraction.chain_impedances`
        at the same ``s``, shapes (n, N) and (n - 1, N); ``None`` builds them.

    Returns
    -------
    ChainResponse
        The admittances, dissipations and gauge responses at ``s``, each of shape (N,).
    """
    s = np.asarray(s, dtype=complex)
    step = KEEP_ELEMENTS // device.n
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if device.n == 1 or s.ndim != 1 or s.size <= step or step < _MIN_BLOCK:
            return _chain_response(device, s, termination, re_termination, want_x, want_left, impedances)
        parts = []
        for a in range(0, s.size, step):
            cut = slice(a, a + step)
            imp = None if impedances is None else (impedances[0][:, cut], impedances[1][:, cut])
            parts.append(_chain_response(device, s[cut], _block(termination, cut), _block(re_termination, cut),
                                         want_x, want_left, imp))
    return _joined(s, parts)


#: the shortest block of frequencies :func:`chain_response` cuts a long vector into (shorter
#: blocks would cost more in per-call overhead than the workspace saves; longer chains then
#: take the whole vector at once, in fresh arrays)
_MIN_BLOCK = 1024


def _block(a, cut: slice):
    """``a[cut]`` for a per-frequency array; a scalar or ``None`` as it is."""
    return a if a is None or np.ndim(a) == 0 else np.asarray(a)[cut]


def _joined(s: np.ndarray, parts: list[ChainResponse]) -> ChainResponse:
    """The responses of consecutive blocks of ``s`` as one :class:`ChainResponse`."""
    fields = {}
    for name in ("y11", "y22", "y12", "re_y11", "re_y22", "x", "sensor_from_handle", "sensor_from_actuator"):
        first = getattr(parts[0], name)
        fields[name] = None if first is None else np.concatenate([getattr(p, name) for p in parts])
    return ChainResponse(s=s, **fields)


def _chain_response(device: Device, s: np.ndarray, termination: np.ndarray | None,
                    re_termination: np.ndarray | None, want_x: bool, want_left: bool,
                    impedances: tuple[np.ndarray, np.ndarray] | None = None) -> ChainResponse:
    """Responses of the chain at complex frequencies ``s``.

    ``termination`` is an impedance (per frequency) from the actuator mass to ground,
    e.g. the PD loop seen through the hold; ``re_termination`` is its exact real part
    (dissipation), given separately so that no cancellation enters.

    Only the continued-fraction sweeps and the minor propagation are sequential over the
    chain (about 18 array operations per mass); node velocities follow from cumulative
    products of transfer ratios and the dissipation sums are reductions over the chain.

    This is a numerical kernel, kept in one piece because the sweeps share their (n-1) x N work
    arrays in place (``r`` becomes ``nu``, ``inv`` becomes ``G``) and the fused pass at the end
    consumes them; split into functions, each would need its own copies of these arrays,
    which is the memory and time the O(N n) design avoids (see the module doc).
    """
    s = np.asarray(s, dtype=complex)
    n = device.n
    N = s.size
    bb = device.dampings
    g = device.ground_dampings
    if impedances is None:
        node, elem = node_element_impedances(device, s, termination)
    else:
        node, elem = impedances
        if termination is not None:
            node = node.copy()
            node[-1] += termination

    if n == 1:
        y = 1.0 / node[0]
        re = _abs2(y) * (g[0] + (0.0 if termination is None else np.asarray(re_termination, float)))
        zero = np.zeros(N, dtype=complex)
        return ChainResponse(s=s, y11=y, y22=y, y12=-y, re_y11=re, re_y22=re, x=zero,
                             sensor_from_handle=np.ones(N, dtype=complex), sensor_from_actuator=zero)

    # every (n-1) x N or N array below that is not returned is a work array of the thread's
    # workspace (see _Workspace), reused from call to call
    ws = _workspace
    # right sweep: R[i] = impedance of nodes i..n-1 seen at node i; v_{i+1} = v_i t_i and
    # nu_i = v_i - v_{i+1} = v_i r_i with r_i = R_{i+1}/(z_i + R_{i+1}) (no subtraction)
    t = ws.get("t", (n - 1, N))
    r = ws.get("r", (n - 1, N))
    # 1/(z_i + R_{i+1}), kept for the minors below (one row buffer when they are not wanted)
    inv_all = ws.get("inv", (n - 1, N)) if want_x else None
    buf = ws.get("row0", (N,))
    R_next = ws.get("row1", (N,))
    R = node[n - 1]
    for i in range(n - 2, -1, -1):
        e = elem[i]
        inv = buf if inv_all is None else inv_all[i]
        np.add(e, R, out=inv)
        np.divide(1.0, inv, out=inv)
        np.multiply(e, inv, out=t[i])
        np.multiply(R, inv, out=r[i])
        R = np.multiply(e, r[i], out=R_next)
        R += node[i]
    v = ws.get("v", (n, N))
    np.divide(1.0, R, out=v[0])
    for i in range(n - 1):
        np.multiply(v[i], t[i], out=v[i + 1])
    # with the minors, nu and the damper sums are formed in one blocked pass at the end
    fused = want_x and bool(np.any(bb))
    if not fused:
        nu = np.multiply(v[:-1], r, out=r)  # r is not needed any more: reuse its memory

    # left sweep: L[i] = impedance of nodes 0..i seen at node i (node n-1 carries the
    # termination); w_i = w_{i+1} tl_i, om_i = w_i - w_{i+1} = -w_{i+1} rl_i
    if want_left:
        tl = ws.get("tl", (n - 1, N))
        rl = ws.get("rl", (n - 1, N))
        inv, L_next = ws.get("row2", (N,)), ws.get("row3", (N,))
        L = node[0]
        for i in range(1, n):
            e = elem[i - 1]
            np.add(e, L, out=inv)
            np.divide(1.0, inv, out=inv)
            np.multiply(e, inv, out=tl[i - 1])
            np.multiply(L, inv, out=rl[i - 1])
            L = np.multiply(e, rl[i - 1], out=L_next)
            L += node[i]
        w = ws.get("w", (n, N))
        np.divide(1.0, L, out=w[n - 1])
        for i in range(n - 2, -1, -1):
            np.multiply(w[i + 1], tl[i], out=w[i])
        om_neg = np.multiply(w[1:], rl, out=rl)  # -om: the sign only matters for the gauge reading
    else:  # the same continued fraction seen from the actuator end: L <- node_i + e L / (e + L)
        y22_only = continued_fraction(node[::-1], elem[::-1], node[0].copy(), work=ws.get("row2", (N,)))
        np.divide(1.0, y22_only, out=y22_only)

    # real parts as dissipated power (non-negative terms only)
    gi = np.flatnonzero(g)  # usually one damper to ground: touch only those rows
    re11 = np.zeros(N)
    if not fused and np.any(bb):
        re11 += _wabs2(bb, nu, ws)
    if gi.size:
        re11 += _wabs2(g[gi], _rows(v, gi, ws), ws)
    if termination is not None and re_termination is not None:
        re11 += np.asarray(re_termination, float) * _abs2(v[n - 1])
    if want_left:
        re22 = np.zeros(N)
        if np.any(bb):
            re22 += _wabs2(bb, om_neg, ws)
        if gi.size:
            re22 += _wabs2(g[gi], _rows(w, gi, ws), ws)
        if termination is not None and re_termination is not None:
            re22 += np.asarray(re_termination, float) * _abs2(w[n - 1])

    # X by the minors (Casoratian), propagated from the actuator end in scaled variables:
    # P~_{n-1} = 0, phi^_{n-2} = 1; phi^_{k-1} = t_k phi^_k + (m_k s + g_k) P~_k,
    # P~_{k-1} = t_{k-1} (P~_k + phi^_{k-1}/z_{k-1}); node minor = v_k P~_k,
    # element minor = v_{k+1} phi^_k / z_k.
    # With t_k / z_k = 1/(z_k + R_{k+1}) = inv_k (right sweep) and G_k = inv_k phi^_k (no
    # division): P~_{k-1} = t_{k-1} P~_k + G_{k-1} and element minor = v_k G_k.
    if want_x:
        gx = gi[gi < n - 1]  # P~_{n-1} = 0: a damper on the actuator mass adds nothing here
        keep = set(gx.tolist())
        P_rows = {}
        G = inv_all  # overwritten in place: inv_k -> G_k
        Pk = G[n - 2]  # phi^_{n-2} = 1: P~_{n-2} = G_{n-2} = inv_{n-2}
        if n - 2 in keep:
            P_rows[n - 2] = Pk.copy()
        phi = None
        phi_rows = (ws.get("row2", (N,)), ws.get("row3", (N,)))  # phi^_k and phi^_{k-1}, alternating
        P_next = ws.get("row1", (N,))
        for k in range(n - 2, 0, -1):
            # phi^_{k-1} = t_k phi^_k + node_k P~_k  (phi^_{n-2} = 1)
            nP = np.multiply(node[k], Pk, out=phi_rows[k % 2])
            nP += t[k] if phi is None else np.multiply(t[k], phi, out=phi)
            phi = nP
            np.multiply(G[k - 1], phi, out=G[k - 1])
            Pk = np.multiply(t[k - 1], Pk, out=P_next)
            Pk += G[k - 1]
            if k - 1 in keep:
                P_rows[k - 1] = Pk.copy()
        if fused:
            nu, re_b, x = _damper_sums(bb, v, r, G, ws)
            re11 += re_b
        else:
            x = np.zeros(N, dtype=complex)
        if gx.size:
            Pg = np.array([P_rows[j] for j in gx.tolist()])
            x = x + _wsum(g[gx], _abs2(v[gx]) * Pg)
    else:
        x = np.zeros(N, dtype=complex)

    se = device.sensor_element
    y12 = -v[n - 1]
    if not want_left:
        # Re X = Re y11 Re y22 - (Re y12)^2, so Re y22 = (Re X + (Re y12)^2) / Re y11 (both >= 0)
        re22 = (x.real + y12.real ** 2) / re11
    return ChainResponse(
        s=s,
        y11=v[0].copy(),
        y22=w[n - 1].copy() if want_left else y22_only,
        y12=y12,
        re_y11=re11,
        re_y22=re22,
        x=x,
        sensor_from_handle=elem[se] * nu[se],  # F_meas = z_s (v_s - v_{s+1})
        sensor_from_actuator=-elem[se] * om_neg[se] if want_left else None,  # per unit force on node n-1
    )
