"""The two-port bound for ``m`` DOF: absolute stability of the device with a virtual coupling (issue 25).

The network
-----------
The haptic interface of Adams & Hannaford's impedance display, with ``m`` Cartesian axes at
each port: port 1 is the handle (force ``F_h`` in, velocity ``v_h`` out), port 2 the coupling's
side (the coupling force ``F_d = -u`` in, minus the sensed velocity out: the sign convention of
the chain's eq. 2).  The device's admittance
matrix at ``z = e^{j w T}`` is the continuous one at the Tustin image ``s = j (2/T) tan(w T/2)``
with the actuator columns multiplied by the hold factor ``h = cos(w T/2) e^{-j w T/2}`` (Adams
& Hannaford, eq. 2, as :class:`analysis.twoport.ImpedanceDisplay` builds it for a chain)::

    G(s) = (M s^2 + C s + K)^{-1}
    Y11 = s J_h G J_h^T,    Y12 = -s J_h G B_a h,    Y21 = -s C_s G J_h^T,    Y22 = s C_s G B_a h

(:func:`device_two_port`, ``m x m`` blocks).  The coupling ``Z_c = S (b H_f(z) + k T z/(z-1))``
(eq. 4 in every axis, wall shape ``S`` positive definite) closes port 2, adding ``Z_c^{-1}`` to
``Y22`` (:func:`coupled_two_port`); for one axis this is the two-port behind eq. (9).

The criterion
-------------
Li, Tavakoli & Huang extend Llewellyn's criterion to networks whose ports carry ``m`` inputs and
outputs, through a positive-real Hermitian matrix: the network, free of right-half-plane (here:
outside the unit circle) poles, is absolutely stable -- stable with every passive termination
of either port -- when at every frequency the immittance matrix becomes passive after a
positive scaling of the second port's variables.  With ``D = diag(I, I/lambda)`` (the same
factor on the port's effort and flow, so a passive termination stays passive), the Hermitian
part of ``D P D^{-1}`` is::

    [[He P11, C(lambda)], [C(lambda)^H, He P22]],   C(lambda) = (lambda P12 + P21^H / lambda) / 2,

positive semidefinite for some ``lambda > 0`` iff ``He P11 > 0``, ``He P22 > 0`` and::

    rho = min_lambda || He(P11)^{-1/2} C(lambda) He(P22)^{-1/2} ||_2  <=  1

(:func:`lth_ratio`; ``||.||^2`` is convex in ``log lambda``, so a golden-section search finds
the minimum).  For ``m = 1`` the minimum is at ``lambda^2 = |p21| / |p12|`` and
``rho^2 = (|p12 p21| + Re(p12 p21)) / (2 Re p11 Re p22)``: ``rho <= 1`` is exactly Llewellyn's
``2 Re p11 Re p22 >= |p12 p21| + Re(p12 p21)`` (:func:`analysis.twoport.llewellyn`), and the
tests check the equality to 1e-12.  For ``m > 1`` one scalar per port is a sufficient condition:
it admits every passive ``m``-port termination, including ones that couple the axes, so it is
conservative against the exact loop with the physical grasps (:func:`lth_stiffness_bound`
against :func:`~analysis.multidof.limits.critical_wall_stiffness`; the guide quantifies it).

The statement implemented here is the scaled-passivity form above; the wording of the paper's
theorem could not be consulted when this module was written, so its conditions should be
checked against the paper (see the guide).

References
----------
J. Li, M. Tavakoli and Q. Huang, "Absolute stability of multi-DOF multilateral haptic systems",
IEEE Trans. Control Syst. Technol. 22(6), 2319-2328, 2014.

R. J. Adams and B. Hannaford, "Stability and performance of haptic displays: theory and
experiments", ASME IMECE, DSC-Vol. 64, 1998 (eqs. 2, 4, 9).

F. B. Llewellyn, "Some fundamental properties of transmission systems", Proc. IRE 40(3), 1952.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from analysis.chain.discretize import check_frequencies, hold_factor, tustin_image
from analysis.chain.velocity_filter import VelocityFilter, display_filter
from analysis.checks import nonnegative
from analysis.errors import ValidationError
from analysis.multidof.loop import wall_shape
from analysis.multidof.model import DeviceLike, structural_model
from analysis.sampled.sweeps import stable_end
from analysis.twoport.impedance import coupling_impedance

__all__ = ["device_two_port", "coupled_two_port", "lth_ratio", "lth_stiffness_bound", "LTHBound",
           "default_frequencies"]

_GOLDEN = 0.5 * (math.sqrt(5.0) - 1.0)
_SEARCH = 12.0  # half-width of the search in log(lambda) around the m = 1 optimum
_ITERATIONS = 64  # golden-section steps: the bracket (24 wide) shrinks to 24 * 0.618^64 ~ 1e-12


def default_frequencies(sample_time: float, count: int = 400) -> np.ndarray:
    """A log grid of ``count`` frequencies from ``1e-4`` Nyquist to just below Nyquist.

    Parameters
    ----------
    sample_time : float
        Sample period ``T`` [s].
    count : int, optional
        Number of frequencies.

    Returns
    -------
    numpy.ndarray
        Angular frequencies [rad/s], shape (count,), increasing, all below ``pi / T``.
    """
    return (math.pi / sample_time) * np.logspace(-4.0, math.log10(0.9999), count)


def device_two_port(device: DeviceLike, w: object) -> np.ndarray:
    """The device's admittance two-port ``[[Y11, Y12], [Y21, Y22]]`` at each frequency (module docstring).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    w : array_like
        Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.

    Returns
    -------
    numpy.ndarray
        Complex, shape (N, 2m, 2m): handle force and coupling force in, handle velocity and
        minus the sensed velocity out (the chain's convention, eq. 2).

    Raises
    ------
    ValidationError
        When a frequency is not finite, > 0 and below Nyquist.
    """
    model = structural_model(device)
    T, m = model.sample_time, model.axes
    w = check_frequencies(w, T)
    s = tustin_image(w, T)[:, None, None]
    h = hold_factor(w, T)[:, None, None]
    inputs = np.concatenate([model.handle.T, -model.actuation], axis=1)  # (n, 2m): F_h, F_d = -u
    outputs = np.concatenate([model.handle, -model.sensing], axis=0)  # (2m, n): v_h, -sensed velocity
    Z = model.mass * s * s + model.damping * s + model.stiffness  # (N, n, n)
    P = s * (outputs @ np.linalg.solve(Z, np.broadcast_to(inputs, (w.size,) + inputs.shape)))
    P[:, :, m:] *= h
    return P


def _coupling_admittance(m: int, w: np.ndarray, T: float, stiffness: float, damping: float, shape: np.ndarray,
                         velocity_filter: VelocityFilter | None) -> np.ndarray:
    """``Z_c^{-1}`` per frequency, shape (N, m, m); ``S`` positive definite."""
    zc = coupling_impedance(w, T, stiffness, damping, velocity_filter)
    return np.linalg.inv(shape)[None] / zc[:, None, None]


def _shape(m: int, normal: object) -> np.ndarray:
    S = wall_shape(m, normal)
    low = float(np.linalg.eigvalsh(S).min())
    if not low > 1e-12 * float(np.abs(S).max()):
        raise ValidationError("normal", "None (isotropic) or a positive definite wall shape: a plane wall's "
                                        "coupling has no admittance in its free directions", np.asarray(normal).tolist())
    return S


def coupled_two_port(device: DeviceLike, w: object, stiffness: float, damping: float, normal: object = None,
                     velocity_filter: VelocityFilter | None = None) -> np.ndarray:
    """The device with the coupling on port 2: ``Y22 + Z_c^{-1}`` (module docstring).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device.
    w : array_like
        Angular frequencies [rad/s], shape (N,), each > 0 and below Nyquist.
    stiffness : float
        Coupling stiffness ``k`` [N/m], >= 0.
    damping : float
        Coupling damping ``b`` [N s/m], >= 0.
    normal : None or array_like of shape (m, m), optional
        The coupling's shape ``S`` (``K_w = k S``, ``B_w = b S``): ``None`` for isotropic, or a
        symmetric positive definite matrix (a plane wall is refused: singular).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter on the damping term; ``None`` for the backward difference.

    Returns
    -------
    numpy.ndarray
        Complex, shape (N, 2m, 2m).

    Raises
    ------
    ValidationError
        When a frequency, the stiffness or the damping is out of range, or the shape is singular.
    """
    model = structural_model(device)
    m, T = model.axes, model.sample_time
    w = check_frequencies(w, T)
    k = nonnegative("stiffness", stiffness, "N/m")
    b = nonnegative("damping", damping, "N s/m")
    vf = display_filter(velocity_filter, T)
    P = device_two_port(model, w)
    P[:, m:, m:] += _coupling_admittance(m, w, T, k, b, _shape(m, normal), vf)
    return P


def _inv_sqrt(H: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``H^{-1/2}`` of Hermitian matrices (N, m, m) and whether each is positive definite."""
    lam, V = np.linalg.eigh(H)
    scale = np.maximum(np.abs(lam).max(axis=-1), np.finfo(float).tiny)
    ok = lam.min(axis=-1) > 1e-14 * scale
    root = np.where(ok[:, None], 1.0 / np.sqrt(np.where(lam > 0, lam, 1.0)), 0.0)
    return (V * root[:, None, :]) @ np.conj(np.swapaxes(V, -1, -2)), ok


def lth_ratio(P: object) -> tuple[np.ndarray, np.ndarray]:
    """The criterion's ratio ``rho`` and its best scale ``lambda`` at each frequency (module docstring).

    Parameters
    ----------
    P : array_like
        Immittance matrices, complex, shape (N, 2m, 2m) (or (2m, 2m)), ports of ``m`` axes.

    Returns
    -------
    rho : numpy.ndarray
        ``min_lambda ||He(P11)^{-1/2} C(lambda) He(P22)^{-1/2}||_2``, shape (N,): absolutely
        stable at that frequency when ``rho <= 1``; ``inf`` where ``He P11`` or ``He P22`` is
        not positive definite (no scaling makes the network passive there).
    scale : numpy.ndarray
        The minimizing ``lambda``, shape (N,).

    Raises
    ------
    ValidationError
        When ``P`` is not of shape (N, 2m, 2m) or has a non-finite entry.
    """
    a = np.asarray(P, dtype=complex)
    if a.ndim == 2:
        a = a[None]
    if a.ndim != 3 or a.shape[1] != a.shape[2] or a.shape[1] % 2 or not np.all(np.isfinite(a)):
        raise ValidationError("P", "finite immittance matrices of shape (N, 2m, 2m)", f"shape {a.shape}")
    m = a.shape[1] // 2
    P11, P12, P21, P22 = a[:, :m, :m], a[:, :m, m:], a[:, m:, :m], a[:, m:, m:]
    herm = lambda x: 0.5 * (x + np.conj(np.swapaxes(x, -1, -2)))  # noqa: E731
    A, okA = _inv_sqrt(herm(P11))
    B, okB = _inv_sqrt(herm(P22))
    U = 0.5 * A @ P12 @ B
    V = 0.5 * A @ np.conj(np.swapaxes(P21, -1, -2)) @ B

    def norm2(t: np.ndarray) -> np.ndarray:  # ||e^t U + e^-t V||_2^2, convex in t
        X = np.exp(t)[:, None, None] * U + np.exp(-t)[:, None, None] * V
        if m == 1:
            return (X.real * X.real + X.imag * X.imag)[:, 0, 0]
        return np.linalg.eigvalsh(np.conj(np.swapaxes(X, -1, -2)) @ X)[:, -1]

    nu = np.linalg.norm(U, ord=2, axis=(-2, -1))
    nv = np.linalg.norm(V, ord=2, axis=(-2, -1))
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = np.clip(0.5 * np.log(nv / nu), -300.0, 300.0)  # exact optimum for m = 1
    t0 = np.where(np.isfinite(t0), t0, 0.0)
    best_t, best = t0, norm2(t0)
    if m > 1:
        lo, hi = t0 - _SEARCH, t0 + _SEARCH
        x1, x2 = hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo)
        f1, f2 = norm2(x1), norm2(x2)
        for _ in range(_ITERATIONS):
            left = f1 <= f2  # the minimum lies in [lo, x2]
            hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
            x_new = np.where(left, hi - _GOLDEN * (hi - lo), lo + _GOLDEN * (hi - lo))
            f_new = norm2(x_new)
            x1, x2, f1, f2 = (np.where(left, x_new, x2), np.where(left, x1, x_new),
                              np.where(left, f_new, f2), np.where(left, f1, f_new))
        for x, f in ((x1, f1), (x2, f2)):
            better = f < best
            best_t, best = np.where(better, x, best_t), np.where(better, f, best)
    rho = np.where(okA & okB, np.sqrt(best), np.inf)
    return rho, np.exp(best_t)


@dataclass(frozen=True)
class LTHBound:
    """The largest coupling stiffness the criterion certifies on a frequency grid.

    Parameters
    ----------
    stiffness : float
        The bound ``k`` [N/m]: the criterion holds at every frequency of the grid for every
        stiffness from the scan's low end up to it (0 when it fails at the low end).
    frequencies : numpy.ndarray
        The grid [rad/s], shape (N,).
    ratio : numpy.ndarray
        ``rho`` at the bound, shape (N,).
    binding_frequency : float
        Where ``rho`` is largest at the bound [rad/s].
    """

    stiffness: float
    frequencies: np.ndarray
    ratio: np.ndarray
    binding_frequency: float


def lth_stiffness_bound(device: DeviceLike, damping: float = 0.0, normal: object = None, *, w: object = None,
                        velocity_filter: VelocityFilter | None = None, k_range: tuple[float, float] = (1.0, 1e9),
                        rtol: float = 1e-10, per_decade: int = 24) -> LTHBound:
    """The largest coupling stiffness with the device absolutely stable by the criterion (module docstring).

    The first failure of ``max_w rho(w; k) <= 1`` from small ``k``: a geometric scan of
    ``per_decade`` points a decade, then Brent's method on ``max_w rho - 1``
    (:func:`analysis.sampled.sweeps.stable_end`, keeping the certified end).

    Parameters
    ----------
    device : StructuralModel, RigidCartesianDevice or Device
        The device (its physical damping must make ``He Y11`` positive definite, or nothing
        is certified).
    damping : float, optional
        Coupling damping ``b`` [N s/m], >= 0.
    normal : None or array_like, optional
        The coupling's shape: ``None`` (isotropic) or a positive definite ``m x m`` matrix.
    w : array_like, optional
        The frequency grid [rad/s] (default :func:`default_frequencies`).
    velocity_filter : VelocityFilter or None, optional
        The velocity estimate's filter; ``None`` for the backward difference.
    k_range : tuple of (float, float), optional
        The scanned stiffness [N/m].
    rtol : float, optional
        Relative width of the final bracket.
    per_decade : int, optional
        Points a decade of the scan.

    Returns
    -------
    LTHBound
        The bound; ``stiffness = 0`` when the criterion fails at ``k_range[0]``, ``k_range[1]``
        when it never fails.

    Raises
    ------
    ValidationError
        When an argument is out of range or the shape is singular.
    """
    model = structural_model(device)
    m, T = model.axes, model.sample_time
    grid = check_frequencies(default_frequencies(T) if w is None else w, T)
    b = nonnegative("damping", damping, "N s/m")
    vf = display_filter(velocity_filter, T)
    S = _shape(m, normal)
    lo, hi = float(k_range[0]), float(k_range[1])
    if not 0 < lo < hi < math.inf:
        raise ValidationError("k_range", "0 < low < high < inf (N/m)", k_range)
    Y = device_two_port(model, grid)
    inv_s = np.linalg.inv(S)[None]

    def ratios(k: float) -> np.ndarray:
        P = Y.copy()
        P[:, m:, m:] += inv_s / coupling_impedance(grid, T, k, b, vf)[:, None, None]
        return lth_ratio(P)[0]

    def g(k: float) -> float:
        return float(np.max(ratios(k))) - 1.0

    ks = np.geomspace(lo, hi, int(math.ceil(per_decade * math.log10(hi / lo))) + 1)
    safe, g_safe = None, None
    for k in ks:
        gk = g(float(k))
        if gk > 0:
            if safe is None:
                return LTHBound(0.0, grid, ratios(lo), float(grid[int(np.argmax(ratios(lo)))]))
            kb = stable_end(g, safe, float(k), rtol, g_safe=g_safe, g_unsafe=gk)
            r = ratios(kb)
            return LTHBound(float(kb), grid, r, float(grid[int(np.argmax(r))]))
        safe, g_safe = float(k), gk
    r = ratios(hi)
    return LTHBound(hi, grid, r, float(grid[int(np.argmax(r))]))
