"""Encoder-quantization noise of the velocity estimate, and the damping it limits.

Chawda, Celik & O'Malley ("A method for selecting velocity filter cut-off frequency for
maximizing impedance width performance in haptic interfaces", ASME J. Dyn. Sys. Meas. Control
137(2), 024503, 2015) trade the time delay of the velocity filter against the noise of the
finite difference; Colgate & Brown ("Factors affecting the Z-width of a haptic display", IEEE
ICRA 1994, pp. 3205-3210) name the encoder resolution among the factors that bound the Z-width.
The exact linear region (:mod:`analysis.sampled.zwidth`) models the delay side only; this module
adds the noise side.

Model (assumption): the encoder of resolution ``q`` (m, at the handle) adds a quantization error
that is white, uniform, of variance ``q^2/12`` (the classical model of uniform quantization; it
holds while the handle moves over many counts between samples, not at rest, where the reading is
constant and the difference is 0).  The velocity estimate is
``v = V(z) x``, ``V(z) = H_f(z) (1 - z^{-1})/T``
(:class:`~analysis.chain.velocity_filter.VelocityFilter`), so its rms noise is
``sigma_v = (q/sqrt(12)) g`` with the noise gain

    g^2 = sum_k h_V[k]^2 = (1/pi) int_0^pi |(1 - e^{-j th})/T H_f(e^{j th})|^2 d th.

:func:`noise_gain` computes ``g`` exactly from the state space of ``V`` by the discrete Lyapunov
equation ``P = A P A' + B B'``, ``g^2 = C P C' + D^2`` (``scipy.linalg.solve_discrete_lyapunov``
by its bilinear transformation to a continuous equation; the estimate's own states, at most
three, whatever the device).  The Kronecker form ``(I - A (x) A) vec P = vec B B'``, scipy's
default below 10 states, is nearly singular for a low cut-off in the filter's controllable
canonical form: against a 60-digit solution, ``butter2`` at T = 1 ms is off by 1e-9 at 1 Hz
and 1.3e-6 at 0.1 Hz that way, by 4e-12 and 3e-10 by the bilinear route.  Closed forms: the
backward difference ``g^2 = 2/T^2``; ``lowpass1`` (``a = e^{-w_f T}``)
``g^2 = 2 (1 - a)^2 / (T^2 (1 + a))``, about ``w_f^2`` for ``w_f T << 1``.

A virtual wall ``F = K x + B v`` renders a force noise of rms at least ``B sigma_v`` from the
damping (the ``K q/sqrt(12)`` part of the spring does not depend on the filter and is left
out).  A wall is *noise-limited* when ``B sigma_v > F_noise``, the user's tolerance;
:func:`noise_limited_damping` returns the largest B within it, ``F_noise/sigma_v``.  The default
tolerance :data:`DEFAULT_FORCE_NOISE` = 0.1 N rms is a judgement, not a paper's figure: two
counts of the HBFD's 0.05 N force gauge (:func:`~analysis.sampled.scenarios.hbfd_options`),
i.e. the smallest noise that gauge resolves reliably, and of the order of the friction felt on
a backdrivable desktop device.  Numpy and scipy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg

from analysis.chain.limits import SAMPLE_TIME, Limit
from analysis.chain.velocity_filter import BACKWARD, VelocityFilter
from analysis.errors import ValidationError

__all__ = ["VelocityNoise", "noise_gain", "transfer_noise_gain", "estimate_noise", "noise_limited_damping", "DEFAULT_FORCE_NOISE",
           "ENCODER_RESOLUTION", "FORCE_NOISE"]

#: Encoder resolution at the handle (m): 1 nm (interferometric scales) to 1 cm.
ENCODER_RESOLUTION = Limit(1e-9, 1e-2, "m")
#: Force-noise tolerance of a rendered wall (N rms): 1 µN to 1 kN.
FORCE_NOISE = Limit(1e-6, 1e3, "N")
#: The default force-noise tolerance (N rms; module docstring).
DEFAULT_FORCE_NOISE = 0.1


@dataclass(frozen=True)
class VelocityNoise:
    """The noise of a velocity estimate: ``gain`` g (1/s), ``velocity_rms`` = q g/sqrt(12) (m/s).

    Parameters
    ----------
    velocity_filter : VelocityFilter
        The velocity estimate's filter (the backward difference for none).
    sample_time : float
        Sample period ``T`` [s].
    encoder_resolution : float
        Encoder resolution ``q`` at the handle [m].
    gain : float
        Noise gain ``g`` [1/s] (:func:`noise_gain`).
    velocity_rms : float
        Rms velocity noise ``sigma_v = q g/sqrt(12)`` [m/s].
    """

    velocity_filter: VelocityFilter
    sample_time: float
    encoder_resolution: float
    gain: float
    velocity_rms: float

    def force_rms(self, b: np.ndarray | float) -> np.ndarray:
        """The damping's force noise ``B sigma_v`` (N rms) at wall damping ``b`` (N s/m).

        Parameters
        ----------
        b : float or numpy.ndarray
            Wall damping ``B`` [N s/m], any shape.

        Returns
        -------
        numpy.ndarray
            Force noise [N rms], the shape of ``b``.
        """
        return np.asarray(b, float) * self.velocity_rms

    def damping_limit(self, force_noise: float = DEFAULT_FORCE_NOISE) -> float:
        """The largest wall damping whose force noise is within ``force_noise`` (N s/m).

        Parameters
        ----------
        force_noise : float, optional
            Force-noise tolerance ``F_noise`` [N rms], 1e-6 to 1e3.

        Returns
        -------
        float
            ``F_noise/sigma_v`` [N s/m].
        """
        return FORCE_NOISE("force_noise", force_noise) / self.velocity_rms


def _estimate_state_space(vf: VelocityFilter, T: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """``V(z)`` from the position: states ``[x[k-1], s]`` (``s`` the filter's), input ``x[k]``."""
    r = vf.realization(T)
    n = r.order
    A = np.zeros((n + 1, n + 1))
    A[1:, 0] = -r.B / T
    A[1:, 1:] = r.A
    B = np.r_[1.0, r.B / T]
    C = np.r_[-r.D / T, r.C]
    return A, B, C, r.D / T


def noise_gain(velocity_filter: VelocityFilter | None, sample_time: float) -> float:
    """The exact noise gain ``g`` (1/s) of ``V(z) = H_f(z)(1 - z^{-1})/T`` (module docstring).

    ``g^2`` is the sum of the squared impulse response, from the discrete Lyapunov equation of
    the estimate's realization.  ``None`` is the backward difference (``g = sqrt(2)/T``).

    Parameters
    ----------
    velocity_filter : VelocityFilter or None
        The velocity estimate's filter ``H_f``; ``None`` for the backward difference.
    sample_time : float
        Sample period ``T`` [s], 1e-6 to 1.

    Returns
    -------
    float
        The noise gain ``g`` [1/s].
    """
    T = SAMPLE_TIME("sample_time", sample_time)
    vf = BACKWARD if velocity_filter is None else velocity_filter
    vf.check(T)
    A, B, C, D = _estimate_state_space(vf, T)
    P = linalg.solve_discrete_lyapunov(A, np.outer(B, B), method="bilinear")
    return math.sqrt(max(float(C @ P @ C) + D * D, 0.0))


def transfer_noise_gain(num: np.ndarray, den: np.ndarray) -> float:
    """The noise gain ``sqrt(sum_k h[k]^2)`` of ``num(z^{-1})/den(z^{-1})`` (``den[0] != 0``), exactly.

    The same route as :func:`noise_gain`: the controllable canonical realization (both
    polynomials padded to one length) and the discrete Lyapunov equation by its bilinear
    transformation.  Used for the rendered environment's force noise ``B V + M A``
    (:mod:`analysis.sampled.renderable`).

    Parameters
    ----------
    num : numpy.ndarray
        Numerator coefficients in powers of ``z^{-1}``.
    den : numpy.ndarray
        Denominator coefficients in powers of ``z^{-1}``, every root of ``den(z^{-1})`` inside
        the unit circle (a stable filter).

    Returns
    -------
    float
        The noise gain (the unit of ``num/den``).
    """
    num, den = np.asarray(num, float), np.asarray(den, float)
    n = max(num.size, den.size) - 1
    b = np.r_[num, np.zeros(n + 1 - num.size)] / den[0]
    a = np.r_[den, np.zeros(n + 1 - den.size)] / den[0]
    if n == 0:
        return abs(float(b[0]))
    A = np.zeros((n, n))
    A[0, :] = -a[1:]
    A[1:, :-1] = np.eye(n - 1)
    B = np.zeros(n)
    B[0] = 1.0
    C = b[1:] - b[0] * a[1:]
    P = linalg.solve_discrete_lyapunov(A, np.outer(B, B), method="bilinear")
    return math.sqrt(max(float(C @ P @ C) + float(b[0]) ** 2, 0.0))


def estimate_noise(velocity_filter: VelocityFilter | None, sample_time: float,
                   encoder_resolution: float) -> VelocityNoise:
    """The rms velocity noise of the estimate for an encoder of resolution ``q`` (m).

    Parameters
    ----------
    velocity_filter : VelocityFilter or None
        The velocity estimate's filter ``H_f``; ``None`` for the backward difference.
    sample_time : float
        Sample period ``T`` [s], 1e-6 to 1.
    encoder_resolution : float
        Encoder resolution ``q`` at the handle [m], 1e-9 to 1e-2.

    Returns
    -------
    VelocityNoise
        The noise gain and the rms velocity noise.
    """
    q = ENCODER_RESOLUTION("encoder_resolution", encoder_resolution)
    g = noise_gain(velocity_filter, sample_time)
    return VelocityNoise(velocity_filter=BACKWARD if velocity_filter is None else velocity_filter,
                         sample_time=float(sample_time), encoder_resolution=q, gain=g,
                         velocity_rms=q * g / math.sqrt(12.0))


def noise_limited_damping(velocity_filter: VelocityFilter | None, sample_time: float,
                          encoder_resolution: float | None, force_noise: float | None = None) -> float:
    """The largest wall damping ``F_noise/sigma_v`` (N s/m) within the force-noise tolerance.

    ``inf`` when ``encoder_resolution`` is ``None`` (the criterion is off; then ``force_noise``
    must be ``None`` too); ``force_noise`` ``None`` is :data:`DEFAULT_FORCE_NOISE`.

    Parameters
    ----------
    velocity_filter : VelocityFilter or None
        The velocity estimate's filter ``H_f``; ``None`` for the backward difference.
    sample_time : float
        Sample period ``T`` [s], 1e-6 to 1.
    encoder_resolution : float or None
        Encoder resolution ``q`` at the handle [m]; ``None`` turns the criterion off.
    force_noise : float or None, optional
        Force-noise tolerance [N rms]; ``None`` for :data:`DEFAULT_FORCE_NOISE`.

    Returns
    -------
    float
        The largest wall damping [N s/m]; ``inf`` when the criterion is off.

    Raises
    ------
    ValidationError
        When ``force_noise`` is given without ``encoder_resolution``, or a value is out of range.
    """
    if encoder_resolution is None:
        if force_noise is not None:
            raise ValidationError("force_noise", "None unless encoder_resolution is given", force_noise)
        return math.inf
    f = DEFAULT_FORCE_NOISE if force_noise is None else force_noise
    return estimate_noise(velocity_filter, sample_time, encoder_resolution).damping_limit(f)
