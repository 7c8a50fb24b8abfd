"""Named, unit-labelled quantities and the one rule that prints them.

The GUI verdict, ``zwidth analyze`` and the report print every headline number through
:meth:`Quantity.format`, so the three say the same thing in the same way.  The stability
reserve (the smallest ``1 - bound/coupling term`` over the band, eq. 9 or 21) is a fraction
in the data and is printed in per cent everywhere.

:func:`format_number` is the one rule for a number: ASCII (``-1.2e-05``) for what programs read
(the command line's text, CSV, JSON), typeset (``−1.2×10⁻⁵``, a true minus sign) for what people
read in the GUI and the report, with the same digits.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import Any

__all__ = ["Quantity", "QUANTITIES", "J_UNIT", "quantity", "format_number", "rich_numbers", "superscript_numbers", "DIGITS",
           "STYLES", "ascii_numbers"]

#: significant digits of a printed number unless a quantity says otherwise
DIGITS = 6


def _rich(text: str) -> str:
    """``1.2e+05`` -> ``1.2×10<sup>5</sup>`` and a true minus sign (Qt rich text / HTML)."""
    if "e" in text:
        mant, exp = text.split("e")
        text = f"{mant}×10<sup>{int(exp)}</sup>"
    return text.replace("-", "−")


_E_NUMBER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?)e([+-]?\d+)(?!\w)")
#: an ASCII minus of a number in a sentence: before a digit, a decimal point or "∞", not after a word
#: character, a point or a closing bracket (so "2nd-order", "eq. 10-11", "x-1" and dates keep their hyphen)
_MINUS = re.compile(r"(?<![\w.)\]])-(?=\.?\d|∞)")


def rich_numbers(text: str) -> str:
    """Every ``1.2e+05`` of a plain text as ``1.2×10<sup>5</sup>``, every minus sign of a number as
    "−" (Qt rich text / HTML).

    The way :func:`format_number` prints with ``rich=True``: for a line built from ASCII numbers
    (a sentence of the analysis, an error message) that a view or the report shows as rich text.

    Parameters
    ----------
    text : str
        Plain text with numbers in ``e`` notation.

    Returns
    -------
    str
        The text with every such number typeset as rich text (a true minus sign in the exponent).
    """
    return _MINUS.sub("−", _E_NUMBER.sub(lambda m: _rich(f"{m.group(1)}e{m.group(2)}"), text))


_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")
_FROM_SUPERSCRIPT = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


def superscript_numbers(text: str) -> str:
    """Every ``2.55e+11`` of a plain text as ``2.55×10¹¹`` in Unicode superscripts, every minus sign
    of a number as "−".

    The typesetting of :func:`format_number`'s ``style="text"`` for a sentence built from ASCII
    numbers (e.g. :func:`~analysis.study.optimum_verdict`, which the command line prints too) where
    the GUI shows plain text only (a plot's text items, a tool tip).

    Parameters
    ----------
    text : str
        Plain text with numbers in ``e`` notation.

    Returns
    -------
    str
        The text with every such number written with a superscript exponent and a true minus
        sign.
    """
    return _MINUS.sub("−", _E_NUMBER.sub(lambda m: _text(f"{m.group(1)}e{m.group(2)}"), text))


_TEXT_NUMBER = re.compile(r"(−?\d+(?:\.\d+)?)×10([⁻]?[⁰¹²³⁴⁵⁶⁷⁸⁹]+)")


def ascii_numbers(text: str) -> str:
    """The inverse of :func:`superscript_numbers`: every ``−2.55×10⁻¹¹`` of a text as ``-2.55e-11``
    and every "−" as "-" (the ASCII form of :func:`format_number`, for files scripts read: a CSV's
    comment lines carry a plot's notes).

    Parameters
    ----------
    text : str
        Text with numbers in the ``"text"`` style.

    Returns
    -------
    str
        The text with ASCII numbers, as ``format_number(x)`` prints them.
    """
    def sub(m: re.Match) -> str:
        return f"{m.group(1)}e{int(m.group(2).translate(_FROM_SUPERSCRIPT)):+03d}"

    return _TEXT_NUMBER.sub(sub, text).replace("−", "-")


#: the three ways a number is printed: ``"ascii"`` for what scripts read (``zwidth analyze``'s text,
#: CSV, JSON, the report's number table), ``"text"`` for plain text a person reads in the GUI and the
#: report (legends, status and tool tips, notes, tab labels), ``"rich"`` for Qt rich text / HTML
STYLES = ("ascii", "text", "rich")


def _text(text: str) -> str:
    """``-1.2e-05`` -> ``−1.2×10⁻⁵``: a true minus sign and a superscript exponent (plain Unicode text)."""
    if "e" in text:
        mant, exp = text.split("e")
        text = f"{mant}×10{str(int(exp)).translate(_SUPERSCRIPT)}"
    return text.replace("-", "−")


def format_number(value: Any, digits: int = DIGITS, *, scale: float = 1.0, rich: bool = False,
                  style: str | None = None) -> str:
    """A number as zwidth prints it.

    ``None`` -> "infeasible", NaN -> "n/a", +-inf -> "∞"/"-∞", booleans -> "yes"/"no", else
    ``digits`` significant digits (Python's ``g`` format: ``1.2e+05``, ``-3.2``).

    The one rule: the GUI's views, the verdict, ``zwidth analyze`` and the report all print
    numbers through it, in one of three styles with the same digits:

    - ``"ascii"`` (the default): what scripts parse, an ASCII hyphen-minus and ``e`` exponent
      (``-1.2e-05``): the command line's text, CSV and JSON, the report's number table.
    - ``"text"``: plain text a person reads (plot legends and notes, status and tool tips, tab
      labels, sentences in the GUI): a true minus sign "−" (U+2212) and a superscript power of
      ten (``−1.2×10⁻⁵``, ``−∞``).
    - ``"rich"`` (or ``rich=True``): Qt rich text / HTML, the same typesetting with ``<sup>``
      (``−1.2×10<sup>−5</sup>``).

    Parameters
    ----------
    value : Any
        The number: a float or int, a numpy scalar, a bool, or ``None`` (an infeasible design).
    digits : int, optional
        Significant digits (default :data:`DIGITS`).
    scale : float, optional
        Factor applied before printing (100 prints a fraction in per cent).
    rich : bool, optional
        Qt rich text / HTML instead of plain text: the same as ``style="rich"``.
    style : str or None, optional
        One of :data:`STYLES`; ``None`` is ``"rich"`` with ``rich=True``, else ``"ascii"``.

    Returns
    -------
    str
        The printed number, without a unit.

    Raises
    ------
    ValueError
        For an unknown style, or ``rich=True`` with another style.
    """
    if style is None:
        style = "rich" if rich else "ascii"
    elif style not in STYLES or (rich and style != "rich"):
        raise ValueError(f"style must be one of {STYLES} (rich=True with 'rich' only), not {style!r}")
    if value is None:
        return "infeasible"
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return "yes" if value else "no"
    x = float(value)
    if math.isnan(x):
        return "n/a"
    if math.isinf(x):
        return "∞" if x > 0 else ("-∞" if style == "ascii" else "−∞")
    text = f"{x * scale:.{digits}g}"
    return {"ascii": text, "text": _text(text), "rich": _rich(text)}[style]


@dataclass(frozen=True)
class Quantity:
    """A result's key, name, symbol (plain text, e.g. ``k_max``), unit, and how it is printed.

    Attributes
    ----------
    key : str
        The result's key, e.g. ``"k_max"`` (the key of :data:`QUANTITIES` and of the summaries).
    name : str
        Its name for people, e.g. ``"largest renderable stiffness"``.
    symbol : str
        Plain-text symbol, e.g. ``"k_max"``; empty when it has none.
    unit : str
        Unit, e.g. ``"N/m"``; empty for a dimensionless number.
    digits : int
        Significant digits of the printed number.
    scale : float
        Printed value = value * scale (100 for a fraction printed in %).
    """

    key: str
    name: str
    symbol: str = ""
    unit: str = ""
    digits: int = DIGITS
    scale: float = 1.0  # printed value = value * scale (100 for a fraction printed in %)

    def number(self, value: Any, *, rich: bool = False, style: str | None = None) -> str:
        """The printed number without its unit.

        Parameters
        ----------
        value : Any
            The value in the data's units (a fraction for a per-cent quantity), or ``None``.
        rich : bool, optional
            Qt rich text / HTML instead of plain text.
        style : str or None, optional
            ``"ascii"``, ``"text"`` or ``"rich"``, as :func:`format_number`.

        Returns
        -------
        str
            The number as :func:`format_number` prints it with this quantity's digits and scale.
        """
        return format_number(value, self.digits, scale=self.scale, rich=rich, style=style)

    def format(self, value: Any, *, unit: bool = True, rich: bool = False, style: str | None = None) -> str:
        """The printed number with its unit (none after "∞" or a word such as "infeasible").

        Parameters
        ----------
        value : Any
            The value in the data's units (a fraction for a per-cent quantity), or ``None``.
        unit : bool, optional
            Append the unit (default ``True``).
        rich : bool, optional
            Qt rich text / HTML instead of plain text.
        style : str or None, optional
            ``"ascii"``, ``"text"`` or ``"rich"``, as :func:`format_number`.

        Returns
        -------
        str
            The printed number, followed by the unit for a finite value.
        """
        text = self.number(value, rich=rich, style=style)
        finite = value is not None and not isinstance(value, bool) and math.isfinite(float(value))
        return f"{text} {self.unit}" if unit and self.unit and finite else text

    def parse(self, text: str) -> float:
        """The value back from :meth:`format`'s plain text (tests compare printed outputs).

        Parameters
        ----------
        text : str
            Plain text as :meth:`format` prints it (``"ascii"`` or ``"text"`` style), with or
            without its unit; "∞", "-∞", "n/a" and the older spelling "unbounded" are read too.

        Returns
        -------
        float
            The value in the data's units (the printed number divided by :attr:`scale`).

        Raises
        ------
        ValueError
            When the text is not a number.
        """
        word = text.split()[0] if text.split() else text
        special = {"∞": math.inf, "-∞": -math.inf, "−∞": -math.inf, "n/a": math.nan,
                   "unbounded": math.inf, "-unbounded": -math.inf}  # the spelling before the one "∞"
        if word in special:
            return special[word]
        if "×10" in word:  # the "text" style: −1.2×10⁻⁵
            mant, exp = word.split("×10")
            word = f"{mant}e{exp.translate(_FROM_SUPERSCRIPT)}"
        return float(word.replace("−", "-")) / self.scale


_RAD_S = "rad/s"
_NSM = "N·s/m"
#: unit of the transparency index J (eq. 10-11): the squared H2 norm of an admittance error
J_UNIT = "m²/(N²·s³)"

#: the headline quantities (``worst_margin``'s unit depends on the display: see :func:`quantity`)
QUANTITIES: dict[str, Quantity] = {q.key: q for q in (
    Quantity("stable", "unconditionally stable"),
    Quantity("stability_reserve", "stability reserve", "", "%", digits=4, scale=100.0),
    Quantity("binding_frequency", "binding frequency", "", _RAD_S),
    Quantity("worst_margin", "worst margin", "", ""),
    Quantity("worst_frequency", "worst-margin frequency", "", _RAD_S),
    Quantity("min_eta", "smallest Llewellyn factor", "η_min"),
    Quantity("k_max", "largest renderable stiffness", "k_max", "N/m"),
    Quantity("b_min", "smallest renderable damping", "b_min", _NSM),
    Quantity("apparent_mass", "apparent free-motion mass", "", "kg"),
    Quantity("apparent_damping", "apparent free-motion damping", "", _NSM),
    Quantity("kc", "coupling stiffness", "k_c", "N/m"),
    Quantity("kp", "PD position-loop stiffness", "k_p", "N/m"),
    Quantity("kd", "PD position-loop damping", "k_d", _NSM),
    Quantity("bc", "for coupling damping", "b_c", _NSM),
    Quantity("kc_max", "largest stable coupling stiffness", "k_c,max", "N/m"),
    Quantity("kc_max_frequency", "binding frequency", "", _RAD_S),
    Quantity("mc", "for coupling mass", "m_c", "kg"),
    Quantity("bc_low", "feasible damping, lower edge", "b_c,low", _NSM),
    Quantity("bc_low_frequency", "binding frequency (lower)", "", _RAD_S),
    Quantity("bc_high", "feasible damping, upper edge", "b_c,high", _NSM),
    Quantity("bc_high_frequency", "binding frequency (upper)", "", _RAD_S),
    Quantity("min_mc", "smallest stable coupling mass", "m_c,min", "kg"),
    Quantity("min_mc_bc", "with damping", "b_c", _NSM),
    Quantity("min_mc_frequency", "binding frequency", "", _RAD_S),
    # the wall controller of Eom, Suh & Yi: J = ||w1 (Y_v - Y_t)||_2^2 (eq. 10-11), the squared H2 norm of an
    # admittance error [m/(N·s)] under a dimensionless weight: [m/(N·s)]^2 times [1/s] of the integral over ω
    Quantity("transparency_index", "transparency index", "J", J_UNIT),
    Quantity("robustness_peak", "robustness peak", "‖L‖∞", ""),
)}


def quantity(key: str, margin_unit: str | None = None) -> Quantity:
    """The quantity ``key``, with the display's unit for the worst margin.

    ``margin_unit`` (the display's, see ``DisplayKind.margin_unit``) completes the worst margin,
    whose unit is that of eq. (9) or (21).

    Parameters
    ----------
    key : str
        A key of :data:`QUANTITIES`, e.g. ``"k_max"``.
    margin_unit : str or None, optional
        The unit of ``"worst_margin"``; ignored for the other keys.

    Returns
    -------
    Quantity
        The quantity.

    Raises
    ------
    KeyError
        When ``key`` is not a key of :data:`QUANTITIES`.
    """
    q = QUANTITIES[key]
    if key == "worst_margin" and margin_unit is not None:
        return replace(q, unit=margin_unit)
    return q
