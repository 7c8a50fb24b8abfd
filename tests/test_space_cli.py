"""``zwidth space`` (issue 24): the renderable space of a profile's device, or the robust space of the
devices of its identified box, as CSV (every number as the API computes it) and a plot.

The commands run in process (:func:`cli_runner.run_cli`); the plot needs Qt (offscreen).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from cli_runner import run_cli

from analysis.identify import parameter_box
from analysis.profiles import RenderableSection, save_profile
from analysis.profiles.identification import IdentificationSection
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.sampled import renderable_space
from analysis.sampled.batch import box_corners, robust_renderable_space
from analysis.study import RenderableRequest, renderable_study

MASS, DAMPING = np.linspace(-0.2, 0.2, 3), np.linspace(1.0, 21.0, 3)
GRID = ["--mass=-0.2:0.2:3", "--damping=1:21:3"]
INTERVALS = {"masses[0]": (0.4, 0.6), "ground_dampings[0]": (1.0, 3.0)}


def read(path: Path) -> tuple[list[str], np.ndarray]:
    rows = [r for r in csv.reader(line for line in path.read_text().splitlines() if not line.startswith("#"))]
    return rows[0], np.array(rows[1:], dtype=float)


def rigid_path() -> Path:
    return Path(bundled_profiles()["rigid"])


@pytest.fixture
def boxed(tmp_path: Path) -> Path:
    """The rigid profile with an identification section: two intervals, so a box of four corners."""
    p = load_profile(rigid_path())
    path = tmp_path / "boxed.json"
    save_profile(p.replace(identification=IdentificationSection(INTERVALS)), path)
    return path


def test_space_of_one_device_is_the_apis(capfd, tmp_path: Path) -> None:
    out = tmp_path / "space.csv"
    r = run_cli(capfd, "space", rigid_path(), "-o", out, *GRID, "--qualities", "stable,passive")
    assert r.returncode == 0, r.stderr
    header, data = read(out)
    assert header == ["M [kg]", "B [N·s/m]", "K_max (all qualities) [N/m]", "K_max (stable) [N/m]",
                      "K_max (passive) [N/m]"]
    req = RenderableRequest.of(load_profile(rigid_path()))  # the profile's filter, delay and settings
    s = renderable_space(req.device, MASS, DAMPING, req.delay_samples, req.velocity_filter, req.acceleration,
                         ("stable", "passive"), settings=req.settings)
    assert np.array_equal(data[:, 0], np.repeat(MASS, 3)) and np.array_equal(data[:, 1], np.tile(DAMPING, 3))
    assert np.array_equal(data[:, 2], s.k_max.ravel())  # repr: every digit survives the CSV
    assert np.array_equal(data[:, 4], s.by_quality["passive"].ravel())
    assert np.any(data[:, 2] > 0)
    png = out.with_suffix(".png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_robust_space_of_the_box_corners(capfd, tmp_path: Path, boxed: Path) -> None:
    out = tmp_path / "robust.csv"
    r = run_cli(capfd, "space", boxed, "-o", out, *GRID, "--corners", "--workers", "1",
                "--plot", tmp_path / "robust.svg")
    assert r.returncode == 0, r.stderr
    header, data = read(out)
    assert header[-1] == "binding device [-]"
    p = load_profile(boxed)
    req = RenderableRequest.of(p)
    ref = robust_renderable_space(box_corners(parameter_box(p.device, INTERVALS)), MASS, DAMPING, req.delay_samples,
                                  workers=1)
    assert np.array_equal(data[:, 2], ref.k_max.ravel())
    assert np.array_equal(data[:, -1], ref.binding.ravel())
    one = renderable_space(p.device, MASS, DAMPING, req.delay_samples)  # the nominal device is inside the box
    assert np.all(data[:, 2] <= one.k_max.ravel())
    assert b"<svg" in (tmp_path / "robust.svg").read_bytes()[:400]


def test_the_profiles_renderable_section_sets_the_defaults(capfd, tmp_path: Path) -> None:
    """Without --mass, --damping, --qualities and --delay: the section's grids and qualities, the
    profile's delay, as the app's Renderable space view computes them."""
    p = load_profile(rigid_path())
    p = p.replace(renderable=RenderableSection(qualities=("stable", "passive"), mass_min=-0.1, mass_max=0.2,
                                               mass_points=3, damping_min=-2.0, damping_max=30.0, damping_points=4))
    path, out = tmp_path / "sec.json", tmp_path / "sec.csv"
    save_profile(p, path)
    r = run_cli(capfd, "space", path, "-o", out)
    assert r.returncode == 0, r.stderr
    header, data = read(out)
    req = RenderableRequest.of(load_profile(path))
    study = renderable_study(req)
    assert header[3:] == ["K_max (stable) [N/m]", "K_max (passive) [N/m]"]
    assert np.array_equal(data[:, 0], np.repeat(req.mass, 4)) and np.array_equal(data[:, 1], np.tile(req.damping, 3))
    assert np.array_equal(data[:, 2], study.space.k_max.ravel())


def test_batch_needs_the_identified_box(capfd, tmp_path: Path) -> None:
    r = run_cli(capfd, "space", rigid_path(), "-o", tmp_path / "x.csv", *GRID, "--batch", "4")
    assert r.returncode == 1 and "$.identification" in r.stderr
    assert not (tmp_path / "x.csv").exists()


@pytest.mark.parametrize(("args", "words"), [
    (["-o", "space.txt"], ".csv"),
    (["-o", "space.csv", "--mass", "1:0"], "--mass"),
    (["-o", "space.csv", "--damping", "a:b"], "--damping"),
    (["-o", "space.csv", "--plot", "space.pdf"], ".png or .svg"),
    (["-o", "space.csv", "--batch", "0"], "--batch"),
])
def test_usage_errors(capfd, tmp_path: Path, args: list[str], words: str) -> None:
    args = [str(tmp_path / a) if a.startswith("space.") else a for a in args]
    r = run_cli(capfd, "space", rigid_path(), *args)
    assert r.returncode == 2 and words in r.stderr


def test_an_unknown_quality_is_named(capfd, tmp_path: Path) -> None:
    r = run_cli(capfd, "space", rigid_path(), "-o", tmp_path / "q.csv", *GRID, "--qualities", "stable,silky")
    assert r.returncode == 1 and "qualities" in r.stderr and "silky" in r.stderr


def test_scheduler_runs_the_batch_on_the_cluster(capfd, tmp_path: Path, boxed: Path) -> None:
    """``--scheduler ADDRESS`` on an in-process LocalCluster: the same numbers as the local run."""
    from distributed import LocalCluster

    local, remote = tmp_path / "local.csv", tmp_path / "remote.csv"
    assert run_cli(capfd, "space", boxed, "-o", local, *GRID, "--batch", "3", "--workers", "1").returncode == 0
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        r = run_cli(capfd, "space", boxed, "-o", remote, *GRID, "--batch", "3", "--scheduler",
                    cluster.scheduler_address)
    assert r.returncode == 0, r.stderr
    assert np.array_equal(read(remote)[1], read(local)[1])
