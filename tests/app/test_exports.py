"""Exports from the main window (PNG, SVG, CSV), the verdict's numbers, About, and the screenshot."""

from __future__ import annotations

import csv
import os
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtGui import QImage
from PySide6.QtWidgets import QDialog, QLabel, QMessageBox

from analysis import ImpedanceDisplay
from analysis.study import QUANTITIES
from app.tabs.stability_tab import StabilityTab

SVG = "{http://www.w3.org/2000/svg}"


def distinct_colours(image: QImage, step: int = 7) -> int:
    seen = set()
    for y in range(0, image.height(), step):
        for x in range(0, image.width(), step):
            seen.add(image.pixel(x, y))
    return len(seen)


def test_png_export_has_the_asked_size_and_content(win, tmp_path):
    view = win.tab(StabilityTab).stability
    path = tmp_path / "stability.png"
    assert win.export_view(view, "png", str(path), width=1200)
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    image = QImage(str(path))
    assert image.width() == 1200 and image.height() > 300
    assert distinct_colours(image) > 20  # curves, text, grid: not a blank frame


def test_svg_export_is_vector_with_labels(win, tmp_path):
    view = win.tab(StabilityTab).stability
    path = tmp_path / "stability.svg"
    assert win.export_view(view, "svg", str(path))
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    assert not list(root.iter(f"{SVG}image")), "axes or markers were rasterised"
    assert len(list(root.iter(f"{SVG}path")) + list(root.iter(f"{SVG}polyline"))) > 10
    text = "".join(t.text or "" for t in root.iter(f"{SVG}text"))
    assert "ω" in text and "rad/s" in text


def test_csv_export_holds_the_plotted_numbers(win, tmp_path):
    view = win.tab(StabilityTab).stability
    path = tmp_path / "stability.csv"
    assert win.export_view(view, "csv", str(path))
    rows = list(csv.reader(path.open(encoding="utf-8", newline="")))
    header, body = rows[0], rows[1:]
    p = win.model.profile
    res = ImpedanceDisplay(p.device).evaluate(p.kc, p.bc)
    col = header.index("Re(1/Z_c): Re(1/Z_c) [m/(N·s)]")  # "curve: quantity [unit]"; x is the column before
    assert header[col - 1] == "Re(1/Z_c): ω [rad/s]"
    x = np.array([float(r[col - 1]) for r in body if r[col]])
    y = np.array([float(r[col]) for r in body if r[col]])
    np.testing.assert_allclose(x, res.w, rtol=1e-15)
    np.testing.assert_allclose(y, res.coupling_term, rtol=1e-15)


def test_failed_export_says_why_and_writes_nothing(win, tmp_path, monkeypatch):
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda *a, **k: shown.append(a[2]))
    target = tmp_path / "missing-dir" / "plot.csv"
    assert not win.export_view(win.tab(StabilityTab).stability, "csv", str(target))
    assert shown and "missing-dir" in shown[0]
    assert not target.exists()


def test_verdict_shows_reserve_and_binding_frequency(win):
    p = win.model.profile
    res = ImpedanceDisplay(p.device).evaluate(p.kc, p.bc)
    reserve, frequency = QUANTITIES["stability_reserve"], QUANTITIES["binding_frequency"]
    # the study's one rule: the reserve in per cent (as `zwidth analyze` and the report print it)
    assert win.verdict.reserve.text() == reserve.format(res.relative_margin, rich=True)
    assert win.verdict.reserve.text().endswith(" %")
    assert reserve.parse(win.verdict.reserve.text()) == pytest.approx(res.relative_margin, rel=1e-3)
    assert win.verdict.frequency.text().startswith(frequency.format(res.binding_frequency, rich=True))
    assert frequency.parse(win.verdict.frequency.text()) == pytest.approx(res.binding_frequency, rel=1e-5)
    assert "✔" in win.verdict.badge.text()


def test_about_box_names_the_papers_and_versions(win, monkeypatch):
    opened = []

    def fake_exec(dialog: QDialog) -> int:
        opened.append(dialog)
        return 0

    monkeypatch.setattr(QDialog, "exec", fake_exec)
    win.show_about()
    assert opened and opened[0].windowTitle() == "About zwidth"
    html = " ".join(label.text() for label in opened[0].findChildren(QLabel))
    assert "Adams" in html and "Eom" in html and "PySide6" in html
    assert not win.windowIcon().isNull()


def test_screenshot_of_the_main_window(win, qtbot, tmp_path, screenshot):
    """The window as a user sees it; with ZWIDTH_SCREENSHOT_DIR set it is also kept (docs/)."""
    qtbot.wait(100)
    tab = win.tab(StabilityTab)
    screenshot(win, "screenshot", [tab.stability, tab.range])
    path = tmp_path / "screenshot.png"
    keep = os.environ.get("ZWIDTH_SCREENSHOT_DIR")
    if keep:
        Path(keep).mkdir(parents=True, exist_ok=True)
        shutil.copy(path, Path(keep) / "screenshot.png")


@pytest.mark.parametrize("fmt", ["png", "svg", "csv"])
def test_every_plot_of_the_stability_tab_exports(win, tmp_path, fmt):
    tab = win.tab(StabilityTab)
    for view in (tab.stability, tab.range):
        path = tmp_path / f"{view.title.split(':')[0].strip().replace(' ', '_')}.{fmt}"
        assert win.export_view(view, fmt, str(path), width=800)
        assert path.stat().st_size > 200


@pytest.fixture
def coarse_eom_win(qtbot, settings, coarse_grids):
    """The main window on the Eom, Suh & Yi preset with every tab's results on the coarse grids
    (conftest.coarse_profile and coarse_grids: the Z-width region and its filter optimum on 25 B
    points, the sampled map and exact chart on 12 and 8 points)."""
    from analysis.profiles.io import bundled_profiles, load_profile
    from conftest import _main_window, coarse_profile

    yield from _main_window(qtbot, settings, coarse_profile(load_profile(bundled_profiles()["eom"])))


def test_every_plots_csv_export_is_in_the_documented_form(coarse_eom_win, tmp_path, monkeypatch):
    """Issue 22: every tab's plots in one CSV notation (``curve: quantity [unit]``, no NaN), the
    views only the GUI draws (the transparency, observer and sampled tabs' curves, the exact
    chart) as well as those the CLI exports too.  On the coarse grids: the test checks the CSV's
    form, not the results' resolution."""
    eom_win = coarse_eom_win
    from app.tabs.design_tab import DesignTab
    from app.tabs.observer_tab import ObserverTab
    from app.tabs.sampled_tab import SampledTab
    from app.tabs.transparency_tab import TransparencyTab
    from app.tabs.zwidth_tab import ZWidthTab
    from csv_form import check_csv, read_csv

    refused: list[str] = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *a, **k: refused.append(a[2]))
    kinds: set[str] = set()
    tabs = (StabilityTab, DesignTab, TransparencyTab, ObserverTab, SampledTab, ZWidthTab)
    views = [v for cls in tabs for v in eom_win.tab(cls).plot_views()]
    for i, view in enumerate(views):
        path = tmp_path / f"{i}.csv"
        if not eom_win.export_view(view, "csv", str(path)):
            continue
        notes, header, rows = read_csv(path)
        if rows:
            check_csv(header, rows, notes)
            kinds.add(type(view).__name__)
    assert {"CurvesPlot", "ExactLimitChart", "StabilityPlot", "RangePlot", "DesignChart", "StabilityMapView",
            "TimePlot", "ZWidthRegionView", "FilterOptimumView"} <= kinds, (kinds, refused)
