"""The velocity estimate of the controller: backward difference, optionally low-pass filtered.

Haptic controllers estimate the device velocity from encoder positions.  The raw backward
difference ``(1 - z^{-1})/T`` (Adams et al., eq. 4; Colgate & Schenkel) is noisy, so real
controllers follow it with a low-pass filter whose phase lag shrinks the stable range.  Chawda,
Celik & O'Malley ("A method for selecting velocity filter cut-off frequency for maximizing
impedance width performance in haptic interfaces", ASME J. Dyn. Sys. Meas. Control 137(2),
024503, 2015, DOI 10.1115/1.4028526) show that a cut-off exists that maximizes the Z-width of
Colgate & Brown ("Factors affecting the Z-width of a haptic display", ICRA 1994).

A :class:`VelocityFilter` is the estimate ``v = V(z) x`` with ``V(z) = H_f(z) (1 - z^{-1})/T``:

* ``"backward"``: ``H_f = 1`` (the default; every analysis keeps its cancellation-free closed
  forms and its numbers bit for bit);
* ``"lowpass1"``: ``H_f = (1 - a)/(1 - a z^{-1})``, ``a = e^{-w_f T}`` (the matched first-order
  low-pass; unity DC gain);
* ``"butter2"``: the second-order Butterworth ``w_f^2/(s^2 + sqrt(2) w_f s + w_f^2)`` by the
  bilinear transform with pre-warping, ``s = K (1 - z^{-1})/(1 + z^{-1})``,
  ``K = w_f / tan(w_f T/2)`` (so the -3 dB point is exactly at ``w_f``; unity DC gain).

The filter is a settings record (profiles): ``kind`` and ``cutoff`` (rad/s).  The sample time is
the device's and is given at use: :meth:`VelocityFilter.coefficients`, :meth:`response` and
:meth:`realization` validate ``0 < cutoff < pi/T``.  The realization (controllable canonical
form of ``H_f``, input the backward difference ``d[k] = (x[k] - x[k-1])/T``) is what the exact
sampled loop and the simulator run; its states are zero at rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from analysis.checks import Real, SettingsRecord, choice
from analysis.errors import ValidationError

__all__ = ["VelocityFilter", "FILTER_KINDS", "BACKWARD", "FilterRealization", "display_filter", "highest_cutoff"]

#: The filter kinds and what they are.
FILTER_KINDS = {
    "backward": "backward difference (no filter)",
    "lowpass1": "backward difference + first-order low-pass",
    "butter2": "backward difference + second-order Butterworth",
}

_CUTOFF = Real(lo=0.0, lo_open=True, allow_inf=True, unit="rad/s")


@dataclass(frozen=True)
class FilterRealization:
    """``H_f`` as ``s[k+1] = A s[k] + B d[k]``, ``v[k] = C s[k] + D d[k]`` (``d`` the difference).

    Parameters
    ----------
    A : numpy.ndarray
        State matrix, shape (p, p) with ``p`` the filter order (0, 1 or 2).
    B : numpy.ndarray
        Input vector, shape (p,).
    C : numpy.ndarray
        Output vector, shape (p,).
    D : float
        Feed-through from the backward difference to the estimate.
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: float

    @property
    def order(self) -> int:
        return int(self.B.size)


@dataclass(frozen=True)
class VelocityFilter(SettingsRecord):
    """The controller's velocity estimate (module docstring): ``kind`` and ``cutoff`` (rad/s).

    ``cutoff`` is ignored by ``"backward"`` (default ``inf``) and required, finite and > 0, by
    the filters; it must also be below the Nyquist frequency of the device it is used with.

    Parameters
    ----------
    kind : str, optional
        One of :data:`FILTER_KINDS`: ``"backward"`` (default), ``"lowpass1"`` or ``"butter2"``.
    cutoff : float, optional
        Cut-off frequency ``w_f`` [rad/s]; ``inf`` (default) for ``"backward"``.

    Raises
    ------
    ValidationError
        When ``kind`` is unknown, or ``cutoff`` is not > 0, or not finite for a filter.
    """

    record_name: ClassVar[str] = "velocity filter"

    kind: str = "backward"
    cutoff: float = math.inf

    def __post_init__(self) -> None:
        choice("kind", self.kind, FILTER_KINDS, allowed=", ".join(FILTER_KINDS))
        c = _CUTOFF("cutoff", self.cutoff)
        if self.kind != "backward" and not math.isfinite(c):
            raise ValidationError("cutoff", f"> 0 and finite (rad/s) for a {self.kind} filter", self.cutoff)
        object.__setattr__(self, "cutoff", c)

    @property
    def is_backward(self) -> bool:
        """True for the raw backward difference (today's behaviour, no filter states)."""
        return self.kind == "backward"

    @property
    def order(self) -> int:
        """Number of filter states (0, 1 or 2)."""
        return {"backward": 0, "lowpass1": 1, "butter2": 2}[self.kind]

    def check(self, sample_time: float) -> float:
        """The cut-off, validated against the Nyquist frequency ``pi/T``.

        ``"butter2"`` needs ``cutoff < pi/T`` (its pre-warping ``tan(w_f T/2)``); ``"lowpass1"``
        accepts the Nyquist frequency itself (``a = e^{-pi}``; up to rounding of ``2 pi f``).

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s] of the device the filter is used with.

        Returns
        -------
        float
            The cut-off [rad/s].

        Raises
        ------
        ValidationError
            When the cut-off is above Nyquist (``"lowpass1"``) or not below it (``"butter2"``).
        """
        nyq = math.pi / sample_time
        if self.kind == "lowpass1" and not self.cutoff <= nyq * (1.0 + 1e-12):
            raise ValidationError("cutoff", f"<= Nyquist = {nyq:.6g} rad/s", self.cutoff)
        if self.kind == "butter2" and not self.cutoff < nyq:
            raise ValidationError("cutoff", f"< Nyquist = {nyq:.6g} rad/s", self.cutoff)
        return self.cutoff

    def coefficients(self, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
        """``(num, den)`` of ``H_f`` in powers of ``z^{-1}`` (``den[0] = 1``).

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s] of the device the filter is used with.

        Returns
        -------
        num : numpy.ndarray
            Numerator coefficients, shape (1,) or (3,).
        den : numpy.ndarray
            Denominator coefficients, ``den[0] = 1``, shape (p + 1,) with ``p`` the order.

        Raises
        ------
        ValidationError
            When the cut-off is not below Nyquist ``pi/T`` (see :meth:`check`).
        """
        wf, T = self.check(sample_time), float(sample_time)
        if self.kind == "backward":
            return np.array([1.0]), np.array([1.0])
        if self.kind == "lowpass1":
            a = math.exp(-wf * T)
            return np.array([-math.expm1(-wf * T)]), np.array([1.0, -a])
        K = wf / math.tan(0.5 * wf * T)
        r2 = math.sqrt(2.0) * wf * K
        d0 = K * K + r2 + wf * wf
        num = wf * wf * np.array([1.0, 2.0, 1.0]) / d0
        den = np.array([1.0, 2.0 * (wf * wf - K * K) / d0, (K * K - r2 + wf * wf) / d0])
        return num, den

    def transfer_function(self, sample_time: float) -> tuple[np.ndarray, np.ndarray]:
        """``(num, den)`` of the whole estimate ``V(z) = H_f(z)(1 - z^{-1})/T`` in ``z^{-1}``.

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s] of the device the filter is used with.

        Returns
        -------
        num : numpy.ndarray
            Numerator coefficients [1/s].
        den : numpy.ndarray
            Denominator coefficients, ``den[0] = 1``.

        Raises
        ------
        ValidationError
            When the cut-off is not below Nyquist ``pi/T`` (see :meth:`check`).
        """
        num, den = self.coefficients(sample_time)
        return np.polymul(num, np.array([1.0, -1.0]) / sample_time), den

    def filter_response(self, w, sample_time: float) -> np.ndarray:
        """``H_f(e^{j w T})`` (unity at DC).

        ``"lowpass1"`` uses ``1 - a e^{-j wT} = (1 - a) + 2 a sin^2(wT/2) + j a sin(wT)`` (no
        cancellation at low frequency); ``"butter2"`` evaluates its polynomials directly.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].

        Returns
        -------
        numpy.ndarray
            ``H_f`` (dimensionless), complex, shape (N,).

        Raises
        ------
        ValidationError
            When the cut-off is not below Nyquist ``pi/T`` (see :meth:`check`).
        """
        w = np.asarray(w, dtype=float)
        th = w * sample_time
        if self.kind == "backward":
            self.check(sample_time)
            return np.ones(w.shape, dtype=complex)
        num, den = self.coefficients(sample_time)
        if self.kind == "lowpass1":
            a = float(-den[1])
            return num[0] / ((num[0] + 2.0 * a * np.sin(0.5 * th) ** 2) + 1j * a * np.sin(th))
        zi = np.exp(-1j * th)
        return np.polyval(num[::-1], zi) / np.polyval(den[::-1], zi)

    def response(self, w, sample_time: float) -> np.ndarray:
        """``V(e^{j w T})``: the whole estimate, ``H_f (1 - e^{-j wT})/T``.

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        sample_time : float
            Sample period ``T`` [s].

        Returns
        -------
        numpy.ndarray
            ``V`` [1/s] (velocity estimate per unit position), complex, shape (N,).

        Raises
        ------
        ValidationError
            When the cut-off is not below Nyquist ``pi/T`` (see :meth:`check`).
        """
        w = np.asarray(w, dtype=float)
        th = 0.5 * w * sample_time
        diff = (2.0j / sample_time) * np.sin(th) * np.exp(-1j * th)
        return self.filter_response(w, sample_time) * diff

    def realization(self, sample_time: float) -> FilterRealization:
        """State space of ``H_f`` driven by the backward difference (controllable canonical form).

        Parameters
        ----------
        sample_time : float
            Sample period ``T`` [s] of the device the filter is used with.

        Returns
        -------
        FilterRealization
            ``(A, B, C, D)`` of order 0, 1 or 2.

        Raises
        ------
        ValidationError
            When the cut-off is not below Nyquist ``pi/T`` (see :meth:`check`).
        """
        num, den = self.coefficients(sample_time)
        n = den.size - 1
        b = np.r_[num, np.zeros(n + 1 - num.size)]
        D = float(b[0])
        A = np.zeros((n, n))
        if n:
            A[0, :] = -den[1:]
            A[1:, :-1] = np.eye(n - 1)
        B = np.zeros(n)
        if n:
            B[0] = 1.0
        C = b[1:] - D * den[1:]
        return FilterRealization(A=A, B=B, C=C, D=D)

    def label(self) -> str:
        """Short description, e.g. ``"first-order low-pass at 30 Hz"``.

        Returns
        -------
        str
            The kind in words, and for a filter its cut-off in Hz.
        """
        if self.is_backward:
            return FILTER_KINDS["backward"]
        return f"{FILTER_KINDS[self.kind]} at {self.cutoff / (2 * math.pi):.4g} Hz"


#: The default velocity estimate.
BACKWARD = VelocityFilter()


def highest_cutoff(sample_time: float) -> float:
    """The highest cut-off (rad/s) zwidth proposes for a filter: 0.9 of Nyquist, ``0.9 pi/T``.

    The top of the default cut-off grid of the Z-width optimum and the clamp of a new filter's
    cut-off in the GUI; a cut-off must stay below Nyquist ``pi/T`` (:meth:`VelocityFilter.check`).
    """
    return 0.9 * math.pi / sample_time


def display_filter(velocity_filter: VelocityFilter | None, sample_time: float) -> VelocityFilter | None:
    """A display's velocity filter, checked against its sample period: ``None`` for the plain
    backward difference (eq. 4, the paper's own coupling, computed by its closed forms), else the
    filter.  A wrong type or a cut-off at or above Nyquist raises :class:`ValidationError`.

    Parameters
    ----------
    velocity_filter : VelocityFilter or None
        The display's filter; ``None`` for the backward difference.
    sample_time : float
        The display's sample period ``T`` [s].

    Returns
    -------
    VelocityFilter or None
        ``None`` for the plain backward difference, else ``velocity_filter``.

    Raises
    ------
    ValidationError
        When ``velocity_filter`` is not a VelocityFilter or None, or its cut-off is not below
        Nyquist.
    """
    if velocity_filter is None:
        return None
    if not isinstance(velocity_filter, VelocityFilter):
        raise ValidationError("velocity_filter", "a VelocityFilter or None", velocity_filter)
    velocity_filter.check(sample_time)
    return None if velocity_filter.is_backward else velocity_filter
