"""Issue 22, "Files and inputs": a command never writes over one of its input files (exit 2, the
input unchanged byte for byte), and its error messages print plain numbers, file lines and the
option at fault."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
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


def test_identify_never_overwrites_the_default_base_without_force(frf, tmp_path, capsys):
    before = HBFD.read_bytes()
    r = run_cli(capsys, "identify", frf, "--masses", "2", "-o", HBFD)
    assert r.returncode == 2 and "--base (default)" in r.stderr and "--force" in r.stderr
    assert HBFD.read_bytes() == before


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


# -- item 2: the messages -----------------------------------------------------------------------


def test_non_increasing_frequency_prints_plain_numbers(frf, tmp_path, capsys):
    lines = frf.read_text().splitlines()
    first = lines[1].split(",")
    lines[2] = ",".join([first[0], *lines[2].split(",")[1:]])  # data row 2 repeats row 1's frequency
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines) + "\n")
    r = run_cli(capsys, "identify", bad, "--masses", "2", "-o", tmp_path / "x.json")
    assert r.returncode == 1 and "line 3" in r.stderr
    assert f"({first[0]} after {first[0]})" in r.stderr and "np." not in r.stderr


def test_validation_error_prints_a_numpy_scalar_as_a_plain_number():
    from analysis.errors import ValidationError

    assert str(ValidationError("masses", "> 0", np.float64(0.45), 1)) == (
        "masses[1] = 0.45 is invalid: allowed range is > 0")


def test_a_5000_digit_integer_in_a_profile_names_its_line(tmp_path, capsys):
    text = HBFD.read_text()
    lines = text.splitlines()
    at = next(i for i, line in enumerate(lines) if '"name"' in line)
    lines.insert(at, '  "comment": ' + "7" * 5000 + ",")
    profile = tmp_path / "long.json"
    profile.write_text("\n".join(lines) + "\n")
    r = run_cli(capsys, "analyze", profile)
    assert r.returncode == 1
    assert f"line {at + 1}, column 14" in r.stderr and "number too long (5000 digits)" in r.stderr
    assert "set_int_max_str_digits" not in r.stderr and len(r.stderr) < 500


def test_a_5000_digit_number_in_a_csv_names_its_line_briefly(frf, tmp_path, capsys):
    lines = frf.read_text().splitlines()
    cells = lines[4].split(",")
    lines[4] = ",".join([cells[0], "9" * 5000, cells[2]])
    bad = tmp_path / "long.csv"
    bad.write_text("\n".join(lines) + "\n")
    r = run_cli(capsys, "identify", bad, "--masses", "2", "-o", tmp_path / "x.json")
    assert r.returncode == 1
    assert "line 5" in r.stderr and "'real'" in r.stderr and "number too long" in r.stderr
    assert "(5000 characters)" in r.stderr and len(r.stderr) < 500


def _time_series(path: Path, glitch: int | None, comments: int = 2) -> Path:
    t = np.arange(256) * 1e-3
    if glitch is not None:
        t[glitch:] += 0.4e-3  # one step of 1.4 ms: still increasing, not uniform
    rng = np.random.default_rng(0)
    f = rng.standard_normal(t.size)
    x = np.convolve(f, np.exp(-np.arange(20) / 5.0), "same") * 1e-3
    rows = [f"{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), f.tolist(), x.tolist())]
    path.write_text("# recorded\n" * comments + "time_s,force_n,position_m\n" + "\n".join(rows) + "\n")
    return path


def test_a_non_uniform_time_step_names_the_file_line(tmp_path, capsys):
    glitch = 200  # 0-based sample; the header is on line 3 (two comment lines), sample 0 on line 4
    bad = _time_series(tmp_path / "ts.csv", glitch)
    r = run_cli(capsys, "identify", bad, "--masses", "1", "-o", tmp_path / "x.json")
    assert r.returncode == 1
    assert f"line {glitch + 4}" in r.stderr and "'time_s'" in r.stderr and "uniform" in r.stderr
    assert "sample" not in r.stderr


@pytest.mark.parametrize("value", ["0", "-0.001", "nan", "inf"])
def test_sample_time_out_of_range_is_a_usage_error(frf, tmp_path, capsys, value):
    r = run_cli(capsys, "identify", frf, "--masses", "2", "--sample-time", value, "-o", tmp_path / "x.json")
    assert r.returncode == 2 and "--sample-time" in r.stderr and "> 0" in r.stderr
    assert str(frf) not in r.stderr and not (tmp_path / "x.json").exists()


def test_negative_delay_is_a_usage_error(frf, tmp_path, capsys):
    r = run_cli(capsys, "identify", frf, "--masses", "2", "--sample-time", "0.001", "--delay", "-1",
                "-o", tmp_path / "x.json")
    assert r.returncode == 2 and "--delay" in r.stderr


def test_parse_fixed_accepts_what_fit_chain_accepts():
    from analysis.study.identify import parse_fixed

    assert parse_fixed(["ground_dampings[2]=0", "dampings[0]=0", "masses[1]=0.3"]) == {
        "ground_dampings[2]": 0.0, "dampings[0]": 0.0, "masses[1]": 0.3}
    for item in ("masses[0]=0", "stiffnesses[0]=0", "dampings[0]=-1", "ground_dampings[0]=nan"):
        with pytest.raises(ValueError, match=r"--fix"):
            parse_fixed([item])


def test_fix_a_ground_damping_at_zero(tmp_path, capsys):
    frf = write_frf(tmp_path / "m.csv")
    r = run_cli(capsys, "identify", frf, "--masses", "4", "--sample-time", "0.001", "--fix", "ground_dampings[2]=0",
                "--json", "-o", tmp_path / "x.json")
    assert r.returncode == 0, r.stderr
    rows = {row["key"]: row for row in json.loads(r.stdout)["parameters"]}
    assert rows["ground_dampings[2]"]["fixed"] is True and rows["ground_dampings[2]"]["value"] == 0.0


def test_identify_help_prints_a_single_percent_sign(capsys):
    r = run_cli(capsys, "identify", "--help")
    assert r.returncode == 0 and "95 % intervals" in " ".join(r.stdout.split()) and "%%" not in r.stdout


def test_analyze_prints_fitted_masses_rounded(tmp_path, capsys):
    raw = json.loads(HBFD.read_text())
    raw["device"]["masses"][0] = 0.08005979194545117
    profile = tmp_path / "fitted.json"
    profile.write_text(json.dumps(raw))
    r = run_cli(capsys, "analyze", profile)
    assert r.returncode == 0, r.stderr
    assert "masses [0.0800598, 2.3, 2, 0.5] kg" in r.stdout and "0.08005979194545117" not in r.stdout
