"""``zwidth space``: the renderable (M, B, K) space of a profile's device, or the robust space of a
batch of devices from its identified parameter box (issue 24).

Usage::

    zwidth space PROFILE -o space.csv [--plot space.png|svg] [--qualities stable,passive,accurate,quiet]
                 [--mass LOW:HIGH:N] [--damping LOW:HIGH:N] [--delay D]
                 [--batch N [--seed S] | --corners] [--workers N | --scheduler ADDRESS]

Everything not given on the command line comes from the profile, as the app's Renderable space
view takes it (:class:`analysis.study.RenderableRequest`: the ``renderable`` section's grids,
qualities, acceleration estimate and quality settings, or their defaults; the profile's velocity
filter and delay).  The CSV is a table in the form of every zwidth CSV
(:func:`app.views.export.table_csv_text`, headers ``quantity [unit]``), one row per (M, B):
``M [kg]``, ``B [N·s/m]``, ``K_max (all qualities) [N/m]``, ``K_max (Q) [N/m]`` for each quality Q
and, with a batch, ``binding device [-]`` (the index from 0 of the device that binds it).  The
plot draws ``k_max`` against B for up to five masses of the grid (PNG or SVG, beside the CSV by
default).  ``--batch N`` draws N devices from the box of the profile's ``identification``
section (:func:`analysis.sampled.batch.box_samples`, seeded), ``--corners`` takes its corners; they
run on a local process pool (``--workers``) or on the Dask cluster at ``--scheduler`` (the
``distributed`` extra).  Exit codes as ``zwidth``'s: 1 for a bad profile or a profile without the
box, 2 for a usage error, 130 after Ctrl-C (nothing written).
"""

from __future__ import annotations

import argparse
import importlib
import sys
from pathlib import Path

import numpy as np

from app.cli_files import command_error, table_outputs, usage_error

__all__ = ["add_space_parser", "run_space", "parse_grid", "space_csv", "DEFAULT_GRID_POINTS", "PLOT_SLICES"]

#: points of each default axis
DEFAULT_GRID_POINTS = 41
#: most masses drawn in the plot
PLOT_SLICES = 5
_COLORS = ("a", "b", "c", "mark", "muted")


def add_space_parser(sub: argparse._SubParsersAction) -> None:
    """Add the ``space`` subcommand to the ``zwidth`` parser."""
    p = sub.add_parser("space", help="write the renderable (M, B, K) space (or a batch's robust space) as CSV and a plot",
                       description="Compute, for a grid of virtual masses M and dampings B, the largest K with the "
                       "chosen qualities (issue 24; docs: the renderable space and the batch pages), write it as CSV "
                       "and draw K_max against B for a few masses.  With --batch or --corners, the robust space of the "
                       "devices of the profile's identified parameter box (the smallest K_max over the devices).")
    p.add_argument("profile", metavar="PROFILE", help="profile JSON file")
    p.add_argument("-o", "--output", required=True, metavar="FILE.csv", help="the CSV (never one of the input files)")
    p.add_argument("--plot", metavar="FILE", help="the plot, .png or .svg (default: the CSV's name with .png)")
    p.add_argument("--qualities", metavar="Q[,Q...]",
                   help="comma-separated: stable, passive, accurate, quiet (default: the profile's renderable section's)")
    p.add_argument("--mass", metavar="LOW:HIGH[:N]",
                   help=f"virtual masses [kg], N evenly spaced (default N {DEFAULT_GRID_POINTS}; default grid: the "
                   "profile's renderable section's)")
    p.add_argument("--damping", metavar="LOW:HIGH[:N]",
                   help="virtual dampings [N s/m], N evenly spaced (default grid: the profile's renderable section's)")
    p.add_argument("--delay", type=int, metavar="D", help="computation delay in samples (default: the profile's)")
    batch = p.add_mutually_exclusive_group()
    batch.add_argument("--batch", type=int, metavar="N", help="N devices drawn from the identified box")
    batch.add_argument("--corners", action="store_true", help="the 2^p corners of the identified box")
    p.add_argument("--seed", type=int, default=0, help="seed of --batch's draw (default 0: the same devices each run)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, metavar="N", help="local processes for a batch (default: one per CPU)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="run a batch on the Dask cluster at ADDRESS, e.g. tcp://host:8786 (zwidth[distributed])")


def parse_grid(text: str, name: str) -> np.ndarray:
    """``"LOW:HIGH[:N]"`` as ``numpy.linspace(LOW, HIGH, N)`` (N defaults to :data:`DEFAULT_GRID_POINTS`).

    Raises ``ValueError`` with a message naming ``--name`` for anything else.
    """
    parts = text.split(":")
    try:
        if len(parts) not in (2, 3):
            raise ValueError
        low, high = float(parts[0]), float(parts[1])
        n = int(parts[2]) if len(parts) == 3 else DEFAULT_GRID_POINTS
    except ValueError:
        raise ValueError(f"--{name} {text}: expected LOW:HIGH or LOW:HIGH:N") from None
    if not (np.isfinite(low) and np.isfinite(high) and low < high and 2 <= n <= 400):
        raise ValueError(f"--{name} {text}: needs finite LOW < HIGH and 2 <= N <= 400")
    return np.linspace(low, high, n)


def space_csv(mass: np.ndarray, damping: np.ndarray, k_max: np.ndarray, by_quality: dict,
              binding: np.ndarray | None, notes: list[str]) -> str:
    """The CSV text as a table (:func:`app.views.export.table_csv_text`): ``# note:`` lines, a header,
    one row per (M, B) (B fastest) with every number in full precision."""
    from analysis.study import QUALITY_LABELS

    from app.views.base import Axis
    from app.views.export import table_csv_text
    from app.views.renderable_view import B_AXIS, K_AXIS, M_AXIS

    m, b = np.meshgrid(np.asarray(mass, float), np.asarray(damping, float), indexing="ij")
    k = K_AXIS.quantity
    columns = [(M_AXIS, m), (B_AXIS, b), (Axis(f"{k} ({QUALITY_LABELS['all']})", K_AXIS.unit), k_max),
               *((Axis(f"{k} ({QUALITY_LABELS[q]})", K_AXIS.unit), a) for q, a in by_quality.items())]
    if binding is not None:
        columns.append((Axis("binding device", "-"), np.asarray(binding, int)))
    return table_csv_text(columns, notes)


def _check_args(args: argparse.Namespace) -> tuple[str | None, Path | None]:
    """The usage error of ``args`` (or ``None``) and the plot's path."""
    if args.batch is not None and not 1 <= args.batch <= 100_000:
        return "--batch must be between 1 and 100000", None
    if args.workers is not None and args.workers < 1:
        return "--workers must be at least 1", None
    return table_outputs(args)


def _devices(profile, args: argparse.Namespace):
    """The batch's devices, or ``None`` without ``--batch``/``--corners``; a string says why there are none."""
    if args.batch is None and not args.corners:
        return None
    from analysis.study import RobustBox

    box = RobustBox.of(profile, "corners" if args.corners else "samples", args.batch or 0, args.seed)
    if isinstance(box, str):
        return f"$.identification: --batch and --corners draw from the identified box: {box}"
    return box.devices(profile.device)


def _client(address: str):
    """A ``dask.distributed.Client`` on ``address``, or a string saying why there is none."""
    try:
        distributed = importlib.import_module("distributed")
    except ImportError:
        return "--scheduler needs Dask: pip install 'zwidth[distributed]' (or 'dask[distributed]')"
    try:
        return distributed.Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        return f"cannot reach the Dask scheduler at {address}: {exc}"


def _progress(total_label: str):
    """Progress on stderr at every tenth of the batch."""
    last = [-1]

    def report(done: int, total: int) -> None:
        tenth = (10 * done) // max(total, 1)
        if tenth != last[0]:
            last[0] = tenth
            print(f"{total_label}: {done}/{total} devices", file=sys.stderr, flush=True)

    return report


def _compute(request, args: argparse.Namespace, devices, qualities, mass, damping):
    """``(space, binding, error message)`` on the request's device, filter, acceleration and settings."""
    from analysis.sampled import renderable_space
    from analysis.sampled.batch import robust_renderable_space

    kw = {"delay_samples": request.delay_samples if args.delay is None else args.delay,
          "velocity_filter": request.velocity_filter, "acceleration": request.acceleration,
          "qualities": qualities, "settings": request.settings}
    if devices is None:
        return renderable_space(request.device, mass, damping, **kw), None, None
    client = None
    if args.scheduler:
        client = _client(args.scheduler)
        if isinstance(client, str):
            return None, None, client
    try:
        r = robust_renderable_space(devices, mass, damping, workers=args.workers, client=client,
                                    progress=_progress("space"), **kw)
    finally:
        if client is not None:
            client.close()
    return r, r.binding, None


def write_plot(path: Path, mass: np.ndarray, damping: np.ndarray, k_max: np.ndarray, title: str) -> None:
    """K_max against B for up to :data:`PLOT_SLICES` masses of the grid (PNG or SVG, headless Qt)."""
    from app.report.figures import FIG_SIZE, ensure_app, prepare_view

    ensure_app()  # offscreen when there is no display
    from app.views import export
    from app.views.curves_plot import CurvesPlot
    from app.views.placement import LegendPlacer

    view = CurvesPlot(title, ("virtual damping B", "N·s/m"), ("K_max", "N/m"), log_y=True)
    rows = np.unique(np.linspace(0, mass.size - 1, min(PLOT_SLICES, mass.size)).round().astype(int))
    for color, i in zip(_COLORS, rows):
        key = f"m{i}"
        none = "" if np.any(k_max[i] > 0) else " (no K)"  # nothing to draw on the log axis
        view.add_curve(key, f"M = {mass[i]:.4g} kg{none}", color, export_name=f"K_max at M = {mass[i]:.6g} kg")
        view.set_curve(key, damping, k_max[i], gaps=True)
    placer = LegendPlacer(view)  # the legend where it hides the fewest points
    prepare_view(view)
    placer.place()
    if path.suffix.lower() == ".svg":
        export.export_svg(view, path)
    else:
        export.export_png(view, path, round(FIG_SIZE[0] * 150 / 96))


def run_space(args: argparse.Namespace) -> int:
    """``zwidth space``: compute, then write the CSV and the plot (nothing when it fails)."""
    from analysis.errors import ValidationError
    from analysis.profiles import atomic_write
    from analysis.sampled.batch import DeviceFailed

    problem, plot = _check_args(args)
    if problem is not None:
        return usage_error("space", problem)
    try:
        mass = None if args.mass is None else parse_grid(args.mass, "mass")
        damping = None if args.damping is None else parse_grid(args.damping, "damping")
    except ValueError as err:
        return usage_error("space", str(err))
    if args.delay is not None and args.delay < 0:
        return usage_error("space", "--delay must be at least 0")
    from analysis.profiles.io import ProfileError, load_profile

    try:
        profile = load_profile(args.profile)
    except ProfileError as err:
        return command_error(str(err))
    from analysis.study import RenderableRequest

    try:
        request = RenderableRequest.of(profile)
        qualities = request.qualities if args.qualities is None else tuple(
            q.strip() for q in args.qualities.split(",") if q.strip())
        mass = np.array(request.mass) if mass is None else mass
        damping = np.array(request.damping) if damping is None else damping
        devices = _devices(profile, args)
        if isinstance(devices, str):
            return command_error(f"{args.profile}: {devices}")
        space, binding, why = _compute(request, args, devices, qualities, mass, damping)
    except (ValidationError, DeviceFailed) as err:
        return command_error(f"{args.profile}: {err}")
    except KeyboardInterrupt:
        print("zwidth space: cancelled, nothing written", file=sys.stderr)
        return 130
    if why is not None:
        return command_error(why)
    n = 1 if devices is None else len(devices)
    delay = request.delay_samples if args.delay is None else args.delay
    notes = [f"zwidth space of {args.profile}: qualities {', '.join(space.qualities)}, delay {delay} samples",
             "one device" if devices is None else f"robust space of {n} devices (binding device: index from 0)"]
    text = space_csv(space.mass, space.damping, space.k_max, dict(space.by_quality), binding, notes)
    title = "K_max against B" + ("" if devices is None else f", robust over {n} devices")
    if not np.any(space.k_max > 0):
        title += ": no (M, B) of the grid renders any K with every quality"
        print(f"zwidth space: {title}", file=sys.stderr)
    try:
        atomic_write(args.output, text.encode("utf-8"))
        write_plot(plot, space.mass, space.damping, space.k_max, title)
    except OSError as err:
        return command_error(str(err))
    print(f"wrote {args.output} and {plot}")
    return 0
