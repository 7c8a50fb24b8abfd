"""A bad trials file fails ``zwidth export-plot --plot zwidth-region`` and ``zwidth report`` (issue 22:
they used to exit 0 without a word), and a relative ``trials`` path is relative to the profile's folder."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from analysis import study
from analysis.profiles import ControllerSection, bundled_profiles, load_profile, save_profile
from analysis.sampled import VelocityFilter, load_trials, score_trials
from cli_runner import run_cli
from trials_files import BAD_TRIALS, GOOD, BadFile

F = VelocityFilter("lowpass1", 2 * math.pi * 60)


def _profile(folder: Path, trials: str) -> Path:
    p = load_profile(bundled_profiles()["hbfd"])
    p = p.replace(controller=ControllerSection(F, (0.5, 50.0), 12, trials))
    save_profile(p, folder / "p.json")
    return folder / "p.json"


@pytest.mark.parametrize("command", ["export-plot", "report"])
@pytest.mark.parametrize("case", BAD_TRIALS, ids=[c.name for c in BAD_TRIALS])
def test_a_bad_trials_file_fails_the_command_naming_file_line_and_column(capfd, tmp_path, monkeypatch,
                                                                          case: BadFile, command: str):
    folder = tmp_path / "bench"
    folder.mkdir()
    case.write(folder / "trials.csv")
    profile = _profile(folder, "trials.csv")  # relative: beside the profile
    monkeypatch.chdir(tmp_path)  # run from another folder
    out = tmp_path / ("region.csv" if command == "export-plot" else "report.html")
    args = ("--plot", "zwidth-region") if command == "export-plot" else ()
    proc = run_cli(capfd, command, profile, *args, "-o", out)
    assert proc.returncode == 1, proc.stderr
    assert proc.stdout == "" and not out.exists()
    err = proc.stderr
    assert err.startswith("zwidth: error: ") and str(profile) in err and "$.controller.trials" in err
    assert str(folder / "trials.csv") in err and case.words in err
    assert "np." not in err  # plain numbers, never numpy reprs
    if case.line is not None:
        assert f"line {case.line}" in err
    if case.column is not None:
        assert f"column {case.column!r}" in err


def test_relative_trials_beside_the_profile_are_scored_from_another_folder(capfd, tmp_path, monkeypatch):
    folder = tmp_path / "bench"
    folder.mkdir()
    trials = "b,k,stable\n1,5000,1\n1,900000,1\n10,8000,0\n30,20000,1\n"
    (folder / "trials.csv").write_text(trials)
    profile = _profile(folder, "trials.csv")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "trials.csv").write_text(GOOD)  # a different file of that name in the working directory
    monkeypatch.chdir(elsewhere)
    out = tmp_path / "region.csv"
    proc = run_cli(capfd, "export-plot", profile, "--plot", "zwidth-region", "-o", out)
    assert proc.returncode == 0, proc.stderr
    region = study.zwidth_region(load_profile(profile))
    wrong = score_trials(region, load_trials(folder / "trials.csv")).wrong_count
    assert f"{wrong} of 4 predicted wrong" in out.read_text()  # the 4 trials beside the profile, not GOOD's 2

