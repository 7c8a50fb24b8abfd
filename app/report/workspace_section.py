"""The report's workspace part (issue 25), when the profile has a ``multidof`` section.

Qt-free: :func:`workspace_part` (called by :func:`app.report.content.gather`) gives the design bound
of the workspace map (the smallest critical stiffness of a plane wall over the grid of handle
positions, with its position and normal) and, at the profile's handle, the critical stiffness of the
isotropic wall, of the profile's wall and of the worst plane wall, and the principal effective
masses, all from :mod:`analysis.study.workspace`.  Its figures (needing Qt) are in
:mod:`app.report.workspace_figures`.
"""

from __future__ import annotations

import html
import math

from analysis.errors import ValidationError
from analysis.profiles import Profile
from analysis.profiles.schema import WALL_KINDS
from analysis.study import WorkspacePoint, format_number, multidof_section, workspace_point, workspace_study
from app.report.model import Numbers, Part, Row, Section, row

__all__ = ["workspace_part", "workspace_map_alone", "workspace_point_alone"]


def _angle(n: object) -> float:
    """A wall normal's angle from the x axis [degrees], in [0, 180) (``n`` and ``-n`` are one wall)."""
    return math.degrees(math.atan2(float(n[1]), float(n[0]))) % 180.0


def _handle_point(profile: Profile) -> tuple[WorkspacePoint | None, str]:
    """The limits at the profile's handle, or ``None`` and the report's sentence saying why not."""
    try:
        return workspace_point(profile), ""
    except ValidationError as err:
        return None, f" At the handle: {html.escape(str(err))}."


def workspace_map_alone(profile: Profile) -> dict[str, object]:
    """The workspace map alone (``workspace_map``, and ``workspace_point`` where the handle is reached),
    for the map figure; ``{}`` without a ``multidof`` section."""
    if profile.multidof is None:
        return {}
    out: dict[str, object] = {"workspace_map": workspace_study(profile)}
    pt, _note = _handle_point(profile)  # the map marks the handle when the linkage reaches it
    if pt is not None:
        out["workspace_point"] = pt
    return out


def workspace_point_alone(profile: Profile) -> dict[str, object]:
    """The limits at the handle alone (``workspace_point``), for the polar figure: not the map over the
    whole workspace; ``{}`` without a ``multidof`` section.  Raises :class:`ValidationError` when the
    linkage does not reach the handle."""
    return {} if profile.multidof is None else {"workspace_point": workspace_point(profile)}


def workspace_part(profile: Profile) -> Part:
    """The report's section on the workspace (empty without a ``multidof`` section), with the map and
    the limits at the handle as its results (``workspace_map``, ``workspace_point``)."""
    if profile.multidof is None:
        return Part()
    sec = multidof_section(profile)
    m = workspace_study(profile)
    b = m.minimum
    numbers: Numbers = {}
    rows: list[Row] = [
        row(numbers, "workspace.bound", "design bound: smallest critical stiffness of a plane wall", "k<sub>min</sub>",
            b.stiffness, "N/m"),
        row(numbers, "workspace.bound_x", "its handle position, x", "x", b.position[0], "m"),
        row(numbers, "workspace.bound_y", "its handle position, y", "y", b.position[1], "m"),
        row(numbers, "workspace.bound_angle", "its wall normal, angle from the x axis", "&theta;", _angle(b.normal),
            "&deg;"),
        row(numbers, "workspace.reachable", "grid points the linkage reaches", "", float(m.reachable.sum()), ""),
    ]
    results: dict[str, object] = {"workspace_map": m}
    pt, note = _handle_point(profile)
    if pt is not None:
        results["workspace_point"] = pt
        rows += [
            row(numbers, "workspace.handle_isotropic", "at the handle: critical stiffness, isotropic wall", "k<sub>iso</sub>",
                pt.isotropic, "N/m"),
            row(numbers, "workspace.handle_wall", "at the handle: critical stiffness, the profile's wall", "k<sub>wall</sub>",
                pt.wall, "N/m"),
            row(numbers, "workspace.handle_worst", "at the handle: critical stiffness, worst plane wall", "k<sub>worst</sub>",
                pt.worst.stiffness, "N/m"),
            row(numbers, "workspace.handle_worst_angle", "at the handle: worst normal, angle from the x axis", "&theta;",
                _angle(pt.worst.normal), "&deg;"),
            row(numbers, "workspace.mass_min", "at the handle: lightest effective mass", "m<sub>1</sub>",
                pt.principal_masses[0], "kg"),
            row(numbers, "workspace.mass_max", "at the handle: heaviest effective mass", "m<sub>2</sub>",
                pt.principal_masses[-1], "kg"),
        ]
    v = {name: format_number(getattr(sec, name), rich=True) for name in
         ("l1", "l2", "base", "x_min", "x_max", "y_min", "y_max", "wall_damping", "handle_x", "handle_y")}
    par = (f"The planar five-bar (links {v['l1']} m and {v['l2']} m, motors "
           f"{v['base']} m apart) is linearized at each of {sec.x_points} &times; {sec.y_points} handle "
           f"positions, x from {v['x_min']} to {v['x_max']} m, y from "
           f"{v['y_min']} to {v['y_max']} m; the exact sampled loop of the impedance "
           f"display is checked against a wall of damping {v['wall_damping']} N&middot;s/m, isotropic "
           f"and along {m.directions} plane-wall normals at each point. The design bound is the smallest critical "
           f"stiffness over the workspace, refined at its point. The handle is at ({v['handle_x']}, "
           f"{v['handle_y']}) m; the profile's wall is the {html.escape(WALL_KINDS[sec.wall_kind])}."
           + note)
    return Part((Section("Multi-DOF workspace", (par,), tuple(rows)),), numbers, results)
