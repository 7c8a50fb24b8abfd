"""``zwidth identify``: fit a chain to measurement files and write a profile (issue 14).

Usage::

    zwidth identify MEASUREMENT... --masses N [--fix KEY=VALUE]... [--quantity Q] [--boundary B]
                    [--sample-time T] [--delay D] [--ground I]... [--base PROFILE] -o profile.json [--json]

The written profile has the fitted device, the couplings and gains of ``--base`` (default: the
bundled HBFD profile) and an ``identification`` section with the 95 % intervals and the
measurements embedded.  A bad measurement file exits with 1 and the file, row and column named.
Never imports Qt.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from collections.abc import Iterable
from pathlib import Path

__all__ = ["add_identify_parser", "run_identify", "format_parameters", "output_clash"]


def add_identify_parser(sub: argparse._SubParsersAction) -> None:
    """Add the ``identify`` subcommand to the ``zwidth`` parser."""
    p = sub.add_parser("identify", help="fit a chain model to measured frequency responses and write a profile",
                       description="Fit an N-mass chain to FRF or time-series CSV files (all together) and write "
                       "a profile with the fitted device and an identification section (95 % intervals, "
                       "embedded measurements).")
    p.add_argument("measurements", metavar="MEASUREMENT", nargs="+", help="FRF or time-series CSV file")
    p.add_argument("--masses", type=int, required=True, metavar="N", help="number of masses of the chain")
    p.add_argument("--fix", action="append", default=[], metavar="KEY=VALUE",
                   help="fix a parameter, e.g. masses[0]=0.2 (repeatable)")
    p.add_argument("--quantity", choices=("actuator", "handle", "gauge"), default="actuator",
                   help="what was measured (default actuator)")
    p.add_argument("--boundary", choices=("free", "clamped"), default="free", help="handle free or clamped")
    p.add_argument("--sample-time", type=float, metavar="T",
                   help="controller sample period in s (default: continuous-time measurement)")
    p.add_argument("--delay", type=int, default=0, metavar="D", help="computation delay in samples (default 0)")
    p.add_argument("--ground", type=int, action="append", metavar="I",
                   help="0-based mass with a damper to ground (repeatable; default: the actuator, N-1)")
    p.add_argument("--orders", action="store_true", help="also fit n = 1..N and print AIC/BIC/residual")
    p.add_argument("--base", metavar="PROFILE", help="profile whose couplings and gains are kept (default: HBFD)")
    p.add_argument("-o", "--output", required=True, metavar="FILE",
                   help="profile JSON to write (never one of the MEASUREMENT files)")
    p.add_argument("--force", action="store_true", help="let -o overwrite the --base profile")
    p.add_argument("--json", action="store_true", help="print the parameter table as JSON")


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


def _fail(message: str, code: int = 1) -> int:
    print(f"zwidth identify: error: {message}", file=sys.stderr)
    return code


def format_parameters(rows: list[dict]) -> str:
    """The parameter table as aligned text (value, standard error, 95 % interval and its method)."""
    head = ("parameter", "value", "std error", "95 % low", "95 % high", "interval", "")
    lines = [head]
    for r in rows:
        t = r["text"]
        note = "fixed" if r["fixed"] else ("" if r["identifiable"] else "NOT identifiable")
        lines.append((r["key"], t["value"], t["std_error"], t["low"], t["high"], r.get("method", ""), note))
    widths = [max(len(line[i]) for line in lines) for i in range(len(head))]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(line, widths)).rstrip() for line in lines)


def _base(path: str | None):
    from analysis.profiles import load_profile
    from analysis.resources import resource_path

    return load_profile(path if path else resource_path("profiles", "hbfd.json"))


def _report(result, rows: list[dict], out: str, as_json: bool) -> None:
    fit = result.fit
    orders = result.orders
    if as_json:
        data = {"output": out, "residual": fit.residual, "aic": fit.aic, "bic": fit.bic, "converged": fit.converged,
                "parameters": [{k: v for k, v in r.items() if k != "text"} for r in rows],
                "non_identifiable": list(fit.non_identifiable), "suggestions": dict(fit.suggestions),
                "warnings": list(fit.warnings)}
        if orders is not None:
            data["orders"] = [{"n": int(n), "aic": float(a), "bic": float(b), "residual": float(r)}
                              for n, a, b, r in zip(orders.n, orders.aic, orders.bic, orders.residual)]
        from analysis.checks import jsonable

        print(json.dumps(jsonable(data), indent=2))
        return
    print(format_parameters(rows))
    print(f"residual (RMS, weighted log-response): {fit.residual:.4g}   AIC {fit.aic:.6g}   BIC {fit.bic:.6g}")
    if orders is not None:
        print("\n n   AIC            BIC            residual")
        for n, a, b, r in zip(orders.n, orders.aic, orders.bic, orders.residual):
            mark = "  <- lowest BIC" if orders.best_bic == n else ""
            print(f"{int(n):2d}   {a:<13.6g}  {b:<13.6g}  {r:<10.4g}{mark}")
    for w in fit.warnings:  # the non-identifiable keys, grouped by what would fix them, among them
        print(f"warning: {w}")
    print(f"wrote {out}")


def run_identify(args: argparse.Namespace) -> int:
    """Fit, write the profile, print the table; 0 ok, 1 bad input or file, 2 usage error."""
    from analysis.errors import ValidationError
    from analysis.identify import MeasurementError
    from analysis.profiles import ProfileError, save_profile
    from analysis.study.identify import identify_chain, load_measurements, parameter_rows, parse_fixed, profile_with_fit

    if args.masses < 1:
        return _fail("--masses must be >= 1", 2)
    if args.sample_time is not None and not (math.isfinite(args.sample_time) and args.sample_time > 0):
        return _fail(f"--sample-time {args.sample_time:g}: the controller sample period must be > 0 and finite (s)", 2)
    if args.delay < 0 or (args.delay and args.sample_time is None):
        return _fail(f"--delay {args.delay}: must be >= 0, and 0 without --sample-time", 2)
    clash = output_clash(args.output, [("MEASUREMENT", m) for m in args.measurements])
    if clash is None and not args.force:
        from analysis.resources import resource_path

        base = ("--base", args.base) if args.base else ("--base (default)", resource_path("profiles", "hbfd.json"))
        clash = output_clash(args.output, [base],
                             remedy="write the output to another file, or add --force to overwrite the base profile")
    if clash:
        return _fail(clash, 2)
    try:
        fixed = parse_fixed(args.fix)
    except ValueError as err:
        return _fail(str(err), 2)
    try:
        base = _base(args.base)
        measurements = load_measurements(args.measurements, args.quantity, args.boundary, args.sample_time,
                                         args.delay)
        result = identify_chain(measurements, args.masses, fixed, args.ground,
                                max_masses=args.masses if args.orders else None,
                                sample_time=args.sample_time if args.sample_time else base.device.sample_time,
                                band_min=base.device.band_min)
        profile = profile_with_fit(base, result.fit, measurements, name=Path(args.output).stem)
        save_profile(profile, args.output)
    except (MeasurementError, ProfileError) as err:
        return _fail(str(err))
    except (ValidationError, ValueError) as err:
        return _fail(str(err))
    _report(result, parameter_rows(result.fit), args.output, args.json)
    return 0
