"""The one reader of zwidth's CSV files: measurements (:mod:`analysis.identify.csvio`) and
hardware trials (:func:`analysis.sampled.load_trials`).

A file is UTF-8 text (a UTF-8 byte-order mark is allowed), comma-separated, with one header row
naming the columns (case and surrounding spaces ignored).  Blank lines and lines whose first cell
starts with ``#`` are skipped but counted, so that a line number is the one an editor shows.
Every data row has as many values as the header has columns.  A numeric column holds finite
numbers; a column with a fixed vocabulary (``choices``, e.g. a trial's ``stable``) holds one of
its spellings.

Every fault raises :class:`CsvError` (or the subclass the caller names) with the file, the 1-based
line (header = line 1 when nothing precedes it) and the column: a missing file, a directory, an
empty file, UTF-16/UTF-32 text or bytes that are not UTF-8, NUL bytes, an unknown, duplicate or
missing column, text in a number column, a non-finite value, a value outside ``choices`` and a row
with too few or too many values.
"""

from __future__ import annotations

import codecs
import csv
import io
import math
import os
from collections.abc import Collection, Mapping
from dataclasses import dataclass

import numpy as np

__all__ = ["CsvError", "Table", "read_header", "read_table"]

_WIDE_BOMS = ((codecs.BOM_UTF32_LE, "UTF-32"), (codecs.BOM_UTF32_BE, "UTF-32"),
              (codecs.BOM_UTF16_LE, "UTF-16"), (codecs.BOM_UTF16_BE, "UTF-16"))


class CsvError(ValueError):
    """A CSV file (or a cell of it) cannot be used.

    The message is ``"<where>: <reason>"`` (:attr:`where`), or ``reason`` alone when no location
    is known.

    Parameters
    ----------
    reason : str
        What is wrong, without the location.
    file : str or os.PathLike or None, optional
        The file, or ``None`` for data passed in memory.
    line : int or None, optional
        1-based line number in the file (header = line 1 when nothing precedes it), or ``None``.
    column : str or None, optional
        Column name, or ``None`` when the problem is the file or a row as a whole.

    Attributes
    ----------
    file : str or None
        The file as given, or ``None`` for data passed in memory.
    line : int or None
        1-based line number in the file (the number an editor shows), or ``None``.
    column : str or None
        Column name, or ``None`` when the problem is the file or a row as a whole.
    reason : str
        The message without the location prefix.
    """

    def __init__(self, reason: str, *, file: str | os.PathLike | None = None, line: int | None = None,
                 column: str | None = None):
        self.reason = reason
        self.file = None if file is None else os.fspath(file)
        self.line = line
        self.column = column
        # explicit: a subclass may also derive from an exception whose __init__ takes other arguments
        ValueError.__init__(self, (self.where + ": " if self.where else "") + reason)

    @property
    def where(self) -> str:
        """``file, line N (data row N-1), column 'c'`` (the parts that are known)."""
        parts = []
        if self.file is not None:
            parts.append(self.file)
        if self.line is not None:
            parts.append(f"line {self.line}" + (f" (data row {self.line - 1})" if self.line > 1 else " (header)"))
        if self.column is not None:
            parts.append(f"column {self.column!r}")
        return ", ".join(parts)


@dataclass(frozen=True)
class Table:
    """The columns of a CSV file as float arrays, with the file line of the header and of each data row.

    Attributes
    ----------
    path : str
        The file as given.
    columns : dict of str to numpy.ndarray
        The known columns present in the file, in the file's order, one value per data row.
    lines : numpy.ndarray
        The file line (1-based) of each data row.
    header_line : int
        The file line of the header.
    error : type
        The class that :meth:`fail` returns (the caller's :class:`CsvError` subclass).
    """

    path: str
    columns: dict[str, np.ndarray]
    lines: np.ndarray
    header_line: int
    error: type[CsvError] = CsvError

    def __len__(self) -> int:
        return int(self.lines.size)

    def fail(self, reason: str, row: int | None = None, column: str | None = None) -> CsvError:
        """The error (to raise) at a data row and a column.

        Parameters
        ----------
        reason : str
            What is wrong.
        row : int, optional
            The 0-based data row index; ``None``: the header line.
        column : str, optional
            The column, or ``None`` for the row as a whole.

        Returns
        -------
        CsvError
            An instance of :attr:`error` with the file, the line and the column.
        """
        line = self.header_line if row is None else int(self.lines[row])
        return self.error(reason, file=self.path, line=line, column=column)


def _text(name: str, error: type[CsvError]) -> str:
    """The file's text, or the error that says why it has none."""
    if os.path.isdir(name):
        raise error("cannot read the file: it is a folder, not a CSV file", file=name)
    try:
        with open(name, "rb") as fh:
            data = fh.read()
    except FileNotFoundError:
        raise error("cannot read the file: no such file", file=name) from None
    except OSError as exc:
        raise error(f"cannot read the file: {exc.strerror or exc}", file=name) from exc
    for bom, kind in _WIDE_BOMS:
        if data.startswith(bom):
            raise error(f"{kind} text: save the file as UTF-8", file=name)
    if b"\x00" in data:
        line = data[:data.index(b"\x00")].count(b"\n") + 1
        raise error("NUL bytes: not a UTF-8 text file (UTF-16? save it as UTF-8)", file=name, line=line)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise error(f"byte 0x{data[exc.start]:02x} is not UTF-8: save the file as UTF-8", file=name,
                    line=line) from None


def _rows(name: str, text: str, error: type[CsvError]) -> list[tuple[int, list[str]]]:
    """``(line, stripped cells)`` of the rows that are neither blank nor comments."""
    reader = csv.reader(io.StringIO(text, newline=""))
    rows = []
    start = 1
    while True:
        try:
            r = next(reader)
        except StopIteration:
            return rows
        except csv.Error as exc:
            raise error(f"not valid CSV: {exc}", file=name, line=reader.line_num) from None
        cells = [c.strip() for c in r]
        if any(cells) and not cells[0].startswith("#"):
            rows.append((start, cells))
        start = reader.line_num + 1


def _number(text: str) -> float:
    if "_" in text:  # float() accepts "1_000"; a CSV number never has one
        raise ValueError(text)
    return float(text)


def _shown(cell: str) -> str:
    """A cell as a message quotes it: a long one (a 5000-digit number) cut to its first characters."""
    return repr(cell) if len(cell) <= 40 else f"{cell[:20]!r}... ({len(cell)} characters)"


def _numbers(table: Table, column: str, cells: list[str], choices: Mapping[str, float] | None) -> np.ndarray:
    """One column's cells as floats, or the error at the first bad cell."""
    if choices is not None:
        allowed = " or ".join(repr(c) for c in choices)
        for i, c in enumerate(cells):
            if c not in choices:
                raise table.fail(f"{_shown(c)} is not {allowed}" if c else f"empty: {allowed} is needed", i, column)
        return np.array([choices[c] for c in cells], float)
    out = np.empty(len(cells))
    for i, c in enumerate(cells):
        try:
            v = _number(c)
        except ValueError:
            raise table.fail(f"{_shown(c)} is not a number" if c else "empty: a number is needed", i, column) from None
        if not math.isfinite(v):
            overflow = not any(ch.isalpha() and ch not in "eE" for ch in c)  # digits too many, not "inf"
            raise table.fail(f"{_shown(c)} is not finite" + (": number too long or too large" if overflow else ""),
                             i, column)
        out[i] = v
    return out


def read_table(path: str | os.PathLike, allowed: Collection[str], *, required: Collection[str] = (),
               other_columns: bool = False, choices: Mapping[str, Mapping[str, float]] | None = None,
               error: type[CsvError] = CsvError) -> Table:
    """Read a CSV with a header row and numeric columns (module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    allowed : collection of str
        The column names the file may have (lower case).
    required : collection of str
        The columns it must have.
    other_columns : bool
        ``True``: columns not in ``allowed`` (unnamed ones too, e.g. a spreadsheet's index) are
        ignored, but still counted in every row; ``False``: they are refused.
    choices : mapping, optional
        Column -> {spelling: value} for columns with a fixed vocabulary.
    error : type
        The :class:`CsvError` subclass raised.

    Returns
    -------
    Table
        The known columns present, as float arrays, and the line of each data row (there may be
        none: the caller says how many rows it needs).

    Raises
    ------
    CsvError
        (``error``) for every fault, with the file, the line and the column.
    """
    name = os.fspath(path)
    rows = _rows(name, _text(name, error), error)
    if not rows:
        raise error("empty file: a header row is needed" + (f" ({', '.join(required)})" if required else ""),
                    file=name)
    hline, header = rows[0]
    header = [h.lower() for h in header]
    known = set(allowed)
    for i, h in enumerate(header):
        if not h and not other_columns:
            raise error(f"column {i + 1} of the header has no name", file=name, line=hline)
        if h not in known and not other_columns:
            raise error(f"unknown column (allowed: {', '.join(allowed)})", file=name, line=hline, column=h)
        if header.count(h) > 1 and (h in known or not other_columns):
            raise error("duplicate column", file=name, line=hline, column=h)
    for c in required:
        if c not in header:
            raise error(f"column is missing (the header has {', '.join(header)})", file=name, line=hline, column=c)
    for ln, r in rows[1:]:
        if len(r) != len(header):
            raise error(f"{len(r)} values, the header has {len(header)} columns", file=name, line=ln)
    lines = np.array([ln for ln, _ in rows[1:]], int)
    table = Table(name, {}, lines, hline, error)
    choices = choices or {}
    for j, h in enumerate(header):
        if h in known:
            table.columns[h] = _numbers(table, h, [r[j] for _, r in rows[1:]], choices.get(h))
    return table


def read_header(path: str | os.PathLike, *, error: type[CsvError] = CsvError) -> tuple[int, list[str]]:
    """The header's line and its column names (lower case) of a CSV file.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    error : type
        The :class:`CsvError` subclass raised.

    Returns
    -------
    tuple of (int, list of str)
        The header's file line and its names.

    Raises
    ------
    CsvError
        (``error``) for a file that cannot be read or has no header row.
    """
    name = os.fspath(path)
    rows = _rows(name, _text(name, error), error)
    if not rows:
        raise error("empty file: a header row is needed", file=name)
    return rows[0][0], [h.lower() for h in rows[0][1]]
