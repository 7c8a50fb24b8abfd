"""Errors raised by the analysis package.

Every error names the offending field (and element index where relevant) and the
allowed range, so that the GUI and the command line can show it next to the input.
The validators that raise it are in :mod:`analysis.checks`.
"""

from __future__ import annotations

__all__ = ["ValidationError"]


class ValidationError(ValueError):
    """A parameter is outside its allowed range.

    Parameters
    ----------
    field : str
        Name of the parameter.
    allowed : str
        The allowed range in words.
    value : object, optional
        The rejected value.
    index : int or None, optional
        Element index inside a vector parameter.
    within : tuple of str, optional
        Names of the enclosing records, outermost first.

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
    within:
        Names of the enclosing records, outermost first (e.g. ``("grasp",)`` for the grasp's
        ``mass`` inside a scenario); empty for a top-level field.  Used to build JSON paths.
    """

    def __init__(self, field: str, allowed: str, value: object = None, index: int | None = None,
                 within: tuple[str, ...] = ()):
        self.field = field
        self.index = index
        self.allowed = allowed
        self.value = value
        self.within = tuple(within)
        where = f"{field}[{index}]" if index is not None else field
        shown = value.item() if type(value).__module__ == "numpy" and getattr(value, "ndim", None) == 0 else value
        super().__init__(f"{where} = {shown!r} is invalid: allowed range is {allowed}")  # 0.45, not np.float64(0.45)

    def inside(self, record: str) -> ValidationError:
        """The same error, raised from inside the record field ``record`` (prepended to ``within``).

        Parameters
        ----------
        record : str
            Name of the record field that holds the offending field, e.g. ``"grasp"``.

        Returns
        -------
        ValidationError
            A new error with ``within = (record, *self.within)`` and the same cause; the
            message is unchanged.
        """
        err = ValidationError(self.field, self.allowed, self.value, self.index, (record, *self.within))
        err.__cause__ = self.__cause__
        return err
