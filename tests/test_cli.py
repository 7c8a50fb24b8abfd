"""Command line: exit codes and error messages (the analysis summary itself is tested elsewhere)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from app.cli import format_table, main

ROOT = Path(__file__).resolve().parents[1]
HBFD = ROOT / "resources" / "profiles" / "hbfd.json"


@pytest.fixture
def bad_profile(tmp_path) -> Path:
    d = json.loads(HBFD.read_text())
    d["device"]["masses"][1] = -1.0
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(d))
    return path


@pytest.mark.parametrize("as_json", [False, True])
def test_analyze_bad_profile_exits_1(capsys, bad_profile, as_json):
    code = main(["analyze", str(bad_profile), *(["--json"] if as_json else [])])
    out, err = capsys.readouterr()
    assert code == 1
    assert out == ""
    assert (
        err
        == f"zwidth: error: {bad_profile}: $.device.masses[1]: expected a number > 0 and finite (kg), got -1.0\n"
    )


def test_analyze_missing_file_exits_1(capsys, tmp_path):
    assert main(["analyze", str(tmp_path / "nope.json")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("zwidth: error: ") and "nope.json: cannot read the file" in err


def test_open_bad_profile_exits_1_before_gui(capsys, bad_profile):
    assert main([str(bad_profile)]) == 1
    assert "$.device.masses[1]" in capsys.readouterr().err
    assert main(["gui", str(bad_profile)]) == 1


@pytest.mark.parametrize(
    "argv",
    [
        ["analyze"],
        ["frobnicate"],
        ["analyze", str(HBFD), "--bogus"],
        [str(HBFD), "extra"],
        ["--no-such-option"],
    ],
)
def test_usage_errors_exit_2(capsys, argv):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "usage: zwidth" in err and "error:" in err


def test_help_exits_0(capsys):
    assert main(["--help"]) == 0
    assert "analyze" in capsys.readouterr().out


def test_module_entry_point_exit_codes(bad_profile):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.run(
        [sys.executable, "-m", "app.cli", "analyze", str(bad_profile)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 1
    assert proc.stderr.startswith("zwidth: error: ") and "Traceback" not in proc.stderr
    proc = subprocess.run(
        [sys.executable, "-m", "app.cli", "analyze"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 2


def test_format_table():
    text = format_table({"device": {"n": 4, "masses": [0.2, 2.3]}, "z_width": float("inf"), "ok": True})
    assert text.splitlines() == [
        "device.n       4",
        "device.masses  [0.2, 2.3]",
        "z_width        inf",
        "ok             True",
    ]
