"""``zwidth identify``: noise-free HBFD measurement files in, the device recovered to 1e-6 and a
profile that loads out; bad files exit 1 with the file, row and column (issue 14)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from analysis.identify import device_response
from analysis.profiles import load_profile
from analysis.resources import resource_path
from cli_runner import run_cli

HBFD = resource_path("profiles", "hbfd.json")


def write_frf(path: Path, quantity: str = "actuator", boundary: str = "free", points: int = 400) -> Path:
    """An FRF CSV of the HBFD, ZOH-sampled at 1 kHz, 1 rad/s .. 0.95 Nyquist, noise-free."""
    d = load_profile(HBFD).device
    w = np.logspace(0, np.log10(0.95 * np.pi / d.sample_time), points)
    h = device_response(d, w, quantity, boundary, d.sample_time, 0)
    rows = [f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(w, h)]
    path.write_text("frequency_rad_s,real,imag\n" + "\n".join(rows) + "\n")
    return path


@pytest.fixture(scope="module")
def frf(tmp_path_factory) -> Path:
    return write_frf(tmp_path_factory.mktemp("frf") / "actuator.csv")


def test_identify_recovers_the_hbfd_and_writes_a_profile(frf, tmp_path, capsys):
    out = tmp_path / "mine.json"
    code, text, err = run_cli(capsys, "identify", frf, "--masses", "4", "--sample-time", "0.001", "-o", out)
    assert code == 0, err
    truth = load_profile(HBFD).device
    p = load_profile(out)
    assert p.name == "mine"
    np.testing.assert_allclose(p.device.masses, truth.masses, rtol=1e-6)
    np.testing.assert_allclose(p.device.stiffnesses, truth.stiffnesses, rtol=1e-6)
    np.testing.assert_allclose(p.device.dampings, truth.dampings, rtol=1e-6)
    assert p.device.ground_dampings[3] == pytest.approx(5.0, rel=1e-6)
    assert json.loads(out.read_text())["schema_version"] == 7
    sec = p.identification
    assert len(sec.intervals) == 11 and len(sec.measurements) == 1
    lo, hi = sec.intervals["masses[1]"]
    assert lo <= 2.3 * (1 + 1e-6) and hi >= 2.3 * (1 - 1e-6) and hi - lo < 1e-6
    assert sec.measurements[0].source == "actuator.csv" and sec.measurements[0].frequency.size == 400
    assert "masses[1]" in text and "2.3 " in text and f"wrote {out}" in text


def test_identify_json_with_fixed_mass_and_orders(frf, tmp_path, capsys):
    out = tmp_path / "fixed.json"
    r = run_cli(capsys, "identify", frf, "--masses", "4", "--sample-time", "0.001", "--fix", "ground_dampings[3]=5",
                "--orders", "--json", "-o", out)
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    rows = {r["key"]: r for r in data["parameters"]}
    assert rows["ground_dampings[3]"]["fixed"] is True and rows["ground_dampings[3]"]["value"] == 5.0
    assert rows["stiffnesses[0]"]["value"] == pytest.approx(130000.0, rel=1e-6)
    assert [o["n"] for o in data["orders"]] == [1, 2, 3, 4]
    # ground_dampings[3] lies outside a chain of 1..3 masses: those orders are reported as "nan"
    assert [o["bic"] for o in data["orders"][:3]] == ["nan"] * 3
    assert data["orders"][3]["bic"] == data["bic"] < -50000
    assert "ground_dampings[3]" not in load_profile(out).identification.intervals  # a fixed parameter has no interval


def test_bad_csv_names_file_row_and_column(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    lines = write_frf(tmp_path / "ok.csv", points=20).read_text().splitlines()
    lines[5] = lines[5].split(",")[0] + ",nan," + lines[5].split(",")[2]
    bad.write_text("\n".join(lines) + "\n")
    out = tmp_path / "never.json"
    code, _, err = run_cli(capsys, "identify", bad, "--masses", "2", "-o", out)
    assert code == 1 and not out.exists()
    assert str(bad) in err and "line 6" in err and "'real'" in err


@pytest.mark.parametrize(("args", "text"), [
    (["--fix", "masses[0]"], "KEY=VALUE"),
    (["--fix", "masses[0]=-1"], "value > 0"),
    (["--masses", "0"], "--masses must be >= 1"),
])
def test_usage_errors_exit_2(frf, tmp_path, capsys, args, text):
    argv = ["identify", str(frf), "--masses", "4", *args, "-o", str(tmp_path / "x.json")]
    r = run_cli(capsys, *argv)
    assert r.returncode == 2 and text in r.stderr


def test_unknown_fixed_key_exits_1(frf, tmp_path, capsys):
    r = run_cli(capsys, "identify", frf, "--masses", "2", "--fix", "masses[7]=1", "-o", tmp_path / "x.json")
    assert r.returncode == 1 and "masses[7]" in r.stderr
