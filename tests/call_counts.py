"""Counting the calls of functions a test expects to run (or not): one helper for the fixtures that
check which study functions a report or an export computes."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Mapping

import pytest


def count_calls(monkeypatch: pytest.MonkeyPatch, targets: Mapping[str, Iterable[tuple[object, str]]]) -> Counter[str]:
    """Wrap each ``owner.name`` of ``targets`` (undone by ``monkeypatch``) so that every call adds one
    under its key; the counter the wrapped functions fill."""
    counter: Counter[str] = Counter()
    for key, pairs in targets.items():
        for owner, name in pairs:
            original = getattr(owner, name)

            def counted(*args: object, _f=original, _key=key, **kwargs: object) -> object:
                counter[_key] += 1
                return _f(*args, **kwargs)

            monkeypatch.setattr(owner, name, counted)
    return counter
