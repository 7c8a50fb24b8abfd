"""The numpydoc check of the public API (docs/_ext/api_docstrings.py, run by the docs build).

The check itself must catch what it promises to catch, and the public API of ``analysis`` must
pass it (the docs build fails on any fault; this test says which one without building the docs).
"""

from __future__ import annotations

import dataclasses
import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def docs_extension(name: str):
    """The docs build's extension ``docs/_ext/<name>.py``, imported as the build imports it."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "docs" / "_ext" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault(name, module)
    spec.loader.exec_module(module)
    return module


checker = docs_extension("api_docstrings")


def undocumented(x: float, y: float) -> float:
    """Add two numbers.

    Parameters
    ----------
    x : float
        The first.
    """
    if x < 0:
        raise ValueError("negative")
    return x + y


def documented(x: float) -> float:
    """Double a number.

    Parameters
    ----------
    x : float
        The number.

    Returns
    -------
    float
        Twice ``x``.

    Raises
    ------
    ValueError
        When ``x`` is negative.
    """
    if x < 0:
        raise ValueError("negative")
    return 2 * x


@dataclasses.dataclass(frozen=True)
class Record:
    """A record.

    Parameters
    ----------
    a : float
        The first field.
    """

    a: float
    b: float | None = None


def codes(obj) -> set[str]:
    return {fault.split()[0] for fault in checker.faults(obj)}


def test_the_checker_finds_a_missing_parameter_return_and_raises():
    assert codes(undocumented) == {"PR01", "RT01", "RA01"}


def test_a_complete_numpydoc_docstring_passes():
    assert checker.faults(documented) == []


def test_a_dataclass_field_with_a_none_default_must_be_documented():
    assert codes(Record) == {"PR01"}
    assert "b" in checker.faults(Record)[0]


def test_the_docs_build_runs_the_check_on_the_whole_api():
    """The public API itself is checked once, by the docs build that ``make test`` runs with -W (each
    fault a warning, so an error): the extension is in docs/conf.py and checks every package when
    the builder starts.  (Checking it here as well cost the suite the same 4 CPU-s again.)"""
    calls: list[tuple[str, object]] = []

    class App:
        def connect(self, event, handler):
            calls.append((event, handler))

    checker.setup(App())
    assert [event for event, _h in calls] == ["builder-inited"]
    seen: list[tuple[str, ...]] = []
    real = checker.report
    try:
        checker.report = lambda packages=checker.PACKAGES: seen.append(packages) or {}
        calls[0][1](object())
    finally:
        checker.report = real
    assert seen == [checker.PACKAGES] and "analysis" in checker.PACKAGES
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert '"api_docstrings"' in conf and '"-W"' not in conf  # -W is the Makefile's SPHINX line
    assert "-W" in (ROOT / "Makefile").read_text(encoding="utf-8").split("SPHINX :=")[1].splitlines()[0]
