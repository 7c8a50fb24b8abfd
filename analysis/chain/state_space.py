"""The one state space of the chain (Adams, Moreyra & Hannaford, eq. 25).

Canonical realization
---------------------
:func:`chain_state_space` writes ``M q'' + B q' + K q = f`` (``M, B, K`` from
:meth:`analysis.chain.Device.matrices`) in absolute coordinates ``X = (q, q')``, ``2n`` states,
with two inputs: ``F_d`` applied as ``-F_d`` to the actuator mass (eq. 25) and an external force
on the handle.  A human grasp (mass, damper and spring from the handle to ground) and extra
dampers to ground (the simulator's stick regime of Coulomb friction) are added here, so that
the sampled-data loop (:mod:`analysis.sampled`) and every other user share one model.

Minimal handle realization
--------------------------
The chain has no spring to ground, so with ``D`` the ``(n-1) x n`` difference matrix
(``d_i = q_i - q_{i+1}``) ``K = D^T diag(k) D``.  In the coordinates ``Z = (d, q') = S X``,
``S = diag(D, I)``, the rigid-body position drops out and the realization
``d' = D q'``, ``q'' = -M^{-1} D^T diag(k) d - M^{-1} B q' + M^{-1} e_0 F_h`` is minimal for the
handle admittance ``y11`` (force at the handle to handle velocity; the collocated plant ``P(s)``
of Eom, Suh & Yi, eq. 7, for a chain).  :func:`handle_state_space` builds it from the canonical
matrices by this transform: the velocity rows are copied, and the spring block
``-M^{-1} D^T diag(k)`` is read exactly (by sign changes only) from the off-diagonal entries of
``-M^{-1} K``.
"""

from __future__ import annotations

import numpy as np

from analysis.chain.device import Device

__all__ = ["chain_state_space", "handle_state_space"]


def chain_state_space(device: Device, handle_mass=(0.0,), handle_damping=(0.0,), handle_stiffness=(0.0,),
                      friction_damping: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Continuous ``A`` (G, 2n, 2n) and ``B`` (G, 2n, 2) in ``X = (q, q')``; inputs ``(F_d, F_ext)``.

    One realization per grasp: ``handle_mass``, ``handle_damping`` and ``handle_stiffness``
    (length G) are added to the handle (mass 0) and from it to ground.  ``friction_damping``
    (length n) adds dampers to ground.

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.
    handle_mass : array_like, optional
        Grasp masses added to the handle [kg], shape (G,).
    handle_damping : array_like, optional
        Grasp dampers from the handle to ground [N s/m], shape (G,).
    handle_stiffness : array_like, optional
        Grasp springs from the handle to ground [N/m], shape (G,).
    friction_damping : numpy.ndarray or None, optional
        Extra dampers from each mass to ground [N s/m], shape (n,); ``None`` for none.

    Returns
    -------
    A : numpy.ndarray
        State matrices [1/s], shape (G, 2n, 2n).
    B : numpy.ndarray
        Input matrices (columns ``F_d`` and ``F_ext``) [1/kg], shape (G, 2n, 2).
    """
    n = device.n
    M, Bm, K = device.matrices()
    mh = np.asarray(handle_mass, dtype=float)
    bh = np.asarray(handle_damping, dtype=float)
    kh = np.asarray(handle_stiffness, dtype=float)
    G = mh.size
    Ms = np.broadcast_to(np.diag(M), (G, n)).copy()
    Ms[:, 0] += mh
    Bs = np.broadcast_to(Bm, (G, n, n)).copy()
    Bs[:, 0, 0] += bh
    if friction_damping is not None:
        Bs[:, np.arange(n), np.arange(n)] += np.asarray(friction_damping, float)
    Ks = np.broadcast_to(K, (G, n, n)).copy()
    Ks[:, 0, 0] += kh
    inv = 1.0 / Ms[:, :, None]
    A = np.zeros((G, 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -Ks * inv
    A[:, n:, n:] = -Bs * inv
    Bu = np.zeros((G, 2 * n, 2))
    Bu[:, 2 * n - 1, 0] = -1.0 / Ms[:, n - 1]
    Bu[:, n, 1] = 1.0 / Ms[:, 0]
    return A, Bu


def handle_state_space(device: Device) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Minimal ``(A, B, C)`` of ``y11``: states ``(d_0..d_{n-2}, v_0..v_{n-1})``, input the handle
    force, output the handle velocity (see the module doc for the transform from
    :func:`chain_state_space`).

    Parameters
    ----------
    device : Device
        The chain of ``n`` masses.

    Returns
    -------
    A : numpy.ndarray
        State matrix, shape (2n - 1, 2n - 1).
    B : numpy.ndarray
        Input matrix (the handle force) [1/kg], shape (2n - 1, 1).
    C : numpy.ndarray
        Output matrix (the handle velocity), shape (1, 2n - 1).
    """
    n = device.n
    Ax, Bx = chain_state_space(device)
    Ax, Bx = Ax[0], Bx[0]
    avq = Ax[n:, :n]  # -M^{-1} K
    N = 2 * n - 1
    A = np.zeros((N, N))
    i = np.arange(n - 1)
    A[i, n - 1 + i] = 1.0  # d_i' = v_i - v_{i+1}
    A[i, n + i] = -1.0
    A[n - 1 + i, i] = -avq[i, i + 1]  # element i pulls mass i back: -k_i/m_i
    A[n + i, i] = avq[i + 1, i]  # and pushes mass i+1: +k_i/m_{i+1}
    A[n - 1:, n - 1:] = Ax[n:, n:]  # -M^{-1} B
    B = np.zeros((N, 1))
    B[n - 1:, 0] = Bx[n:, 1]  # the handle force
    C = np.zeros((1, N))
    C[0, n - 1] = 1.0
    return A, B, C
