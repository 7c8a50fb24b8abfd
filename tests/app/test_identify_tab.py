"""The Identify tab (issue 14): load measurement files, fit on the worker, show the fit, and
"Use this device" as one undo step that restores the old device exactly."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from analysis.identify import device_response
from analysis.profiles import profile_from_dict, profile_to_dict
from analysis.profiles.identification import IdentificationSection
from analysis.study import robust_designs
from app.core.nodes_identify import FIT_NODE, ROBUST_NODE
from app.tabs.identify_tab import IdentifyTab


def write_frf(path: Path, device, quantity: str = "actuator", boundary: str = "free", points: int = 400,
              noise: float = 0.0) -> Path:
    T = device.sample_time
    w = np.logspace(0, np.log10(0.95 * np.pi / T), points)
    h = device_response(device, w, quantity, boundary, T, 0)
    if noise:
        rng = np.random.default_rng(2005)
        h = h * (1 + noise * (rng.normal(size=w.size) + 1j * rng.normal(size=w.size)) / np.sqrt(2))
    coh = np.clip(1 - 0.02 * np.log10(w), 0, 1)
    rows = [f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r},{float(c)!r}" for a, b, c in zip(w, h, coh)]
    path.write_text("frequency_rad_s,real,imag,coherence\n" + "\n".join(rows) + "\n")
    return path


def show(win, qtbot) -> IdentifyTab:
    tab = win.tab(IdentifyTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale and tab.refreshes > 0, timeout=10000)
    return tab


def fit(tab: IdentifyTab, qtbot, win) -> None:
    with qtbot.waitSignal(win.graph.ready, timeout=60000, check_params_cb=lambda name: name == FIT_NODE):
        tab.panel.fit_button.click()
    qtbot.waitUntil(lambda: tab.result is not None, timeout=5000)


def test_load_fit_use_and_undo(win, qtbot, tmp_path):
    tab = show(win, qtbot)
    old = win.model.profile
    truth = old.device
    path = write_frf(tmp_path / "actuator.csv", truth)
    assert tab.load_files([path]) == []
    assert tab.panel.measurements[0].sample_time is None  # continuous by default: remove, reload sampled
    tab.panel.files.setCurrentRow(0)
    tab.panel.remove_selected()
    assert tab.panel.measurements == [] and not tab.panel.fit_button.isEnabled()
    tab.panel.sampled.setChecked(True)
    assert tab.load_files([path]) == []
    assert tab.panel.measurements[0].sample_time == pytest.approx(truth.sample_time)
    tab.panel.max_order.setValue(0)  # the chosen order only
    fit(tab, qtbot, win)
    f = tab.result.fit
    np.testing.assert_allclose(f.device.masses, truth.masses, rtol=1e-6)
    np.testing.assert_allclose(f.device.stiffnesses, truth.stiffnesses, rtol=1e-6)
    # the parameter table shows the fitted numbers; the Bode plot draws the fitted response
    cells = {row[0]: row for row in tab.parameters.texts()}  # m₁, k₁, ...: 1-based as the device editor
    assert cells["m₂"][1:3] == ["kg", "2.3"] and cells["k₃"][1:3] == ["N/m", "874000"]
    assert tab.parameters.keys()[:2] == ["masses[0]", "masses[1]"]  # the file's keys stay 0-based
    x, y = tab.bode.magnitude.data("fitted")
    assert x.size == 400 and np.allclose(y, np.abs(f.responses[0]), rtol=1e-12)
    xm, ym = tab.bode.magnitude.data("measured")
    assert np.max(np.abs(y / ym - 1)) < 1e-6
    assert tab.bode.residual.data("coherence")[1].size == 400
    # Use this device: one undo step; undo restores the old device exactly
    depth = win.undo_stack.count()
    assert tab.panel.use_button.isEnabled()
    tab.panel.use_button.click()
    assert win.undo_stack.count() == depth + 1
    now = win.model.profile
    assert now.identification is not None and len(now.identification.intervals) == 11
    np.testing.assert_allclose(now.device.masses, truth.masses, rtol=1e-6)
    assert profile_from_dict(profile_to_dict(now)) == now  # the profile with the section saves and loads
    win.undo_stack.undo()
    assert win.model.profile.device == old.device and win.model.profile.identification is None
    assert np.array_equal(win.model.profile.device.dampings, old.device.dampings)
    assert win.model.profile == old


def test_order_table_and_bad_file(win, qtbot, tmp_path):
    tab = show(win, qtbot)
    bad = tmp_path / "bad.csv"
    bad.write_text("frequency_hz,real,imag\n1,1,0\n2,oops,0\n")
    errors = tab.load_files([bad])
    assert len(errors) == 1 and str(bad) in errors[0] and "line 3" in errors[0] and "'real'" in errors[0]
    assert str(bad) in tab.panel.error.text() and not tab.panel.fit_button.isEnabled()
    tab.panel.sampled.setChecked(True)
    tab.load_files([write_frf(tmp_path / "a.csv", win.model.device, points=200)])
    tab.panel.masses.setValue(3)
    tab.panel.max_order.setValue(3)
    fit(tab, qtbot, win)
    orders = tab.result.orders
    assert list(orders.n) == [1, 2, 3] and tab.orders.rowCount() == 3
    texts = tab.orders.texts()
    assert [row[0] for row in texts] == ["1", "2", "3"]
    assert tab.orders.best_row() == list(orders.n).index(orders.best_bic)
    assert orders.residual[0] > orders.residual[2]  # a 3-mass chain fits a 4-mass device better than 1 mass


def test_robust_verdict_for_the_seed_case(win, qtbot):
    tab = show(win, qtbot)
    p = win.model.profile
    section = IdentificationSection({"ground_dampings[3]": (1.2, 5.0)})
    with qtbot.waitSignal(win.graph.ready, timeout=60000, check_params_cb=lambda name: name == ROBUST_NODE):
        win.editor.edit_many({"identification": section}, "Set intervals")
        tab.refresh()
    qtbot.waitUntil(lambda: "hold" in tab.robust.text(), timeout=5000)
    expected = robust_designs(p.replace(identification=section))
    assert expected.stiffness.kc == pytest.approx(49.15e3, rel=1e-3)
    assert "does NOT hold" in tab.robust.text() and f"{expected.stiffness.kc:.6g} N/m" in tab.robust.text()
    assert "nominal 117118" in tab.robust.text()


def test_screenshots(win, qtbot, tmp_path, screenshot):
    """The fitted tab's plots show data, at one size (1280x800, the smaller of the two it took):
    the window sizes are swept by test_laptop_layout (1024x700 to 1600x1000, every tab)."""
    tab = show(win, qtbot)
    tab.panel.sampled.setChecked(True)
    tab.load_files([write_frf(tmp_path / "a.csv", win.model.device)])
    fit(tab, qtbot, win)
    win.resize(1280, 800)
    qtbot.wait(100)
    screenshot(win, "tab_identify_1280", tab.plot_views())


def test_robust_design_action_and_verdict_line(win, qtbot):
    acts = win.robust_actions
    assert not acts.kc_action.isEnabled() and not acts.bc_action.isEnabled()  # no box: not offered
    assert win.verdict.robust.isHidden()
    section = IdentificationSection({"ground_dampings[3]": (1.2, 5.0)})
    win.editor.edit_many({"identification": section}, "Set intervals")
    assert acts.kc_action.isEnabled() and not acts.bc_action.isEnabled()
    qtbot.waitUntil(lambda: not win.verdict.robust.isHidden(), timeout=30000)
    assert "k_c = 50000 N/m does NOT hold for the whole box" in win.verdict.robust.text()
    depth = win.undo_stack.count()
    acts.kc_action.trigger()
    qtbot.waitUntil(lambda: win.model.profile.kc != 50000.0, timeout=30000)
    assert win.model.profile.kc == pytest.approx(49.15e3, rel=1e-3)
    assert win.undo_stack.count() == depth + 1
    qtbot.waitUntil(lambda: "holds for the whole box" in win.verdict.robust.text()
                    and "NOT" not in win.verdict.robust.text(), timeout=30000)
    win.undo_stack.undo()
    assert win.model.profile.kc == 50000.0
    win.undo_stack.undo()
    assert win.model.profile.identification is None
    qtbot.waitUntil(lambda: win.verdict.robust.isHidden(), timeout=5000)


def test_cancel_stops_a_long_fit_at_once(win, qtbot, tmp_path):
    # the actuator FRF alone at 1 % noise: the handle mode is not detected and the fit scans the
    # handle family and profiles the rest (20-40 s); Cancel must stop it within one evaluation
    tab = show(win, qtbot)
    tab.panel.sampled.setChecked(True)
    tab.load_files([write_frf(tmp_path / "noisy.csv", win.model.device, noise=0.01)])
    with qtbot.waitSignal(win.graph.started, timeout=10000, check_params_cb=lambda name: name == FIT_NODE):
        tab.panel.fit_button.click()
    # inside the fit (it runs 20-40 s): its progress shows, with Cancel
    qtbot.waitUntil(lambda: tab.fit_progress.running and tab.fit_progress.cancel_button.isVisible(), timeout=5000)
    with qtbot.waitSignal(win.graph.cancelled, timeout=5000, check_params_cb=lambda name: name == FIT_NODE):
        tab.fit_progress.cancel_button.click()
    assert "cancelled" in tab.fit_progress.label.text()
    assert tab.result is None and not tab.panel.use_button.isEnabled()



def test_unbounded_intervals_say_why_there_is_no_robust_design(win, qtbot):
    section = IdentificationSection({"masses[0]": (0.0, float("inf")), "ground_dampings[3]": (1.2, 5.0)})
    win.editor.edit_many({"identification": section}, "Set intervals")
    qtbot.waitUntil(lambda: not win.verdict.robust.isHidden(), timeout=30000)
    assert "no robust design: the measurements do not bound masses[0]" in win.verdict.robust.text()
    kc = win.model.profile.kc
    win.robust_actions.kc_action.trigger()
    qtbot.wait(500)
    assert win.model.profile.kc == kc  # nothing designed over a box that is not one


def test_parameter_tables_show_symbols_units_and_whole_columns(qtbot):
    """Both tables name m₁, k₁ ... (the keys stay masses[0] ...), have a unit column, print numbers by
    format_number, and show every column at the Identify tab's width (a number that does not fit
    is elided, never cut)."""
    from types import SimpleNamespace

    from PySide6.QtCore import Qt

    from analysis.identify import parameter_keys
    from analysis.study.quantities import format_number
    from app.panels.identify_panel import IdentifyPanel
    from app.views.bode_view import PARAMETER_COLUMNS, ParameterTable

    keys = parameter_keys(4)
    params = [SimpleNamespace(key=k, value=9.41192e-9 * (i + 1), std_error=1.234567e-10, low=-2.5e-9,
                              high=1.87654e12, fixed=i == 0, identifiable=i != 3, method="profile")
              for i, k in enumerate(keys)]
    table = ParameterTable()
    qtbot.addWidget(table)
    table.show_fit(SimpleNamespace(parameters=params, suggestions={}))
    rows = table.texts()
    assert [r[0] for r in rows[:4]] == ["m₁", "m₂", "m₃", "m₄"] and rows[4][0] == "k₁" and rows[7][0] == "b₁"
    assert rows[-1][0] == "g₄" and [rows[0][1], rows[4][1], rows[7][1]] == ["kg", "N/m", "N·s/m"]
    assert rows[1][2] == format_number(2 * 9.41192e-9) and rows[0][5] == format_number(1.87654e12)
    assert rows[0][7] == "fixed" and rows[3][7] == "not identifiable"
    assert table.keys() == keys
    table.resize(520, 300)  # the tables' width on the Identify tab at 1280×800
    table.show()
    qtbot.waitExposed(table)
    header = table.horizontalHeader()
    used = sum(header.sectionSize(c) for c in range(table.columnCount()))
    assert used <= table.viewport().width() + 1  # no column behind a scroll bar
    assert all(header.sectionSize(c) > 0 for c in range(table.columnCount()))
    assert table.textElideMode() == Qt.TextElideMode.ElideRight and not table.wordWrap()
    value = table.item(1, 2)
    assert value.toolTip() == value.text()  # an elided number's whole text
    # at 1280×720 the table is 280 px wide: a narrowed column's title elides ("9…", not a clipped "% l")
    # and keeps its whole name in the tooltip
    table.resize(280, 300)
    assert header.textElideMode() == Qt.TextElideMode.ElideRight
    assert [table.horizontalHeaderItem(c).toolTip() for c in range(table.columnCount())] == list(PARAMETER_COLUMNS)
    narrowed = [c for c in range(table.columnCount())
                if header.sectionSize(c) < header.fontMetrics().horizontalAdvance(PARAMETER_COLUMNS[c])]
    assert narrowed  # the case the elision is for

    panel = IdentifyPanel(0.001)
    qtbot.addWidget(panel)
    panel.masses.setValue(3)
    fixed = panel.fixed_table
    names = [fixed.item(r, 0).text() for r in range(fixed.rowCount())]
    assert names == ["m₁", "m₂", "m₃", "k₁", "k₂", "b₁", "b₂", "g₁", "g₂", "g₃"]
    assert [fixed.item(r, 3).text() for r in (0, 3, 5)] == ["kg", "N/m", "N·s/m"]
    panel.set_fixed("masses[0]", 2.5e-5)
    assert panel.fixed() == {"masses[0]": pytest.approx(2.5e-5)}  # the 0-based key the fit and files use
    assert fixed.cellWidget(0, 2).text() == format_number(2.5e-5)
