"""The headline of a profile: the verdict, the impedance range and the conservative designs.

One record, :class:`Headline`, holds what the GUI verdict, ``zwidth analyze`` and the report
show first: unconditional stability (eq. 9 or 21 of Adams, Moreyra & Hannaford), the stability
reserve and the frequency where it binds, the worst margin, the smallest Llewellyn factor
(eq. 3), k_max and b_min (eq. 11-12 or 23-24), and the designs (the largest k_c at the
current b_c; the feasible b_c interval at the current m_c and the smallest m_c).  A design value
outside the physical range of the field it would set is flagged (:attr:`Headline.beyond_limits`)
and printed as "beyond the physical range" (:mod:`analysis.study.design_limits`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from analysis.profiles.model import Profile
from analysis.study.design_limits import BeyondLimit, design_beyond_limits
from analysis.study.displays import DISPLAY_KINDS, DisplayKind, display_kind
from analysis.study.quantities import Quantity, quantity
from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.display_base import DisplayBase
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.twoport.results import StabilityResult

__all__ = ["Headline", "headline", "designs", "HEADLINE_KEYS", "DESIGN_KEYS"]

#: the verdict quantities, in the order they are printed
HEADLINE_KEYS = ("stable", "stability_reserve", "binding_frequency", "worst_margin", "worst_frequency", "min_eta",
                 "k_max", "b_min", "apparent_mass", "apparent_damping")
#: the design quantities of each display, in the order they are printed
DESIGN_KEYS = {kind.name: kind.design_keys for kind in DISPLAY_KINDS.values()}


@dataclass(frozen=True)
class Headline:
    """The headline numbers of one display of a profile (see the module docstring).

    Attributes
    ----------
    kind : DisplayKind
        The display type the numbers belong to.
    stable : bool
        Whether the coupled display is unconditionally stable (eq. 9 or 21).
    stability_reserve : float
        The smallest ``1 - bound/coupling term`` over the band (a fraction, printed in %).
    binding_frequency : float
        Where the reserve binds [rad/s].
    worst_margin : float
        The smallest margin of eq. (9) [m/(N·s)] or (21) [N·s/m].
    worst_frequency : float
        Where the worst margin lies [rad/s].
    min_eta : float
        The smallest Llewellyn factor η over the band (eq. 3).
    k_max : float
        The largest renderable stiffness [N/m] (eq. 12 or 24).
    b_min : float
        The smallest renderable damping [N·s/m] (eq. 11 or 23).
    apparent_mass : float
        The apparent free-motion mass [kg].
    apparent_damping : float
        The apparent free-motion damping [N·s/m].
    designs : dict of str to float or None
        The design values by key (see :func:`designs`); ``None`` for an infeasible design; empty
        when the designs were not computed.
    beyond_limits : dict of str to BeyondLimit
        The design keys whose value lies outside the physical range of the profile field it would
        set (derived from :attr:`designs`; :func:`~analysis.study.design_limits.design_beyond_limits`).
        Their numbers stay in :attr:`designs`; :meth:`text` prints the phrase instead.
    """

    kind: DisplayKind
    stable: bool
    stability_reserve: float
    binding_frequency: float
    worst_margin: float
    worst_frequency: float
    min_eta: float
    k_max: float
    b_min: float
    apparent_mass: float
    apparent_damping: float
    designs: dict[str, float | None] = field(default_factory=dict)
    beyond_limits: dict[str, BeyondLimit] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "beyond_limits", design_beyond_limits(self.designs))

    @classmethod
    def from_result(cls, result: StabilityResult, designs: dict[str, float | None] | None = None) -> Headline:
        """The headline of an evaluated :class:`StabilityResult` (what the GUI already has).

        Parameters
        ----------
        result : StabilityResult
            Eq. (9) or (21) evaluated at the profile's coupling.
        designs : dict of str to float or None, optional
            The designs (:func:`designs`); ``None`` for none.

        Returns
        -------
        Headline
            The headline.
        """
        return cls(kind=display_kind(result), stable=bool(result.stable), stability_reserve=result.relative_margin,
                   binding_frequency=result.binding_frequency, worst_margin=result.worst_margin,
                   worst_frequency=result.worst_frequency, min_eta=result.min_eta, k_max=result.k_max,
                   b_min=result.b_min, apparent_mass=result.apparent_mass, apparent_damping=result.apparent_damping,
                   designs=dict(designs or {}))

    @property
    def question(self) -> str:
        """Which question the verdict answers: the two-port test of the virtual coupling
        (Llewellyn's unconditional stability, eq. 9 or 21), not the wall controller's robustness."""
        return f"Virtual coupling (Llewellyn, eq. {self.kind.bound_equation})"

    @property
    def answer(self) -> str:
        """``"unconditionally stable"`` or ``"not unconditionally stable"``."""
        return "unconditionally stable" if self.stable else "not unconditionally stable"

    def verdict(self) -> str:
        """The verdict with its question: ``"Virtual coupling (Llewellyn, eq. 9): not unconditionally stable"``.

        Returns
        -------
        str
            :attr:`question` and :attr:`answer`.
        """
        return f"{self.question}: {self.answer}"

    def value(self, key: str) -> Any:
        """A headline or design value by its key.

        Parameters
        ----------
        key : str
            A key of :data:`HEADLINE_KEYS` or of :attr:`designs`.

        Returns
        -------
        Any
            The value (a bool, a float, or ``None`` for an infeasible design).

        Raises
        ------
        AttributeError
            When ``key`` is neither a headline field nor a design key.
        """
        return self.designs[key] if key in self.designs else getattr(self, key)

    def quantity(self, key: str) -> Quantity:
        """The :class:`Quantity` of ``key`` (the worst margin in this display's units).

        Parameters
        ----------
        key : str
            A key of :data:`~analysis.study.quantities.QUANTITIES`.

        Returns
        -------
        Quantity
            The quantity (:func:`~analysis.study.quantities.quantity`).
        """
        return quantity(key, self.kind.margin_unit)

    def text(self, key: str, *, unit: bool = True, rich: bool = False) -> str:
        """``key``'s value as every front end prints it.

        Parameters
        ----------
        key : str
            A key of :data:`HEADLINE_KEYS` or of :attr:`designs`.
        unit : bool, optional
            Append the unit (default ``True``).
        rich : bool, optional
            Qt rich text / HTML instead of plain text.

        Returns
        -------
        str
            The value printed by :meth:`Quantity.format`, or "beyond the physical range (b_c ≤
            1e+08 N·s/m)" for a design key of :attr:`beyond_limits`.
        """
        if key in self.beyond_limits:
            return self.beyond_limits[key].text(rich=rich)
        return self.quantity(key).format(self.value(key), unit=unit, rich=rich)

    def rows(self) -> list[tuple[Quantity, Any]]:
        """(quantity, value) of the verdict, then of the designs.

        Returns
        -------
        list of (Quantity, Any)
            One row per key of :data:`HEADLINE_KEYS`, then per design key of the display that
            :attr:`designs` holds, in print order.
        """
        keys = HEADLINE_KEYS + tuple(k for k in self.kind.design_keys if k in self.designs)
        return [(self.quantity(k), self.value(k)) for k in keys]

    def as_dict(self) -> dict[str, Any]:
        """Plain values by key (the verdict and the designs).

        Returns
        -------
        dict of str to Any
            The values of :meth:`rows` by their quantity's key.
        """
        return {q.key: v for q, v in self.rows()}


def _impedance_designs(profile: Profile, disp: ImpedanceDisplay) -> dict[str, float | None]:
    d = disp.max_stiffness(profile.bc)
    return {"bc": d.bc, "kc_max": None if d.kc is None else float(d.kc), "kc_max_frequency": d.frequency,
            "kc_max_margin": d.margin}


def _admittance_designs(profile: Profile, disp: AdmittanceDisplay) -> dict[str, float | None]:
    fd = disp.feasible_damping(profile.mc)
    try:
        mm = disp.min_mass()
    except ValueError:
        mm = None
    return {"mc": fd.mc, "bc_low": fd.low, "bc_low_frequency": fd.low_frequency, "bc_high": fd.high,
            "bc_high_frequency": fd.high_frequency, "min_mc": None if mm is None else mm.mc,
            "min_mc_bc": None if mm is None else mm.bc, "min_mc_frequency": None if mm is None else mm.frequency,
            "min_mc_bc_low": None if mm is None else mm.interval.low,
            "min_mc_bc_high": None if mm is None else mm.interval.high}


def designs(profile: Profile, kind: DisplayKind | str | None = None,
            display: DisplayBase | None = None) -> dict[str, float | None]:
    """The conservative designs of one display.

    The largest k_c at the profile's b_c (eq. 9), or the feasible b_c interval at the profile's
    m_c and the smallest m_c (eq. 21).

    Keys: :data:`DESIGN_KEYS` plus ``kc_max_margin`` (the worst margin at k_c,max) and
    ``min_mc_bc_low``/``min_mc_bc_high`` (the feasible b_c interval at m_c,min).

    Parameters
    ----------
    profile : Profile
        The device profile.
    kind : DisplayKind or str or None, optional
        The display type; ``None`` takes the profile's.
    display : DisplayBase or None, optional
        A built display object of this type (:meth:`DisplayKind.build`), to reuse its cache;
        ``None`` builds a fresh one.

    Returns
    -------
    dict of str to float or None
        The design values in SI units (N/m, N·s/m, kg, rad/s) by key; ``None`` where the design
        is infeasible.
    """
    k = display_kind(profile if kind is None else kind)
    disp = k.build(profile) if display is None else display
    if isinstance(disp, ImpedanceDisplay):
        return _impedance_designs(profile, disp)
    assert isinstance(disp, AdmittanceDisplay)
    return _admittance_designs(profile, disp)


def headline(profile: Profile, kind: DisplayKind | str | None = None, *, with_designs: bool = True) -> Headline:
    """The headline of ``profile`` for its display (or ``kind``), designs included by default.

    Parameters
    ----------
    profile : Profile
        The device profile.
    kind : DisplayKind or str or None, optional
        The display type; ``None`` takes the profile's.
    with_designs : bool, optional
        Compute the designs too (default ``True``).

    Returns
    -------
    Headline
        The verdict, the impedance range and (with ``with_designs``) the designs.
    """
    k = display_kind(profile if kind is None else kind)
    disp = k.build(profile)
    result = k.evaluate(profile, disp)
    return Headline.from_result(result, designs(profile, k, disp) if with_designs else None)
