"""Reading and writing a section declared key by key in :data:`analysis.profiles.schema.SCHEMA`.

The ``renderable`` (schema 6) and ``multidof`` (schema 7) sections declare each of their keys in
the schema, with its rule (type, range, unit) and the API name of the record field that holds
it.  These three functions are what both sections share:

* :func:`declared_value` -- one value checked by the declaration of its API name (the record's
  ``__post_init__`` uses it, so the record and the loader apply the same rule);
* :func:`read_declared` -- the values under a declared object, by API name, a bad or unknown key
  reported as a :class:`~analysis.profiles.errors.ProfileError` at its JSON path;
* :func:`declared_tree` -- the JSON-ready tree of a record, every declared key written.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from analysis.errors import ValidationError
from analysis.profiles.errors import MISSING, ProfileError
from analysis.profiles.schema import FIELDS_BY_NAME, Field

__all__ = ["declared_value", "read_declared", "declared_tree"]


def declared_value(name: str, value: object) -> Any:
    """``value`` checked by the schema's declaration of the API name ``name``.

    Parameters
    ----------
    name : str
        The API name (a record field) declared in the schema.
    value : object
        The value.

    Returns
    -------
    object
        The value as the record holds it: a float for a number, a tuple for a list.

    Raises
    ------
    ValidationError
        Naming ``name`` when the value breaks the declaration's rule.
    """
    node = FIELDS_BY_NAME[name][1]
    if node.kind == "choice":
        if not isinstance(value, str) or value not in node.options:
            raise ValidationError(name, node.expected(), value)
        return value
    if node.kind == "choices":
        names = (value,) if isinstance(value, str) else value
        try:
            out = tuple(names)
        except TypeError:
            raise ValidationError(name, node.expected(), value) from None
        if not out or len(set(out)) != len(out) or any(not isinstance(q, str) or q not in node.options for q in out):
            raise ValidationError(name, node.expected(), value)
        return out
    if node.kind == "numbers":
        if isinstance(value, (str, bytes, Mapping)):
            raise ValidationError(name, node.expected(), value)
        try:
            items = tuple(value)  # type: ignore[arg-type]
        except TypeError:
            raise ValidationError(name, node.expected(), value) from None
        return tuple(node.rule(name, v, i) for i, v in enumerate(items))
    if node.kind == "integer":
        if isinstance(value, bool) or not isinstance(value, int):
            raise ValidationError(name, f"an integer {node.range_text}".rstrip(), value)
        node.rule(name, value)
        return value
    return node.rule(name, value)


def _json(value: Any) -> Any:
    if isinstance(value, float) and math.isinf(value):
        return "inf" if value > 0 else "-inf"
    return [_json(v) for v in value] if isinstance(value, tuple) else value


def declared_tree(node: Field, record: object) -> dict[str, Any]:
    """The JSON-ready tree of ``record`` under the declared object ``node`` (``inf`` as ``"inf"``).

    Parameters
    ----------
    node : Field
        A declared section or object of the schema.
    record : object
        The record whose attributes are the declared API names.

    Returns
    -------
    dict of str to Any
        Every declared key with the record's value.
    """
    return {c.key: declared_tree(c, record) if c.kind == "object" else _json(getattr(record, c.name))
            for c in node.children}


def read_declared(node: Field, value: object, path: str, out: dict[str, Any],
                  nullable: frozenset[str] = frozenset()) -> None:
    """Collect the values under the declared ``node`` into ``out`` by their API names.

    Parameters
    ----------
    node : Field
        A declared section or object of the schema.
    value : object
        Its JSON value.
    path : str
        Its JSON path, e.g. ``"$.renderable"``.
    out : dict of str to Any
        Filled with API name -> value for every key present.
    nullable : frozenset of str, optional
        API names whose JSON ``null`` means "not set" (left out of ``out``).

    Raises
    ------
    ProfileError
        At the JSON path of the first bad or unknown key.
    """
    if node.kind == "object" or node.kind == "section":
        if not isinstance(value, Mapping):
            raise ProfileError.at(path, "a JSON object with keys " + ", ".join(node.keys), value)
        unknown = set(value) - set(node.keys)
        if unknown:
            raise ProfileError.at(f"{path}.{sorted(map(str, unknown))[0]}", f"no such key ({', '.join(node.keys)})", None)
        for c in node.children:
            if value.get(c.key, MISSING) is not MISSING:
                read_declared(c, value[c.key], f"{path}.{c.key}", out, nullable)
        return
    if node.name in nullable and value is None:
        return
    if isinstance(value, str) and node.kind == "number" and value in ("inf", "-inf"):
        value = float(value)
    try:
        out[node.name] = declared_value(node.name, value)
    except ValidationError as err:
        where = path if err.index is None else f"{path}[{err.index}]"
        raise ProfileError.at(where, err.allowed, err.value) from err
