"""Identification end to end, as users run it (issue 23): a time-series chirp record written as a
lab writes it, through ``zwidth identify`` -> ``zwidth report`` -> ``zwidth analyze --json``; a mixed
actuator (time series) + gauge + clamped set named ``FILE:QUANTITY[:BOUNDARY]``; and a fit the
goodness-of-fit test rejects, whose warning reaches the profile's notes and the report.

Every command runs in process (:func:`cli_runner.run_cli`).  Promises only: the masses within 5 %
of the truth, the report written with the bins used and the verdict, the JSON parsed; never which
local optimum or floating-point path a run takes.  The Identify view on the same files is
``tests/app/test_identify_end_to_end_gui.py``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from analysis.identify import COHERENCE_THRESHOLD
from analysis.profiles import load_profile
from analysis.study import UNUSED_BINS_LABEL
from cli_runner import run_cli
from tests.identify_data import CHIRP_DEVICE
from tests.identify_files import write_chirp_csv, write_frf_csv

pytestmark = pytest.mark.numerics  # fits: run under the second OpenBLAS kernel too

TRUE_MASSES = np.array(CHIRP_DEVICE["masses"])


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    d = tmp_path_factory.mktemp("e2e")
    return {"chirp": write_chirp_csv(d / "chirp.csv"), "gauge": write_frf_csv(d / "gauge.csv", "gauge"),
            "clamped": write_frf_csv(d / "clamped.csv", "actuator", "clamped", seed=1)}


def _identify(capsys, out: Path, *args: str) -> dict:
    r = run_cli(capsys, "identify", *args, "-o", out, "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def _report_and_analyze(capsys, profile: Path) -> tuple[str, dict]:
    html = profile.with_suffix(".html")
    r = run_cli(capsys, "report", profile, "-o", html)
    assert r.returncode == 0, r.stderr
    assert html.stat().st_size > 0
    r = run_cli(capsys, "analyze", profile, "--json")
    assert r.returncode == 0, r.stderr
    return html.read_text(encoding="utf-8"), json.loads(r.stdout)


def _masses(data: dict) -> np.ndarray:
    return np.array([p["value"] for p in data["parameters"] if p["key"].startswith("masses[")])


def test_chirp_time_series_through_identify_report_and_analyze(files, tmp_path, capsys):
    out = tmp_path / "chirp.json"
    data = _identify(capsys, out, str(files["chirp"]), "--masses", "3")
    assert data["measurements"][0]["time_series"] and data["measurements"][0]["sample_time_from"] == "time step"
    np.testing.assert_allclose(_masses(data), TRUE_MASSES, rtol=0.05)
    profile = load_profile(out)
    np.testing.assert_allclose(profile.device.masses, TRUE_MASSES, rtol=0.05)
    # the notes written with the fit: the bins used and why, and the goodness verdict
    assert "Bins: chirp.csv: " in profile.notes and "bins used (by coherence and input power)" in profile.notes
    assert "with input power below" in profile.notes  # nothing was excited above 300 Hz
    assert "Goodness of fit: the model explains the data" in profile.notes
    assert str(files["chirp"].parent) not in profile.notes  # file names, not the folder
    page, summary = _report_and_analyze(capsys, out)
    assert "Bins used" in page and "chirp.csv: " in page
    assert "Goodness of fit" in page and "not trustworthy" not in page
    assert ">" + UNUSED_BINS_LABEL.replace("<", "&lt;") + "<" in page  # the greyed bins' legend, whole
    np.testing.assert_allclose(summary["profile"]["masses"], profile.device.masses, rtol=1e-12)


def test_mixed_actuator_gauge_clamped_set_end_to_end(files, tmp_path, capsys):
    out = tmp_path / "mixed.json"
    data = _identify(capsys, out, str(files["chirp"]), f"{files['gauge']}:gauge",
                     f"{files['clamped']}:actuator:clamped", "--masses", "3", "--sample-time", "0.001")
    kinds = [(m["quantity"], m["boundary"]) for m in data["measurements"]]
    assert kinds == [("actuator", "free"), ("gauge", "free"), ("actuator", "clamped")]
    np.testing.assert_allclose(_masses(data), TRUE_MASSES, rtol=0.05)
    assert not any("clamped-handle test" in s for s in data["suggestions"].values())  # it was given
    profile = load_profile(out)
    assert [m.quantity for m in profile.identification.measurements] == ["actuator", "gauge", "actuator"]
    assert "gauge.csv: all 300 bins used" in profile.notes
    page, summary = _report_and_analyze(capsys, out)
    assert "gauge.csv: all 300 bins used" in page and "chirp.csv: " in page
    np.testing.assert_allclose(summary["profile"]["masses"], TRUE_MASSES, rtol=0.05)


def test_a_fit_the_goodness_test_rejects_is_flagged_in_notes_and_report(files, tmp_path, capsys):
    out = tmp_path / "one.json"
    data = _identify(capsys, out, str(files["chirp"]), "--masses", "1")  # one mass for a 3-mass device
    assert data["warnings"][0].startswith("the model does not explain the data")
    profile = load_profile(out)
    assert "Warning: the model does not explain the data" in profile.notes
    assert "Goodness of fit: the model explains" not in profile.notes
    page, _ = _report_and_analyze(capsys, out)
    assert "interval (<b class='bad'>not trustworthy</b>)" in page
    assert "Warning: the model does not explain the data" in page
    assert "95&nbsp;% interval [" not in page  # no interval offered as a 95 % one


def test_the_greyed_bins_legend_names_the_analysis_threshold():
    assert f"coherence < {COHERENCE_THRESHOLD:g}" in UNUSED_BINS_LABEL
