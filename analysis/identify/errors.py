"""Errors of the identification package.

:class:`MeasurementError` is raised for a measurement file or array that cannot be used.  Like a
bad profile (:class:`analysis.profiles.ProfileError`), it names the file, the row and the
column.  Rows are *file line numbers*, 1-based, counting the header as line 1 (the number an
editor shows); the message also gives the 1-based data row (line - 1).
"""

from __future__ import annotations

from analysis.csvtable import CsvError
from analysis.progress import OperationCancelled

__all__ = ["FitCancelled", "MeasurementError", "ParameterKeyError"]


class MeasurementError(CsvError):
    """A measurement (file or arrays) cannot be used.

    A :class:`~analysis.csvtable.CsvError` (the one CSV reader's error): the attributes ``file``
    (``None`` for arrays passed in memory), ``line`` (1-based, header = line 1), ``column`` and
    ``reason`` (the message without the location prefix).
    """

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


#: A fit stopped because its ``cancelled()`` hook returned true (checked before every model
#: evaluation, so a worker's Cancel takes effect within one evaluation).  Deprecated alias of
#: :class:`analysis.progress.OperationCancelled` (the one cancel protocol, issue 21), kept for one
#: release: ``except FitCancelled`` catches every cancel.
FitCancelled = OperationCancelled
