"""The error a profile file or dict is refused with, and how a rejected JSON value is described.

:class:`ProfileError` names the file and the JSON path of the offending value, e.g.
``hbfd.json: $.device.masses[2] (mass 3): expected a number > 0 and finite, ..., got -1.0``
(JSON paths count from 0; the name in brackets is the GUI's, counting from 1).

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Mapping

import numpy as np

__all__ = ["MISSING", "NonFinite", "ProfileError", "describe", "element_label"]

#: Stands for "the key is absent" (``None`` is JSON ``null``).
MISSING = object()


class ProfileError(ValueError):
    """A profile file or dict cannot be used.

    Attributes
    ----------
    path:
        The file (as given), or ``None`` for a dict that did not come from a file.
    json_path:
        Location of the offending value, e.g. ``"$.device.masses[2]"``; ``None`` when the
        problem is the file as a whole (unreadable, not JSON).
    expected:
        What was expected there, e.g. ``"a number > 0 and finite"``.
    reason:
        The message without the file and JSON path prefixes.
    """

    def __init__(
        self,
        reason: str,
        *,
        path: str | os.PathLike | None = None,
        json_path: str | None = None,
        expected: str | None = None,
    ):
        self.reason = reason
        self.path = None if path is None else os.fspath(path)
        self.json_path = json_path
        self.expected = expected
        where = f"{json_path} ({element_label(json_path)})" if json_path and element_label(json_path) else json_path
        prefix = "".join(f"{part}: " for part in (self.path, where) if part)
        super().__init__(prefix + reason)

    @classmethod
    def at(cls, json_path: str, expected: str, got: object = MISSING) -> ProfileError:
        """``$.x: expected <expected>, got <value>`` (``missing`` when the key is absent).

        Parameters
        ----------
        json_path : str
            Location of the offending value, e.g. ``"$.device.masses[2]"``.
        expected : str
            What was expected there, e.g. ``"a number > 0 and finite (kg)"``.
        got : object, optional
            The value found (described by :func:`describe`); :data:`MISSING` (the default) when
            the key is absent.

        Returns
        -------
        ProfileError
            The error, with no file yet (:meth:`with_path` adds it).
        """
        return cls(f"expected {expected}, got {describe(got)}", json_path=json_path, expected=expected)

    def with_path(self, path: str | os.PathLike | None) -> ProfileError:
        """The same error attributed to file ``path``.

        Parameters
        ----------
        path : str or os.PathLike or None
            The file the profile came from; ``None`` for none.

        Returns
        -------
        ProfileError
            A new error naming ``path``, with the same cause; this error itself when ``path`` is
            ``None`` or the error already names a file.
        """
        if path is None or self.path is not None:
            return self
        err = ProfileError(self.reason, path=path, json_path=self.json_path, expected=self.expected)
        err.__cause__ = self.__cause__
        return err


#: The GUI's 1-based name of an element of a device vector (JSON paths count from 0).
_ELEMENT_LABELS = {
    "masses": "mass {}",
    "ground_dampings": "ground damping of mass {}",
    "friction": "mass {}",
    "stiffnesses": "element {}",
    "dampings": "element {}",
    "damping_ratios": "element {}",
}
_INDEXED = re.compile(r"\.(\w+)\[(\d+)\]$")


def element_label(json_path: str) -> str:
    """The GUI's name of the element a 0-based JSON path points at: ``"$.device.masses[2]"`` ->
    ``"mass 3"`` (as the chain editor says "Mass 3"); ``""`` for any other path."""
    match = _INDEXED.search(json_path)
    if match is None or match.group(1) not in _ELEMENT_LABELS:
        return ""
    return _ELEMENT_LABELS[match.group(1)].format(int(match.group(2)) + 1)


class NonFinite:
    """Stands for a NaN / Infinity literal in the JSON text (the strict reader's ``parse_constant``);
    rejected wherever it appears."""

    __slots__ = ("literal",)

    def __init__(self, literal: str):
        self.literal = literal

    def __repr__(self) -> str:
        return self.literal


def describe(value: object) -> str:
    """A short JSON-flavoured description of a rejected value (``"the string \"x\""``, ``"-1.0"``)."""
    if value is MISSING:
        return "nothing (the key is missing)"
    if isinstance(value, NonFinite):
        return f"{value.literal} (NaN and Infinity are not allowed)"
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, np.integer, np.floating)):
        text = repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))
        return text if len(text) <= 40 else text[:37] + "..."
    if isinstance(value, str):
        shown = value if len(value) <= 40 else value[:37] + "..."
        return f"the string {json.dumps(shown)}"
    if isinstance(value, (list, tuple)):
        return f"a list of {len(value)} item{'s' if len(value) != 1 else ''}"
    if isinstance(value, Mapping):
        return "an object"
    return type(value).__name__
