"""The documented form of a zwidth CSV export (issue 22), checked by the CLI and the GUI tests.

Each header is ``curve: quantity [unit]`` (:data:`app.views.export.HEADER_PATTERN`) in the plots'
own spelling (``ω``, ``ρ``, ``‖L‖∞``, ``N·s/m``, ``N²·s/m²``, ``m/(N·s)``, ``-`` when
dimensionless), never an old spelling or an internal name (``omega``, ``N s/m``, ``lowpass1``,
``area_linear``); every field is a number ``float()`` reads (``inf`` included) or empty, never
``nan``: an empty field is "not defined here".  A table (one row per grid point: ``zwidth space``,
``zwidth workspace``) is the same form with one ``quantity [unit]`` column per quantity
(:data:`app.views.export.TABLE_HEADER_PATTERN`, :func:`check_table`).
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

from app.views.export import DIMENSIONLESS, HEADER_PATTERN, TABLE_HEADER_PATTERN

#: the CSV section of the results page, which documents the form
DOC = Path(__file__).resolve().parents[1] / "docs" / "guide" / "results.md"


def documented_form() -> tuple[str, set[str]]:
    """The header pattern the results page gives, and every code span of its CSV section (its units)."""
    text = DOC.read_text(encoding="utf-8")
    section = text[text.index("## Plot data (CSV)"):]
    spans = set(re.findall(r"`([^`]+)`", section))
    pattern = next(s for s in spans if s.startswith("^(?P<curve>"))
    return pattern, spans


def documented_table_pattern() -> str:
    """The table header pattern the results page gives."""
    return next(s for s in documented_form()[1] if s.startswith("^(?P<quantity>"))


#: spellings of the old headers and of the code that a header must not show
FORBIDDEN = re.compile(r"omega|\brho\b|spectral radius|\^|N s/m|lowpass|butter|area_linear|area_log|\bnan\b|<[a-z/]",
                       re.IGNORECASE)


def read_csv(path: Path) -> tuple[list[str], list[str], list[list[str]]]:
    """A CSV export: (note lines, header, rows)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    notes = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader([line for line in lines if not line.startswith("#")]))
    return notes, rows[0], rows[1:]


def _check_unit(name: str, unit: str, documented: set[str]) -> None:
    assert not FORBIDDEN.search(name), name
    assert unit == DIMENSIONLESS or (" " not in unit and "-" not in unit), name  # N·s/m, never N s/m
    assert unit in documented, f"{name}: the unit is not listed in {DOC.name}"


def _check_fields(header: list[str], rows: list[list[str]], notes: list[str]) -> None:
    """One field per column, each a number ``float()`` reads (``inf`` too) or empty, never NaN."""
    assert rows, "no data"
    for i, row in enumerate(rows):
        assert len(row) == len(header), i
        for field in row:
            assert field.strip().lower() not in ("nan", "-nan", "+nan"), (i, row)
            if field:
                assert not math.isnan(float(field)), (i, field)  # float() reads every field (inf too)
    assert not any(re.search(r"\bnan\b", note, re.IGNORECASE) for note in notes), notes
    assert all(note.startswith("# note: ") for note in notes), notes


def check_csv(header: list[str], rows: list[list[str]], notes: list[str] = ()) -> None:
    """The documented form: headers, units, one field per column, numbers or empty, no NaN."""
    pattern, documented = documented_form()
    assert pattern == HEADER_PATTERN.pattern  # the page gives the pattern the code writes
    assert header and len(header) % 2 == 0  # an x and a y column per curve
    for j, name in enumerate(header):
        m = HEADER_PATTERN.match(name)
        assert m, name
        _check_unit(name, m["unit"], documented)
        if j % 2 == 0:  # the pair names one curve: the x and the y column start alike
            assert HEADER_PATTERN.match(header[j + 1])["curve"] == m["curve"], (name, header[j + 1])
    _check_fields(header, rows, notes)


def check_table(header: list[str], rows: list[list[str]], notes: list[str] = ()) -> None:
    """The documented table form: ``quantity [unit]`` headers, each once, then the fields as :func:`check_csv`'s."""
    _, documented = documented_form()
    assert documented_table_pattern() == TABLE_HEADER_PATTERN.pattern
    assert header and len(set(header)) == len(header), header
    for name in header:
        m = TABLE_HEADER_PATTERN.match(name)
        assert m, name
        _check_unit(name, m["unit"], documented)
    _check_fields(header, rows, notes)


def column(header: list[str], rows: list[list[str]], name: str) -> list[str]:
    """The fields of the column ``name``."""
    j = header.index(name)
    return [r[j] for r in rows]
