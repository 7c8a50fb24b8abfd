"""Design reports (issue 6): both formats for every bundled profile, their text, figures and numbers."""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from html.parser import HTMLParser
from io import BytesIO

import pypdf
import PySide6  # noqa: F401 - the reports need Qt: fail loudly, never skip
import pytest

from analysis import AdmittanceDisplay, ImpedanceDisplay  # noqa: E402
from analysis.profiles.io import bundled_profiles, load_profile  # noqa: E402
from analysis.study import QUANTITIES, display_kind  # noqa: E402
from analysis.study.summary import summarize  # noqa: E402
from report_builds import BuiltReport, bundled_reports, flat

PROFILES = sorted(bundled_profiles().items())
IDS = [name for name, _ in PROFILES]


@pytest.fixture(scope="module")
def app():
    from app.report.figures import ensure_app

    return ensure_app()


@pytest.fixture(scope="module")
def built(app, tmp_path_factory) -> Mapping[str, BuiltReport]:
    """{name: BuiltReport} for every bundled profile (built once per process: test_report_faults
    reads the same reports, :mod:`report_builds`)."""
    return bundled_reports(str(tmp_path_factory.getbasetemp()))


_flat = flat


def _canon(text: str) -> str:
    """Plain and typeset numbers alike: ``−4.8×10⁻⁸`` (the page: a true minus, a power of ten
    whose exponent the PDF and HTML text give as ``−8``) and ``-4.8e-08`` -> ``-4.8e-8``."""
    text = text.replace("−", "-")
    text = re.sub(r"×10\s*(-?\d+)", r"e\1", text)
    return re.sub(r"e\+?(-?)0*(\d)", r"e\1\2", text)


def _expected_pages(profile) -> int:
    # 2 pages of text (3 with the observer's section), then 2 figures a page, methods sharing the last
    # figure page when it fits
    n_figs = 4 + (3 if profile.wall is not None else 0) + (3 if profile.simulation is not None else 0) \
        + (2 if profile.observer is not None else 0)
    return {4: 5, 7: 6, 9: 8}[n_figs]


@pytest.mark.parametrize("name", IDS)
def test_pdf_pages_and_text(built, name):
    content, _pdf, info, _html, pages, text = built[name]
    profile = content.profile
    assert pages == info["pages"] == _expected_pages(profile)
    flat = _flat(text)
    assert "Haptic interface design report" in flat
    assert profile.name in flat
    assert f"Page {pages} of {pages}" in flat and "Page 1 of" in flat
    for heading in ("Device", "Sampling and analysis band", "Display and controller", "Verdict",
                    "Design results", "Impedance range (Z-width)", "Figures", "Methods"):
        assert heading in flat, heading
    assert "Adams, Moreyra & Hannaford" in flat and "Eom, Suh & Yi" in flat
    assert "Stability and Performance of Haptic Displays" in flat
    for key, (_value, printed) in content.numbers.items():
        assert _canon(printed) in _canon(flat), (key, printed)
    assert f"zwidth {content.version}" in flat


@pytest.mark.parametrize("name", IDS)
def test_report_numbers_equal_analysis(built, name):
    content = built[name][0]
    p = content.profile
    s = summarize(p)
    from app.report.content import num

    if display_kind(p).is_impedance:
        r = ImpedanceDisplay(p.device).evaluate(p.kc, p.bc)
        assert content.printed("design.kc_max") == num(s["impedance"]["design"]["kc_max"])
        assert content.printed("design.frequency") == num(s["impedance"]["design"]["frequency"])
    else:
        r = AdmittanceDisplay(p.device, p.kp, p.kd).evaluate(p.mc, p.bc_adm)
    expected = {
        "verdict.worst_margin": r.worst_margin, "verdict.worst_frequency": r.worst_frequency,
        "verdict.relative_margin": r.relative_margin, "verdict.binding_frequency": r.binding_frequency,
        "verdict.min_eta": r.min_eta, "range.k_max": r.k_max, "range.b_min": r.b_min,
        "range.apparent_mass": r.apparent_mass, "range.apparent_damping": r.apparent_damping,
        "sample_time": p.device.sample_time, "band.max": p.device.nyquist,
    }
    reserve = QUANTITIES["stability_reserve"]
    for key, value in expected.items():
        got, printed = content.numbers[key]
        assert printed == (reserve.number(value) if key == "verdict.relative_margin" else num(value)), key
        assert got == pytest.approx(value, rel=1e-12) or (math.isnan(got) and math.isnan(value)), key
    assert content.printed("verdict.stable") == ("yes" if r.stable else "no")
    for i, m in enumerate(p.device.masses):
        assert content.printed(f"device.mass[{i}]") == num(m)
    if p.wall is not None:
        from analysis.transparency.design import WallDesign

        best = WallDesign.from_settings(p.wall).optimal_damping()
        assert content.printed("wall.optimum.bc") == num(best.bc)


class _Collect(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.tags: list[str] = []
        self.refs: list[str] = []
        self.svg_in_figure = 0
        self._figure = 0

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        if tag == "figure":
            self._figure += 1
        if tag == "svg" and self._figure:
            self.svg_in_figure += 1
        for k, v in attrs:
            if k in ("src", "href", "xlink:href") and v and not v.startswith(("#", "data:")):
                self.refs.append(v)
        if tag == "link":
            self.refs.append(dict(attrs).get("href", "link"))

    def handle_endtag(self, tag):
        if tag == "figure":
            self._figure -= 1


@pytest.mark.parametrize("name", IDS)
def test_html_self_contained(built, name):
    content, _pdf, info, text, _pages, _text = built[name]
    parser = _Collect()
    parser.feed(text)
    parser.close()
    n_figs = info["figures"]
    assert parser.tags.count("figure") == n_figs
    assert parser.svg_in_figure == n_figs
    assert parser.refs == []
    assert "<script" not in text and "<style>" in text
    ids = re.findall(r'\bid="([^"]+)"', text)
    assert len(ids) == len(set(ids)), "duplicate ids between inline SVGs"
    plain = _flat(re.sub(r"<[^>]+>", " ", re.sub(r"<svg.*?</svg>", " ", text, flags=re.S)))
    for key, (_value, printed) in content.numbers.items():
        assert _canon(printed) in _canon(plain), (key, printed)


def test_letter_size_and_bad_extension(app, tmp_path):
    from app.report import build_report

    profile = load_profile(bundled_profiles()["rigid"])
    out = tmp_path / "r.pdf"
    build_report(profile, out, page_size="letter")
    box = pypdf.PdfReader(str(out)).pages[0].mediabox
    assert (round(float(box.width)), round(float(box.height))) == (612, 792)
    build_report(profile, out, page_size="a4")
    box = pypdf.PdfReader(str(out)).pages[0].mediabox
    assert (round(float(box.width)), round(float(box.height))) == (595, 842)
    with pytest.raises(ValueError):
        build_report(profile, tmp_path / "r.docx")


def test_figures_are_the_app_views(built, app):
    from app.report.figures import build_figures
    from app.views.design_chart import DesignChart
    from app.views.range_plot import RangePlot
    from app.views.stability_plot import StabilityPlot

    figs = build_figures(built["hbfd"][0])
    kinds = {f.key: type(f.view) for f in figs}
    assert kinds["bound"] is StabilityPlot and kinds["range"] is RangePlot and kinds["chart"] is DesignChart
    assert {"map", "scenario_position", "scenario_force"} <= set(kinds)


def test_pdf_plots_are_vector(built):
    reader = pypdf.PdfReader(BytesIO(built["rigid"].pdf))
    figure_page = reader.pages[2]
    assert not figure_page.images  # curves, axes and text as vector paths and text
    assert "rad/s" in figure_page.extract_text()


def test_report_typesets_numbers_and_names(built):
    """Issue 13: one way of writing numbers and names. The page shows powers of ten, not
    ``4.8e-08``; scenarios and swept parameters by their names, not their JSON keys; and the
    reserve figure says the verdict's reserve."""
    content, text = built["hbfd"].content, built["hbfd"].html
    body = re.sub(r"<svg.*?</svg>", " ", text, flags=re.S)
    assert not re.search(r"\d\.?\d*e[+-]\d\d", re.sub(r"<[^>]+>", " ", body)), "raw e-notation on the page"
    assert "Impedance worst case" in body and "impedance_worst_case" not in body
    assert "k<sub>obj</sub>" in body and "(kc &times; kobj)" not in body
    reserve = 100 * content.headline.value("stability_reserve")
    caption = re.search(r"Stability reserve\.</b>(.*?)</figcaption>", body, flags=re.S)
    assert caption is not None
    printed = re.search(r"([\d.]+) % at", caption.group(1))
    assert printed is not None and float(printed.group(1)) == pytest.approx(reserve, rel=1e-3)


def test_report_into_a_folder_fails_clearly_and_leaves_nothing(app, tmp_path, monkeypatch, capsys):
    """Issue 22: ``report -o dir.html`` where dir.html is a folder says so, before any analysis,
    and leaves nothing behind (it used to leave ``dir.html.part``)."""
    from analysis.profiles import WriteError
    from app import cli
    from app.report import build_report

    folder = tmp_path / "dir.html"
    folder.mkdir()
    with pytest.raises(WriteError) as info:
        build_report(load_profile(bundled_profiles()["rigid"]), folder, sampled=False)
    assert info.value.strerror == f"Is a folder: {folder}"
    monkeypatch.setattr("app.allocator.tune_allocator", lambda: False)
    code = cli.main(["report", str(bundled_profiles()["rigid"]), "-o", str(folder), "--no-sampled"])
    assert code == 1
    assert capsys.readouterr().err == f"zwidth: error: cannot write {folder}: Is a folder: {folder}\n"
    assert [p.name for p in tmp_path.iterdir()] == ["dir.html"] and list(folder.iterdir()) == []


def test_a_failing_report_leaves_no_temporary_and_keeps_the_old_file(app, tmp_path, monkeypatch):
    from app.report import build_report, pdf

    profile = load_profile(bundled_profiles()["rigid"])
    for name in ("old.pdf", "old.html"):
        (tmp_path / name).write_bytes(b"old report")

    def broken(*_args, **_kwargs):
        raise RuntimeError("renderer failed")

    monkeypatch.setattr(pdf, "section_html", broken)  # fails once Qt's writer has its (temporary) file
    with pytest.raises(RuntimeError):
        build_report(profile, tmp_path / "old.pdf", sampled=False)
    monkeypatch.setattr("app.report.html.report_html", broken)
    with pytest.raises(RuntimeError):
        build_report(profile, tmp_path / "old.html", sampled=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old.html", "old.pdf"]
    assert {p.read_bytes() for p in tmp_path.iterdir()} == {b"old report"}

