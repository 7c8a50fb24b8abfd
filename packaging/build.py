"""Build the standalone one-folder zwidth with PyInstaller (what ``make package`` runs).

Usage::

    python packaging/build.py [--clean] [--distpath DIR] [--workpath DIR]

Runs PyInstaller on packaging/zwidth.spec, prints the size of the result and checks what it
contains (:func:`check_build`): it exits 1 when the build is over :data:`SIZE_LIMIT` (Linux) or
freezes a package that zwidth does not need at run time (one of the spec's ``DEV_ONLY``, or any
installed package outside zwidth's runtime requirements).  The result is ``dist/zwidth/`` (run
``dist/zwidth/zwidth``), or ``dist/zwidth.app`` on macOS.  Needs the ``package`` extra:
``pip install -e '.[package]'``.  tests/test_packaging.py uses the same checks.
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "packaging" / "zwidth.spec"
DIST = ROOT / "dist"
WORK = ROOT / "build" / "pyinstaller"
#: bytes, unpacked, of the Linux one-folder build
SIZE_LIMIT = 250e6
#: zwidth's own top-level packages (an editable install maps them to no distribution)
OWN_PACKAGES = frozenset({"analysis", "app"})

__all__ = ["build", "tree_size", "app_dir", "executable", "SIZE_LIMIT", "dev_only", "frozen_packages",
           "runtime_distributions", "foreign_packages", "check_build"]


def tree_size(path: Path) -> int:
    """Bytes in the files under ``path`` (symlinks not followed, not counted twice)."""
    total = 0
    for root, _dirs, files in os.walk(path):
        for name in files:
            p = os.path.join(root, name)
            if not os.path.islink(p):
                total += os.path.getsize(p)
    return total


def app_dir(dist: Path = DIST) -> Path:
    return dist / "zwidth"


def executable(dist: Path = DIST) -> Path:
    if sys.platform == "win32":
        return app_dir(dist) / "zwidth.exe"
    return app_dir(dist) / "zwidth"


def dev_only(spec: Path = SPEC) -> list[str]:
    """The spec's ``DEV_ONLY`` list: test and docs packages that must never be frozen."""
    for node in ast.parse(spec.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "DEV_ONLY" for t in node.targets):
            return list(ast.literal_eval(node.value))
    raise ValueError(f"{spec} has no DEV_ONLY list")


def _internal(exe: Path) -> Path:
    folder = exe.parent / "_internal"
    return folder if folder.is_dir() else exe.parent


def frozen_packages(exe: Path) -> set[str]:
    """Top-level module and package names in a one-folder build.

    Both the Python modules inside the executable's archive (PYZ; needs PyInstaller) and the
    package folders beside it (data files and extension modules), so that a pure-Python package
    is seen as well as one with data.
    """
    from PyInstaller.archive.readers import CArchiveReader

    names: set[str] = set()
    archive = CArchiveReader(str(exe))
    for entry in archive.toc:
        if entry.endswith(".pyz"):
            names.update(name.split(".")[0] for name in archive.open_embedded_archive(entry).toc)
    for path in _internal(exe).iterdir():
        if path.is_dir() and "." not in path.name and path.name != "resources":
            names.add(path.name)
        elif (path.suffix == ".so" and ".cpython-" in path.name) or path.suffix == ".pyd":
            names.add(path.name.split(".")[0])
    return names


def _key(distribution: str) -> str:
    return re.sub(r"[-_.]+", "-", distribution).lower()


def runtime_distributions(name: str = "zwidth") -> set[str]:
    """Normalised names of ``name`` and of every distribution it needs at run time (no extras)."""
    from importlib import metadata

    from packaging.requirements import Requirement  # PyInstaller's own dependency

    seen: set[str] = set()
    todo = [name]
    while todo:
        dist = todo.pop()
        if _key(dist) in seen:
            continue
        seen.add(_key(dist))
        try:
            requires = metadata.requires(dist) or []
        except metadata.PackageNotFoundError:
            continue
        for line in requires:
            req = Requirement(line)
            if req.marker is None or req.marker.evaluate({"extra": ""}):
                todo.append(req.name)
    return seen


def foreign_packages(names: set[str]) -> dict[str, list[str]]:
    """Of the frozen top-level ``names``, those installed by a distribution zwidth does not need
    at run time (a test, docs or build tool), with their distributions."""
    from importlib import metadata

    owners = metadata.packages_distributions()
    needed = runtime_distributions()
    foreign = {}
    for name in sorted(names - OWN_PACKAGES - set(sys.stdlib_module_names)):
        dists = owners.get(name, [])
        if dists and not any(_key(d) in needed for d in dists):
            foreign[name] = sorted(set(dists))
    return foreign


def check_build(exe: Path) -> list[str]:
    """What is wrong with a build: over the size limit (Linux), or freezing packages that zwidth
    does not need at run time.  Empty when the build is fine."""
    problems = []
    size = tree_size(exe.parent)
    if sys.platform.startswith("linux") and size >= SIZE_LIMIT:
        problems.append(f"{exe.parent} is {size / 1e6:.1f} MB unpacked (limit {SIZE_LIMIT / 1e6:.0f} MB)")
    names = frozen_packages(exe)
    banned = sorted(names & set(dev_only()))
    if banned:
        problems.append(f"test/docs packages frozen (the spec's DEV_ONLY): {' '.join(banned)}")
    foreign = foreign_packages(names - set(banned))
    if foreign:
        problems.append("packages outside zwidth's runtime requirements frozen: "
                        + ", ".join(f"{n} ({'/'.join(d)})" for n, d in foreign.items()))
    if problems:
        problems.append(f"who imports them: {WORK / 'zwidth' / 'xref-zwidth.html'} (PyInstaller's "
                        "import graph); exclude them in packaging/zwidth.spec")
    return problems


def build(clean: bool = False, dist: Path = DIST, work: Path = WORK) -> Path:
    try:
        import PyInstaller  # noqa: F401
    except ImportError:
        raise SystemExit("build.py: PyInstaller is not installed; run: pip install -e '.[package]'") from None
    cmd = [sys.executable, "-m", "PyInstaller", "--noconfirm", "--log-level", "WARN",
           "--distpath", str(dist), "--workpath", str(work), str(SPEC)]
    if clean:
        cmd.insert(3, "--clean")
    print("+ " + " ".join(cmd), flush=True)
    start = time.perf_counter()
    subprocess.run(cmd, cwd=ROOT, check=True)
    exe = executable(dist)
    if not exe.exists():
        raise SystemExit(f"build.py: PyInstaller finished but {exe} is missing")
    size = tree_size(app_dir(dist))
    print(f"built {exe.relative_to(ROOT) if exe.is_relative_to(ROOT) else exe} in "
          f"{time.perf_counter() - start:.0f} s; {app_dir(dist)} is {size / 1e6:.1f} MB unpacked "
          f"(limit {SIZE_LIMIT / 1e6:.0f} MB)")
    problems = check_build(exe)
    if problems:
        raise SystemExit("build.py: the build is not fit to ship:\n  " + "\n  ".join(problems))
    return exe


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Build the standalone zwidth with PyInstaller.")
    parser.add_argument("--clean", action="store_true", help="empty PyInstaller's cache first")
    parser.add_argument("--distpath", type=Path, default=DIST, help="output folder (default: dist)")
    parser.add_argument("--workpath", type=Path, default=WORK, help="work folder (default: build/pyinstaller)")
    args = parser.parse_args(argv)
    build(clean=args.clean, dist=args.distpath.resolve(), work=args.workpath.resolve())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
