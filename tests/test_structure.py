"""Size limits and the public-name rule, checked on the source's syntax tree (issue 12, item 7).

- no module of ``analysis/`` or ``app/`` over 600 lines (issue 21: one concept may take up to about
  600 lines; the old 400-line cap forced splits of one concept);
- no class over 250 lines;
- no function over 60 lines, unless its docstring says it is a "numerical kernel" (and why);
- docstrings are not counted in any of these sizes: the rule serves readability, and the numpydoc
  sections of the public API (issue 21) document code without making it longer to read;
- no private name (one leading underscore, not a dunder) imported from another module, neither as
  ``from x import _y`` nor as ``x._y`` on an imported module;
- the tests use public names only: no ``from analysis... import _y`` / ``from app... import _y``,
  no ``module._y`` on an imported ``analysis``/``app`` module, no ``obj._y`` on anything but
  ``self``/``cls`` and no ``getattr``/``setattr``/``monkeypatch.setattr`` of a private name;
- every ``analysis`` package lists its public names in ``__all__``, and they all resolve.

``python tests/test_structure.py --list [FILE]`` prints every violation (and writes them to FILE),
then, for information, the numerical-kernel exemptions and the comparisons with a display string.
"""

from __future__ import annotations

import ast
import functools
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("analysis", "app")
MAX_MODULE_LINES = 600
MAX_CLASS_LINES = 250
MAX_FUNCTION_LINES = 60
KERNEL_PHRASE = "numerical kernel"


@dataclass(frozen=True)
class Violation:
    """One broken rule at one place in the source."""

    path: Path
    line: int
    message: str

    def __str__(self) -> str:
        shown = self.path.relative_to(ROOT) if self.path.is_relative_to(ROOT) else self.path
        return f"{shown}:{self.line}: {self.message}"


def package_files() -> list[Path]:
    """Every Python module of the ``analysis`` and ``app`` packages, sorted."""
    return sorted(p for pkg in PACKAGES for p in (ROOT / pkg).rglob("*.py"))


def files_of_tests() -> list[Path]:
    """Every Python file under ``tests/`` (benchmarks included), sorted."""
    return sorted((ROOT / "tests").rglob("*.py"))


def parse(path: Path) -> ast.Module:
    """The syntax tree of one file (read-only: the checks share it, parsed once per file version)."""
    return parse_version(path, path.stat().st_mtime_ns)


@functools.lru_cache(maxsize=None)
def parse_version(path: Path, mtime_ns: int) -> ast.Module:
    """The syntax tree of ``path`` as it was at ``mtime_ns`` (the key of the cache)."""
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


def module_name(path: Path) -> str:
    """``analysis/chain/device.py`` -> ``analysis.chain.device``; a package is its ``__init__``."""
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def is_private(name: str) -> bool:
    """A leading underscore that is not a dunder."""
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def is_module(dotted: str) -> bool:
    """Whether ``dotted`` names a module or package of this repository."""
    base = ROOT.joinpath(*dotted.split("."))
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def resolve_from(path: Path, node: ast.ImportFrom) -> str:
    """The absolute module name of a ``from ... import`` (relative imports resolved)."""
    if not node.level:
        return node.module or ""
    package = module_name(path).split(".")
    if path.name != "__init__.py":
        package.pop()
    package = package[: len(package) - (node.level - 1)]
    return ".".join(package + ([node.module] if node.module else []))


# -- sizes -------------------------------------------------------------------------------------------

def docstring_lines(tree: ast.AST) -> int:
    """Lines taken by the docstrings of ``tree`` and of every definition inside it."""
    total = 0
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if (body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
                    and isinstance(body[0].value.value, str)):
                total += body[0].end_lineno - body[0].lineno + 1  # type: ignore[operator]
    return total


def module_size_violations(path: Path) -> Iterator[Violation]:
    """A module over ``MAX_MODULE_LINES`` lines, docstrings not counted."""
    text = path.read_text(encoding="utf-8")
    lines = len(text.splitlines()) - docstring_lines(parse(path))
    if lines > MAX_MODULE_LINES:
        yield Violation(path, 1, f"module has {lines} lines without docstrings (limit {MAX_MODULE_LINES})")


def node_lines(node: ast.AST) -> int:
    """Lines from the ``def``/``class`` statement to its last line (decorators and docstrings not
    counted)."""
    return node.end_lineno - node.lineno + 1 - docstring_lines(node)  # type: ignore[attr-defined]


def definition_size_violations(path: Path, tree: ast.AST, prefix: str = "") -> Iterator[Violation]:
    """Classes over ``MAX_CLASS_LINES`` and functions over ``MAX_FUNCTION_LINES`` lines (nested too)."""
    for node in ast.iter_child_nodes(tree):
        if isinstance(node, ast.ClassDef):
            name = prefix + node.name
            if node_lines(node) > MAX_CLASS_LINES:
                yield Violation(path, node.lineno,
                                f"class {name} has {node_lines(node)} lines (limit {MAX_CLASS_LINES})")
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            name = prefix + node.name
            doc = ast.get_docstring(node) or ""
            if node_lines(node) > MAX_FUNCTION_LINES and KERNEL_PHRASE not in doc.lower():
                yield Violation(path, node.lineno,
                                f"function {name} has {node_lines(node)} lines (limit {MAX_FUNCTION_LINES} "
                                f"unless its docstring says it is a {KERNEL_PHRASE})")
        else:
            yield from definition_size_violations(path, node, prefix)
            continue
        yield from definition_size_violations(path, node, name + ".")


# -- private names -------------------------------------------------------------------------------------

def module_aliases(path: Path, tree: ast.Module) -> dict[str, str]:
    """Local names bound to modules of this repository: ``{local name: module}``."""
    aliases: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.split(".")[0] not in PACKAGES:
                    continue
                if alias.asname:
                    aliases[alias.asname] = alias.name
                else:
                    top = alias.name.split(".")[0]
                    aliases[top] = top
        elif isinstance(node, ast.ImportFrom):
            source = resolve_from(path, node)
            if source.split(".")[0] not in PACKAGES:
                continue
            for alias in node.names:
                if is_module(f"{source}.{alias.name}"):
                    aliases[alias.asname or alias.name] = f"{source}.{alias.name}"
    return aliases


def dotted_module(node: ast.AST, aliases: dict[str, str]) -> str | None:
    """The module an expression such as ``analysis.chain`` or ``dev`` names, if it names one."""
    if isinstance(node, ast.Name):
        return aliases.get(node.id)
    if isinstance(node, ast.Attribute):
        base = dotted_module(node.value, aliases)
        if base is not None and is_module(f"{base}.{node.attr}"):
            return f"{base}.{node.attr}"
    return None


def private_import_violations(path: Path, tree: ast.Module) -> Iterator[Violation]:
    """``from <our module> import _name`` and ``<our module>._name``, from any other module."""
    here = module_name(path)
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            source = resolve_from(path, node)
            if source.split(".")[0] not in PACKAGES or source == here:
                continue
            for alias in node.names:
                if is_private(alias.name):
                    yield Violation(path, node.lineno, f"imports private name {alias.name} from {source}")
    aliases = module_aliases(path, tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and is_private(node.attr):
            source = dotted_module(node.value, aliases)
            if source is not None and source != here:
                yield Violation(path, node.lineno, f"uses private name {node.attr} of module {source}")


# Names with a leading underscore that are public API (namedtuple's methods).
PUBLIC_UNDERSCORE = {"_replace", "_asdict", "_fields", "_make", "_field_defaults"}
ATTRIBUTE_CALLS = {"getattr", "setattr", "delattr", "hasattr"}


def private_attribute_violations(path: Path) -> Iterator[Violation]:
    """In tests: ``obj._y`` (``obj`` not ``self``/``cls``) and ``getattr(obj, "_y")``-like calls."""
    for node in ast.walk(parse(path)):
        if isinstance(node, ast.Attribute) and is_private(node.attr) and node.attr not in PUBLIC_UNDERSCORE:
            if not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls")):
                yield Violation(path, node.lineno, f"uses private attribute {node.attr}")
        elif isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else func.attr if isinstance(func, ast.Attribute) else ""
            if name not in ATTRIBUTE_CALLS:
                continue
            for arg in node.args[:2]:
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str):
                    last = arg.value.rsplit(".", 1)[-1]
                    if is_private(last):
                        yield Violation(path, node.lineno, f"{name} of private name {arg.value}")


# -- for information (not failed on) --------------------------------------------------------------------

DISPLAY_STRINGS = {"impedance", "admittance"}


def display_string_comparisons() -> list[Violation]:
    """``x == "impedance"``-style comparisons (issue 12 item 3: a display is an object, not a string)."""
    found: list[Violation] = []
    for path in package_files():
        for node in ast.walk(parse(path)):
            if isinstance(node, ast.Compare) and any(isinstance(op, (ast.Eq, ast.NotEq)) for op in node.ops):
                sides = [node.left, *node.comparators]
                if any(isinstance(x, ast.Constant) and x.value in DISPLAY_STRINGS for x in sides):
                    found.append(Violation(path, node.lineno, f"compares with a display string: {ast.unparse(node)}"))
    return sorted(found, key=lambda v: (v.path, v.line))


def numerical_kernels() -> list[Violation]:
    """Functions over the limit that are exempt because their docstring says "numerical kernel"."""
    found: list[Violation] = []
    for path in package_files():
        for node in ast.walk(parse(path)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node_lines(node) > MAX_FUNCTION_LINES:
                if KERNEL_PHRASE in (ast.get_docstring(node) or "").lower():
                    found.append(Violation(path, node.lineno, f"numerical kernel {node.name}: {node_lines(node)} lines"))
    return sorted(found, key=lambda v: (v.path, v.line))


# -- collecting ----------------------------------------------------------------------------------------

def size_violations() -> list[Violation]:
    """Every module, class and function over its size limit in ``analysis/`` and ``app/``."""
    found: list[Violation] = []
    for path in package_files():
        found += module_size_violations(path)
        found += definition_size_violations(path, parse(path))
    return found


def package_private_violations() -> list[Violation]:
    """Private names imported across modules inside ``analysis/`` and ``app/``."""
    found = [v for path in package_files() for v in private_import_violations(path, parse(path))]
    return sorted(set(found), key=lambda v: (v.path, v.line, v.message))


def private_names_in_tests() -> list[Violation]:
    """Private names of ``analysis``/``app`` used by the tests."""
    found = [v for path in files_of_tests()
             for v in [*private_import_violations(path, parse(path)), *private_attribute_violations(path)]]
    return sorted(set(found), key=lambda v: (v.path, v.line, v.message))


def report(violations: list[Violation]) -> str:
    """One violation a line, for the assertion message."""
    return f"{len(violations)} violation(s):\n" + "\n".join(str(v) for v in violations)


def test_module_class_function_sizes() -> None:
    found = size_violations()
    assert not found, report(found)


def test_no_private_name_across_modules() -> None:
    found = package_private_violations()
    assert not found, report(found)


def test_tests_use_public_names() -> None:
    found = private_names_in_tests()
    assert not found, report(found)


def test_analysis_packages_export_what_all_lists() -> None:
    """Every ``analysis`` package has an ``__all__`` whose names all resolve (the public API)."""
    import importlib

    missing: list[str] = []
    for path in package_files():
        if path.name != "__init__.py" or path.parts[len(ROOT.parts)] != "analysis":
            continue
        name = module_name(path)
        package = importlib.import_module(name)
        names = getattr(package, "__all__", None)
        if names is None:
            missing.append(f"{name}: no __all__")
            continue
        missing += [f"{name}.{n}: listed in __all__ but not defined" for n in names if not hasattr(package, n)]
    assert not missing, "\n".join(missing)


def test_checker_sees_a_planted_violation() -> None:
    """The checker itself: a long function, a kernel and a private import, in a scratch file."""
    body = "\n".join(f"    x{i} = {i}" for i in range(61))
    source = (
        "from analysis.chain import _hidden\n"
        f"def long_one():\n{body}\n"
        f'def kernel():\n    """One piece: a numerical kernel."""\n{body}\n'
    )
    path = ROOT / "tests" / "_scratch_structure.py"
    tree = ast.parse(source)
    sizes = list(definition_size_violations(path, tree))
    assert [(v.line, v.message.split(" has ")[0]) for v in sizes] == [(2, "function long_one")]
    assert "62 lines" in sizes[0].message
    private = list(private_import_violations(path, tree))
    assert [(v.line, v.message) for v in private] == [(1, "imports private name _hidden from analysis.chain")]


def test_checker_sees_private_attributes_in_tests(tmp_path: Path) -> None:
    """``obj._y`` and ``monkeypatch.setattr(obj, "_y", ...)`` are found; ``self._y``, ``_replace`` not."""
    path = tmp_path / "test_planted.py"
    path.write_text(
        "def test_x(monkeypatch, imp, rec):\n"
        "    imp._bound_parts(1.0)\n"
        '    monkeypatch.setattr(imp, "_cache", {})\n'
        "    rec._replace(a=1)\n"
        "class T:\n"
        "    def f(self):\n"
        "        return self._y\n",
        encoding="utf-8",
    )
    found = sorted((v.line, v.message) for v in private_attribute_violations(path))
    assert found == [(2, "uses private attribute _bound_parts"), (3, "setattr of private name _cache")]


def main(argv: list[str]) -> int:
    """``--list [FILE]``: print (and write) every violation; exit status 1 when there are any."""
    if not argv or argv[0] != "--list":
        print(__doc__)
        return 2
    sections = [
        ("Sizes (module 600, class 250, function 60 lines)", size_violations()),
        ("Private names imported across modules (analysis/, app/)", package_private_violations()),
        ("Private names used by tests/", private_names_in_tests()),
    ]
    info = [
        ("For information: functions over 60 lines exempt as numerical kernels", numerical_kernels()),
        ("For information: comparisons with a display string (issue 12 item 3)", display_string_comparisons()),
    ]
    text = "".join(f"## {title}: {len(found)}\n" + "".join(f"{v}\n" for v in found) + "\n"
                   for title, found in sections + info)
    print(text, end="")
    if len(argv) > 1:
        Path(argv[1]).write_text(text, encoding="utf-8")
    return 1 if any(found for _, found in sections) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
