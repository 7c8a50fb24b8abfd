"""One set of validators, settings-record helpers and the JSON spelling of non-finite numbers.

Every settings class of :mod:`analysis` (the device chain, :class:`~analysis.transparency.WallSettings`,
:class:`~analysis.transparency.ObserverSettings`, :class:`~analysis.sampled.SimulationOptions`,
:class:`~analysis.sampled.Scenario`, :class:`~analysis.sampled.Grasp`,
:class:`~analysis.sampled.Environment`, the profile record ...) validates its fields here.

Validators
    :class:`Real` is a rule for one real number (range, open/closed ends, whether ``inf`` is
    allowed, and the wording of each kind of rejection); :func:`real`, :func:`positive` and
    :func:`nonnegative` apply one.  :func:`integer`, :func:`choice`, :func:`boolean`,
    :func:`string`, :func:`vector` and :func:`check_elements` cover the rest.  Every failure is a
    :class:`~analysis.errors.ValidationError` naming the field (and element index) and the allowed
    range, e.g. ``mass = -1.0 is invalid: allowed range is > 0 and finite (kg)``.
Records
    A settings record is a frozen dataclass validated in ``__post_init__``, deriving from
    :class:`SettingsRecord` for ``to_dict``/``from_dict``/``replace``.
    :func:`record_to_dict` and :func:`record_from_dict` turn one into a JSON-ready dict and back,
    driven by the dataclass fields: unknown keys are refused naming the key, nested records
    (a scenario's grasp) are built recursively, and float fields accept the strings ``"inf"`` and
    ``"-inf"``.
JSON
    Strict JSON has no ``Infinity``: :func:`json_float` writes ``inf``/``-inf``/``nan`` as the
    strings ``"inf"``/``"-inf"``/``"nan"``, :func:`from_json_float` reads ``"inf"`` and ``"-inf"``
    back, and :func:`jsonable` makes any nested result (dicts, lists, numpy arrays and scalars)
    JSON-ready that way.  Profiles, the command line's ``--json`` output and the report use it.

This is the bottom layer of :mod:`analysis`: it imports numpy and :mod:`analysis.errors` only.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import types
import typing
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar, Self, TypeVar

import numpy as np

from analysis.errors import ValidationError

__all__ = [
    "REAL_TYPES",
    "Real",
    "POSITIVE",
    "NONNEGATIVE",
    "is_real",
    "describe_range",
    "real",
    "positive",
    "nonnegative",
    "integer",
    "choice",
    "boolean",
    "string",
    "vector",
    "check_elements",
    "frequencies",
    "record_to_dict",
    "record_from_dict",
    "SettingsRecord",
    "json_float",
    "from_json_float",
    "jsonable",
]

#: The Python and numpy types accepted as real numbers (``bool`` excluded by :func:`is_real`).
REAL_TYPES = (int, float, np.integer, np.floating)

R = TypeVar("R")


# -- numbers -------------------------------------------------------------------------------------


def is_real(value: object) -> bool:
    """True for an int, float or numpy number that is not a boolean.

    Parameters
    ----------
    value : object
        Any value.

    Returns
    -------
    bool
        Whether ``value`` is one of :data:`REAL_TYPES` and not a (numpy) boolean.
    """
    return isinstance(value, REAL_TYPES) and not isinstance(value, (bool, np.bool_))


def describe_range(lo: float | None = None, hi: float | None = None, *, lo_open: bool = False,
                   hi_open: bool = False, allow_inf: bool = False, unit: str = "") -> str:
    """The usual wording of a range: ``"> 0 and finite (kg)"``, ``"in [0, 1)"``, ``"finite (N)"``.

    Parameters
    ----------
    lo : float or None, optional
        Lower bound; ``None`` for none.
    hi : float or None, optional
        Upper bound; ``None`` for none.
    lo_open : bool, optional
        Whether ``lo`` itself is excluded.
    hi_open : bool, optional
        Whether ``hi`` itself is excluded.
    allow_inf : bool, optional
        Whether an infinity is allowed (drops "and finite" from a one-sided range).
    unit : str, optional
        Unit appended in parentheses; ``""`` for none.

    Returns
    -------
    str
        The allowed range in words.
    """
    if lo is not None and hi is not None:
        text = f"in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
    elif lo is not None:
        text = f"{'>' if lo_open else '>='} {lo:g}" + ("" if allow_inf else " and finite")
    elif hi is not None:
        text = f"{'<' if hi_open else '<='} {hi:g}" + ("" if allow_inf else " and finite")
    else:
        text = "a number" if allow_inf else "finite"
    return f"{text} ({unit})" if unit else text


@dataclass(frozen=True)
class Real:
    """A rule for one real number; calling it validates a value and returns it as a float.

    ``lo``/``hi`` bound the value (``lo_open``/``hi_open`` exclude the end itself); NaN is always
    refused and ``inf`` unless ``allow_inf``.  The error's allowed range is ``allowed`` (default
    :func:`describe_range` of the rule, with ``unit``); ``not_real`` and ``not_finite`` override
    it for a value that is not a real number, and for NaN or a refused infinity.  The error
    carries the value as given, or (``report_float``) as converted to float where it converts.
    A Python int too large for a float is refused with the allowed range.

    Calling the rule, ``rule(name, value, index=None)``, returns the value as a float or raises
    :class:`~analysis.errors.ValidationError` naming ``name`` (and ``index``).

    Parameters
    ----------
    lo, hi : float or None, optional
        Lower and upper bounds, in ``unit``; ``None`` for none.
    lo_open, hi_open : bool, optional
        Whether the bound itself is excluded.
    allow_inf : bool, optional
        Whether ``inf`` (and ``-inf``) pass, within the bounds.
    unit : str, optional
        Unit shown in the default wording of the range.
    allowed : str or None, optional
        The allowed range shown in errors; ``None`` for :func:`describe_range` of the rule.
    not_real : str or None, optional
        The allowed range shown for a value that is not a real number.
    not_finite : str or None, optional
        The allowed range shown for NaN or a refused infinity.
    report_float : bool, optional
        Whether the error carries the value converted to float (else as given).
    """

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    allow_inf: bool = False
    unit: str = ""
    allowed: str | None = None
    not_real: str | None = None
    not_finite: str | None = None
    report_float: bool = False

    @property
    def text(self) -> str:
        """The allowed range as shown in errors."""
        if self.allowed is not None:
            return self.allowed
        return describe_range(self.lo, self.hi, lo_open=self.lo_open, hi_open=self.hi_open,
                              allow_inf=self.allow_inf, unit=self.unit)

    def in_range(self, x: float) -> bool:
        """True if the float ``x`` is within the bounds (finiteness aside).

        Parameters
        ----------
        x : float
            The value.

        Returns
        -------
        bool
            Whether ``x`` lies within ``lo`` and ``hi`` (open ends excluded).
        """
        lo, hi = self.lo, self.hi
        return not ((lo is not None and (x < lo or (self.lo_open and x == lo)))
                    or (hi is not None and (x > hi or (self.hi_open and x == hi))))

    def accepts(self, x: float) -> bool:
        """True if the float ``x`` passes the rule (no error built; the fast path for arrays).

        Parameters
        ----------
        x : float
            The value.

        Returns
        -------
        bool
            Whether ``x`` is not NaN, finite unless ``allow_inf``, and within the bounds.
        """
        if x - x != 0.0 and (x != x or not self.allow_inf):  # NaN, or an infinity not allowed
            return False
        return self.in_range(x)

    def __call__(self, name: str, value: object, index: int | None = None) -> float:
        if not is_real(value):
            raise ValidationError(name, self.not_real or self.text, value, index)
        try:
            x = float(value)
        except OverflowError:
            raise ValidationError(name, self.text, value, index) from None
        if x - x != 0.0 and (x != x or not self.allow_inf):  # NaN, or an infinity not allowed
            raise ValidationError(name, self.not_finite or self.text, x if self.report_float else _python(value), index)
        if not self.in_range(x):
            raise ValidationError(name, self.text, x if self.report_float else _python(value), index)
        return x


#: ``> 0 and finite`` and ``>= 0 and finite``.
POSITIVE = Real(lo=0.0, lo_open=True)
NONNEGATIVE = Real(lo=0.0)


def _python(value: object) -> object:
    """A numpy scalar as the Python number it holds (errors print ``0.45``, not ``np.float64(0.45)``)."""
    return value.item() if isinstance(value, np.generic) else value


def real(name: str, value: object, *, index: int | None = None, **rule: Any) -> float:
    """``Real(**rule)(name, value, index)``: a real number as float, validated by the rule.

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    index : int or None, optional
        Element index named in the error.
    **rule
        The :class:`Real` fields (``lo``, ``hi``, ``lo_open``, ``unit``, ...).

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    ValidationError
        When the value is not a real number, or NaN, or a refused infinity, or out of range.
    """
    return Real(**rule)(name, value, index)


@functools.cache
def _unit_rule(positive: bool, unit: str) -> Real:
    return Real(lo=0.0, lo_open=positive, unit=unit)


def positive(name: str, value: object, unit: str = "") -> float:
    """A finite number > 0 (``"> 0 and finite (unit)"``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    unit : str, optional
        Unit shown in the error.

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    ValidationError
        When the value is not a finite real number > 0.
    """
    return _unit_rule(True, unit)(name, value)


def nonnegative(name: str, value: object, unit: str = "") -> float:
    """A finite number >= 0 (``">= 0 and finite (unit)"``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    unit : str, optional
        Unit shown in the error.

    Returns
    -------
    float
        The value as a float.

    Raises
    ------
    ValidationError
        When the value is not a finite real number >= 0.
    """
    return _unit_rule(False, unit)(name, value)


def integer(name: str, value: object, lo: int, hi: int | None = None, allowed: str | None = None) -> int:
    """An int (Python or numpy, not bool) in ``[lo, hi]`` (``"an integer in [lo, hi]"``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    lo : int
        Smallest allowed value.
    hi : int or None, optional
        Largest allowed value; ``None`` for no upper bound.
    allowed : str or None, optional
        The allowed range shown in the error; ``None`` for the default wording.

    Returns
    -------
    int
        The value as a Python int.

    Raises
    ------
    ValidationError
        When the value is not an integer (a bool is not) or lies outside ``[lo, hi]``.
    """
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not (
            lo <= value and (hi is None or value <= hi)):
        if allowed is None:
            allowed = f"an integer in [{lo}, {hi}]" if hi is not None else f"an integer >= {lo}"
        raise ValidationError(name, allowed, _python(value))
    return int(value)


def choice(name: str, value: object, options: Iterable[str], allowed: str | None = None) -> str:
    """One of the strings ``options`` (``"one of 'a', 'b'"``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    options : iterable of str
        The allowed strings.
    allowed : str or None, optional
        The allowed range shown in the error; ``None`` lists ``options``.

    Returns
    -------
    str
        The value.

    Raises
    ------
    ValidationError
        When the value is not one of ``options``.
    """
    options = tuple(options)
    if not isinstance(value, str) or value not in options:
        raise ValidationError(name, allowed or "one of " + ", ".join(repr(o) for o in options), value)
    return value


def boolean(name: str, value: object) -> bool:
    """A Python or numpy boolean (``"true or false"``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.

    Returns
    -------
    bool
        The value as a Python bool.

    Raises
    ------
    ValidationError
        When the value is not a boolean (an int is not).
    """
    if not isinstance(value, (bool, np.bool_)):
        raise ValidationError(name, "true or false", value)
    return bool(value)


def string(name: str, value: object, nonempty: bool = False) -> str:
    """A string; ``nonempty``: with a non-blank character.

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    value : object
        The value to check.
    nonempty : bool, optional
        Whether the string must have a non-blank character.

    Returns
    -------
    str
        The value.

    Raises
    ------
    ValidationError
        When the value is not a string, or is blank and ``nonempty``.
    """
    if not isinstance(value, str) or (nonempty and not value.strip()):
        raise ValidationError(name, "a non-empty string" if nonempty else "a string", value)
    return value


def vector(name: str, values: object, length: int | None = None) -> np.ndarray:
    """A read-only float copy of ``values`` as a 1-D array; ``length``: exactly that many.

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    values : object
        A number or (nested) sequence of real numbers.
    length : int or None, optional
        The number of values required; ``None`` for any.

    Returns
    -------
    numpy.ndarray
        The values as floats, flattened, read-only, shape (n,).

    Raises
    ------
    ValidationError
        When the values do not convert to floats, or their number is not ``length``.
    """
    try:
        arr = np.array(values, dtype=float, copy=True).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise ValidationError(name, "a list of real numbers", values) from exc
    if length is not None and arr.size != length:
        raise ValidationError(name, f"exactly {length} values", arr.tolist())
    arr.setflags(write=False)
    return arr


def check_elements(name: str, values: Iterable[object], rule: Real = NONNEGATIVE) -> None:
    """Every element by ``rule``; an error names the element index (``masses[2]``).

    Parameters
    ----------
    name : str
        The field's name, as the error names it.
    values : iterable of object
        The elements (a float array takes a fast path).
    rule : Real, optional
        The rule of each element (default :data:`NONNEGATIVE`).

    Raises
    ------
    ValidationError
        When an element fails ``rule`` (the first such, with its index).
    """
    if isinstance(values, np.ndarray) and values.dtype.kind == "f" and all(map(rule.accepts, values.tolist())):
        return
    for i, x in enumerate(values):
        rule(name, x, i)


def frequencies(values: object, name: str = "frequency") -> np.ndarray:
    """Angular frequencies as a float array (any shape), all finite and > 0 (rad/s).

    Parameters
    ----------
    values : object
        Angular frequencies [rad/s], array_like of any shape.
    name : str, optional
        The field's name, as the error names it.

    Returns
    -------
    numpy.ndarray
        The frequencies as a float array of the same shape.

    Raises
    ------
    ValidationError
        When a frequency is not finite or not > 0.
    """
    w = np.asarray(values, dtype=float)
    if w.size and (not np.all(np.isfinite(w)) or np.any(w <= 0)):
        raise ValidationError(name, "finite and > 0 (rad/s)", w)
    return w


# -- JSON ----------------------------------------------------------------------------------------


def json_float(x: float) -> float | str:
    """``x``, or ``"inf"``, ``"-inf"``, ``"nan"`` for the non-finite values strict JSON lacks.

    Parameters
    ----------
    x : float
        A number.

    Returns
    -------
    float or str
        ``x`` when finite, else its string spelling.
    """
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return x


def from_json_float(value: object) -> object:
    """``"inf"``/``"-inf"`` back to floats; anything else unchanged (and validated by its field).

    Parameters
    ----------
    value : object
        A value read from JSON.

    Returns
    -------
    object
        ``inf`` or ``-inf`` for those strings, else ``value`` unchanged.
    """
    if isinstance(value, str):
        return {"inf": math.inf, "-inf": -math.inf}.get(value, value)
    return value


def jsonable(value: object) -> object:
    """Plain JSON values: mappings, sequences and numpy arrays recursively; numpy scalars as Python
    numbers; non-finite floats by :func:`json_float`; anything else as ``str``.

    Parameters
    ----------
    value : object
        Any value, e.g. a nested result of dicts, lists and numpy arrays.

    Returns
    -------
    object
        A dict (string keys), list, bool, int, float, string (including ``"inf"``, ``"-inf"``,
        ``"nan"``) or ``None``.
    """
    if isinstance(value, Mapping):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return [jsonable(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return json_float(float(value))
    if value is None or isinstance(value, str):
        return value
    return str(value)


# -- settings records ----------------------------------------------------------------------------


def _plain(value: object) -> object:
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return record_to_dict(value)
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, float):
        return json_float(value)
    return value


def record_to_dict(record: object) -> dict[str, Any]:
    """The JSON-ready dict of a settings record: one key per dataclass field, in field order.

    Nested records become dicts, tuples lists, non-finite floats ``"inf"``/``"-inf"``.

    Parameters
    ----------
    record : object
        A dataclass instance (a settings record).

    Returns
    -------
    dict of str to object
        One JSON-ready value per field, in field order.
    """
    return {f.name: _plain(getattr(record, f.name)) for f in dataclasses.fields(record)}


@functools.cache
def _field_kinds(cls: type) -> dict[str, tuple[bool, type | None]]:
    """Field name -> (holds a float, nested record class or None), from the type hints."""
    hints = typing.get_type_hints(cls)
    out: dict[str, tuple[bool, type | None]] = {}
    for f in dataclasses.fields(cls):
        hint = hints.get(f.name, object)
        union = typing.get_origin(hint) in (typing.Union, types.UnionType)
        args = typing.get_args(hint) if union else (hint,)
        nested = next((a for a in args if isinstance(a, type) and dataclasses.is_dataclass(a)), None)
        out[f.name] = (float in args, nested)
    return out


def record_from_dict(cls: type[R], data: object, name: str) -> R:
    """Build (and so validate) the record ``cls`` from a dict; missing keys take the defaults.

    ``name`` names the record in the error for a ``data`` that is not a mapping.  An unknown key
    is refused with the key as the field; float fields accept ``"inf"``/``"-inf"``; a nested
    record given as a dict is built the same way, its errors marked
    :meth:`~analysis.errors.ValidationError.inside` the field.

    The first argument, ``cls``, is the record class: a dataclass that validates its fields on
    construction.  (numpydoc reads a first parameter named ``cls`` as a class method's, so it is
    described here rather than under Parameters.)

    Parameters
    ----------
    data : object
        The dict read, e.g. from JSON.
    name : str
        The record's name, used in the error when ``data`` is not a mapping.

    Returns
    -------
    object
        The record, an instance of ``cls``.

    Raises
    ------
    ValidationError
        When ``data`` is not a mapping, has an unknown key, or a value fails its field's check.
    """
    if not isinstance(data, Mapping):
        raise ValidationError(name, "an object", data)
    kinds = _field_kinds(cls)
    unknown = sorted((key for key in data if key not in kinds), key=str)
    if unknown:
        raise ValidationError(str(unknown[0]), "a known field: " + ", ".join(sorted(kinds)), data[unknown[0]])
    values: dict[str, object] = {}
    for key, value in data.items():
        is_float, nested = kinds[key]
        if nested is not None and isinstance(value, Mapping):
            try:
                value = record_from_dict(nested, value, key)
            except ValidationError as err:
                raise err.inside(key) from err
        elif is_float:
            value = from_json_float(value)
        values[key] = value
    return cls(**values)


class SettingsRecord:
    """Base of the frozen-dataclass settings records: ``to_dict``, ``from_dict`` and ``replace``.

    A subclass sets :attr:`record_name` (the field an error names when ``from_dict`` gets
    something that is not a mapping) and validates its fields in ``__post_init__``.
    """

    record_name: ClassVar[str] = "settings"

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready dict (:func:`record_to_dict`: ``inf`` as ``"inf"``, tuples as lists).

        Returns
        -------
        dict of str to object
            One JSON-ready value per field, in field order.
        """
        return record_to_dict(self)

    @classmethod
    def from_dict(cls, data: object) -> Self:
        """Validated construction (:func:`record_from_dict`); missing keys take the defaults.

        Parameters
        ----------
        data : object
            The dict read, e.g. from JSON.

        Returns
        -------
        Self
            The record.

        Raises
        ------
        ValidationError
            When ``data`` is not a mapping, has an unknown key, or a value is invalid.
        """
        return record_from_dict(cls, data, cls.record_name)

    def replace(self, **changes: Any) -> Self:
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New field values, by name.

        Returns
        -------
        Self
            The new record.

        Raises
        ------
        ValidationError
            When a changed value is invalid.
        """
        return dataclasses.replace(self, **changes)
