"""``zwidth export-plot --plot zwidth-region|filter-optimum`` and the report's Z-width part (issue 15)."""

from __future__ import annotations

import csv
import html
import math
from pathlib import Path

import numpy as np
import pytest

from analysis.profiles import ControllerSection, bundled_profiles, load_profile, save_profile
from analysis.sampled import VelocityFilter, ZWidthRegion, load_trials, score_trials
from analysis import study
from cli_runner import run_cli

F = VelocityFilter("lowpass1", 2 * math.pi * 60)


@pytest.fixture(scope="module")
def profile_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("zw")
    trials = d / "trials.csv"
    trials.write_text("b,k,stable\n1,5000,1\n1,900000,1\n10,8000,0\n30,20000,1\n")
    p = load_profile(bundled_profiles()["hbfd"])
    p = p.replace(controller=ControllerSection(F, (0.5, 50.0), 12, str(trials)))
    save_profile(p, d / "p.json")
    return d / "p.json"


@pytest.fixture(scope="module")
def region(profile_file) -> ZWidthRegion:
    """The analysis's region of the profile (the reference the export and the report are compared with)."""
    return study.zwidth_region(load_profile(profile_file))


def _csv(path: Path) -> tuple[list[str], list[list[float]]]:
    rows = [r for r in csv.reader(path.read_text(encoding="utf-8").splitlines()) if r and not r[0].startswith("#")]
    return rows[0], [[float(x) if x else math.nan for x in r] for r in rows[1:]]


def test_export_region_csv_has_the_region_in_the_header_units(capfd, profile_file, tmp_path, region):
    out = tmp_path / "region.csv"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", "zwidth-region", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    header, rows = _csv(out)
    assert header[0].endswith(": B [N·s/m]") and header[1].endswith(": K [N/m]")
    assert header[0].startswith("exact largest stable K") and "first-order low-pass at 60 Hz" in header[0]
    assert any(h.startswith("two-port limit K (eq. 9)") for h in header)
    p, r = load_profile(profile_file), region
    data = np.array([row[:2] for row in rows[:12]])
    np.testing.assert_allclose(data[:, 0], r.b, rtol=1e-12)
    np.testing.assert_allclose(data[:, 1], r.k_max, rtol=1e-12)
    text = out.read_text(encoding="utf-8")
    wrong = score_trials(r, load_trials(p.controller.trials)).wrong_count
    assert f"{wrong} of 4 predicted wrong" in text


def test_export_filter_optimum_csv(capfd, profile_file, tmp_path):
    out = tmp_path / "opt.csv"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", "filter-optimum", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    header, rows = _csv(out)
    assert header[0].endswith(": cut-off f_c [Hz]") and header[1].endswith(": area ∫K dB [N²·s/m²]")
    o = study.filter_optimum(load_profile(profile_file))
    got = np.array([row[:2] for row in rows if not math.isnan(row[0])][:o.cutoffs.size])
    np.testing.assert_allclose(got[:, 0], o.cutoffs / (2 * math.pi), rtol=1e-12)
    np.testing.assert_allclose(got[:, 1], o.areas, rtol=1e-12)
    # the star is called the optimum only where it beats no filter (issue 22: never offer a worse design)
    star = "best cut-off (worse than no filter)" if o.best.is_backward else "optimum"
    assert header[2].startswith(star + ":") and rows[0][2] == pytest.approx(o.cutoff / (2 * math.pi), rel=1e-12)
    # the verdict (issue 22): the same sentence as the report's, against no filter and the profile's 60 Hz filter
    assert o.current == F and study.optimum_verdict(o) in out.read_text(encoding="utf-8")


def test_report_has_the_zwidth_section_only_with_the_controller_section(profile_file, region):
    from app.report.content import gather

    # the Z-width parts alone: the section is written as in the whole report (gather writes a section
    # when all its parts are asked), without the design chart
    zwidth_parts = ("zwidth_region", "zwidth_optimum")
    p, r = load_profile(profile_file), region
    c = gather(p, sampled=False, parts=zwidth_parts)
    assert c.numbers["zwidth.area_linear"][0] == r.area_linear
    assert c.numbers["zwidth.trials_wrong"][0] == score_trials(r, load_trials(p.controller.trials)).wrong_count
    assert any(s.title.startswith("Controller as built") for s in c.sections)
    # the verdict's sentence, its numbers typeset as the report's text prints them (a true minus)
    verdict = study.rich_numbers(html.escape(study.optimum_verdict(c.results["zwidth_optimum"])))
    assert any(verdict in par for s in c.sections for par in s.paragraphs)
    plain = gather(load_profile(bundled_profiles()["hbfd"]), sampled=False, parts=zwidth_parts)
    assert "zwidth.area_linear" not in plain.numbers and "zwidth_region" not in plain.results
