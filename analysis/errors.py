"""Errors raised by the analysis package.

Every error names the offending field (and element index where relevant) and the
allowed range, so that the GUI and the command line can show it next to the input.
"""

from __future__ import annotations


class ValidationError(ValueError):
    """A parameter is outside its allowed range.

    Attributes
    ----------
    field:
        Name of the parameter, e.g. ``"masses"``.
    index:
        Element index inside a vector parameter, or ``None`` for scalars.
    allowed:
        Human-readable description of the allowed range, e.g. ``"> 0 and finite"``.
    value:
        The rejected value.
    """

    def __init__(self, field: str, allowed: str, value: object = None, index: int | None = None):
        self.field = field
        self.index = index
        self.allowed = allowed
        self.value = value
        where = f"{field}[{index}]" if index is not None else field
        super().__init__(f"{where} = {value!r} is invalid: allowed range is {allowed}")
