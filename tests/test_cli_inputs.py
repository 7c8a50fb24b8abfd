"""Issue 22, "Files and inputs": a command never writes over one of its input files (exit 2, the
input unchanged byte for byte), and its error messages print plain numbers, file lines and the
option at fault."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from analysis.resources import resource_path
from cli_runner import run_cli
from test_identify_cli import write_frf

HBFD = resource_path("profiles", "hbfd.json")


@pytest.fixture(scope="module")
def frf(tmp_path_factory) -> Path:
    return write_frf(tmp_path_factory.mktemp("frf") / "m.csv", points=60)


def _copy(src: Path, dst: Path) -> tuple[Path, bytes]:
    shutil.copyfile(src, dst)
    return dst, dst.read_bytes()


# -- item 1: the output is never an input -------------------------------------------------------


@pytest.mark.parametrize("spelling", ["same", "relative", "symlink"])
def test_identify_refuses_to_write_over_a_measurement(frf, tmp_path, capsys, monkeypatch, spelling):
    m, before = _copy(frf, tmp_path / "m.csv")
    out: str | Path = m
    if spelling == "relative":
        monkeypatch.chdir(tmp_path)
        (tmp_path / "sub").mkdir()
        out = "sub/../m.csv"
    elif spelling == "symlink":
        out = tmp_path / "link.csv"
        out.symlink_to(m)
    r = run_cli(capsys, "identify", m, "--masses", "2", "-o", out)
    assert r.returncode == 2
    assert "-o" in r.stderr and "MEASUREMENT" in r.stderr and str(m) in r.stderr
    assert m.read_bytes() == before


def test_identify_refuses_the_second_measurement_too_even_with_force(frf, tmp_path, capsys):
    a, _ = _copy(frf, tmp_path / "a.csv")
    b, before = _copy(frf, tmp_path / "b.csv")
    r = run_cli(capsys, "identify", a, b, "--masses", "2", "--force", "-o", b)
    assert r.returncode == 2 and str(b) in r.stderr and b.read_bytes() == before


def test_identify_over_the_base_profile_needs_force(frf, tmp_path, capsys):
    base, before = _copy(HBFD, tmp_path / "p.json")
    r = run_cli(capsys, "identify", frf, "--masses", "4", "--sample-time", "0.001", "--base", base, "-o", base)
    assert r.returncode == 2 and "--base" in r.stderr and "--force" in r.stderr
    assert base.read_bytes() == before
    r = run_cli(capsys, "identify", frf, "--masses", "4", "--sample-time", "0.001", "--base", base, "-o", base,
                "--force")
    assert r.returncode == 0, r.stderr
    assert "identification" in json.loads(base.read_text())


@pytest.mark.parametrize("command", [["report"], ["export-plot", "--plot", "bound"]])
def test_report_and_export_refuse_to_write_over_the_profile(tmp_path, capsys, command):
    # a profile named .pdf/.csv: the extension check passes, the clash check must refuse
    out = tmp_path / ("p.pdf" if command[0] == "report" else "p.csv")
    profile, before = _copy(HBFD, out)
    r = run_cli(capsys, command[0], profile, *command[1:], "-o", out)
    assert r.returncode == 2 and "PROFILE" in r.stderr and str(profile) in r.stderr
    assert profile.read_bytes() == before


def test_export_refuses_to_write_over_the_trials_file(tmp_path, capsys, monkeypatch):
    raw = json.loads(HBFD.read_text())
    raw["controller"] = {"trials": "trials.csv"}
    profile = tmp_path / "p.json"
    profile.write_text(json.dumps(raw))
    trials = tmp_path / "trials.csv"
    trials.write_text("b,k,stable\n1,100,yes\n")
    before = trials.read_bytes()
    monkeypatch.chdir(tmp_path.parent)  # the trials path is relative to the profile's folder, not the cwd
    r = run_cli(capsys, "export-plot", profile, "--plot", "bound", "-o", trials)
    assert r.returncode == 2 and "$.controller.trials" in r.stderr, r.stderr
    assert trials.read_bytes() == before
