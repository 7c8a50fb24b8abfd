"""Build the standalone one-folder zwidth with PyInstaller (what ``make package`` runs).

Usage::

    python packaging/build.py [--clean] [--distpath DIR] [--workpath DIR]

Runs PyInstaller on packaging/zwidth.spec and prints the size of the result.  The result is
``dist/zwidth/`` (run ``dist/zwidth/zwidth``), or ``dist/zwidth.app`` on macOS.  Needs the
``package`` extra: ``pip install -e '.[package]'``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "packaging" / "zwidth.spec"
DIST = ROOT / "dist"
WORK = ROOT / "build" / "pyinstaller"

__all__ = ["build", "tree_size", "app_dir", "executable"]


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
          f"{time.perf_counter() - start:.0f} s; {app_dir(dist)} is {size / 1e6:.1f} MB unpacked")
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
