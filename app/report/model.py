"""What a report is made of (no Qt): table rows, sections, figures, the parts each section returns,
and the one way the report prints a number.

Every other module of :mod:`app.report` imports this one and it imports none of them, so the
package has no import cycle: the Qt-free content (:mod:`.content`, :mod:`.identify_section`,
:mod:`.zwidth_section`) and the Qt figures (:mod:`.figures`, :mod:`.identify_figures`,
:mod:`.zwidth_figures`) meet only here.
"""

from __future__ import annotations

import html
import re
from dataclasses import dataclass, field
from typing import Any

from analysis.profiles import Profile
from analysis.progress import OperationCancelled
from analysis.study import PARAMETER_LABELS, Headline, format_number

__all__ = ["Row", "Section", "Figure", "Part", "ReportContent", "ReportCancelled", "num", "symbol_html", "row",
           "Numbers", "DIGITS"]

DIGITS = 6

#: the report's numbers: key -> (value, printed text); ``None`` where the analysis found none
Numbers = dict[str, tuple[float | None, str]]


#: A report build stopped by its ``cancelled()`` hook.  Deprecated alias of
#: :class:`analysis.progress.OperationCancelled` (the one cancel protocol, issue 21), kept for one release.
ReportCancelled = OperationCancelled


def num(x: Any, digits: int = DIGITS, *, rich: bool = False) -> str:
    """A number as the report prints it (``inf`` -> ``∞``, ``None`` -> ``infeasible``):
    :func:`analysis.study.format_number`, the rule the CLI and the GUI use too.  ``rich``: HTML
    powers of ten (``4.8×10<sup>−8</sup>``) for the page; the plain text is for the number table."""
    return format_number(x, digits, rich=rich)


def symbol_html(name: str) -> str:
    """A swept parameter's symbol in HTML (``kobj`` -> k<sub>obj</sub>)."""
    text = html.escape(PARAMETER_LABELS.get(name, (name, ""))[0])
    return re.sub(r"_(\w+)", r"<sub>\1</sub>", text)


@dataclass(frozen=True)
class Row:
    """One table row: quantity, symbol (HTML), value (printed), unit."""

    label: str
    symbol: str
    value: str
    unit: str = ""


@dataclass(frozen=True)
class Section:
    title: str
    paragraphs: tuple[str, ...] = ()
    rows: tuple[Row, ...] = ()
    after: tuple[str, ...] = ()


@dataclass
class Figure:
    """One figure: ``view`` is the laid-out :class:`~app.views.base.PlotView` that draws it."""

    key: str
    title: str
    caption: str
    view: Any


@dataclass(frozen=True)
class Part:
    """What one part of the report returns: its sections, the numbers it printed (key -> value
    and text) and the results its figures draw (key -> result object)."""

    sections: tuple[Section, ...] = ()
    numbers: Numbers = field(default_factory=dict)
    results: dict[str, Any] = field(default_factory=dict)


def row(numbers: Numbers, key: str, label: str, symbol: str, value: Any, unit: str = "") -> Row:
    """A table row of ``value`` printed by :func:`num`, its value and plain text noted in
    ``numbers`` under ``key`` (the caller's own dict, which it returns in its :class:`Part`)."""
    numbers[key] = (None if value is None else float(value), num(value))
    return Row(label, symbol, num(value, rich=True), unit)


@dataclass(frozen=True)
class ReportContent:
    title: str
    profile: Profile
    source: str | None
    date: str
    version: str
    sections: tuple[Section, ...]
    methods: tuple[str, ...]
    numbers: Numbers
    headline: Headline
    results: dict[str, Any] = field(default_factory=dict)

    def printed(self, key: str) -> str:
        return self.numbers[key][1]
