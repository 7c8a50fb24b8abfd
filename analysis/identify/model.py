"""Model responses of the chain for the measured quantities, continuous and exact ZOH-sampled.

The chain is Adams, Moreyra & Hannaford's eq. (25): masses ``m_i`` (handle ``i = 0``, actuator
``i = n - 1``), elements ``k_i + b_i s`` between mass ``i`` and ``i + 1``, dampers ``g_i`` to
ground.  The input is the actuator force ``F`` *on* the actuator mass (positive along ``x``;
the paper's ``F_d`` enters eq. 25 as ``-F_d``).  Quantities:

``actuator``  ``x_{n-1} / F`` (m/N), the collocated encoder measurement;
``handle``    ``x_0 / F`` (m/N), an external sensor on the handle (handle free only);
``gauge``     ``F_meas / F`` with ``F_meas = k_s (x_s - x_{s+1}) + b_s (x_s' - x_{s+1}')`` of the
              gauge on element ``s`` (eq. 27 as read in the design notes; ``-m_0/M`` at DC with
              the handle free, ``-1`` with it clamped).

Boundary ``free``: nothing holds the handle; ``clamped``: ``x_0 = 0``.

Continuous (:func:`continuous_response`, ``s = j w``)
    Cancellation-free continued fraction in dynamic stiffnesses ``a_i = m_i s^2 + g_i s``,
    ``c_i = k_i + b_i s``: ``L_0 = a_0`` (free; clamped: ``L_1 = a_1 + c_0``),
    ``L_i = a_i + c_{i-1} L_{i-1} / (c_{i-1} + L_{i-1})``, ``x_{n-1} / F = 1 / L_{n-1}``.
    Displacements follow from transfer ratios ``x_{i-1} = x_i c_{i-1} / (c_{i-1} + L_{i-1})`` and
    the gauge from the force balance of the sub-chain left of the gauge,
    ``F_meas = -L_s x_s`` (no difference of nearly equal displacements is ever formed, so
    antiresonances keep their relative accuracy).
Sampled (:func:`sampled_response`)
    Exact zero-order-hold response for a force through a ZOH and a sampled output with a delay of
    ``d`` samples: ``H(e^{jwT}) = C (zI - Phi)^{-1} Gamma z^{-d}`` with ``(Phi, Gamma)`` the exact
    ZOH discretization of the state space of eq. (25), evaluated in modal form (the same
    ``Phi`` and ``Gamma`` as :func:`analysis.chain.discretize_zoh`), not by a Tustin or
    half-sample approximation.  The rigid-body position is an integral of the actuator velocity,
    handled in closed form, so the state matrix has no defective double eigenvalue at 0.
"""

from __future__ import annotations

import numpy as np

from analysis.identify.params import ChainParameters

__all__ = ["MEASURED_QUANTITIES", "QUANTITIES", "BOUNDARIES", "continuous_response", "sampled_response", "response",
           "state_space"]

#: What a measured frequency response is of: the actuator's, the handle's or the gauge's
#: (``analysis.study.QUANTITIES`` is another thing: the results zwidth names and prints).
MEASURED_QUANTITIES = ("actuator", "handle", "gauge")
#: deprecated alias of :data:`MEASURED_QUANTITIES` (one release)
QUANTITIES = MEASURED_QUANTITIES
BOUNDARIES = ("free", "clamped")


def check_quantity(quantity: str, boundary: str, n: int, sensor_element: int) -> None:
    """Refuse combinations without a meaning (a clamped handle does not move, ...)."""
    from analysis.errors import ValidationError

    if quantity not in MEASURED_QUANTITIES:
        raise ValidationError("quantity", " | ".join(MEASURED_QUANTITIES), quantity)
    if boundary not in BOUNDARIES:
        raise ValidationError("boundary", " | ".join(BOUNDARIES), boundary)
    if boundary == "clamped" and (n < 2 or quantity == "handle"):
        raise ValidationError("boundary", "free (a clamped handle does not move; a clamped "
                              "1-mass chain has no actuator left)", boundary)
    if quantity == "gauge" and not 0 <= sensor_element < n - 1:
        raise ValidationError("sensor_element", f"0..{n - 2} (the gauge needs an element)", sensor_element)


def continuous_response(params: ChainParameters, w: np.ndarray, quantity: str = "actuator",
                        boundary: str = "free", sensor_element: int = 0) -> np.ndarray:
    """Continuous response (P, F) at ``s = j w`` by the continued fraction (module doc).

    This is a numerical kernel: one sweep keeps the continued-fraction values ``L_i`` and the
    transfer ratios together, as every quantity reads them (splitting it would repeat the sweep).

    Parameters
    ----------
    params : ChainParameters
        ``P`` chains of ``n`` masses.
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (F,).
    quantity : str, optional
        ``"actuator"`` (m/N), ``"handle"`` (m/N) or ``"gauge"`` (N/N) (module doc).
    boundary : str, optional
        ``"free"`` or ``"clamped"`` (handle held).
    sensor_element : int, optional
        The element of the gauge, ``0 <= sensor_element < n - 1`` (``gauge`` only).

    Returns
    -------
    numpy.ndarray
        Complex response in the quantity's unit, shape (P, F).

    Raises
    ------
    ValidationError
        For an unknown quantity or boundary, a clamped handle or 1-mass chain, or a gauge
        element outside the chain.
    """
    n = params.n
    check_quantity(quantity, boundary, n, sensor_element)
    s = 1j * np.asarray(w, dtype=float)[None, :]
    a = params.masses[:, :, None] * (s * s)[:, None, :] + params.ground_dampings[:, :, None] * s[:, None, :]
    c = params.stiffnesses[:, :, None] + params.dampings[:, :, None] * s[:, None, :]
    first = 0 if boundary == "free" else 1
    L = np.empty(a.shape, dtype=complex)
    t = np.ones(c.shape, dtype=complex)  # x_i = x_{i+1} t_i
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        L[:, first] = a[:, 0] if first == 0 else a[:, 1] + c[:, 0]
        for i in range(first + 1, n):
            den = c[:, i - 1] + L[:, i - 1]
            t[:, i - 1] = c[:, i - 1] / den
            L[:, i] = a[:, i] + c[:, i - 1] * L[:, i - 1] / den
        xa = 1.0 / L[:, n - 1]
        if quantity == "actuator":
            return xa
        # x_j / x_{n-1} = prod_{i=j}^{n-2} t_i
        if quantity == "handle":
            return xa * np.prod(t[:, : n - 1], axis=1)
        se = sensor_element
        x_next = xa * np.prod(t[:, se + 1: n - 1], axis=1)  # x_{s+1}
        if boundary == "clamped" and se == 0:
            return -c[:, 0] * x_next
        return -L[:, se] * t[:, se] * x_next


def state_space(params: ChainParameters, quantity: str, boundary: str,
                sensor_element: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Batched ``(A, B, C_direct, C_integral)`` of the quantity (eq. 25), input the actuator force.

    The output is ``C_direct X + integral(C_integral X)``.  Handle free: states
    ``(d_0..d_{n-2}, v_0..v_{n-1})`` with ``d_i = x_i - x_{i+1}`` (the rigid-body position is
    not a state, so ``A`` has no double eigenvalue at 0 even without any damper to ground);
    positions are ``x_{n-1} = integral(v_{n-1})`` and ``x_0 = x_{n-1} + sum d_i``.  Handle
    clamped: absolute states ``(x_1..x_{n-1}, v_1..v_{n-1})``, element 0 tied to ground.
    """
    n = params.n
    check_quantity(quantity, boundary, n, sensor_element)
    if boundary == "clamped":
        return _clamped_state_space(params, quantity, sensor_element)
    P, nd = params.count, n - 1
    N = nd + n
    A = np.zeros((P, N, N))
    inv_m = 1.0 / params.masses
    k, b, g = params.stiffnesses, params.dampings, params.ground_dampings
    e = np.arange(nd)  # element e joins mass e (pulled back) and mass e + 1 (pushed)
    A[:, e, nd + e] = 1.0
    A[:, e, nd + e + 1] = -1.0
    A[:, nd + e, e] = -k * inv_m[:, :nd]
    A[:, nd + e + 1, e] = k * inv_m[:, 1:]
    diag = g.copy()  # the damping matrix: g_i + b_{i-1} + b_i on its diagonal, -b_e off it
    diag[:, :nd] += b
    diag[:, 1:] += b
    v = np.arange(n)
    A[:, nd + v, nd + v] = -diag * inv_m
    A[:, nd + e, nd + e + 1] = b * inv_m[:, :nd]
    A[:, nd + e + 1, nd + e] = b * inv_m[:, 1:]
    B = np.zeros((P, N))
    B[:, N - 1] = inv_m[:, n - 1]
    Cd = np.zeros((P, N))
    Ci = np.zeros((P, N))
    if quantity in ("actuator", "handle"):
        Ci[:, N - 1] = 1.0
        if quantity == "handle":
            Cd[:, :nd] = 1.0
    else:
        se = sensor_element
        Cd[:, se] = k[:, se]
        Cd[:, nd + se] = b[:, se]
        Cd[:, nd + se + 1] = -b[:, se]
    return A, B, Cd, Ci


def _clamped_state_space(params: ChainParameters, quantity: str,
                         se: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Absolute states of masses 1..n-1 with the handle held (see :func:`state_space`)."""
    n, P = params.n, params.count
    nodes = n - 1
    K = np.zeros((P, n, n))
    Bm = np.zeros((P, n, n))
    idx = np.arange(n)
    Bm[:, idx, idx] = params.ground_dampings
    for i in range(n - 1):
        for mat, val in ((K, params.stiffnesses[:, i]), (Bm, params.dampings[:, i])):
            mat[:, i, i] += val
            mat[:, i + 1, i + 1] += val
            mat[:, i, i + 1] -= val
            mat[:, i + 1, i] -= val
    inv_m = 1.0 / params.masses[:, 1:, None]
    A = np.zeros((P, 2 * nodes, 2 * nodes))
    A[:, :nodes, nodes:] = np.eye(nodes)
    A[:, nodes:, :nodes] = -K[:, 1:, 1:] * inv_m
    A[:, nodes:, nodes:] = -Bm[:, 1:, 1:] * inv_m
    B = np.zeros((P, 2 * nodes))
    B[:, 2 * nodes - 1] = 1.0 / params.masses[:, n - 1]
    Cd = np.zeros((P, 2 * nodes))
    if quantity == "actuator":
        Cd[:, nodes - 1] = 1.0
    else:
        ks, bs = params.stiffnesses[:, se], params.dampings[:, se]
        for node, sign in ((se, 1.0), (se + 1, -1.0)):
            if node >= 1:
                Cd[:, node - 1] += sign * ks
                Cd[:, nodes + node - 1] += sign * bs
    return A, B, Cd, np.zeros_like(Cd)


def _phi(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``phi1 = (e^x - 1)/x`` and ``phi2 = (e^x - 1 - x)/x^2`` without cancellation (series
    for ``|x| < 0.1``)."""
    small = np.abs(x) < 0.1
    xs = np.where(small, 1.0, x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        em1 = np.expm1(xs)
        p1 = em1 / xs
        p2 = (em1 - xs) / (xs * xs)
    if not np.any(small):
        return p1, p2
    # Horner forms of the series to x^6: 1 + x/2 + x^2/6 + ... and 1/2 + x/6 + x^2/24 + ...
    s1 = 1 + x * (1 / 2 + x * (1 / 6 + x * (1 / 24 + x * (1 / 120 + x * (1 / 720 + x / 5040)))))
    s2 = 1 / 2 + x * (1 / 6 + x * (1 / 24 + x * (1 / 120 + x * (1 / 720 + x * (1 / 5040 + x / 40320)))))
    return np.where(small, s1, p1), np.where(small, s2, p2)


def sampled_response(params: ChainParameters, w: np.ndarray, sample_time: float, quantity: str = "actuator",
                     boundary: str = "free", sensor_element: int = 0, delay_samples: int = 0) -> np.ndarray:
    """Exact ZOH-sampled response (P, F) with a delay of ``d`` samples, ``z = e^{j w T}``.

    Modal form of ``C (zI - Phi)^{-1} Gamma`` (one eigendecomposition ``A = V diag(lam) V^{-1}``
    per chain, ``beta = V^{-1} B``): a mode contributes ``T phi1(lam T) beta / (z - e^{lam T})`` to
    its coordinate at the samples, and over one held step its integral grows by
    ``T phi1 eta + T^2 phi2 beta u``, so with ``c = C V``::

        H(z) = sum_i c_d,i T phi1_i beta_i / (z - e_i)
               + 1/(z - 1) sum_i c_i,i T^2 beta_i (phi1_i^2 / (z - e_i) + phi2_i),

    ``e_i = e^{lam_i T}``, times ``z^{-d}``.  This is the exact ZOH discretization (the same
    ``Phi = e^{AT}``, ``Gamma = int_0^T e^{At} B dt`` as :func:`analysis.chain.discretize_zoh`),
    evaluated in O(F N) per chain after the eigendecomposition.

    Parameters
    ----------
    params : ChainParameters
        ``P`` chains of ``n`` masses.
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (F,).
    sample_time : float
        Sample period T [s].
    quantity : str, optional
        ``"actuator"`` (m/N), ``"handle"`` (m/N) or ``"gauge"`` (N/N) (module doc).
    boundary : str, optional
        ``"free"`` or ``"clamped"`` (handle held).
    sensor_element : int, optional
        The element of the gauge, ``0 <= sensor_element < n - 1`` (``gauge`` only).
    delay_samples : int, optional
        Output delay d [samples].

    Returns
    -------
    numpy.ndarray
        Complex response in the quantity's unit, shape (P, F).

    Raises
    ------
    ValidationError
        For an unknown quantity or boundary, a clamped handle or 1-mass chain, or a gauge
        element outside the chain.
    numpy.linalg.LinAlgError
        When the eigendecomposition of a chain's state matrix fails or its eigenvector matrix is
        singular (a defective state matrix).
    """
    A, B, Cd, Ci = state_space(params, quantity, boundary, sensor_element)
    T = float(sample_time)
    lam, V = np.linalg.eig(A)
    beta = np.linalg.solve(V, B[..., None].astype(complex))[..., 0]
    cd = np.einsum("pn,pnm->pm", Cd, V)
    p1, p2 = _phi(lam * T)
    e = np.exp(lam * T)
    z = np.exp(1j * np.asarray(w, dtype=float) * T)
    inv = 1.0 / (z[None, :, None] - e[:, None, :])  # (P, F, N)
    if not Ci.any():
        h = (inv @ (cd * T * p1 * beta)[:, :, None])[:, :, 0]
    else:
        ib = np.einsum("pn,pnm->pm", Ci, V) * T * T * beta
        both = inv @ np.stack([cd * T * p1 * beta, ib * p1 * p1], axis=2)  # (P, F, 2): one product
        h = both[:, :, 0] + (both[:, :, 1] + np.sum(ib * p2, axis=1)[:, None]) / (z[None, :] - 1.0)
    if delay_samples:
        h = h * z[None, :] ** (-int(delay_samples))
    return h


def response(params: ChainParameters, w: np.ndarray, quantity: str = "actuator", boundary: str = "free",
             sensor_element: int = 0, sample_time: float | None = None, delay_samples: int = 0) -> np.ndarray:
    """:func:`continuous_response` when ``sample_time`` is ``None``, else :func:`sampled_response`.

    Parameters
    ----------
    params : ChainParameters
        ``P`` chains of ``n`` masses.
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (F,).
    quantity : str, optional
        ``"actuator"`` (m/N), ``"handle"`` (m/N) or ``"gauge"`` (N/N) (module doc).
    boundary : str, optional
        ``"free"`` or ``"clamped"`` (handle held).
    sensor_element : int, optional
        The element of the gauge, ``0 <= sensor_element < n - 1`` (``gauge`` only).
    sample_time : float or None, optional
        Sample period [s] of a response through the sampled controller; ``None``: continuous.
    delay_samples : int, optional
        Output delay [samples] (sampled only).

    Returns
    -------
    numpy.ndarray
        Complex response in the quantity's unit, shape (P, F).

    Raises
    ------
    ValidationError
        For an unknown quantity or boundary, a clamped handle or 1-mass chain, or a gauge
        element outside the chain.
    """
    if sample_time is None:
        return continuous_response(params, w, quantity, boundary, sensor_element)
    return sampled_response(params, w, sample_time, quantity, boundary, sensor_element, delay_samples)
