"""What the impedance and admittance displays share: caching, grids, evaluation."""

from __future__ import annotations

import dataclasses
from collections import OrderedDict
from collections.abc import Callable

import numpy as np

from analysis.chain import grids
from analysis.chain.device import Device
from analysis.chain.discretize import check_frequencies, theta_of, tustin_image
from analysis.twoport.results import BoundResult, StabilityResult, TwoPort

__all__ = ["DisplayBase", "APPARENT_FREQUENCY", "safe_ratio", "FrequencyGrid"]

#: frequency (rad/s) at which the apparent free-motion mass and damping are read off Z_min
APPARENT_FREQUENCY = 1e-3


def safe_ratio(num: np.ndarray, den: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``num/den`` with ``den == 0`` mapped to +-inf (0 where num is 0 too) and a flag.

    Parameters
    ----------
    num : numpy.ndarray
        Numerators, shape (N,).
    den : numpy.ndarray
        Denominators, shape (N,).

    Returns
    -------
    ratio : numpy.ndarray
        ``num/den``, with ``sign(num) inf`` where ``den == 0`` (0 where ``num`` is 0 too),
        shape (N,).
    singular : numpy.ndarray
        Booleans, ``den == 0``, shape (N,).
    """
    singular = den == 0
    with np.errstate(divide="ignore", invalid="ignore"):
        out = num / np.where(singular, 1.0, den)
    if np.any(singular):
        out = np.where(singular, np.sign(num) * np.inf, out)
        out = np.where(singular & (num == 0), 0.0, out)
    return out, singular


class FrequencyGrid:
    """``theta = w T / 2`` and its sine, cosine and tangent for one validated frequency
    vector, computed once and shared by the bound, the coupling term and Z_max.

    ``W = (2/T) tan(theta)`` is the Tustin image ``s = j W`` (eq. 2); ``imp`` holds the
    chain's (node, element) impedances at ``s`` once a display has built them.

    Parameters
    ----------
    key : bytes
        Identity of the frequency vector (its bytes), compared to reuse the grid.
    w : numpy.ndarray
        Validated angular frequencies [rad/s], shape (N,), below Nyquist.
    sample_time : float
        Sample period ``T`` [s].
    """

    __slots__ = ("key", "w", "th", "sin", "cos", "tan", "W", "imp")

    def __init__(self, key: bytes, w: np.ndarray, sample_time: float):
        self.key = key
        self.w = w
        self.th = theta_of(w, sample_time)
        self.sin = np.sin(self.th)
        self.cos = np.cos(self.th)
        self.tan = self.sin / self.cos  # 0 < theta < pi/2: cos > 0
        self.W = (2.0 / sample_time) * self.tan
        self.imp: tuple[np.ndarray, np.ndarray] | None = None

    @property
    def s(self) -> np.ndarray:
        return 1j * self.W


def _no_nan(res: BoundResult) -> BoundResult:
    """Map a NaN bound (exact pole of a lossless chain: the responses are infinite) to +inf,
    flagged singular, as documented on :class:`BoundResult` (+inf is the conservative value)."""
    bad = np.isnan(res.bound)
    if not np.any(bad):
        return res
    return dataclasses.replace(res, bound=np.where(bad, np.inf, res.bound), singular=res.singular | bad)


class DisplayBase:
    """Caches device-dependent arrays per frequency vector; subclasses define the bound.

    Parameters
    ----------
    device : Device
        The device chain and its sample period.

    Raises
    ------
    TypeError
        When ``device`` is not an :class:`~analysis.chain.Device`.
    """

    display = ""

    def __init__(self, device: Device):
        if not isinstance(device, Device):
            raise TypeError("device must be an analysis.Device")
        self.device = device
        self._cache: OrderedDict[bytes, tuple[BoundResult, TwoPort]] = OrderedDict()
        self._grid: np.ndarray | None = None
        self._fgrid: FrequencyGrid | None = None  # trigonometry of the last frequency vector
        self.bound_evaluations = 0  # frequencies evaluated, for tests and benchmarks

    # -- grids ------------------------------------------------------------------------
    def modes(self) -> np.ndarray:  # pragma: no cover - overridden
        """The undamped modes that shape this display's bound (defined by each display).

        Returns
        -------
        numpy.ndarray
            Continuous-time modes [rad/s], sorted, shape (M,).

        Raises
        ------
        NotImplementedError
            Always: a display subclass defines it.
        """
        raise NotImplementedError

    def frequencies(self) -> np.ndarray:
        """Resonance-aware grid on the analysis band (cached).

        Returns
        -------
        numpy.ndarray
            Angular frequencies [rad/s], sorted and unique, shape (N,)
            (:func:`~analysis.chain.grids.resonance_grid` on :meth:`modes`).
        """
        if self._grid is None:
            self._grid = grids.resonance_grid(self.device, self.modes())
        return self._grid

    # -- bound -------------------------------------------------------------------------
    def _compute(self, w: np.ndarray) -> tuple[BoundResult, TwoPort]:  # pragma: no cover - overridden
        raise NotImplementedError

    def _compute_checked(self, w: np.ndarray) -> tuple[BoundResult, TwoPort]:
        br, tp = self._compute(w)
        return _no_nan(br), tp

    def bound_parts(self, w: np.ndarray) -> BoundResult:
        """The bound of eq. (9) or (21) with its parts, not cached (dense checks and refinement).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.

        Returns
        -------
        BoundResult
            The bound and its parts at ``w`` (NaN bounds mapped to +inf, flagged singular).
        """
        return self._compute_checked(np.asarray(w, float))[0]

    def _freq_grid(self, w: np.ndarray, key: bytes | None = None) -> FrequencyGrid:
        """Trigonometry of ``theta`` for the (validated) vector ``w``, kept for the last one."""
        if key is None:
            key = w.tobytes()
        fg = self._fgrid
        if fg is None or fg.key != key:
            fg = self._fgrid = FrequencyGrid(key, w, self.device.sample_time)
        return fg

    def _cached(self, w, checked: bool = False) -> tuple[BoundResult, TwoPort]:
        """Bound and two-port from one chain sweep, cached for the last few vectors.

        ``checked``: ``w`` already went through :func:`check_frequencies`."""
        if not checked:
            w = check_frequencies(w, self.device.sample_time)
        key = w.tobytes()
        hit = self._cache.get(key)
        if hit is not None:
            self._cache.move_to_end(key)
            return hit
        res = self._compute_checked(np.ascontiguousarray(w))
        self.bound_evaluations += w.size
        self._cache[key] = res
        if len(self._cache) > 4:
            self._cache.popitem(last=False)
        return res

    def bound_result(self, w) -> BoundResult:
        """The bound with its parts (cached).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.

        Returns
        -------
        BoundResult
            The bound and its parts at ``w``.

        Raises
        ------
        ValidationError
            When a frequency is not finite, > 0 and below Nyquist.
        """
        return self._cached(w)[0]

    def two_port(self, w) -> TwoPort:
        """The display's two-port: Y(z) of eq. (2) or G(z) of eq. (14) (cached).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.

        Returns
        -------
        TwoPort
            The two-port at ``w``.

        Raises
        ------
        ValidationError
            When a frequency is not finite, > 0 and below Nyquist.
        """
        return self._cached(w)[1]

    def bound(self, w) -> np.ndarray:
        """Right-hand side of the design inequality, eq. (9) or (21).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.

        Returns
        -------
        numpy.ndarray
            The bound, shape (N,): on ``Re(1/Z_c)`` [m/(N s)] or on ``Re(Z_cA)`` [N s/m].

        Raises
        ------
        ValidationError
            When a frequency is not finite, > 0 and below Nyquist.
        """
        return self.bound_result(w).bound

    def _uncached_bound(self, w: np.ndarray) -> np.ndarray:
        self.bound_evaluations += w.size
        return self._compute_checked(w)[0].bound

    # -- generic pieces ----------------------------------------------------------------
    def _s(self, w: np.ndarray) -> np.ndarray:
        return tustin_image(w, self.device.sample_time)

    def _theta(self, w: np.ndarray) -> np.ndarray:
        return theta_of(w, self.device.sample_time)

    def coupling_term(self, w, a: float, b: float) -> np.ndarray:  # pragma: no cover
        """The left side of the design inequality for the coupling ``(a, b)`` (defined by each display).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        a, b : float
            The coupling's parameters: ``(k_c, b_c)`` of the impedance display or
            ``(m_c, b_c)`` of the admittance display.

        Returns
        -------
        numpy.ndarray
            ``Re(1/Z_c)`` (eq. 9) or ``Re(Z_cA)`` (eq. 21), shape (N,).

        Raises
        ------
        NotImplementedError
            Always: a display subclass defines it.
        """
        raise NotImplementedError

    def margin(self, w, a: float, b: float) -> np.ndarray:
        """Coupling term minus bound (>= 0 everywhere means unconditionally stable).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], shape (N,).
        a, b : float
            The coupling's parameters, as for :meth:`coupling_term`.

        Returns
        -------
        numpy.ndarray
            The margin, shape (N,), in the units of the bound.

        Raises
        ------
        ValidationError
            When a frequency is not finite, > 0 and below Nyquist.
        """
        w = check_frequencies(w, self.device.sample_time)
        return self.coupling_term(w, a, b) - self.bound(w)

    def _worst(self, func: Callable[[np.ndarray], np.ndarray], w: np.ndarray, values: np.ndarray) -> tuple[float, float]:
        lo, hi = grids.band_edges(self.device)
        inband = (w >= lo) & (w <= hi)
        if not np.any(inband):
            j = int(np.argmin(values))
            return float(values[j]), float(w[j])
        wb, vb = w[inband], values[inband]
        rw, rv = grids.refine_minima(func, wb, vb, lo, hi, candidates=6)
        j = int(np.argmin(vb))
        if rv.size and rv[0] <= vb[j]:
            return float(rv[0]), float(rw[0])
        return float(vb[j]), float(wb[j])

    def _result(self, w, a, b, br, term, margin, zmin, zmax, k_max, b_min, app_m, app_b, refine) -> StabilityResult:
        eta = self.eta_from_margin(br.re_p11, margin, br.abs_p, br.re_p)
        if refine:
            worst, wf = self._worst(lambda x: self.coupling_term(x, a, b) - self._uncached_bound(x), w, margin)
        else:
            j = int(np.argmin(margin))
            worst, wf = float(margin[j]), float(w[j])
        with np.errstate(divide="ignore", invalid="ignore"):
            rel = np.where(term > 0, margin / term, np.where(margin >= 0, 1.0, -np.inf))
        rel = np.minimum(rel, 1.0)
        if refine:

            def rel_of(x: np.ndarray) -> np.ndarray:
                t = self.coupling_term(x, a, b)
                with np.errstate(divide="ignore", invalid="ignore"):
                    r = np.where(t > 0, 1.0 - self._uncached_bound(x) / t, -np.inf)
                return np.minimum(r, 1.0)

            rel_min, rel_f = self._worst(rel_of, w, rel)
        else:
            j = int(np.argmin(rel))
            rel_min, rel_f = float(rel[j]), float(w[j])
        finite_eta = eta[np.isfinite(eta)]
        return StabilityResult(
            display=self.display,
            w=w,
            bound=br.bound,
            coupling_term=term,
            margin=margin,
            eta=eta,
            zmin=zmin,
            zmax=zmax,
            singular=br.singular,
            worst_margin=worst,
            worst_frequency=wf,
            min_eta=float(finite_eta.min()) if finite_eta.size else float("inf"),
            stable=bool(worst >= 0.0),
            k_max=k_max,
            b_min=b_min,
            apparent_mass=app_m,
            apparent_damping=app_b,
            relative_margin=rel_min,
            binding_frequency=rel_f,
        )

    @staticmethod
    def eta_from_margin(re_p11: np.ndarray, margin: np.ndarray, abs_p: np.ndarray, re_p: np.ndarray) -> np.ndarray:
        """Llewellyn's factor of the coupled interface, ``1 + 2 Re p11 * margin / |p|``.

        Equivalent to ``(2 Re p11 Re p22' - Re p)/|p|`` but without its cancellation.
        Where ``Re p11 = 0`` (margin infinite) the definition is used directly.

        Parameters
        ----------
        re_p11 : numpy.ndarray
            ``Re p11`` of the device two-port, shape (N,).
        margin : numpy.ndarray
            Coupling term minus bound, shape (N,).
        abs_p : numpy.ndarray
            ``|p12 p21|``, shape (N,).
        re_p : numpy.ndarray
            ``Re(p12 p21)``, shape (N,).

        Returns
        -------
        numpy.ndarray
            ``eta`` of the coupled interface (dimensionless), shape (N,); ``inf`` where
            ``|p| = 0``.
        """
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            eta = 1.0 + 2.0 * re_p11 * margin / abs_p
            direct = -re_p / abs_p
        eta = np.where(re_p11 == 0, direct, eta)
        return np.where(abs_p == 0, np.inf, eta)
