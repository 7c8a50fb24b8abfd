"""Errors of the identification package.

:class:`MeasurementError` is raised for a measurement file or array that cannot be used.  Like a
bad profile (:class:`analysis.profiles.ProfileError`), it names the file, the row and the
column.  Rows are *file line numbers*, 1-based, counting the header as line 1 (the number an
editor shows); the message also gives the 1-based data row (line - 1).
"""

from __future__ import annotations

import os

__all__ = ["FitCancelled", "MeasurementError", "ParameterKeyError"]


class MeasurementError(ValueError):
    """A measurement (file or arrays) cannot be used.

    Attributes
    ----------
    file:
        The file as given, or ``None`` for arrays passed in memory.
    line:
        1-based line number in the file (header = line 1), or ``None``.
    column:
        Column name, or ``None`` when the problem is the file or a row as a whole.
    reason:
        The message without the location prefix.
    """

    def __init__(self, reason: str, *, file: str | os.PathLike | None = None, line: int | None = None,
                 column: str | None = None):
        self.reason = reason
        self.file = None if file is None else os.fspath(file)
        self.line = line
        self.column = column
        where = []
        if self.file is not None:
            where.append(self.file)
        if line is not None:
            where.append(f"line {line}" + (f" (data row {line - 1})" if line > 1 else " (header)"))
        if column is not None:
            where.append(f"column {column!r}")
        super().__init__((", ".join(where) + ": " if where else "") + reason)

    @property
    def row(self) -> int | None:
        """1-based data row (the line below the header is data row 1)."""
        return None if self.line is None or self.line < 2 else self.line - 1


class ParameterKeyError(ValueError):
    """A parameter key such as ``"masses[7]"`` does not name a parameter of the chain."""

    def __init__(self, key: object, expected: str):
        self.key = key
        self.expected = expected
        super().__init__(f"parameter key {key!r} is invalid: expected {expected}")


class FitCancelled(Exception):
    """A fit stopped because its ``cancelled()`` callback returned True (checked before every
    model evaluation, so a worker's Cancel takes effect within one evaluation)."""
