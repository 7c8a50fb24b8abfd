"""``zwidth workspace``: the workspace map of a profile's multi-DOF linkage as CSV and a plot (issue 25).

Usage::

    zwidth workspace PROFILE -o map.csv [--plot map.png|svg]

The linkage, the handle, the wall and the grid are the profile's ``multidof`` section (the
section's defaults, said on stderr, when it has none); the loop (sample period, velocity filter,
delay) is the profile's.  Everything comes from :mod:`analysis.study.workspace`.  The CSV has one row
per grid point, in the table form of every zwidth CSV (:func:`app.views.export.table_csv_text`,
headers ``quantity [unit]``, an empty field where a quantity is not defined): ``x [m]``, ``y [m]``,
``reachable [-]`` (1 or 0), the critical stiffness of the isotropic wall ``k_isotropic [N/m]`` and
of the worst plane wall ``k_worst [N/m]``, and that wall's unit normal ``n_x [-]``, ``n_y [-]``
(empty where unreachable), every digit; ``# note:`` lines before the header give the design bound
(the minimum over the workspace, its position and normal).  The plot (PNG or SVG, beside the CSV
by default) is the app's Workspace map with the linkage at the handle.  Exit codes as ``zwidth``'s: 1 for a bad profile or a grid the
linkage does not reach, 2 for a usage error, 130 after Ctrl-C (nothing written).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from app.cli_files import command_error, table_outputs, usage_error

__all__ = ["add_workspace_parser", "run_workspace", "workspace_csv"]


def add_workspace_parser(sub: argparse._SubParsersAction) -> None:
    """Add the ``workspace`` subcommand to the ``zwidth`` parser."""
    p = sub.add_parser("workspace", help="write the workspace map of the profile's multi-DOF linkage as CSV and a plot",
                       description="Compute, over the grid of handle positions of the profile's multidof section, "
                       "the critical stiffness of the isotropic wall and of the worst plane wall, and the design "
                       "bound (the minimum over the workspace, with its position and normal) (issue 25; docs: the "
                       "multi-DOF guide page).")
    p.add_argument("profile", metavar="PROFILE", help="profile JSON file")
    p.add_argument("-o", "--output", required=True, metavar="FILE.csv", help="the CSV (never one of the input files)")
    p.add_argument("--plot", metavar="FILE", help="the plot, .png or .svg (default: the CSV's name with .png)")


def workspace_csv(m: object, notes: list[str]) -> str:
    """The CSV text of a :class:`~analysis.multidof.WorkspaceMap` as a table
    (:func:`app.views.export.table_csv_text`): ``# note:`` lines, a header, one row per point (x fastest)."""
    import numpy as np

    from app.views.base import Axis
    from app.views.export import table_csv_text
    from app.views.workspace_view import K_AXIS, X_AXIS, Y_AXIS

    x, y = np.meshgrid(np.asarray(m.x, float), np.asarray(m.y, float))
    n = np.asarray(m.worst_normal, float)
    return table_csv_text([(X_AXIS, x), (Y_AXIS, y), (Axis("reachable", "-"), np.asarray(m.reachable, bool)),
                           (Axis("k_isotropic", "N/m"), m.k_max), (K_AXIS, m.worst_stiffness),
                           (Axis("n_x", "-"), n[..., 0]), (Axis("n_y", "-"), n[..., 1])], notes)


def _progress(done: int, total: int) -> None:
    print(f"workspace: {done}/{total} bands of the grid", file=sys.stderr, flush=True)


def write_plot(path: Path, m: object, point: object, handle: tuple[float, float]) -> None:
    """The app's workspace map with the linkage at the handle (PNG or SVG, headless Qt)."""
    from app.report.figures import FIG_SIZE, ensure_app, prepare_view

    ensure_app()  # offscreen when there is no display
    from app.views import export
    from app.views.workspace_view import WorkspaceMapView

    view = WorkspaceMapView()
    view.update_map(m)
    view.update_point(point, handle)
    prepare_view(view)
    if path.suffix.lower() == ".svg":
        export.export_svg(view, path)
    else:
        export.export_png(view, path, round(FIG_SIZE[0] * 150 / 96))


def run_workspace(args: argparse.Namespace) -> int:
    """``zwidth workspace``: compute, then write the CSV and the plot (nothing when it fails)."""
    from analysis.errors import ValidationError
    from analysis.profiles import atomic_write
    from analysis.profiles.io import ProfileError, load_profile
    from analysis.study import format_number, multidof_section, workspace_point, workspace_study

    problem, plot = table_outputs(args)
    if problem is not None:
        return usage_error("workspace", problem)
    try:
        profile = load_profile(args.profile)
    except ProfileError as err:
        return command_error(str(err))
    if profile.multidof is None:
        print(f"zwidth workspace: {args.profile} has no multidof section: the default five-bar and grid",
              file=sys.stderr)
    sec = multidof_section(profile)
    try:
        m = workspace_study(profile, progress=_progress)
    except ValidationError as err:
        return command_error(f"{args.profile}: $.multidof.map: {err}")
    except KeyboardInterrupt:
        print("zwidth workspace: cancelled, nothing written", file=sys.stderr)
        return 130
    try:
        point = workspace_point(profile)
    except ValidationError as err:  # a singular handle: the map is still drawn, without the linkage
        print(f"zwidth workspace: $.multidof.handle: {err}", file=sys.stderr)
        point = None
    b = m.minimum
    notes = [f"zwidth workspace {Path(args.profile).name}: {sec.x_points} x {sec.y_points} handle positions, "
             f"wall damping {format_number(sec.wall_damping)} N·s/m",
             f"design bound (worst plane wall over the workspace): {float(b.stiffness)!r} N/m at x = "
             f"{float(b.position[0])!r} m, y = {float(b.position[1])!r} m, normal ({float(b.normal[0])!r}, "
             f"{float(b.normal[1])!r})"]
    try:
        atomic_write(args.output, workspace_csv(m, notes))
        write_plot(plot, m, point, (sec.handle_x, sec.handle_y))
    except OSError as err:
        return command_error(str(err))
    print(f"design bound {format_number(b.stiffness)} N/m at ({format_number(b.position[0])}, "
          f"{format_number(b.position[1])}) m; wrote {args.output} and {plot}")
    return 0
