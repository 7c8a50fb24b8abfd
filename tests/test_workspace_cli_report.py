"""``zwidth workspace``, ``export-plot --plot workspace|workspace-polar`` and the report's workspace part (issue 25)."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from PySide6.QtGui import QImage

from analysis.multidof import workspace_map
from analysis.profiles import MultiDofSection, bundled_profiles, load_profile, save_profile
from analysis.study import WorkspaceRequest, workspace_point
from analysis.study.workspace import K_RANGE
from app.report.content import gather
from cli_runner import run_cli

SECTION = MultiDofSection(x_points=6, y_points=5, handle_x=0.03, handle_y=0.22, wall_kind="normal",
                          wall_normal=(0.0, 1.0))


@pytest.fixture(scope="module")
def profile_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("ws")
    save_profile(load_profile(bundled_profiles()["hbfd"]).replace(multidof=SECTION), d / "p.json")
    return d / "p.json"


@pytest.fixture(scope="module")
def handle_point(profile_file):
    """The analysis's limits at the section's handle (the reference the exports are compared with)."""
    return workspace_point(load_profile(profile_file))


def _rows(path) -> tuple[list[str], list[list[str]]]:
    rows = [r for r in csv.reader(path.read_text(encoding="utf-8").splitlines()) if r and not r[0].startswith("#")]
    return rows[0], rows[1:]


def test_workspace_writes_the_map_whose_minimum_is_the_analysis(capfd, profile_file, tmp_path):
    out = tmp_path / "map.csv"
    proc = run_cli(capfd, "workspace", str(profile_file), "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    header, rows = _rows(out)
    assert header[:5] == ["x [m]", "y [m]", "reachable [-]", "k_isotropic [N/m]", "k_worst [N/m]"]
    req = WorkspaceRequest.of(load_profile(profile_file))
    m = workspace_map(req.linkage, req.x, req.y, req.damping, req.delay_samples, sample_time=req.sample_time, k_range=K_RANGE)
    assert len(rows) == m.x.size * m.y.size
    worst = np.array([float(r[4]) if r[4] else math.nan for r in rows]).reshape(m.y.size, m.x.size)
    np.testing.assert_array_equal(worst, m.worst_stiffness)
    j, i = np.unravel_index(int(np.nanargmin(worst)), worst.shape)
    assert (m.x[i], m.y[j]) == tuple(m.minimum.position)
    note = out.read_text(encoding="utf-8").splitlines()[1]
    assert note.startswith("# note: design bound") and repr(float(m.minimum.stiffness)) in note
    assert {r[2] for r in rows} <= {"0", "1"} and all(r[3] == "" for r in rows if r[2] == "0")
    image = QImage(str(out.with_suffix(".png")))
    assert image.width() > 600 and image.height() > 200


def test_workspace_refuses_an_output_that_is_its_input_and_a_bad_extension(capfd, profile_file, tmp_path):
    assert run_cli(capfd, "workspace", str(profile_file), "-o", str(profile_file)).returncode == 2
    assert run_cli(capfd, "workspace", str(profile_file), "-o", str(tmp_path / "m.txt")).returncode == 2
    assert run_cli(capfd, "workspace", str(profile_file), "-o", str(tmp_path / "m.csv"), "--plot",
                   str(tmp_path / "m.jpg")).returncode == 2


@pytest.mark.parametrize("plot", ["workspace", "workspace-polar"])
def test_export_plot_draws_the_workspace(capfd, profile_file, tmp_path, plot):
    out = tmp_path / f"{plot}.png"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", plot, "-o", str(out), "--width", "640")
    assert proc.returncode == 0, proc.stderr
    image = QImage(str(out))
    assert image.width() == 640 and image.height() > 100
    assert len({image.pixel(x, y) for y in range(0, image.height(), 9) for x in range(0, image.width(), 9)}) > 8


def test_export_polar_csv_is_the_handles_limits(capfd, profile_file, tmp_path, handle_point):
    out = tmp_path / "polar.csv"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", "workspace-polar", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    _, rows = _rows(out)
    pt = handle_point
    k = np.hypot([float(r[0]) for r in rows], [float(r[1]) for r in rows])
    np.testing.assert_allclose(k[:-1], pt.stiffness, rtol=1e-12)


def test_the_report_has_the_section_only_with_the_multidof_section(profile_file, handle_point):
    # the workspace part alone: the section is written as in the whole report (gather writes a section
    # when all its parts are asked), without the design chart and the other sections' results
    with_section = gather(load_profile(profile_file), sampled=False, parts=("workspace_map", "workspace_point"))
    titles = [s.title for s in with_section.sections]
    assert "Multi-DOF workspace" in titles
    m = with_section.results["workspace_map"]
    assert with_section.numbers["workspace.bound"][0] == pytest.approx(m.minimum.stiffness, abs=1e-12)
    assert with_section.numbers["workspace.handle_wall"][0] == pytest.approx(handle_point.wall, rel=1e-9)
    without = gather(load_profile(bundled_profiles()["hbfd"]), sampled=False, parts=("workspace_map", "workspace_point"))
    assert "Multi-DOF workspace" not in [s.title for s in without.sections]
    assert "workspace_map" not in without.results
