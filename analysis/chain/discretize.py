"""Discretization: the exact zero-order hold, and the closed forms used by the two-port analysis
(Adams et al., eq. 2, 4, 16, 30).

:func:`discretize_zoh` is the one exact ZOH discretization of a state space (Van Loan's matrix
exponential), used by the sampled-data loop (Adams et al., section III), its simulator and the
wall controller of Eom, Suh & Yi (the ``discrete`` hold and every step response, Figs. 7, 10).

On the unit circle ``z = exp(j w T)`` every quantity is written with ``theta = w T / 2`` in
closed forms that are free of cancellation:

* the Tustin image ``s = (2/T)(z-1)/(z+1) = j (2/T) tan(theta)`` (eq. 2);
* the hold factor ``[1/s]_Tustin (z-1)/(Tz) = (z+1)/(2z) = cos(theta) exp(-j theta)`` (eq. 2);
* the rectangular integrator ``Tz/(z-1) = T/2 - j (T/2) cot(theta)`` (eq. 4, 30);
* the backward difference ``(z-1)/(Tz)`` used by eq. (16).

A spring-damper ``b + k Tz/(z-1)`` seen through the hold (``h * (b + k Tz/(z-1))``) is
``b cos^2(theta) - j cos(theta) (b sin(theta) + k T / (2 sin(theta)))``.  Its real part is
exactly ``b cos^2(theta)`` although the naive product subtracts two large numbers.
"""

from __future__ import annotations

import numpy as np
from scipy import linalg

__all__ = [
    "discretize_zoh",
    "theta_of",
    "tustin_image",
    "hold_factor",
    "spring_damper",
    "held_spring_damper",
    "mass_damper_admittance",
    "check_frequencies",
]


def discretize_zoh(A: np.ndarray, B: np.ndarray, h) -> tuple[np.ndarray, np.ndarray]:
    """Exact zero-order-hold discretization ``(Phi, Gamma)`` by one (batched) ``expm`` of
    ``[[A, B], [0, 0]] h`` (Van Loan): ``x[k+1] = Phi x[k] + Gamma u[k]`` for ``u`` held.

    ``A`` (..., N, N) and ``B`` (..., N, m) may carry leading batch axes; ``h`` is a step length
    or an array of them (a further leading batch axis, broadcast with those of ``A`` and ``B``).

    Parameters
    ----------
    A : numpy.ndarray
        Continuous state matrix [1/s], shape (..., N, N).
    B : numpy.ndarray
        Continuous input matrix, shape (..., N, m).
    h : float or array_like
        Step length(s) [s]: a scalar or an array broadcast with the batch axes of ``A`` and
        ``B``.

    Returns
    -------
    Phi : numpy.ndarray
        ``exp(A h)``, shape (..., N, N) (the broadcast batch shape).
    Gamma : numpy.ndarray
        ``integral_0^h exp(A t) dt B``, shape (..., N, m).
    """
    N, m = A.shape[-1], B.shape[-1]
    hb = np.asarray(h, dtype=float)[..., None, None]
    Ah, Bh = A * hb, B * hb
    aug = np.zeros(np.broadcast_shapes(Ah.shape[:-2], Bh.shape[:-2]) + (N + m, N + m))
    aug[..., :N, :N] = Ah
    aug[..., :N, N:] = Bh
    E = linalg.expm(aug)
    return E[..., :N, :N], E[..., :N, N:]


def check_frequencies(w, sample_time: float) -> np.ndarray:
    """Validate a frequency vector: finite, > 0 and below Nyquist (rad/s).

    Parameters
    ----------
    w : array_like
        Angular frequencies [rad/s], any shape.
    sample_time : float
        Sample period ``T`` [s]; Nyquist is ``pi/T``.

    Returns
    -------
    numpy.ndarray
        ``w`` as a float array, same shape.

    Raises
    ------
    ValidationError
        When a frequency is not finite, not > 0 or not below Nyquist.
    """
    w = np.asarray(w, dtype=float)
    nyq = np.pi / sample_time
    # min/max propagate NaN, and a comparison with NaN is False: one test covers all cases
    if w.size and not (w.min() > 0 and w.max() < nyq):
        from analysis.errors import ValidationError

        bad = w[~(np.isfinite(w) & (w > 0) & (w < nyq))]
        raise ValidationError("frequency", f"finite, > 0 and < Nyquist = {nyq:.6g} rad/s", float(bad.flat[0]))
    return w


def theta_of(w: np.ndarray, sample_time: float) -> np.ndarray:
    """Half the sampled phase, ``theta = w T / 2``.

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].

    Returns
    -------
    numpy.ndarray
        ``theta`` [rad], shape (N,).
    """
    return 0.5 * np.asarray(w, dtype=float) * sample_time


def tustin_image(w: np.ndarray, sample_time: float) -> np.ndarray:
    """Tustin image of ``z = exp(j w T)``: ``s = j (2/T) tan(w T / 2)`` (eq. 2).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].

    Returns
    -------
    numpy.ndarray
        The purely imaginary ``s`` [rad/s], complex, shape (N,).
    """
    return 1j * (2.0 / sample_time) * np.tan(theta_of(w, sample_time))


def hold_factor(w: np.ndarray, sample_time: float) -> np.ndarray:
    """Half-sample model of the zero-order hold, ``(z+1)/(2z) = cos(theta) e^{-j theta}``.

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].

    Returns
    -------
    numpy.ndarray
        The hold factor (dimensionless), complex, shape (N,).
    """
    th = theta_of(w, sample_time)
    return np.cos(th) * np.exp(-1j * th)


def spring_damper(w: np.ndarray, sample_time: float, k: float, b: float) -> np.ndarray:
    """``b + k T z/(z-1)`` on the unit circle (eq. 4 for the coupling, eq. 30 for the PD loop).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    k : float
        Stiffness [N/m].
    b : float
        Damping [N s/m].

    Returns
    -------
    numpy.ndarray
        The discrete spring-damper impedance [N s/m], complex, shape (N,).
    """
    th = theta_of(w, sample_time)
    T = sample_time
    return (b + 0.5 * k * T) - 0.5j * k * T / np.tan(th)


def held_spring_damper(w: np.ndarray, sample_time: float, k: float, b: float) -> np.ndarray:
    """Hold factor times spring-damper, in the cancellation-free closed form (see module doc).

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    k : float
        Stiffness [N/m].
    b : float
        Damping [N s/m].

    Returns
    -------
    numpy.ndarray
        ``b cos^2(theta) - j cos(theta) (b sin(theta) + k T / (2 sin(theta)))`` [N s/m],
        complex, shape (N,).
    """
    th = theta_of(w, sample_time)
    c, s = np.cos(th), np.sin(th)
    return b * c * c - 1j * c * (b * s + 0.5 * k * sample_time / s)


def mass_damper_admittance(w: np.ndarray, sample_time: float, mc: float, bc: float) -> np.ndarray:
    """Admittance of the series mass-damper coupling, eq. (16): ``1/b_c + 1/(m_c s)``.

    with ``s = (z-1)/(Tz)``, i.e. ``1/(m_c s) = (T/(2 m_c)) (1 - j cot(theta))``.
    ``bc = inf`` gives a pure mass coupling.

    Parameters
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (N,).
    sample_time : float
        Sample period ``T`` [s].
    mc : float
        Coupling mass ``m_c`` [kg].
    bc : float
        Coupling damping ``b_c`` [N s/m]; ``inf`` for a pure mass.

    Returns
    -------
    numpy.ndarray
        The coupling admittance [m/(N s)], complex, shape (N,).
    """
    th = theta_of(w, sample_time)
    a = 0.5 * sample_time / mc
    inv_b = 0.0 if np.isinf(bc) else 1.0 / bc
    return (inv_b + a) - 1j * a / np.tan(th)
