"""The report's identification part and ``export-plot --plot identify`` (issue 14): the fit figure,
the parameter table with intervals, and the robust designs of the seed's case (HBFD,
ground_dampings[3] in [1.2, 5], b_c = 100: robust k_c 49.15 kN/m against the nominal 117.1 kN/m)."""

from __future__ import annotations

import csv

import numpy as np
import pypdf
import PySide6  # noqa: F401 - the reports need Qt: fail loudly, never skip
import pytest

from analysis.identify import device_response
from analysis.profiles import load_profile, save_profile
from analysis.profiles.identification import IdentificationSection, MeasurementData
from analysis.resources import resource_path
from app.cli import main


@pytest.fixture(scope="module")
def app():
    from app.report.figures import ensure_app

    return ensure_app()


@pytest.fixture(scope="module")
def seed_profile(tmp_path_factory):
    """The HBFD with the seed's interval on b4 and one embedded actuator measurement, saved."""
    p = load_profile(resource_path("profiles", "hbfd.json"))
    d = p.device
    w = np.logspace(0, np.log10(0.95 * np.pi / d.sample_time), 120)
    m = MeasurementData(w, device_response(d, w, "actuator", "free", d.sample_time), "actuator", "free",
                        d.sample_time, 0, None, "actuator.csv")
    p = p.replace(identification=IdentificationSection({"ground_dampings[3]": (1.2, 5.0)}, (m,)))
    path = tmp_path_factory.mktemp("seed") / "seed.json"
    save_profile(p, path)
    return path


def test_report_numbers_of_the_seed_case(app, seed_profile):
    from app.report.content import gather

    c = gather(load_profile(seed_profile), sampled=False)
    titles = [s.title for s in c.sections]
    assert "Identification" in titles and "Designs that hold for the whole parameter box" in titles
    kc, text = c.numbers["robust.kc"]
    assert kc == pytest.approx(49.15e3, rel=1e-3) and text == "49149"
    assert c.numbers["robust.nominal_kc"][0] == pytest.approx(117.1e3, rel=1e-3)
    assert c.numbers["identify.ground_dampings[3].low"] == (1.2, "1.2")
    assert c.numbers["identify.ground_dampings[3]"] == (5.0, "5")
    robust = next(s for s in c.sections if s.title.startswith("Designs"))
    binding = [r for r in robust.rows if r.label.startswith("binding device")]
    assert len(binding) == 1 and binding[0].value == "1.2"
    assert "does NOT hold" in robust.after[0]  # the profile's k_c = 50 kN/m exceeds 49.15 kN/m
    ident = next(s for s in c.sections if s.title == "Identification")
    row = next(r for r in ident.rows if "ground_dampings[3]" in r.label)
    assert row.value == "5" and row.unit == "N&middot;s/m" and "95&nbsp;% interval [1.2, 5]" in row.label
    for sec in c.sections:  # issue 22: the Unit column says units, never values (an interval, a coefficient)
        assert not any(ch.isdigit() for r in sec.rows for ch in r.unit if ch.isascii()), sec.title


def test_html_and_pdf_reports_have_the_section_and_the_fit_figure(app, seed_profile, tmp_path):
    html_path, pdf_path = tmp_path / "r.html", tmp_path / "r.pdf"
    assert main(["report", str(seed_profile), "-o", str(html_path), "--no-sampled"]) == 0
    text = html_path.read_text()
    assert 'id="fig-identify"' in text and 'id="fig-identify_phase"' in text
    assert "<h2>Identification</h2>" in text and "49149" in text and "117118" in text
    assert "[1.2, 5]" in text
    assert main(["report", str(seed_profile), "-o", str(pdf_path), "--no-sampled"]) == 0
    pages = pypdf.PdfReader(str(pdf_path)).pages
    pdf = " ".join(" ".join(page.extract_text().split()) for page in pages).replace("\ufb01", "fi")
    assert "Identification" in pdf and "49149" in pdf


def test_export_plot_identify(app, seed_profile, tmp_path, capsys):
    out = tmp_path / "fit.csv"
    assert main(["export-plot", str(seed_profile), "--plot", "identify", "-o", str(out)]) == 0
    rows = list(csv.reader(out.read_text().splitlines()))
    assert any("measured" in cell for cell in rows[0]) or any("measured" in " ".join(r) for r in rows[:3])
    png = tmp_path / "fit.png"
    assert main(["export-plot", str(seed_profile), "--plot", "identify", "-o", str(png)]) == 0
    assert png.stat().st_size > 5000
    plain = tmp_path / "plain.json"
    save_profile(load_profile(resource_path("profiles", "hbfd.json")), plain)
    assert main(["export-plot", str(plain), "--plot", "identify", "-o", str(tmp_path / "x.png")]) == 1
    assert "$.identification" in capsys.readouterr().err


def test_a_profile_with_unbounded_intervals_reports_why_there_is_no_robust_design(app, seed_profile, tmp_path):
    from app.report.content import gather

    p = load_profile(seed_profile)
    sec = p.identification
    note = "the handle mode is not detected in these measurements: <the device is the merged chain>"
    p = p.replace(identification=IdentificationSection({**sec.intervals, "masses[0]": (0.0, float("inf"))},
                                                       sec.measurements, (note,)))
    path = tmp_path / "open.json"
    save_profile(p, path)
    c = gather(load_profile(path), sampled=False)
    robust = next(s for s in c.sections if s.title.startswith("Designs"))
    assert robust.rows == () and "robust.kc" not in c.numbers
    assert "no robust design: the measurements do not bound masses[0]" in robust.after[0]
    ident = next(s for s in c.sections if s.title == "Identification")
    assert any("∞]" in r.label for r in ident.rows)  # the interval [0, ∞]: format_number's one spelling of inf
    assert ident.after[0].startswith("<b>What the fit said</b>")
    assert ident.after[1] == "&bull;&nbsp;the handle mode is not detected in these measurements: " \
                             "&lt;the device is the merged chain&gt;"
    # the PDF is written (without the sampled-data checks: they read neither the identification nor
    # its intervals, and their map and scenario cost seconds, issue 21)
    assert main(["report", str(path), "-o", str(tmp_path / "open.pdf"), "--no-sampled"]) == 0

