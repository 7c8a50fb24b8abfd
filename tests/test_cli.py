"""Command line: exit codes and error messages (the analysis summary itself is tested elsewhere)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from analysis.study import display_kind
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
        == f"zwidth: error: {bad_profile}: $.device.masses[1] (mass 2): expected a number > 0 and finite, "
        "within the physical range [1e-06, 1000] (kg), got -1.0\n"
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


# -- issue 6: every subcommand through the module entry point, JSON shapes, export-plot, report ------------

EOM = ROOT / "resources" / "profiles" / "eom.json"
RIGID = ROOT / "resources" / "profiles" / "rigid.json"


def _run(*argv: str, timeout: float = 180) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("QT_QPA_PLATFORM", None)  # the command must go headless by itself
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    return subprocess.run([sys.executable, "-m", "app.cli", *argv], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=timeout)


@pytest.mark.parametrize("sub", ["analyze", "design", "export-plot", "report", "bench", "gui"])
def test_every_subcommand_has_help(capsys, sub):
    assert main([sub, "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"usage: zwidth {sub}")


def test_analyze_json_shape():
    proc = _run("analyze", str(HBFD), "--json")
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert set(d) == {"summary_version", "profile", "impedance", "admittance"}
    assert d["summary_version"] == 1
    assert set(d["profile"]) >= {"name", "display", "sample_time", "band", "masses", "stiffnesses", "dampings",
                                 "damping_ratios", "ground_dampings", "sensor_element"}
    verdict = {"stable", "stability_reserve", "binding_frequency", "worst_margin", "worst_frequency", "min_eta",
               "k_max", "b_min", "apparent_mass", "apparent_damping"}
    assert set(d["impedance"]) == verdict | {"coupling", "design"}
    assert set(d["impedance"]["design"]) == {"bc", "kc_max", "frequency", "margin"}
    assert set(d["admittance"]) == verdict | {"coupling", "pd", "design"}
    assert set(d["admittance"]["design"]) == {"feasible_damping", "min_mass"}


@pytest.mark.parametrize("display", ["impedance", "admittance"])
def test_design_json_shape(display):
    proc = _run("design", str(HBFD), "--display", display, "--json")
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert d["display"] == display and d["summary_version"] == 1
    if display_kind(display).is_impedance:
        assert set(d) == {"summary_version", "display", "design", "chart"}
        assert set(d["chart"]) == {"bc", "kc_max", "frequency"}
    else:
        assert set(d) == {"summary_version", "display", "pd", "feasible_damping", "min_mass", "chart"}
        assert set(d["chart"]) == {"mc", "low", "high"}


def test_design_text_and_bad_display():
    assert _run("design", str(RIGID)).returncode == 0
    assert _run("design", str(RIGID), "--display", "nonsense").returncode == 2


@pytest.mark.parametrize("plot,ext", [("bound", "png"), ("range", "svg"), ("chart", "csv"), ("map", "svg"),
                                      ("transparency", "csv"), ("reserve", "csv")])
def test_export_plot(tmp_path, plot, ext):
    profile = EOM if plot == "transparency" else HBFD
    out = tmp_path / f"p.{ext}"
    args = ["export-plot", str(profile), "--plot", plot, "-o", str(out)]
    if ext == "png":
        args += ["--width", "640"]
    proc = _run(*args)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    data = out.read_bytes()
    if ext == "png":
        assert data[:8] == b"\x89PNG\r\n\x1a\n"
        assert int.from_bytes(data[16:20], "big") == 640
    elif ext == "svg":
        assert b"<svg" in data
    else:
        assert data.splitlines()[0].count(b",") >= 1


def test_export_plot_errors(tmp_path, bad_profile):
    out = tmp_path / "x.png"
    proc = _run("export-plot", str(bad_profile), "--plot", "bound", "-o", str(out))
    assert proc.returncode == 1 and "$.device.masses[1]" in proc.stderr and "Traceback" not in proc.stderr
    proc = _run("export-plot", str(RIGID), "--plot", "map", "-o", str(out))
    assert proc.returncode == 1 and "$.simulation" in proc.stderr and str(RIGID) in proc.stderr
    assert _run("export-plot", str(HBFD), "--plot", "bound", "-o", str(tmp_path / "x.gif")).returncode == 2
    assert _run("export-plot", str(HBFD), "--plot", "nope", "-o", str(out)).returncode == 2
    assert _run("export-plot", str(HBFD), "-o", str(out)).returncode == 2
    assert not out.exists()


@pytest.mark.parametrize("ext", ["pdf", "html"])
def test_report_command(tmp_path, ext):
    out = tmp_path / f"report.{ext}"
    proc = _run("report", str(RIGID), "-o", str(out), "--page-size", "letter")
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    head = out.read_bytes()[:16]
    assert head.startswith(b"%PDF") if ext == "pdf" else head.startswith(b"<!DOCTYPE html>")


@pytest.mark.parametrize("case", ["bad_value", "not_json", "missing"])
def test_report_bad_profile_clean_error(tmp_path, bad_profile, case):
    path = {"bad_value": bad_profile, "missing": tmp_path / "nope.json"}.get(case)
    if case == "not_json":
        path = tmp_path / "broken.json"
        path.write_text("{ not json")
    out = tmp_path / "r.pdf"
    proc = _run("report", str(path), "-o", str(out))
    assert proc.returncode == 1
    assert proc.stderr.startswith("zwidth: error: ") and str(path) in proc.stderr
    assert "Traceback" not in proc.stderr and not out.exists()
    if case == "bad_value":
        assert "$.device.masses[1]" in proc.stderr


def test_report_usage_errors(tmp_path):
    assert _run("report", str(HBFD), "-o", str(tmp_path / "r.docx")).returncode == 2
    assert _run("report", str(HBFD)).returncode == 2
    assert _run("report", str(HBFD), "-o", str(tmp_path / "r.pdf"), "--page-size", "a3").returncode == 2


def test_bench_quick_usage():
    assert _run("bench", "--bogus").returncode == 2
