"""Designs beyond the tool's own physical limits (issue 22).

A design that zwidth proposes (the largest k_c, the feasible b_c interval, the smallest m_c and
its b_c, the robust designs) is a value of a profile field.  Each such field has one physical
range, the :class:`~analysis.chain.limits.Limit` that the profile loader reads it with
(:data:`analysis.profiles.schema.FIELDS_BY_NAME`); a design outside that range could not be typed
back in, so the front ends say :data:`BEYOND` (and which limit) instead of the number, and offer
no "Apply" for it.  No number is typed here: every bound is the loader's own.

* :func:`field_limit` -- the loader's :class:`Limit` of a profile field;
* :func:`beyond_limit` -- whether a reported design value lies outside its field's range;
* :func:`edits_beyond_limits` -- why a set of profile edits (an "Apply") cannot be made;
* :data:`DESIGN_FIELDS` -- which profile field each design key of
  :func:`analysis.study.headline.designs` is a value of.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from analysis.chain.limits import Limit
from analysis.profiles.schema import FIELDS_BY_NAME
from analysis.study.quantities import format_number

__all__ = ["BEYOND", "BeyondLimit", "DESIGN_FIELDS", "field_limit", "beyond_limit", "edits_beyond_limits",
           "design_beyond_limits"]

#: the phrase every front end shows instead of a design value outside its field's physical range
BEYOND = "beyond the physical range"

#: design key (:func:`analysis.study.headline.designs`) -> the profile field it is a value of
DESIGN_FIELDS: dict[str, str] = {
    "kc_max": "kc",
    "bc_low": "bc_adm",
    "bc_high": "bc_adm",
    "min_mc": "mc",
    "min_mc_bc": "bc_adm",
    "min_mc_bc_low": "bc_adm",
    "min_mc_bc_high": "bc_adm",
}

#: plain-text symbols of the profile fields (subscript after ``_``)
_SYMBOLS = {"kc": "k_c", "bc": "b_c", "mc": "m_c", "bc_adm": "b_c", "kp": "k_p", "kd": "k_d"}


def field_limit(field: str) -> Limit:
    """The physical range the profile loader reads ``field`` with.

    Parameters
    ----------
    field : str
        A :class:`~analysis.profiles.model.Profile` field with a physical range, e.g. ``"bc_adm"``.

    Returns
    -------
    Limit
        The field's rule in :data:`analysis.profiles.schema.SCHEMA`.

    Raises
    ------
    KeyError
        When the schema declares no :class:`Limit` for ``field``.
    """
    rule = FIELDS_BY_NAME[field][1].rule
    if not isinstance(rule, Limit):
        raise KeyError(f"the profile schema declares no physical range for {field!r}")
    return rule


@dataclass(frozen=True)
class BeyondLimit:
    """A design value outside the physical range of the profile field it would set.

    Attributes
    ----------
    field : str
        The profile field, e.g. ``"bc_adm"``.
    value : float
        The design value, in the field's unit.
    limit : Limit
        The field's range (:func:`field_limit`).
    """

    field: str
    value: float
    limit: Limit

    @property
    def above(self) -> bool:
        """Whether the value lies above the range (else below it, or NaN)."""
        return self.value > self.limit.hi

    def bound(self, *, rich: bool = False) -> str:
        """The limit it crosses: ``"b_c ≤ 1e+08 N·s/m"`` (rich: ``b<sub>c</sub> ≤ 1×10<sup>8</sup> N·s/m``).

        Parameters
        ----------
        rich : bool, optional
            Qt rich text / HTML instead of plain text.

        Returns
        -------
        str
            The field's symbol, the side of the range, the edge and the unit.
        """
        symbol = _SYMBOLS.get(self.field, self.field)
        if rich:
            head, _, sub = symbol.partition("_")
            symbol = f"{head}<sub>{sub}</sub>" if sub else head
        edge = self.limit.hi if self.above else self.limit.lo
        unit = self.limit.unit.replace(" ", "·")
        side = "≤" if self.above else (">" if self.limit.positive and self.limit.lo == 0.0 else "≥")
        return f"{symbol} {side} {format_number(edge, rich=rich)}" + (f" {unit}" if unit else "")

    def text(self, *, rich: bool = False) -> str:
        """What is shown instead of the number: ``"beyond the physical range (b_c ≤ 1e+08 N·s/m)"``.

        Parameters
        ----------
        rich : bool, optional
            Qt rich text / HTML instead of plain text.

        Returns
        -------
        str
            :data:`BEYOND` and the limit (:meth:`bound`).
        """
        return f"{BEYOND} ({self.bound(rich=rich)})"


def beyond_limit(field: str, value: float | None) -> BeyondLimit | None:
    """Whether a reported design value lies outside the physical range of ``field``.

    ``None`` (an infeasible design), NaN and infinities (an unbounded design or interval end,
    printed "∞") are not values to set and are never beyond; a finite value is beyond when it is
    below the range's lower edge or above its upper edge.  (An open lower edge such as b_c > 0 is
    not crossed by the edge itself: an interval that starts at 0 starts inside.)

    Parameters
    ----------
    field : str
        The profile field the value is for (see :data:`DESIGN_FIELDS`).
    value : float or None
        The design value, in the field's unit.

    Returns
    -------
    BeyondLimit or None
        The crossing, or ``None`` when the value is inside (or no value).
    """
    if value is None:
        return None
    x = float(value)
    if not math.isfinite(x):
        return None
    limit = field_limit(field)
    if limit.lo <= x <= limit.hi:
        return None
    return BeyondLimit(field, x, limit)


def design_beyond_limits(values: Mapping[str, float | None]) -> dict[str, BeyondLimit]:
    """The design values of :func:`analysis.study.headline.designs` outside their field's range.

    Parameters
    ----------
    values : mapping of str to float or None
        Design values by design key; keys not in :data:`DESIGN_FIELDS` (the profile's own
        gains, frequencies, margins) are not checked.

    Returns
    -------
    dict of str to BeyondLimit
        The design keys beyond their limit, in the order of ``values``.
    """
    out: dict[str, BeyondLimit] = {}
    for key, value in values.items():
        field = DESIGN_FIELDS.get(key)
        found = None if field is None else beyond_limit(field, value)
        if found is not None:
            out[key] = found
    return out


def edits_beyond_limits(edits: Mapping[str, float]) -> BeyondLimit | None:
    """Why a design's profile edits cannot be applied: the first value the loader would refuse.

    Each edit is checked by its field's rule exactly as the loader checks it
    (:meth:`Limit.contains`).

    Parameters
    ----------
    edits : mapping of str to float
        Profile field -> the value an "Apply" would set, e.g. ``{"mc": 0.68, "bc_adm": 1.3e12}``.

    Returns
    -------
    BeyondLimit or None
        The first edit outside its field's range, or ``None`` when all of them can be applied.
    """
    for field, value in edits.items():
        limit = field_limit(field)
        if not limit.contains(value):
            return BeyondLimit(field, float(value), limit)
    return None
