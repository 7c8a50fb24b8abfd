"""Issue 22, the report's faults: J's unit, figures that clip, values in the Unit column, internal
names and raw notation, the Eom profile's observer section, the File row of a report made in the app."""

from __future__ import annotations

import re
import shutil
from html.parser import HTMLParser

import pypdf
import PySide6  # noqa: F401 - the reports need Qt: fail loudly, never skip
import pytest

from analysis.profiles.io import bundled_profiles
from analysis.study import HOLD_LABELS, QUANTITIES
from report_builds import bundled_reports, flat

NAMES = ("eom", "hbfd")


@pytest.fixture(scope="module")
def app():
    from app.report.figures import ensure_app

    return ensure_app()


@pytest.fixture(scope="module")
def reports(app, tmp_path_factory):
    """{name: (content, pdf text, html text)} for the Eom profile (wall, observer) and HBFD (simulation):
    the reports test_report reads too, built once per process (:mod:`report_builds`)."""
    built = bundled_reports(str(tmp_path_factory.getbasetemp()), NAMES)
    return {name: (built[name].content, flat(built[name].pdf_text), built[name].html) for name in NAMES}


class _Cells(HTMLParser):
    """The cells of the report's quantity tables (``table class="q"``), row by row, as text."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[list[str]] = []
        self._in_q = False
        self._cell: list[str] | None = None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self._in_q = ("class", "q") in attrs
        elif self._in_q and tag == "tr":
            self.rows.append([])
        elif self._in_q and tag == "td":
            self._cell = []

    def handle_endtag(self, tag):
        if tag == "td" and self._cell is not None:
            self.rows[-1].append(re.sub(r"\s+", " ", "".join(self._cell)).strip())
            self._cell = None
        elif tag == "table":
            self._in_q = False

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def _rows(page: str) -> list[list[str]]:
    parser = _Cells()
    parser.feed(re.sub(r"<svg.*?</svg>", " ", page, flags=re.S))
    return [r for r in parser.rows if r]


def test_transparency_index_has_its_unit_everywhere(reports):
    """1. J = ||w1 (Y_v - Y_t)||_2^2 (eq. 10-11) of an admittance [m/(N·s)] under a dimensionless weight:
    m²/(N²·s³), the one unit of the study's quantity in the report's table, figure and the app's summary."""
    from app.views.wall_summary import wall_summary
    from analysis.study import wall_design, wall_point, wall_settings

    unit = QUANTITIES["transparency_index"].unit
    assert unit == "m²/(N²·s³)"
    content, text, page = reports["eom"]
    j_rows = [r for r in _rows(page) if r[0].startswith("transparency index")]
    assert len(j_rows) == 1 and j_rows[0][3] == unit
    assert f"J = {content.printed('wall.optimum.index')} {unit}" in text  # the figure's caption
    assert "J [–]" not in text and "J [-]" not in text
    profile = content.profile
    st = wall_settings(profile)
    summary = wall_summary(st, wall_point(wall_design(profile), 10.0), None)
    assert unit in summary and "m²/(N²·s)" not in summary


def test_no_unit_cell_holds_a_value(reports):
    """3. The Unit column says units: a scenario, a second coefficient or a verdict sit elsewhere."""
    number = re.compile(r"^[−-]?\d")
    for name in NAMES:
        rows = _rows(reports[name][2])
        assert rows
        for r in rows:
            assert len(r) == 4, r
            assert not number.match(r[3]), (name, r)
            assert not re.search(r"[0-9]", r[3]), (name, r)  # units only: m², never a value
            assert not any(w in r[3] for w in ("Impedance worst case", "stable", "infeasible")), (name, r)
    eom = {r[0]: r for r in _rows(reports["eom"][2])}
    alpha = [r for r in eom.values() if r[1] == "α"]
    beta = [r for r in eom.values() if r[1] == "β"]
    assert alpha and beta and all(r[2] == "0.5" and r[3] == "" for r in alpha + beta)
    scenario = [r for r in _rows(reports["hbfd"][2]) if r[0] == "scenario"]
    assert scenario == [["scenario", "", "Impedance worst case", ""]]


def test_no_internal_names_or_raw_notation(reports):
    """4. The hold model by its label, no unit after "infeasible", no e-notation, typeset symbols."""
    for name in NAMES:
        content, text, page = reports[name]
        body = re.sub(r"<svg.*?</svg>", " ", page, flags=re.S)
        for raw in ("lowpass2", "1e+04", "1e+4", "F_d", "F_h", "k_c", "b_c", "infeasible N/m"):
            assert raw not in text, (name, raw)
            assert raw not in body, (name, raw)
        assert not re.search(r"\d\.?\d*e[+-]\d", text), name
        assert not any(r[2] == "infeasible" and r[3] for r in _rows(page)), name
    eom_text = reports["eom"][1]
    assert HOLD_LABELS["lowpass2"] in eom_text
    assert reports["eom"][0].printed("design.kc_max") == "infeasible"  # the row the fault was seen on
    assert "actuator F d" in reports["hbfd"][1]  # the PDF's legend: F with a subscript d


def test_eom_report_has_the_observer_section(reports):
    """5. The profile's observer section is reported: its settings and what the observer does."""
    content, text, page = reports["eom"]
    profile = content.profile
    assert profile.observer is not None
    assert "Disturbance observer (Eom, Suh & Yi)" in text
    assert "Figure" in text and "Disturbance observer: cross-axis coupling" in text
    n = content.numbers
    assert n["observer.cutoff"][0] == profile.observer.cutoff
    assert n["observer.order"][0] == profile.observer.order
    # the observer rejects the disturbance and decouples the axes (Eom, Suh & Yi, section 2)
    assert n["observer.disturbance_with"][0] < 0.2 * n["observer.disturbance_without"][0]
    assert n["observer.coupling_with"][0] < 0.2 * n["observer.coupling_without"][0]
    assert n["observer.step_y_with"][0] < n["observer.step_y_without"][0]
    for key in ("observer.disturbance_with", "observer.coupling_with", "observer.step_y_with"):
        assert n[key][1] in text, key
    assert "Disturbance observer (Eom" not in reports["hbfd"][1]  # no section, no heading


def test_figures_leave_room_for_their_labels(app, reports):
    """2. The line label of the robust-stability figure and the top tick label of a figure lie
    inside the figure (they were clipped at its left and top edges)."""
    from PySide6.QtCore import QRectF
    from PySide6.QtGui import QFont, QFontMetricsF

    from app.report.figures import make_view

    content = reports["eom"][0]
    fig = make_view(content, "tradeoff_l")
    try:
        view = fig.view
        scene = QRectF(view.plot_widget.rect())
        labels = [item for item in view.plot.items if hasattr(item, "label") and item.label is not None]
        assert labels
        for line in labels:
            box = line.label.sceneBoundingRect()
            assert scene.contains(box), (box, scene)
            assert box.left() >= view.plot.vb.sceneBoundingRect().left()
        left = view.plot.getAxis("left")
        font = left.style.get("tickFont") or QFont()
        half_line = QFontMetricsF(font).height() / 2  # a tick label is centred on its tick
        assert left.sceneBoundingRect().top() >= half_line  # so the top one has room above the axis
    finally:
        fig.view.deleteLater()


def test_report_made_in_the_app_names_its_file(app, tmp_path):
    """6. File → Export Report names the document's file: a bundled preset's and an opened file's.
    (The action's export of the preset is test_report's former test_export_report_action: its
    menu text and figures are checked here, on the same export.)"""
    from app.report.action import export_report
    from app.window.main_window import MainWindow

    win = MainWindow()
    try:
        assert win.act_export_report.text().startswith("Export")
        out = tmp_path / "preset.html"
        assert export_report(win, str(out))
        page = out.read_text(encoding="utf-8")
        assert re.search(r"<td><b>File</b></td><td>hbfd\.json</td>", page)
        assert page.count("<svg") >= 3
        mine = tmp_path / "my-device.json"
        shutil.copy(bundled_profiles()["rigid"], mine)
        assert win.documents.open_path(str(mine), ask=False)
        out2 = tmp_path / "mine.html"
        assert export_report(win, str(out2))
        assert re.search(r"<td><b>File</b></td><td>my-device\.json</td>", out2.read_text(encoding="utf-8"))
    finally:
        win.close()
        win.deleteLater()


def test_pdf_of_a_report_made_in_the_app_has_the_file_row(app, tmp_path):
    from app.report.action import export_report
    from app.window.main_window import MainWindow

    win = MainWindow()
    try:
        out = tmp_path / "app.pdf"
        assert export_report(win, str(out))
        first = re.sub(r"\s+", " ", pypdf.PdfReader(str(out)).pages[0].extract_text())
        assert "File hbfd.json" in first
    finally:
        win.close()
        win.deleteLater()
