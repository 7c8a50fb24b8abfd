"""What every ``zwidth`` command checks of its files, and how it says what went wrong.

* :func:`output_clash`: an output file that is one of the command's inputs is a usage error
  (issue 22: ``identify m.csv -o m.csv`` overwrote the measurement);
* :func:`table_outputs`: the CSV and its plot of ``zwidth space`` and ``zwidth workspace``;
* :func:`usage_error` (exit 2) and :func:`command_error` (exit 1): the two messages on stderr.

Standard library only: no numpy, no Qt.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Iterable
from pathlib import Path

__all__ = ["output_clash", "table_outputs", "usage_error", "command_error"]


def usage_error(command: str, message: str) -> int:
    """Print ``zwidth COMMAND``'s usage error to stderr; returns its exit code, 2."""
    print(f"usage: zwidth {command} ... (see zwidth {command} --help)\nzwidth {command}: error: {message}",
          file=sys.stderr)
    return 2


def command_error(message: str) -> int:
    """Print a command's error (bad file, failed computation) to stderr; returns its exit code, 1."""
    print(f"zwidth: error: {message}", file=sys.stderr)
    return 1


def _same_file(a: str | os.PathLike, b: str | os.PathLike) -> bool:
    """Whether two paths name the same file: :func:`os.path.samefile` when both exist (hard and
    symbolic links too), else their resolved absolute paths compared (case-folded where the file
    system folds case)."""
    try:
        if os.path.exists(a) and os.path.exists(b):
            return os.path.samefile(a, b)
        return os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b))
    except (OSError, TypeError, ValueError):  # an unusable name is reported where it is used
        return False


def output_clash(output: str | os.PathLike, inputs: Iterable[tuple[str, str | os.PathLike | None]],
                 option: str = "-o", remedy: str = "write the output to another file") -> str | None:
    """Why ``output`` must not be written, or ``None``: the usage error (exit 2) of every ``zwidth``
    command when its output file is one of its input files (issue 22: ``identify m.csv -o m.csv``
    overwrote the measurement).  ``inputs`` are ``(what, path)`` pairs, e.g. ``("MEASUREMENT",
    "m.csv")`` or ``("--base", "p.json")``; ``None`` paths are skipped; ``remedy`` ends the message."""
    for what, path in inputs:
        if path is not None and _same_file(output, path):
            return f"{option} {os.fspath(output)}: this is the input file {what} {os.fspath(path)}; {remedy}"
    return None


def table_outputs(args: argparse.Namespace) -> tuple[str | None, Path | None]:
    """The usage error of a table command's files (``args.output`` a CSV, ``args.plot`` or the CSV's
    name with .png a PNG or SVG, neither the input ``args.profile`` nor each other), or ``None``, and
    the plot's path."""
    if Path(args.output).suffix.lower() != ".csv":
        return f"-o {args.output}: the extension must be .csv", None
    plot = Path(args.plot) if args.plot else Path(args.output).with_suffix(".png")
    if plot.suffix.lower() not in (".png", ".svg"):
        return f"--plot {plot}: the extension must be .png or .svg", None
    for out in (args.output, str(plot)):
        clash = output_clash(out, [("PROFILE", args.profile)])
        if clash is not None:
            return clash, None
    if Path(args.output).resolve() == plot.resolve():
        return "--plot and -o name the same file", None
    return None, plot
