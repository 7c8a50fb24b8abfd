"""``zwidth identify``: fit a chain to measurement files and write a profile (issue 14).

Usage::

    zwidth identify FILE[:QUANTITY[:BOUNDARY]]... --masses N [--fix KEY=VALUE]... [--quantity Q]
                    [--boundary B] [--sample-time T | --continuous] [--delay D] [--ground I]...
                    [--base PROFILE] -o profile.json [--json]

Each file may name its own kind (``g.csv:gauge``, ``c.csv:actuator:clamped``); ``--quantity`` and
``--boundary`` are the default for the others.  A time series without ``--sample-time`` is
sampled at its own time step (``--continuous``: an analyser's record).  ``--masses`` is checked
against :data:`analysis.study.identify.MAX_MASSES` before anything is read; above 4 masses the
estimated time and the progress go to stderr; Ctrl-C cancels (exit 130, nothing written).
The written profile has the fitted device, the couplings and gains of ``--base`` (default: the
bundled HBFD profile) and an ``identification`` section with the 95 % intervals and the
measurements embedded.  A bad measurement file exits with 1 and the file, row and column named.
Never imports Qt.
"""

from __future__ import annotations

import argparse
import json
import math
import signal
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO

from app.cli_files import output_clash

__all__ = ["add_identify_parser", "run_identify", "format_parameters", "output_clash", "FitWatch",
           "PROGRESS_ORDER", "CANCELLED_EXIT"]

#: above this many masses the estimated time and the progress of the fit are printed on stderr
PROGRESS_ORDER = 4
#: exit status after Ctrl-C (128 + SIGINT, as a shell reports it)
CANCELLED_EXIT = 130


def add_identify_parser(sub: argparse._SubParsersAction) -> None:
    """Add the ``identify`` subcommand to the ``zwidth`` parser."""
    p = sub.add_parser("identify", help="fit a chain model to measured frequency responses and write a profile",
                       description="Fit an N-mass chain to FRF or time-series CSV files (all together) and write "
                       "a profile with the fitted device and an identification section (95 % intervals, "
                       "embedded measurements).  Each FILE may name what it measured, FILE:QUANTITY[:BOUNDARY] "
                       "(g.csv:gauge, c.csv:actuator:clamped).  A time series without --sample-time is sampled "
                       "at its own time step.  Ctrl-C cancels (exit 130, nothing written).")
    p.add_argument("measurements", metavar="FILE[:QUANTITY[:BOUNDARY]]", nargs="+",
                   help="FRF or time-series CSV file, optionally with its own kind, e.g. g.csv:gauge or "
                   "c.csv:actuator:clamped (default: --quantity, --boundary)")
    p.add_argument("--masses", type=int, required=True, metavar="N",
                   help="number of masses of the chain (1..6: a larger fit takes over a minute)")
    p.add_argument("--fix", action="append", default=[], metavar="KEY=VALUE",
                   help="fix a parameter, e.g. masses[0]=0.2 (repeatable)")
    p.add_argument("--quantity", choices=("actuator", "handle", "gauge"), default="actuator",
                   help="what was measured, for files without their own :QUANTITY (default actuator)")
    p.add_argument("--boundary", choices=("free", "clamped"), default="free",
                   help="handle free or clamped, for files without their own :BOUNDARY (default free)")
    p.add_argument("--sample-time", type=float, metavar="T",
                   help="controller sample period in s (default: a time series' own step; FRF files "
                   "continuous-time)")
    p.add_argument("--continuous", action="store_true",
                   help="read time series as continuous-time records (an analyser's), not sampled")
    p.add_argument("--delay", type=int, default=0, metavar="D", help="computation delay in samples (default 0)")
    p.add_argument("--ground", type=int, action="append", metavar="I",
                   help="0-based mass with a damper to ground (repeatable; default: the actuator, N-1)")
    p.add_argument("--orders", action="store_true", help="also fit n = 1..N and print AIC/BIC/residual")
    p.add_argument("--base", metavar="PROFILE", help="profile whose couplings and gains are kept (default: HBFD)")
    p.add_argument("-o", "--output", required=True, metavar="FILE",
                   help="profile JSON to write (never one of the MEASUREMENT files)")
    p.add_argument("--force", action="store_true", help="let -o overwrite the --base profile")
    p.add_argument("--json", action="store_true", help="print the parameter table as JSON")


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


class FitWatch:
    """Progress and cancel of ``zwidth identify``: the hooks of :mod:`analysis.progress`.

    :meth:`cancelled` is the fit's ``cancelled()`` hook (asked before every model evaluation): it
    counts the evaluations, reports them through :meth:`progress` (``progress(done, total)``, the
    total the expected count; at most every ``interval`` seconds) and returns true once Ctrl-C
    was pressed (:meth:`sigint`).  A second Ctrl-C raises :class:`KeyboardInterrupt` at once, for a
    step that does not ask.  ``verbose`` prints the progress lines on ``stream``.
    """

    def __init__(self, expected: int, verbose: bool, stream: TextIO | None = None, interval: float = 2.0) -> None:
        self.expected = max(int(expected), 1)
        self.verbose = verbose
        self.stream = stream
        self.interval = interval
        self.evaluations = 0
        self.interrupted = False
        self.started = time.monotonic()
        self._shown = self.started

    def cancelled(self) -> bool:
        self.evaluations += 1
        now = time.monotonic()
        if self.verbose and now - self._shown >= self.interval:
            self._shown = now
            self.progress(self.evaluations, max(self.expected, self.evaluations + 1))
        return self.interrupted

    def progress(self, done: int, total: int) -> None:
        """Print ``done`` of ``total`` model evaluations and the time so far (verbose only)."""
        if self.verbose:
            share = min(99, 100 * done // max(total, 1)) if done < total else 100
            print(f"zwidth identify: {done} of about {total} model evaluations ({share} %), "
                  f"{time.monotonic() - self.started:.0f} s", file=self.stream or sys.stderr, flush=True)

    def sigint(self, _signum: int, _frame: object) -> None:
        if self.interrupted:
            raise KeyboardInterrupt
        self.interrupted = True

    @contextmanager
    def installed(self) -> Iterator[FitWatch]:
        """Ctrl-C sets the cancel flag while the fit runs (the main thread only; restored after)."""
        if threading.current_thread() is not threading.main_thread():
            yield self
            return
        previous = signal.signal(signal.SIGINT, self.sigint)
        try:
            yield self
        finally:
            signal.signal(signal.SIGINT, previous)


#: model evaluations of one fit by order on the reference case of FIT_SECONDS (issue 23)
_EVALUATIONS = {1: 30, 2: 40, 3: 85, 4: 175, 5: 276, 6: 5700}


def _measurement_rows(loaded: list) -> list[dict]:
    return [{"file": r.spec.path, "quantity": r.measurement.quantity, "boundary": r.measurement.boundary,
             "time_series": r.time_series, "sample_time": r.measurement.sample_time,
             "sample_time_from": r.sample_time_source, "points": int(r.measurement.size)} for r in loaded]


def _report(result, rows: list[dict], out: str, as_json: bool, measured: list[dict] | None = None,
            sample_time: float | None = None) -> None:
    fit = result.fit
    orders = result.orders
    if as_json:
        data = {"output": out, "residual": fit.residual, "aic": fit.aic, "bic": fit.bic, "converged": fit.converged,
                "parameters": [{k: v for k, v in r.items() if k != "text"} for r in rows],
                "non_identifiable": list(fit.non_identifiable), "suggestions": dict(fit.suggestions),
                "warnings": list(fit.warnings), "sample_time": sample_time, "measurements": measured or []}
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


def _notes(loaded: list) -> None:
    """Say on stderr how each time series was read (its sample time)."""
    for r in loaded:
        if r.time_series and r.sample_time_source == "time step":
            print(f"zwidth identify: {r.spec.path}: a time series, fitted as sampled through the controller at "
                  f"its own time step T = {r.measurement.sample_time:.6g} s (--sample-time T to give it, "
                  "--continuous for an analyser's record)", file=sys.stderr)
        elif r.time_series and r.sample_time_source == "continuous":
            print(f"zwidth identify: {r.spec.path}: a time series, fitted as continuous-time (--continuous)",
                  file=sys.stderr)


def _usage(args: argparse.Namespace) -> str | None:
    """The usage error of the options alone (checked before any file is read), or ``None``."""
    from analysis.study.identify import MAX_MASSES

    if not 1 <= args.masses <= MAX_MASSES:
        return (f"--masses must be >= 1 and <= {MAX_MASSES} (got {args.masses}): a fit of more than {MAX_MASSES} "
                f"masses takes over a minute on the reference machine")
    if args.sample_time is not None and not (math.isfinite(args.sample_time) and args.sample_time > 0):
        return f"--sample-time {args.sample_time:g}: the controller sample period must be > 0 and finite (s)"
    if args.continuous and args.sample_time is not None:
        return "--continuous and --sample-time exclude each other: a record is either sampled or continuous-time"
    if args.delay < 0 or (args.delay and (args.sample_time is None and args.continuous)):
        return f"--delay {args.delay}: must be >= 0, and 0 for continuous-time measurements"
    return None


def run_identify(args: argparse.Namespace) -> int:
    """Fit, write the profile, print the table; 0 ok, 1 bad input or file, 2 usage error, 130 cancelled."""
    try:
        return _run(args)
    except KeyboardInterrupt:  # a second Ctrl-C, or one outside the fit
        return _fail("cancelled; nothing written", CANCELLED_EXIT)


def _run(args: argparse.Namespace) -> int:
    usage = _usage(args)  # before anything is read or allocated (--masses 600 grew to 22 GB)
    if usage:
        return _fail(usage, 2)
    from analysis.errors import ValidationError
    from analysis.identify import MeasurementError
    from analysis.profiles import ProfileError, save_profile
    from analysis.study.identify import identify_chain, parameter_rows, parse_fixed, profile_with_fit
    from analysis.study.measurement_files import parse_measurement_spec, read_measurement_files

    try:
        specs = [parse_measurement_spec(m) for m in args.measurements]
    except ValueError as err:
        return _fail(str(err), 2)
    clash = output_clash(args.output, [("MEASUREMENT", s.path) for s in specs])
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
        loaded = read_measurement_files(specs, args.quantity, args.boundary, args.sample_time, args.delay,
                                        step_as_sample_time=not args.continuous)
        measurements = [r.measurement for r in loaded]
        _notes(loaded)
        T = args.sample_time or _common_sample_time(measurements) or base.device.sample_time
        watch = _watch(args, sum(m.size for m in measurements))
        with watch.installed():
            result = identify_chain(measurements, args.masses, fixed, args.ground,
                                    max_masses=args.masses if args.orders else None, cancelled=watch.cancelled,
                                    sample_time=T, band_min=base.device.band_min)
        if result is None or watch.interrupted:
            return _fail("cancelled; nothing written", CANCELLED_EXIT)
        watch.progress(watch.evaluations, watch.evaluations)
        profile = profile_with_fit(base, result.fit, measurements, name=Path(args.output).stem)
        save_profile(profile, args.output)
    except (MeasurementError, ProfileError) as err:
        return _fail(str(err))
    except (ValidationError, ValueError) as err:
        return _fail(str(err))
    _report(result, parameter_rows(result.fit), args.output, args.json, _measurement_rows(loaded), T)
    return 0


def _common_sample_time(measurements: list) -> float | None:
    """The sample time of the sampled measurements when they share one, else ``None``."""
    ts = {m.sample_time for m in measurements if m.sample_time is not None}
    return ts.pop() if len(ts) == 1 else None


def _watch(args: argparse.Namespace, points: int) -> FitWatch:
    """The progress and cancel hooks; above :data:`PROGRESS_ORDER` masses, the estimate on stderr."""
    from analysis.study.identify import fit_time_estimate

    n = args.masses
    orders = range(1, n + 1) if args.orders else (n,)
    expected = sum(_EVALUATIONS[k] for k in orders)
    verbose = n > PROGRESS_ORDER
    if verbose:
        seconds = fit_time_estimate(n, points, orders=args.orders)
        print(f"zwidth identify: fitting {n} masses to {points} points takes about {seconds:.0f} s of CPU time "
              "(estimate: measured on 2 cores with an actuator and a gauge FRF; longer on a busy machine or with "
              "the actuator alone); progress below, Ctrl-C cancels", file=sys.stderr, flush=True)
    return FitWatch(expected, verbose)
