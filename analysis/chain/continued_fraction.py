"""The one continued fraction of the chain: its driving-point impedance at the handle.

The chain's impedance matrix ``A(s) = M s + B + K/s`` (Adams, Moreyra & Hannaford, eq. 25) is
tridiagonal, so the impedance seen at the handle (mass 0) follows from the actuator end by the
right continued-fraction sweep

    ``R_{n-1} = m_{n-1} s + g_{n-1} (+ a termination)``,
    ``R_i = m_i s + g_i + z_i R_{i+1} / (z_i + R_{i+1})``,  ``z_i = b_i + k_i/s``,

four operations per mass.  ``1/R_0 = y11`` is the handle admittance of eq. (26), the device
``P(s)`` of Eom, Suh & Yi (eq. 7) when the device is a chain.  Every handle impedance in zwidth
(:mod:`analysis.twoport.impedance`, :mod:`analysis.transparency`) is computed here.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from analysis.chain.device import Device

__all__ = [
    "continued_fraction",
    "node_element_impedances",
    "chain_impedances",
    "frozen_impedances",
    "handle_impedance",
    "terminated_handle_impedance",
    "handle_impedance_at",
    "handle_admittance",
]


def continued_fraction(node: Sequence, elem: Sequence, R, work: np.ndarray | None = None):
    """``R <- node_i + z_i R / (z_i + R)`` for ``i = n-2 .. 0``; returns ``R_0``.

    This is a numerical kernel: the sweep is kept in one piece so that the array form (in place, no
    temporaries per mass) and the Python-complex form (one frequency, no per-mass array
    overhead) perform the same floating-point operations in the same order (Python's and
    numpy's complex division may still differ in the last bit).  ``node`` has ``n`` entries,
    ``elem`` ``n - 1``; ``R`` is ``R_{n-1}`` (an array is overwritten).  ``work``, an array of
    ``R``'s shape and dtype, is used as the sweep's one temporary instead of a new one.

    Parameters
    ----------
    node : sequence of complex or of numpy.ndarray
        The ``n`` node impedances ``m_i s + g_i`` [N s/m], each a Python complex or an array of
        shape (N,) (one value per frequency).
    elem : sequence of complex or of numpy.ndarray
        The ``n - 1`` element impedances ``z_i = b_i + k_i/s`` [N s/m], of the same kind as
        ``node``.
    R : complex or numpy.ndarray
        ``R_{n-1}``, the impedance at the actuator node [N s/m]; a complex array of shape (N,)
        is overwritten with the result.
    work : numpy.ndarray or None, optional
        A scratch array of ``R``'s shape and dtype used as the sweep's temporary; ``None``
        allocates one.  Ignored when ``R`` is a Python number.

    Returns
    -------
    complex or numpy.ndarray
        ``R_0``, the driving-point impedance at the handle [N s/m]: a Python complex, or the
        array ``R`` itself (shape (N,)).
    """
    if isinstance(R, np.ndarray):
        d = np.empty_like(R) if work is None else work
        for i in range(len(elem) - 1, -1, -1):
            e = elem[i]
            np.add(e, R, out=d)
            np.multiply(e, R, out=R)
            np.divide(R, d, out=R)
            np.add(R, node[i], out=R)
        return R
    for i in range(len(elem) - 1, -1, -1):
        e = elem[i]
        R = node[i] + e * R / (e + R)
    return R


def node_element_impedances(device: Device, s: np.ndarray,
                            termination: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Node impedances ``m_i s + g_i`` (n x N) and element impedances ``b_i + k_i/s`` (writable).

    On the unit circle the Tustin image is purely imaginary, ``s = j W``; then the arrays
    are filled part by part (see :func:`frozen_impedances`).  ``termination`` is added to the
    actuator node.

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    s : numpy.ndarray
        Complex frequencies [rad/s], shape (N,).
    termination : numpy.ndarray or None, optional
        An impedance from the actuator mass to ground [N s/m], shape (N,) or scalar, added to
        the last node; ``None`` adds nothing.

    Returns
    -------
    node : numpy.ndarray
        Node impedances ``m_i s + g_i`` [N s/m], complex, shape (n, N), writable.
    elem : numpy.ndarray
        Element impedances ``b_i + k_i/s`` [N s/m], complex, shape (n - 1, N), writable.
    """
    if not np.any(s.real):
        node, elem = _impedances_jw(device, s.imag)
    else:
        m = device.masses
        node = m[:, None] * s[None, :] + device.ground_dampings[:, None]
        with np.errstate(divide="ignore", invalid="ignore"):
            inv_s = 1.0 / s
        elem = device.dampings[:, None] + device.stiffnesses[:, None] * inv_s[None, :]
    if termination is not None:
        node[-1] += termination
    return node, elem


def _impedances_jw(device: Device, W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Node and element impedances at ``s = j W`` (W real, shape N).

    Real and imaginary parts are written into an ``(rows, N, 2)`` float buffer that is then
    viewed as complex (about 8x faster than complex broadcasting for long chains, and
    faster than writing the strided ``.real``/``.imag`` views).
    """
    m = device.masses
    n, N = m.size, W.size
    fn = np.empty((n, N, 2))
    fn[:, :, 0] = device.ground_dampings[:, None]
    np.multiply.outer(m, W, out=fn[:, :, 1])
    fe = np.empty((n - 1, N, 2))
    fe[:, :, 0] = device.dampings[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        np.multiply.outer(-device.stiffnesses, 1.0 / W, out=fe[:, :, 1])
    return fn.view(complex)[:, :, 0], fe.view(complex)[:, :, 0]


def chain_impedances(device: Device, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Node impedances ``m_i s + g_i`` and element impedances ``b_i + k_i/s`` (read-only).

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    s : array_like
        Complex frequencies [rad/s], shape (N,).

    Returns
    -------
    node : numpy.ndarray
        Node impedances [N s/m], complex, shape (n, N), read-only.
    elem : numpy.ndarray
        Element impedances [N s/m], complex, shape (n - 1, N), read-only.
    """
    node, elem = node_element_impedances(device, np.asarray(s, dtype=complex))
    node.setflags(write=False)
    elem.setflags(write=False)
    return node, elem


def frozen_impedances(device: Device, W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`chain_impedances` at ``s = j W`` (W real), read-only.

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    W : array_like
        Real frequencies [rad/s] (for a sampled display, the Tustin image of the angular
        frequency), shape (N,).

    Returns
    -------
    node : numpy.ndarray
        Node impedances ``g_i + j m_i W`` [N s/m], complex, shape (n, N), read-only.
    elem : numpy.ndarray
        Element impedances ``b_i - j k_i/W`` [N s/m], complex, shape (n - 1, N), read-only.
    """
    node, elem = _impedances_jw(device, np.asarray(W, dtype=float))
    node.setflags(write=False)
    elem.setflags(write=False)
    return node, elem


def handle_impedance(device: Device, s: np.ndarray, termination: np.ndarray | None = None,
                     impedances: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Driving-point impedance at the handle (mass 0), optionally with an impedance from
    the actuator mass to ground (:func:`continued_fraction`).

    ``impedances`` may pass the (node, element) arrays of :func:`chain_impedances` for the
    same ``s`` (they depend on the device only), so that a coupling change does not rebuild
    them; they are not modified.

    Parameters
    ----------
    device : Device
        The chain.
    s : array_like
        Complex frequencies [rad/s], shape (N,).
    termination : numpy.ndarray or None, optional
        An impedance from the actuator mass to ground [N s/m], shape (N,) or scalar; ``None``
        leaves the actuator end free.
    impedances : tuple of numpy.ndarray or None, optional
        The ``(node, elem)`` arrays of :func:`chain_impedances` at the same ``s``; ``None``
        builds them.

    Returns
    -------
    numpy.ndarray
        The handle impedance ``R_0 = 1/y11`` [N s/m], complex, shape (N,); inf or nan at an
        exact pole.
    """
    s = np.asarray(s, dtype=complex)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        node, elem = node_element_impedances(device, s) if impedances is None else impedances
        R = node[-1].copy() if termination is None else node[-1] + termination
        return continued_fraction(node, elem, R)


def terminated_handle_impedance(device: Device, impedances: tuple[np.ndarray, np.ndarray],
                                termination: np.ndarray) -> np.ndarray:
    """:func:`handle_impedance` from prebuilt impedances, with a termination.

    Parameters
    ----------
    device : Device
        The chain (its impedances are ``impedances``).
    impedances : tuple of numpy.ndarray
        The ``(node, elem)`` arrays of :func:`chain_impedances`, shapes (n, N) and (n - 1, N);
        not modified.
    termination : numpy.ndarray
        The impedance from the actuator mass to ground [N s/m], shape (N,) or scalar.

    Returns
    -------
    numpy.ndarray
        The handle impedance [N s/m], complex, shape (N,).
    """
    node, elem = impedances
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return continued_fraction(node, elem, node[-1] + termination)


def handle_impedance_at(device: Device, W: float) -> complex | None:
    """:func:`handle_impedance` at the single frequency ``s = j W``, in Python complex arithmetic
    (the same operations, without per-mass array overhead).  ``None`` on an exact pole
    (division by zero) or overflow; :func:`handle_impedance` then gives numpy's inf/nan.

    Parameters
    ----------
    device : Device
        The chain.
    W : float
        The real frequency [rad/s] of ``s = j W``.

    Returns
    -------
    complex or None
        The handle impedance [N s/m], or ``None`` on an exact pole or overflow.
    """
    m, g = device.masses.tolist(), device.ground_dampings.tolist()
    b, k = device.dampings.tolist(), device.stiffnesses.tolist()
    inv_w = 1.0 / W
    node = [complex(gi, mi * W) for gi, mi in zip(g, m)]
    elem = [complex(bi, -ki * inv_w) for bi, ki in zip(b, k)]
    try:
        return continued_fraction(node, elem, node[-1])
    except (ZeroDivisionError, OverflowError):
        return None


def handle_admittance(device: Device, s) -> np.ndarray:
    """``P(s) = y11(s)`` of a chain: handle velocity per unit handle force (eq. 26; the device
    of Eom, Suh & Yi, eq. 7, read at the handle).

    Parameters
    ----------
    device : Device
        The chain.
    s : array_like
        Complex frequencies [rad/s], shape (N,).

    Returns
    -------
    numpy.ndarray
        ``y11(s)`` [m/(N s)], complex, shape (N,).
    """
    return 1.0 / handle_impedance(device, np.asarray(s, dtype=complex))
