"""Frequency response of the lumped-mass chain in O(n) per frequency.

The chain's impedance matrix ``A(s) = M s + B + K/s`` (eq. 25) is tridiagonal.  Instead of
an n-by-n solve per frequency, the responses to a unit force at either end are obtained
from continued-fraction sweeps (driving-point impedance of the sub-chain to the right or
left of a node) and products of transfer ratios.  Everything is vectorized over frequency
and costs O(N n) time and memory.

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

from dataclasses import dataclass

import numpy as np

from .device import Device

__all__ = ["ChainResponse", "chain_response", "chain_impedances", "handle_impedance"]


@dataclass(frozen=True)
class ChainResponse:
    """Continuous responses of the chain at the complex frequencies ``s`` (shape N).

    Attributes (all arrays of shape ``(N,)`` unless stated)
    ----------------------------------------------------------
    y11, y22, y12:
        Continuous two-port admittance with the port convention of eq. (26):
        ``y11 = v_h/F_h``, ``y22 = (-v_d)/F_d``, ``y12 = y21 = v_h/F_d``.
    re_y11, re_y22:
        Their real parts as dissipated powers (non-negative, cancellation-free).
    x:
        ``Re y11 Re y22 - (Re y12)^2 + j (Re y11 Im y22 - Re y12 Im y12)``, accurate.
    sensor_from_handle, sensor_from_actuator:
        Gauge force per unit ``F_h`` and per unit force *on* the actuator mass (N x 1).
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


def _abs2(a: np.ndarray) -> np.ndarray:
    return a.real * a.real + a.imag * a.imag


def _wabs2(weights: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``sum_i weights_i |rows_i|^2`` over the chain, on the contiguous float view.

    (``a.real * a.real + a.imag * a.imag`` on 2-D complex arrays walks strided memory and is
    about 10x slower for long chains.)
    """
    f = rows.view(np.float64)
    acc = np.einsum("i,ij->j", weights, f * f)
    return acc[0::2] + acc[1::2]


def _wsum(weights: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``weights @ rows`` without BLAS (its threads only add latency at these sizes)."""
    return np.einsum("i,ij->j", weights, rows)


def _impedances(device: Device, s: np.ndarray, termination: np.ndarray | None):
    """Node impedances ``m_i s + g_i`` (n x N) and element impedances ``b_i + k_i/s``.

    On the unit circle the Tustin image is purely imaginary, ``s = j W``; then the arrays
    are filled part by part (about 8x faster than complex broadcasting for long chains).
    """
    m, g = device.masses, device.ground_dampings
    n, N = m.size, s.size
    if not np.any(s.real):
        W = s.imag
        node = np.empty((n, N), dtype=complex)
        node.real[...] = g[:, None]
        np.multiply.outer(m, W, out=node.imag)
        elem = np.empty((n - 1, N), dtype=complex)
        elem.real[...] = device.dampings[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            np.multiply.outer(-device.stiffnesses, 1.0 / W, out=elem.imag)
    else:
        node = m[:, None] * s[None, :] + g[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            inv_s = 1.0 / s
        elem = device.dampings[:, None] + device.stiffnesses[:, None] * inv_s[None, :]
    if termination is not None:
        node[-1] += termination
    return node, elem


def handle_impedance(device: Device, s: np.ndarray, termination: np.ndarray | None = None,
                     impedances: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Driving-point impedance at the handle (mass 0), optionally with an impedance from
    the actuator mass to ground.  Right continued-fraction sweep only: 4 operations per mass.

    ``impedances`` may pass the (node, element) arrays of :func:`chain_impedances` for the
    same ``s`` (they depend on the device only), so that a coupling change does not rebuild
    them.
    """
    s = np.asarray(s, dtype=complex)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        node, elem = _impedances(device, s, None) if impedances is None else impedances
        R = node[-1] if termination is None else node[-1] + termination
        for i in range(device.n - 2, -1, -1):
            e = elem[i]
            R = node[i] + e * R / (e + R)
    return R


def chain_impedances(device: Device, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Node impedances ``m_i s + g_i`` and element impedances ``b_i + k_i/s`` (read-only)."""
    node, elem = _impedances(device, np.asarray(s, dtype=complex), None)
    node.setflags(write=False)
    elem.setflags(write=False)
    return node, elem


def chain_response(device: Device, s: np.ndarray, termination: np.ndarray | None = None,
                   re_termination: np.ndarray | None = None, want_x: bool = True,
                   want_left: bool = True) -> ChainResponse:
    """Responses of the chain at complex frequencies ``s`` (see :func:`_chain_response`).

    A lossless chain has exact poles on the imaginary axis; there the responses are
    infinite.  No floating-point warning is raised: the callers map the resulting
    non-finite bounds to ``+inf`` with the ``singular`` flag.

    With ``want_left=False`` the responses to a force on the actuator are not formed (only
    ``y22``, by a continued fraction): ``re_y22`` is then ``(Re X + (Re y12)^2)/Re y11``
    (requires ``want_x``) and ``sensor_from_actuator`` is ``None``.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _chain_response(device, s, termination, re_termination, want_x, want_left)


def _chain_response(device: Device, s: np.ndarray, termination: np.ndarray | None,
                    re_termination: np.ndarray | None, want_x: bool, want_left: bool) -> ChainResponse:
    """Responses of the chain at complex frequencies ``s``.

    ``termination`` is an impedance (per frequency) from the actuator mass to ground,
    e.g. the PD loop seen through the hold; ``re_termination`` is its exact real part
    (dissipation), given separately so that no cancellation enters.

    Only the continued-fraction sweeps and the minor propagation are sequential over the
    chain (about 18 array operations per mass); node velocities follow from cumulative
    products of transfer ratios and the dissipation sums are reductions over the chain.
    """
    s = np.asarray(s, dtype=complex)
    n = device.n
    N = s.size
    bb = device.dampings
    g = device.ground_dampings
    node, elem = _impedances(device, s, termination)

    if n == 1:
        y = 1.0 / node[0]
        re = _abs2(y) * (g[0] + (0.0 if termination is None else np.asarray(re_termination, float)))
        zero = np.zeros(N, dtype=complex)
        return ChainResponse(s=s, y11=y, y22=y, y12=-y, re_y11=re, re_y22=re, x=zero,
                             sensor_from_handle=np.ones(N, dtype=complex), sensor_from_actuator=zero)

    # right sweep: R[i] = impedance of nodes i..n-1 seen at node i; v_{i+1} = v_i t_i and
    # nu_i = v_i - v_{i+1} = v_i r_i with r_i = R_{i+1}/(z_i + R_{i+1}) (no subtraction)
    t = np.empty((n - 1, N), dtype=complex)
    r = np.empty((n - 1, N), dtype=complex)
    R = node[n - 1]
    for i in range(n - 2, -1, -1):
        e = elem[i]
        inv = 1.0 / (e + R)
        np.multiply(e, inv, out=t[i])
        np.multiply(R, inv, out=r[i])
        R = node[i] + e * r[i]
    v = np.empty((n, N), dtype=complex)
    v[0] = 1.0 / R
    for i in range(n - 1):
        np.multiply(v[i], t[i], out=v[i + 1])
    nu = np.multiply(v[:-1], r, out=r)  # r is not needed any more: reuse its memory

    # left sweep: L[i] = impedance of nodes 0..i seen at node i (node n-1 carries the
    # termination); w_i = w_{i+1} tl_i, om_i = w_i - w_{i+1} = -w_{i+1} rl_i
    if want_left:
        tl = np.empty((n - 1, N), dtype=complex)
        rl = np.empty((n - 1, N), dtype=complex)
        L = node[0]
        for i in range(1, n):
            e = elem[i - 1]
            inv = 1.0 / (e + L)
            np.multiply(e, inv, out=tl[i - 1])
            np.multiply(L, inv, out=rl[i - 1])
            L = node[i] + e * rl[i - 1]
        w = np.empty((n, N), dtype=complex)
        w[n - 1] = 1.0 / L
        for i in range(n - 2, -1, -1):
            np.multiply(w[i + 1], tl[i], out=w[i])
        om_neg = w[1:] * rl  # -om: the sign only matters for the gauge reading below
    else:
        L = node[0]
        for i in range(1, n):
            e = elem[i - 1]
            L = node[i] + e * L / (e + L)
        y22_only = 1.0 / L

    # real parts as dissipated power (non-negative terms only)
    gi = np.flatnonzero(g)  # usually one damper to ground: touch only those rows
    re11 = np.zeros(N)
    if np.any(bb):
        re11 = re11 + _wabs2(bb, nu)
    if gi.size:
        re11 = re11 + _wabs2(g[gi], v[gi])
    if termination is not None and re_termination is not None:
        re11 = re11 + np.asarray(re_termination, float) * _abs2(v[n - 1])
    if want_left:
        re22 = np.zeros(N)
        if np.any(bb):
            re22 = re22 + _wabs2(bb, om_neg)
        if gi.size:
            re22 = re22 + _wabs2(g[gi], w[gi])
        if termination is not None and re_termination is not None:
            re22 = re22 + np.asarray(re_termination, float) * _abs2(w[n - 1])

    # X by the minors (Casoratian), propagated from the actuator end in scaled variables:
    # P~_{n-1} = 0, phi^_{n-2} = 1; phi^_{k-1} = t_k phi^_k + (m_k s + g_k) P~_k,
    # P~_{k-1} = t_{k-1} (P~_k + phi^_{k-1}/z_{k-1}); node minor = v_k P~_k,
    # element minor = v_{k+1} phi^_k / z_k.
    if want_x:
        phi = np.ones(N, dtype=complex)
        Q = np.empty((n - 1, N), dtype=complex)  # phi^_k / z_k
        P = np.empty((n, N), dtype=complex)
        P[n - 1] = 0.0
        np.divide(phi, elem[n - 2], out=Q[n - 2])
        P[n - 2] = t[n - 2] * Q[n - 2]
        for k in range(n - 2, 0, -1):
            phi = t[k] * phi + node[k] * P[k]
            np.divide(phi, elem[k - 1], out=Q[k - 1])
            P[k - 1] = t[k - 1] * (P[k] + Q[k - 1])
        x = np.zeros(N, dtype=complex)
        if np.any(bb):
            tmp = np.conjugate(nu)
            tmp *= v[1:]
            tmp *= Q
            x = x + _wsum(bb, tmp)
        gx = gi[gi < n - 1]  # P~_{n-1} = 0: a damper on the actuator mass adds nothing here
        if gx.size:
            x = x + _wsum(g[gx], _abs2(v[gx]) * P[gx])
    else:
        x = np.zeros(N, dtype=complex)

    se = device.sensor_element
    y12 = -v[n - 1]
    if not want_left:
        # Re X = Re y11 Re y22 - (Re y12)^2, so Re y22 = (Re X + (Re y12)^2) / Re y11 (both >= 0)
        re22 = (x.real + y12.real ** 2) / re11
    return ChainResponse(
        s=s,
        y11=v[0],
        y22=w[n - 1] if want_left else y22_only,
        y12=y12,
        re_y11=re11,
        re_y22=re22,
        x=x,
        sensor_from_handle=elem[se] * nu[se],  # F_meas = z_s (v_s - v_{s+1})
        sensor_from_actuator=-elem[se] * om_neg[se] if want_left else None,  # per unit force on node n-1
    )
