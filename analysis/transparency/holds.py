"""Models of the zero-order hold in the wall loop of Eom, Suh & Yi (the ``ZOH(s)`` of eq. 9, 16).

The paper says only that the hold is "approximated by a low pass filter with unity steady-state
gain and 90 degrees phase lag at the Nyquist frequency"; which filter it used is unknown, so the
hold model is a named choice (``HOLDS``):

``none``
    ``H(s) = 1`` (no hold at all).
``pade``
    First-order Pade approximation of the half-sample delay ``e^{-sT/2}``:
    ``H(s) = (1 - sT/4) / (1 + sT/4)`` (all-pass, -90 deg at ``w = 4/T``, not at Nyquist).
``lowpass2``
    Second-order low-pass at the Nyquist frequency ``w_n = pi/T``:
    ``H(s) = w_n^2 / (s^2 + 2 zeta w_n s + w_n^2)`` -- exactly -90 deg at Nyquist for any
    ``zeta`` (default 0.7071), the filter the paper's sentence describes.
``zoh``
    The hold's own frequency response ``H(s) = (1 - e^{-sT}) / (sT)`` (not rational).
``discrete``
    No continuous ``H``: the loop is analysed exactly at the sample instants (ZOH
    discretization of the plant, discrete controller, evaluated on the unit circle).  See
    :mod:`analysis.transparency`.

The rational models also have a state-space realization (for the H2 norm by a Lyapunov equation
and for closed-loop poles).
"""

from __future__ import annotations

import numpy as np

__all__ = ["HOLDS", "RATIONAL_HOLDS", "hold_response", "hold_state_space"]

HOLDS: tuple[str, ...] = ("none", "pade", "lowpass2", "zoh", "discrete")
RATIONAL_HOLDS: tuple[str, ...] = ("none", "pade", "lowpass2")


def hold_response(hold: str, s: np.ndarray, sample_time: float, damping: float = 0.7071,
                  oscillating: bool = True) -> np.ndarray:
    """``H(s)`` of a continuous hold model at complex frequencies ``s``.

    ``oscillating=False`` drops the ``e^{-sT}`` term of ``zoh`` (its non-oscillatory part
    ``1/(sT)``); used only far above Nyquist, in the tail of the quadrature, where the dropped
    term integrates to a negligible amount.

    Parameters
    ----------
    hold : str
        The hold model: ``"none"``, ``"pade"``, ``"lowpass2"`` or ``"zoh"``.
    s : numpy.ndarray
        Complex frequencies [rad/s], any shape.
    sample_time : float
        Sample time ``T`` [s].
    damping : float, optional
        Damping ratio ``zeta`` of ``lowpass2``.
    oscillating : bool, optional
        False drops the ``e^{-sT}`` term of ``zoh``.

    Returns
    -------
    numpy.ndarray
        ``H(s)`` (dimensionless), complex, the shape of ``s``.

    Raises
    ------
    ValueError
        When ``hold`` has no continuous response (``"discrete"`` or an unknown name).
    """
    s = np.asarray(s, dtype=complex)
    T = sample_time
    if hold == "none":
        return np.ones_like(s)
    if hold == "pade":
        return (1.0 - 0.25 * T * s) / (1.0 + 0.25 * T * s)
    if hold == "lowpass2":
        wn = np.pi / T
        return wn * wn / (s * s + 2.0 * damping * wn * s + wn * wn)
    if hold == "zoh":
        x = s * T
        small = np.abs(x) < 1e-4
        with np.errstate(divide="ignore", invalid="ignore"):
            exact = (1.0 - np.exp(-x)) / x if oscillating else 1.0 / x
        series = 1.0 - x / 2.0 + x * x / 6.0 - x**3 / 24.0  # (1 - e^{-x})/x near x = 0
        return np.where(small, series, exact)
    raise ValueError(f"no continuous response for hold {hold!r}")


def hold_state_space(hold: str, sample_time: float, damping: float = 0.7071
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(A, B, C, D)`` of a rational hold model (``none``, ``pade``, ``lowpass2``).

    Parameters
    ----------
    hold : str
        The hold model: ``"none"``, ``"pade"`` or ``"lowpass2"``.
    sample_time : float
        Sample time ``T`` [s].
    damping : float, optional
        Damping ratio ``zeta`` of ``lowpass2``.

    Returns
    -------
    A : numpy.ndarray
        State matrix, shape (n, n) with n = 0, 1 or 2.
    B : numpy.ndarray
        Input matrix, shape (n, 1).
    C : numpy.ndarray
        Output matrix, shape (1, n).
    D : numpy.ndarray
        Feedthrough, shape (1, 1).

    Raises
    ------
    ValueError
        When ``hold`` is not rational.
    """
    T = sample_time
    if hold == "none":
        return np.zeros((0, 0)), np.zeros((0, 1)), np.zeros((1, 0)), np.ones((1, 1))
    if hold == "pade":
        # (1 - sT/4)/(1 + sT/4) = -1 + (8/T)/(s + 4/T)
        return (np.array([[-4.0 / T]]), np.array([[1.0]]), np.array([[8.0 / T]]), np.array([[-1.0]]))
    if hold == "lowpass2":
        wn = np.pi / T
        return (np.array([[0.0, 1.0], [-wn * wn, -2.0 * damping * wn]]), np.array([[0.0], [1.0]]),
                np.array([[wn * wn, 0.0]]), np.zeros((1, 1)))
    raise ValueError(f"hold {hold!r} is not rational")
