"""Command line: exit codes and error messages (the analysis summary itself is tested elsewhere).

The commands run in this process (:func:`cli_runner.run_cli`); the two tests at the end of the
first part start real processes, for what only a process shows (the entry points' exit codes,
going headless without display variables)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from analysis.profiles.schema import DISPLAYS
from analysis.study import DISPLAY_KINDS, display_kind
from app.cli import format_table
from cli_runner import console_script, run_cli, run_process

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
    r = run_cli(capsys, "analyze", bad_profile, *(["--json"] if as_json else []))
    assert r.returncode == 1
    assert r.stdout == ""
    assert (
        r.stderr
        == f"zwidth: error: {bad_profile}: $.device.masses[1] (mass 2): expected a number > 0 and finite, "
        "within the physical range [1e-06, 1000] (kg), got -1.0\n"
    )


def test_analyze_missing_file_exits_1(capsys, tmp_path):
    r = run_cli(capsys, "analyze", tmp_path / "nope.json")
    assert r.returncode == 1
    assert r.stderr.startswith("zwidth: error: ") and "nope.json: cannot read the file" in r.stderr


def test_open_bad_profile_exits_1_before_gui(capsys, bad_profile):
    r = run_cli(capsys, bad_profile)
    assert r.returncode == 1 and "$.device.masses[1]" in r.stderr
    assert run_cli(capsys, "gui", bad_profile).returncode == 1


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
    r = run_cli(capsys, *argv)
    assert r.returncode == 2
    assert "usage: zwidth" in r.stderr and "error:" in r.stderr


def test_help_exits_0(capsys):
    r = run_cli(capsys, "--help")
    assert r.returncode == 0 and "analyze" in r.stdout


def test_module_entry_point_exit_codes(bad_profile):
    """A real process: ``python -m app.cli`` and the console script exit with main()'s code."""
    proc = run_process("analyze", bad_profile, timeout=120)
    assert proc.returncode == 1
    assert proc.stderr.startswith("zwidth: error: ") and "Traceback" not in proc.stderr
    script = console_script()
    proc = run_process("analyze", timeout=120, script=script)  # the console script when installed
    assert proc.returncode == 2
    assert proc.stderr.startswith("usage: zwidth") and "Traceback" not in proc.stderr


def test_export_plot_headless_process(tmp_path):
    """A real process with no display variables goes offscreen by itself, quietly."""
    out = tmp_path / "p.png"
    proc = run_process("export-plot", HBFD, "--plot", "bound", "-o", out, "--width", "640", display=False,
                       timeout=180)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == "" and proc.stdout == ""
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and int.from_bytes(data[16:20], "big") == 640


def test_format_table():
    text = format_table({"device": {"n": 4, "masses": [0.2, 2.3]}, "z_width": float("inf"), "ok": True})
    assert text.splitlines() == [
        "device.n       4",
        "device.masses  [0.2, 2.3]",
        "z_width        inf",
        "ok             True",
    ]


# -- issue 6: every subcommand (in process), JSON shapes, export-plot, report -----------------------------

EOM = ROOT / "resources" / "profiles" / "eom.json"
RIGID = ROOT / "resources" / "profiles" / "rigid.json"


@pytest.mark.parametrize("sub", ["analyze", "design", "export-plot", "report", "bench", "gui"])
def test_every_subcommand_has_help(capsys, sub):
    r = run_cli(capsys, sub, "--help")
    assert r.returncode == 0 and r.stdout.startswith(f"usage: zwidth {sub}")


def test_analyze_json_shape(capsys):
    proc = run_cli(capsys, "analyze", str(HBFD), "--json")
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert set(d) == {"summary_version", "profile", "impedance", "admittance"}
    assert d["summary_version"] == 1
    assert set(d["profile"]) >= {"name", "display", "sample_time", "band", "masses", "stiffnesses", "dampings",
                                 "damping_ratios", "ground_dampings", "sensor_element"}
    verdict = {"stable", "stability_reserve", "binding_frequency", "worst_margin", "worst_frequency", "min_eta",
               "k_max", "b_min", "apparent_mass", "apparent_damping"}
    assert set(d["impedance"]) == verdict | {"coupling", "design"}
    assert set(d["impedance"]["design"]) == {"bc", "kc_max", "frequency", "margin", "beyond_limit", "beyond"}
    assert set(d["admittance"]) == verdict | {"coupling", "pd", "design"}
    assert set(d["admittance"]["design"]) == {"feasible_damping", "min_mass"}


@pytest.mark.parametrize("display", ["impedance", "admittance"])
def test_design_json_shape(capsys, display):
    proc = run_cli(capsys, "design", str(HBFD), "--display", display, "--json")
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert d["display"] == display and d["summary_version"] == 1
    if display_kind(display).is_impedance:
        assert set(d) == {"summary_version", "display", "design", "chart"}
        assert set(d["chart"]) == {"bc", "kc_max", "frequency"}
    else:
        assert set(d) == {"summary_version", "display", "pd", "feasible_damping", "min_mass", "chart"}
        assert set(d["chart"]) == {"mc", "low", "high"}


def test_design_text_and_bad_display(capsys):
    r = run_cli(capsys, "design", RIGID)
    assert r.returncode == 0 and "b_c" in r.stdout
    assert run_cli(capsys, "design", RIGID, "--display", "nonsense").returncode == 2
    # --display offers the profile loader's names (the parser loads no analysis.study): the display kinds
    assert DISPLAYS == tuple(DISPLAY_KINDS)


@pytest.mark.parametrize("plot,ext", [("bound", "png"), ("range", "svg"), ("chart", "csv"), ("map", "svg"),
                                      ("transparency", "csv"), ("reserve", "csv")])
def test_export_plot(capfd, tmp_path, plot, ext):
    profile = EOM if plot == "transparency" else HBFD
    out = tmp_path / f"p.{ext}"
    args = ["export-plot", str(profile), "--plot", plot, "-o", str(out)]
    if ext == "png":
        args += ["--width", "640"]
    proc = run_cli(capfd, *args)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == "" and proc.stdout == ""
    data = out.read_bytes()
    if ext == "png":
        assert data[:8] == b"\x89PNG\r\n\x1a\n"
        assert int.from_bytes(data[16:20], "big") == 640
    elif ext == "svg":
        assert b"<svg" in data
    else:
        assert data.splitlines()[0].count(b",") >= 1


def test_export_plot_errors(capsys, tmp_path, bad_profile):
    out = tmp_path / "x.png"
    proc = run_cli(capsys, "export-plot", str(bad_profile), "--plot", "bound", "-o", str(out))
    assert proc.returncode == 1 and "$.device.masses[1]" in proc.stderr and "Traceback" not in proc.stderr
    proc = run_cli(capsys, "export-plot", str(RIGID), "--plot", "map", "-o", str(out))
    assert proc.returncode == 1 and "$.simulation" in proc.stderr and str(RIGID) in proc.stderr
    assert run_cli(capsys, "export-plot", HBFD, "--plot", "bound", "-o", tmp_path / "x.gif").returncode == 2
    assert run_cli(capsys, "export-plot", HBFD, "--plot", "nope", "-o", out).returncode == 2
    assert run_cli(capsys, "export-plot", HBFD, "-o", out).returncode == 2
    assert not out.exists()


@pytest.mark.parametrize("ext", ["pdf", "html"])
def test_report_command(capfd, tmp_path, ext):
    out = tmp_path / f"report.{ext}"
    proc = run_cli(capfd, "report", str(RIGID), "-o", str(out), "--page-size", "letter")
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    head = out.read_bytes()[:16]
    assert head.startswith(b"%PDF") if ext == "pdf" else head.startswith(b"<!DOCTYPE html>")


@pytest.mark.parametrize("case", ["bad_value", "not_json", "missing"])
def test_report_bad_profile_clean_error(capsys, tmp_path, bad_profile, case):
    path = {"bad_value": bad_profile, "missing": tmp_path / "nope.json"}.get(case)
    if case == "not_json":
        path = tmp_path / "broken.json"
        path.write_text("{ not json")
    out = tmp_path / "r.pdf"
    proc = run_cli(capsys, "report", str(path), "-o", str(out))
    assert proc.returncode == 1
    assert proc.stderr.startswith("zwidth: error: ") and str(path) in proc.stderr
    assert "Traceback" not in proc.stderr and not out.exists()
    if case == "bad_value":
        assert "$.device.masses[1]" in proc.stderr


def test_report_usage_errors(capsys, tmp_path):
    assert run_cli(capsys, "report", HBFD, "-o", tmp_path / "r.docx").returncode == 2
    assert run_cli(capsys, "report", HBFD).returncode == 2
    assert run_cli(capsys, "report", HBFD, "-o", tmp_path / "r.pdf", "--page-size", "a3").returncode == 2
    assert not (tmp_path / "r.pdf").exists()


def test_bench_quick_usage(capsys):
    r = run_cli(capsys, "bench", "--bogus")
    assert r.returncode == 2 and "usage: zwidth" in r.stderr
