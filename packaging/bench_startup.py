"""Start-up time and size of the standalone build against ``zwidth`` from the venv.

Usage::

    python packaging/bench_startup.py [--runs 7] [--exe dist/zwidth/zwidth] [--venv-zwidth .venv/bin/zwidth]

Prints a Markdown table (the "## Packaging" section of BENCHMARKS.md).  Each run is a fresh
process, offscreen, with a throw-away settings folder:

* "window shown": the self-check's time from process start to the main window's ``show()``
  (``selftest: window shown after X s``, read from /proc on Linux);
* "selftest exit": wall time of the whole self-check (window built, computations finished,
  rendered, About box, exit);
* "analyze": wall time of ``zwidth analyze hbfd.json`` (the command line path, no Qt).

The median of ``--runs`` runs is reported, after one warm-up run that is discarded.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "packaging"))

from build import tree_size  # noqa: E402


def _env(tmp: str, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ZWIDTH_")}
    env.update(QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=tmp, **extra)
    return env


def _time(cmd: list[str], env: dict[str, str]) -> tuple[float, str]:
    start = time.perf_counter()
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        raise SystemExit(f"bench_startup: {' '.join(cmd)} failed:\n{proc.stdout}\n{proc.stderr}")
    return elapsed, proc.stdout


def measure(selftest_cmd: list[str], selftest_env: dict[str, str], analyze_cmd: list[str],
            env: dict[str, str], runs: int) -> dict[str, float]:
    shown, total, analyze = [], [], []
    for i in range(runs + 1):
        elapsed, out = _time(selftest_cmd, selftest_env)
        match = re.search(r"window shown after ([0-9.]+) s", out)
        a_elapsed, _ = _time(analyze_cmd, env)
        if i == 0:
            continue  # warm-up: page cache, font cache
        total.append(elapsed)
        analyze.append(a_elapsed)
        if match:
            shown.append(float(match.group(1)))
    return {
        "shown": statistics.median(shown) if shown else float("nan"),
        "total": statistics.median(total),
        "analyze": statistics.median(analyze),
    }


def _compressed_size(folder: Path) -> int:
    with tempfile.TemporaryDirectory() as tmp:
        archive = Path(tmp) / "zwidth.tar.gz"
        with tarfile.open(archive, "w:gz", compresslevel=6) as tar:
            tar.add(folder, arcname=folder.name)
        return archive.stat().st_size


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description="Start-up time and size of the standalone build.")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--exe", type=Path, default=ROOT / "dist" / "zwidth" / "zwidth")
    parser.add_argument("--venv-zwidth", type=Path, default=ROOT / ".venv" / "bin" / "zwidth")
    args = parser.parse_args(argv)
    profile_frozen = args.exe.parent / "_internal" / "resources" / "profiles" / "hbfd.json"
    profile_src = ROOT / "resources" / "profiles" / "hbfd.json"
    with tempfile.TemporaryDirectory() as tmp:
        env = _env(tmp)
        frozen = measure([str(args.exe)], _env(tmp, ZWIDTH_SELFTEST="1"),
                         [str(args.exe), "analyze", str(profile_frozen)], env, args.runs)
        venv = measure([str(args.venv_zwidth), "selftest"], env,
                       [str(args.venv_zwidth), "analyze", str(profile_src)], env, args.runs)
    size = tree_size(args.exe.parent)
    packed = _compressed_size(args.exe.parent)
    print(f"Median of {args.runs} runs (after one warm-up), offscreen, "
          f"{os.cpu_count()} CPUs, other jobs running; measured {time.strftime('%Y-%m-%d %H:%M')}.\n")
    print("| | standalone (`dist/zwidth/zwidth`) | `zwidth` from the venv |")
    print("|---|---:|---:|")
    print(f"| window shown (s, from process start) | {frozen['shown']:.2f} | {venv['shown']:.2f} |")
    print(f"| selftest exit (s, wall) | {frozen['total']:.2f} | {venv['total']:.2f} |")
    print(f"| `analyze hbfd.json` (s, wall) | {frozen['analyze']:.2f} | {venv['analyze']:.2f} |")
    print(f"\nBuild size: {size / 1e6:.1f} MB ({size / 2**20:.1f} MiB) unpacked, "
          f"{packed / 1e6:.1f} MB as .tar.gz.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
