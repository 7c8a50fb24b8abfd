"""``zwidth export-plot --plot space|m-width`` and the report's renderable part (issue 24)."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from PySide6.QtGui import QImage

from analysis.profiles import RenderableSection, bundled_profiles, load_profile, save_profile
from analysis.study import renderable_study
from cli_runner import run_cli

SECTION = RenderableSection(mass_points=7, damping_points=9, qualities=("stable", "passive"), virtual_mass=0.001)


@pytest.fixture(scope="module")
def profile_file(tmp_path_factory):
    d = tmp_path_factory.mktemp("rs")
    save_profile(load_profile(bundled_profiles()["rigid"]).replace(renderable=SECTION), d / "p.json")
    return d / "p.json"


@pytest.mark.parametrize("plot", ["space", "m-width"])
def test_export_plot_of_a_slice_writes_a_png(capfd, profile_file, tmp_path, plot):
    out = tmp_path / f"{plot}.png"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", plot, "-o", str(out), "--width", "640")
    assert proc.returncode == 0, proc.stderr
    image = QImage(str(out))
    assert image.width() == 640 and image.height() > 100
    assert len({image.pixel(x, y) for y in range(0, image.height(), 9) for x in range(0, image.width(), 9)}) > 8


def test_export_space_csv_is_the_studys_k_max(capfd, profile_file, tmp_path):
    out = tmp_path / "space.csv"
    proc = run_cli(capfd, "export-plot", str(profile_file), "--plot", "space", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    rows = [r for r in csv.reader(out.read_text(encoding="utf-8").splitlines()) if r and not r[0].startswith("#")]
    s = renderable_study(load_profile(profile_file)).space
    data = np.array([[float(x) if x else math.nan for x in r] for r in rows[1:]])
    np.testing.assert_allclose(data[:, 0], s.damping, rtol=1e-12)
    np.testing.assert_allclose(data[:, 1], s.k_max[0], rtol=1e-12)


def test_without_the_section_the_plot_uses_the_defaults(capfd, tmp_path):
    out = tmp_path / "w.png"
    proc = run_cli(capfd, "export-plot", str(bundled_profiles()["rigid"]), "--plot", "m-width", "-o", str(out))
    assert proc.returncode == 0, proc.stderr and out.exists()


def test_report_has_the_m_width_only_with_the_section(profile_file):
    from app.report.content import gather

    p = load_profile(profile_file)
    # the renderable part alone: its section is written as in the whole report (all its parts asked)
    c = gather(p, sampled=False, parts=("renderable",))
    w = renderable_study(p).width
    assert c.numbers["renderable.m_min"][0] == w.m_min and c.numbers["renderable.m_max"][0] == w.m_max
    assert c.numbers["renderable.m_max.passive"][0] == w.by_quality["passive"][1]
    section = next(s for s in c.sections if s.title == "Renderable space and M-width")
    assert any(r.value == c.printed("renderable.m_width") for r in section.rows)
    plain = gather(load_profile(bundled_profiles()["rigid"]), sampled=False, parts=("renderable",))
    assert "renderable.m_min" not in plain.numbers and "renderable_study" not in plain.results


def test_report_html_contains_the_m_width(profile_file, tmp_path):
    from app.report import build_report
    from app.report.content import gather

    out = tmp_path / "r.html"
    build_report(load_profile(profile_file), out, sampled=False)
    text = out.read_text(encoding="utf-8")
    c = gather(load_profile(profile_file), sampled=False, parts=("renderable",))
    assert "Renderable space and M-width" in text and c.printed("renderable.m_max") in text
