"""The numpydoc check of the public API of ``analysis`` (issue 21), run by the docs build.

Every function, class and public method that a subpackage of ``analysis`` lists in its ``__all__``
carries a numpydoc docstring: a summary line; a ``Parameters`` section that names every parameter of
the signature and nothing else (numpydoc's PR01/PR02); a ``Returns`` (or ``Yields``) section where
the code returns a value (RT01); a ``Raises`` section where the body itself raises (RA01, our own
rule: numpydoc does not check it).  A class documents its constructor's parameters in its own
docstring (numpydoc's convention), a frozen dataclass its fields under ``Parameters`` or
``Attributes``.

Each fault is a Sphinx warning, so ``make test`` (Sphinx with ``-W``) fails on it.  From the
command line, ``python docs/_ext/api_docstrings.py [PACKAGE ...]`` prints the faults of the named
packages (default: all) and exits 1 when there is one.
"""

from __future__ import annotations

import ast
import dataclasses
import enum
import importlib
import inspect
import sys
import textwrap
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

#: The packages whose ``__all__`` is the public API.
PACKAGES = (
    "analysis", "analysis.chain", "analysis.twoport", "analysis.sampled", "analysis.transparency",
    "analysis.identify", "analysis.multidof", "analysis.profiles", "analysis.study", "analysis.checks", "analysis.errors",
    "analysis.resources", "analysis.progress",
)
#: numpydoc's checks that we enforce (the style checks, such as the summary's mood, are not).
CHECKS = ("GL08", "SS01", "PR01", "PR02", "RT01")


def _public_objects(package: str) -> Iterator[tuple[str, Any]]:
    """Yield ``(qualified name, object)`` for the functions, classes and their public methods
    that ``package.__all__`` exports (each object once, under the name of its definition)."""
    module = importlib.import_module(package)
    for name in getattr(module, "__all__", ()):
        obj = getattr(module, name)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        if not getattr(obj, "__module__", "").startswith("analysis"):
            continue
        qual = f"{obj.__module__}.{obj.__qualname__}"
        yield qual, obj
        if inspect.isclass(obj) and not issubclass(obj, enum.Enum):
            for attr, value in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if isinstance(value, (staticmethod, classmethod)):
                    value = value.__func__
                if inspect.isfunction(value):
                    yield f"{qual}.{attr}", value


def _raises_itself(func: Any) -> bool:
    """Whether the body of ``func`` (not a nested function) has a ``raise`` with an exception."""
    try:
        source = textwrap.dedent(inspect.getsource(func))
    except (OSError, TypeError):
        return False
    tree = ast.parse(source)
    if not tree.body or not isinstance(tree.body[0], (ast.FunctionDef, ast.AsyncFunctionDef)):
        return False

    def walk(node: ast.AST) -> Iterator[ast.AST]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
                continue
            yield child
            yield from walk(child)

    return any(isinstance(n, ast.Raise) and n.exc is not None for n in walk(tree.body[0]))


def _dataclass_faults(cls: type, doc: Any) -> list[str]:
    documented = {p.name.split(":")[0].strip() for p in doc["Parameters"]}
    documented |= {p.name.split(":")[0].strip() for p in doc["Attributes"]}
    documented = {n.lstrip("*") for part in documented for n in part.split(",")}
    documented = {n.strip() for n in documented}
    missing = [f.name for f in dataclasses.fields(cls) if f.init and f.name not in documented]
    return [f"PR01 fields not documented: {', '.join(missing)}"] if missing else []


def faults(obj: Any) -> list[str]:
    """The enforced numpydoc faults of one object, as ``"CODE message"`` strings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = _faults(obj, name=f"{obj.__module__}.{obj.__qualname__}")
    # numpydoc warns of a malformed section (a wrong underline, an unknown section title)
    out += [f"DS01 {str(w.message).splitlines()[0].strip()} (numpydoc cannot parse the docstring)"
            for w in caught if issubclass(w.category, UserWarning)]
    return out


def _faults(obj: Any, name: str) -> list[str]:
    from numpydoc.docscrape import ClassDoc, FunctionDoc
    from numpydoc.validate import validate

    if inspect.isclass(obj) and dataclasses.is_dataclass(obj):
        if not inspect.getdoc(obj) or obj.__doc__ is None:
            return ["GL08 The object does not have a docstring"]
        out = [f"{e[0]} {e[1]}" for e in validate(name)["errors"]
               if e[0] in ("GL08", "SS01")]
        return out + _dataclass_faults(obj, ClassDoc(obj, config={"show_class_members": False}))
    if inspect.isclass(obj) and issubclass(obj, (enum.Enum, BaseException)):
        checks: tuple[str, ...] = ("GL08", "SS01")
    else:
        checks = CHECKS
    result = validate(name)
    out = [f"{code} {message}" for code, message in result["errors"] if code in checks]
    if inspect.isfunction(obj) and obj.__doc__ and _raises_itself(obj):
        if not FunctionDoc(obj)["Raises"]:
            out.append("RA01 The body raises, and there is no Raises section")
    return out


def report(packages: tuple[str, ...] = PACKAGES) -> dict[str, list[str]]:
    """Every public object of ``packages`` with its faults (only those that have any)."""
    out: dict[str, list[str]] = {}
    seen: set[int] = set()
    for package in packages:
        for qual, obj in _public_objects(package):
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            found = faults(obj)
            if found:
                out[qual] = found
    return out


def _check(app: Any) -> None:
    from sphinx.util import logging

    logger = logging.getLogger(__name__)
    for qual, found in report().items():
        for fault in found:
            logger.warning("public API docstring of %s: %s", qual, fault, type="zwidth", subtype="docstring")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _check)
    return {"version": "1", "parallel_read_safe": True}


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    found = report(tuple(sys.argv[1:]) or PACKAGES)
    for qual, items in found.items():
        for item in items:
            print(f"{qual}: {item}")
    print(f"{sum(map(len, found.values()))} faults in {len(found)} objects")
    sys.exit(1 if found else 0)
