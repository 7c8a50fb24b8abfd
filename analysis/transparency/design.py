"""Transparency and robust stability of a virtual-wall controller (Eom, Suh & Yi, sections 2-3).

Reading of the paper (eq. 7-17) used here
-----------------------------------------
* Device (eq. 7): ``P(s) = 1/(m s + b)``, force at the handle to handle velocity.  A flexible
  device may be given instead as an :class:`analysis.Device` chain; then ``P(s)`` is the chain's
  driving-point admittance at the handle (``y11`` of :func:`analysis.chain.chain_response`, here
  evaluated by the chain's one continued fraction, :mod:`analysis.chain.continued_fraction`), its
  realization is the minimal handle state space (:func:`analysis.chain.handle_state_space`), and
  the controller is read as *collocated*: it measures the handle position and its force acts at
  the handle (the paper's ``v_d = v_h``).  The
  robustness weight of a chain uses its rigid-body parameters, ``m = sum m_i``, ``b = sum g_i``.
* Virtual wall (eq. 8): ``V(s) = (K + B s)/s``; its admittance ``Y_v(s) = s/(K + B s)``.
* Controller (eq. 12): ``C(s) = B_c + K_c/s`` acting on the velocity (``K_c x + B_c v``),
  ``K_c = K`` unless ``controller_stiffness`` is given.
* Transmitted admittance (eq. 9): ``Y_t = P/(1 + H P C)`` with ``H`` the hold model
  (:mod:`analysis.transparency.holds`), i.e. the velocity answer to the human force ``F_h``.
* Index (eq. 10-11): ``J = ||w1 (Y_v - Y_t)||_2^2 = (1/2 pi) int |w1 (Y_v - Y_t)|^2 dw`` over
  the whole axis, with ``w1 = (w_c/(s + w_c))^r`` (default ``r = 1``, ``w_c = 100`` rad/s).
  ``J`` is the H2 norm squared and is finite only if the closed loop is asymptotically stable and
  ``w1 (Y_v - Y_t)`` is strictly proper; otherwise it is ``inf`` and :class:`IndexResult` says
  why.  Ambiguity: the paper says ``J`` is unbounded unless ``K_c = K``; with eq. (11) as printed
  the error vanishes at DC like ``s (1/K - 1/K_c)`` for any ``K_c``, so ``J`` stays finite (the
  statement holds for the *position* error of a force step, ``(Y_v - Y_t)/s``).  We follow
  eq. (11) and allow ``K_c != K``.  ``Y_v - Y_t -> 1/B`` at high frequency, so ``r = 0``
  (no weight) gives ``J = inf``, and ``B = 0`` needs ``r >= 2``.
* Robustness (eq. 13-17): ``P~ = P/(1 + W Delta P)`` with ``W = alpha m s + beta b`` (eq. 15);
  ``L = -W P/(1 + H P C) = -W Y_t`` (eq. 16) and the condition ``||L||_inf <= 1`` (eq. 17).
  ``|L| -> alpha`` as ``w -> inf`` for every continuous hold (and 0 at DC when ``K_c > 0``), so the
  supremum may be the limit at infinity; :class:`RobustnessPeak` reports ``frequency = inf`` then.
* ``discrete`` hold: the exact sampled loop with a ZOH actuator and a position controller
  ``u_k = K_c x_k + B_c (x_k - x_{k-1})/T`` (backward-difference velocity, no computation
  delay).  ``Y_t(z)`` is the answer of the sampled velocity to a *held* human force (exact for
  forces that are constant between samples), evaluated on the unit circle; ``J`` is then the
  integral over the Nyquist band ``[0, pi/T)`` only (the error has no content beyond it in this
  model) -- not directly comparable with the continuous models, whose ``J`` includes the tail
  ``~ w_c^2/(pi B^2) (T/pi)``.  ``L(z)`` is the ZOH discretization of ``W P`` closed through the
  same loop (the Delta channel read as held too).
* Step response (Figs. 7, 10): always the exact sampled loop above (whatever the hold model),
  ZOH discretization by the matrix exponential; between samples the continuous state is exact as
  well (``substeps`` points per sample).

Numerics
--------
* ``J`` for rational holds: closed-form H2 norm from a Lyapunov equation; for ``zoh`` and
  ``discrete``: composite 16-point Gauss-Legendre on panels adapted to the closed-loop poles (for
  ``zoh``, those of the Pade and low-pass surrogates), half-period panels above Nyquist, and a
  ``w = Omega/u`` tail in which the ``e^{-sT}`` part of the hold is dropped (it integrates to
  < 1e-11 relative there).  Agreement with scipy quad and the Lyapunov value is checked in tests.
* ``||L||_inf``: a grid with points on every closed-loop resonance (``w0 + sigma * {...}``), 48
  per decade elsewhere and 8 per period above Nyquist for ``zoh``, then a zoom refinement of the
  three best local maxima (:func:`analysis.transparency.hinf.refine_peaks`).  Above the grid the
  ``zoh`` ripple is bounded analytically; ``certified`` is False if that bound could exceed the peak.
* Curves over ``B_c`` (Fig. 8) reuse everything that does not depend on ``B_c``: with
  ``a = 1/P + H K_c/s`` and ``h = H``, ``Y_t = 1/(a + B_c h)`` on a shared grid.

Structure
---------
:class:`WallDesign` is a thin facade over small objects, each with its own typed cache:
:class:`~analysis.transparency.plant.WallPlant` (``P(s)``, eq. 7),
:class:`~analysis.transparency.loops.LoopRealizations` (eq. 9 in its frequency-domain, rational and
sampled forms), :class:`~analysis.transparency.index.TransparencyIndex` (``J``, eq. 10-11),
:class:`~analysis.transparency.robustness.RobustnessAnalysis` (``||L||_inf``, eq. 13-17),
:class:`~analysis.transparency.search.DampingSearch` (Fig. 8 and the optimal ``B_c``) and
:class:`~analysis.transparency.step.StepSimulation` (Figs. 7, 10).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from analysis.chain.continued_fraction import handle_admittance
from analysis.chain.device import Device
from analysis.checks import frequencies
from analysis.errors import ValidationError
from analysis.transparency.holds import HOLDS
from analysis.transparency.index import TransparencyIndex, wall_admittance, weight
from analysis.transparency.loops import LoopRealizations, check_bc
from analysis.transparency.plant import WallPlant
from analysis.transparency.robustness import RobustnessAnalysis
from analysis.transparency.search import DampingSearch
from analysis.transparency.settings import (
    IndexResult,
    OptimalDamping,
    RobustnessPeak,
    StepResponse,
    TradeoffCurves,
    WallSettings,
)
from analysis.transparency.step import StepSimulation

__all__ = [
    "HOLDS",
    "WallSettings",
    "WallDesign",
    "IndexResult",
    "RobustnessPeak",
    "OptimalDamping",
    "TradeoffCurves",
    "StepResponse",
    "handle_admittance",
]


class WallDesign:
    """A virtual-wall controller design problem (Eom, Suh & Yi, section 3); see the module doc.

    ``WallDesign(mass=0.01, damping=0.022, wall_stiffness=1000.0, wall_damping=1.0,
    sample_time=1e-3, hold="lowpass2", weight_cutoff=100.0)`` -- any :class:`WallSettings` field
    as a keyword, or ``settings=``; ``device=`` a chain (then ``P = y11``, ``plant = "chain"``;
    the device's own ``sample_time`` is not used, the design's is).

    The parts: ``plant``, ``loops``, ``index`` (``J``), ``robustness`` (``||L||_inf``), ``search``
    (curves and optimum) and ``step`` (step response).

    Parameters
    ----------
    settings : WallSettings or None, optional
        The design; ``None`` for the defaults of :class:`WallSettings`.
    device : Device or None, optional
        A device chain read at the handle (sets ``plant = "chain"`` unless ``plant`` is given
        as a keyword); ignored when the resulting ``plant`` is ``"rigid"``.
    **params
        :class:`WallSettings` fields that replace those of ``settings``.

    Raises
    ------
    ValidationError
        When ``plant = "chain"`` without a device, or a field is out of its range.
    """

    def __init__(self, settings: WallSettings | None = None, *, device: Device | None = None, **params):
        base = settings if settings is not None else WallSettings()
        if device is not None:
            params.setdefault("plant", "chain")
        self.settings = replace(base, **params) if params else base
        if self.settings.plant == "chain" and device is None:
            raise ValidationError("plant", "'rigid' unless a device chain is given", "chain")
        if self.settings.plant == "rigid":
            device = None
        self.device = device
        self.plant = WallPlant(self.settings, device)
        self.loops = LoopRealizations(self.settings, self.plant)
        self.index = TransparencyIndex(self.loops)
        self.robustness = RobustnessAnalysis(self.loops)
        self.search = DampingSearch(self.index, self.robustness)
        self.step = StepSimulation(self.settings, self.plant)

    @classmethod
    def from_settings(cls, settings: WallSettings, device: Device | None = None) -> WallDesign:
        """The design of a settings record (the profile's ``transparency`` section).

        Parameters
        ----------
        settings : WallSettings
            The design.
        device : Device or None, optional
            The profile's device chain, used when ``settings.plant`` is ``"chain"``.

        Returns
        -------
        WallDesign
            ``WallDesign(settings, device=device)``.
        """
        return cls(settings, device=device)

    @property
    def kc(self) -> float:
        """The controller stiffness ``K_c`` (eq. 12)."""
        return self.settings.kc

    def weight(self, s: np.ndarray) -> np.ndarray:
        """``w1(s) = (w_c/(s + w_c))^r`` (eq. 11).

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.

        Returns
        -------
        numpy.ndarray
            The weight (dimensionless), the shape of ``s``.
        """
        return weight(self.settings, s)

    def wall_admittance(self, s: np.ndarray) -> np.ndarray:
        """``Y_v(s) = s/(K + B s)`` (eq. 8).

        Parameters
        ----------
        s : numpy.ndarray
            Complex frequencies [rad/s], any shape.

        Returns
        -------
        numpy.ndarray
            The virtual wall's admittance [m/(N s)], complex, the shape of ``s``.
        """
        return wall_admittance(self.settings, s)

    def closed_loop_poles(self, bc: float, hold: str | None = None) -> np.ndarray:
        """Closed-loop poles (rad/s) for a rational hold, or ``log(z)/T`` for ``discrete``.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        hold : str or None, optional
            A rational hold model or ``"discrete"``; ``None`` for the settings' hold.

        Returns
        -------
        numpy.ndarray
            Poles [rad/s], complex, shape (N,) (N the loop's order).

        Raises
        ------
        ValidationError
            When the hold is ``"zoh"`` (infinitely many poles) or ``bc`` is not finite.
        """
        hold = hold or self.settings.hold
        if hold == "zoh":
            raise ValidationError("hold", "a rational hold or 'discrete' (zoh has infinitely many poles)", hold)
        return self.loops.poles_many(check_bc(bc)[:1], hold)[0]

    # -- J (eq. 10-11) ----------------------------------------------------------------------------
    def index_result(self, bc: float, method: str = "auto", per_decade: float = 8.0, order: int = 16) -> IndexResult:
        """``J(B_c)`` (eq. 11) with its status; ``method`` ``auto``/``lyapunov``/``quadrature``.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        method : str, optional
            ``"auto"`` (Lyapunov for a rational hold, else quadrature), ``"lyapunov"`` or
            ``"quadrature"``.
        per_decade : float, optional
            Quadrature panels per decade.
        order : int, optional
            Gauss-Legendre points per panel.

        Returns
        -------
        IndexResult
            ``J``, whether it is finite and why not, the method and the number of nodes.

        Raises
        ------
        ValidationError
            When ``bc`` is not finite or ``method`` does not fit the hold
            (:meth:`TransparencyIndex.index_result`).
        """
        return self.index.index_result(bc, method, per_decade, order)

    def performance_index(self, bc: float) -> float:
        """``J(B_c)`` of eq. (11); ``inf`` when not finite (see :meth:`index_result` for why).

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.

        Returns
        -------
        float
            ``J`` [(m/s/N)^2 rad/s], or ``inf``.
        """
        return self.index.performance_index(bc)

    def quadrature_nodes(self, bcs: np.ndarray, per_decade: float = 8.0, order: int = 16,
                         tail_eps: float = 1e-4) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Nodes/weights of the ``J`` quadrature (:meth:`TransparencyIndex.quadrature_nodes`).

        Parameters
        ----------
        bcs : numpy.ndarray
            Controller dampings ``B_c`` [N s/m] that share the nodes, shape (R,).
        per_decade : float, optional
            Panels per decade between the singularities.
        order : int, optional
            Gauss-Legendre points per panel.
        tail_eps : float, optional
            Bound of ``|H P C|`` at the start of the ``zoh`` tail.

        Returns
        -------
        w : numpy.ndarray
            Nodes of the main part [rad/s], shape (P,).
        wt : numpy.ndarray
            Their weights [rad/s], shape (P,).
        w_tail : numpy.ndarray
            Nodes of the tail [rad/s], shape (Q,) (empty for ``discrete``).
        wt_tail : numpy.ndarray
            Their weights [rad/s], shape (Q,).
        """
        return self.index.quadrature_nodes(bcs, per_decade, order, tail_eps)

    # -- ||L||_inf (eq. 13-17), curves and optimum ------------------------------------------------
    def robustness_peak(self, bc: float, alpha: float | None = None, beta: float | None = None) -> RobustnessPeak:
        """``||L||_inf`` (eq. 16-17) and its frequency; ``alpha``, ``beta`` default to the settings.

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.

        Returns
        -------
        RobustnessPeak
            The peak gain, its frequency and whether it is certified.

        Raises
        ------
        ValidationError
            When ``bc`` is not finite or ``alpha``/``beta`` is negative or not finite.
        """
        return self.robustness.robustness_peak(bc, alpha, beta)

    def tradeoff(self, bc_values=None, alpha: float | None = None, beta: float | None = None) -> TradeoffCurves:
        """``J(B_c)`` and ``||L||_inf(B_c)`` over ``bc_values`` (default: the settings' range; Fig. 8).

        Parameters
        ----------
        bc_values : array_like or None, optional
            Controller dampings ``B_c`` [N s/m], finite, shape (N,); ``None`` for the settings'
            ``bc_count`` values from ``bc_min`` to ``bc_max``.
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.

        Returns
        -------
        TradeoffCurves
            ``J``, ``||L||_inf`` and the peak frequencies at each ``B_c``.

        Raises
        ------
        ValidationError
            When a ``B_c`` is not finite or ``alpha``/``beta`` is negative.
        """
        return self.search.tradeoff(bc_values, alpha, beta)

    def optimal_damping(self, alpha: float | None = None, beta: float | None = None,
                        bc_range: tuple[float, float] | None = None) -> OptimalDamping:
        """Minimize ``J(B_c)`` subject to ``||L||_inf <= 1`` (:meth:`DampingSearch.optimal_damping`).

        Parameters
        ----------
        alpha : float or None, optional
            Mass uncertainty of the weight ``W`` (eq. 15), >= 0; ``None`` for the settings' value.
        beta : float or None, optional
            Damping uncertainty of the weight ``W``, >= 0; ``None`` for the settings' value.
        bc_range : tuple of (float, float) or None, optional
            The searched ``(low, high)`` range of ``B_c`` [N s/m]; ``None`` for the settings'
            ``(bc_min, bc_max)``.

        Returns
        -------
        OptimalDamping
            The optimum, or ``feasible = False`` with the reason.

        Raises
        ------
        ValidationError
            When ``alpha``/``beta`` is negative or the range is not finite.
        """
        return self.search.optimal_damping(alpha, beta, bc_range)

    # -- views ----------------------------------------------------------------------------------
    def admittances(self, w, bc: float) -> tuple[np.ndarray, np.ndarray]:
        """``(Y_v, Y_t)`` at ``s = j w`` (Fig. 9); for ``discrete``, ``Y_t(e^{jwT})`` (w < pi/T).

        Parameters
        ----------
        w : array_like
            Angular frequencies [rad/s], positive and finite, any shape; below ``pi/T`` for the
            ``discrete`` hold.
        bc : float
            The controller damping ``B_c`` [N s/m], finite.

        Returns
        -------
        Y_v : numpy.ndarray
            The virtual wall's admittance (eq. 8) [m/(N s)], complex, the shape of ``w``.
        Y_t : numpy.ndarray
            The transmitted admittance (eq. 9) [m/(N s)], complex, the shape of ``w``.

        Raises
        ------
        ValidationError
            When a frequency is invalid or, for ``discrete``, not below Nyquist, or ``bc`` is not
            finite.
        """
        w = frequencies(w)
        bcs = check_bc(bc)[:1]
        flat = w.ravel()
        if self.settings.hold == "discrete":
            if np.any(flat >= np.pi / self.settings.sample_time):
                raise ValidationError("frequency", "< Nyquist for the discrete hold", float(flat.max()))
        yt = self.loops.admittance_rows(bcs, flat)[0]
        return self.wall_admittance(1j * w), yt.reshape(w.shape)

    def step_response(self, bc: float, force: float | None = None, duration: float | None = None,
                      substeps: int = 8) -> StepResponse:
        """Human-force step on the exact sampled loop (:meth:`StepSimulation.step_response`).

        Parameters
        ----------
        bc : float
            The controller damping ``B_c`` [N s/m], finite.
        force : float or None, optional
            The human-force step [N], finite; ``None`` for the settings' ``step_force``.
        duration : float or None, optional
            Duration [s], in (0, 100]; ``None`` for the settings' ``step_duration``.
        substeps : int, optional
            Points per sample between the samples, 1 .. 1000.

        Returns
        -------
        StepResponse
            ``ceil(duration/T) * substeps + 1`` points from ``t = 0``.

        Raises
        ------
        ValidationError
            When an argument is out of its range.
        """
        return self.step.step_response(bc, force, duration, substeps)
