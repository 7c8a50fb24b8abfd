"""File → Export and the plots' right-click menus; exports from tabs that were never opened (issue 13)."""

from __future__ import annotations

import csv
import os

import numpy as np
import pytest
from PySide6.QtWidgets import QMenu, QMessageBox

from analysis.study.quantities import ascii_numbers
from app.tabs.design_tab import DesignTab
from app.tabs.sampled_tab import SampledTab
from app.tabs.stability_tab import StabilityTab
from app.window.menus import EXPORT_FORMATS, plain_title


def export_tree(menu: QMenu) -> dict:
    """The menu as nested dicts: submenu title -> subtree; a plain action -> None."""
    menu.aboutToShow.emit()
    out = {}
    for act in menu.actions():
        if act.isSeparator():
            continue
        sub = act.menu()
        out[act.text()] = export_tree(sub) if sub is not None else None
    return out


def test_plain_title():
    assert plain_title("J(B<sub>c</sub>), eq. 11 (Fig. 8)") == "J(B_c), eq. 11 (Fig. 8)"
    assert plain_title("‖L‖<sub>∞</sub>(B<sub>c</sub>)") == "‖L‖_∞(B_c)"
    assert plain_title("a &lt; b  <b>c</b>") == "a < b c"


def check_file_export_is_grouped_by_tab_with_readable_unique_names(win) -> None:
    tree = export_tree(win.export_menu)
    tabs = [t for t in win.analysis_tabs if t.plot_views()]
    assert list(tree) == [t.title for t in tabs]  # one submenu per tab, in tab order
    leaves = 0
    for tab in tabs:
        plots = tree[tab.title]
        assert len(plots) == len(tab.plot_views())  # unique names: none swallowed by a duplicate key
        for name, formats in plots.items():
            assert "<" not in name and ">" not in name and "&lt;" not in name, name
            assert list(formats) == [label for _fmt, label in EXPORT_FORMATS]
            leaves += 1
    assert leaves == len(win.plot_views())
    names = [name for plots in tree.values() for name in plots]
    assert "J(B_c), eq. 11 (Fig. 8)" in names
    steps = [n for n in names if n.startswith("Step")]
    assert len(steps) == len(set(steps)) >= 2  # the two step plots no longer read "Step" twice


def test_export_menu_action_exports_that_view(win, tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(win, "export_view", lambda v, f: calls.append((v, f)))
    win.export_menu.aboutToShow.emit()
    stab = next(a.menu() for a in win.export_menu.actions() if a.text() == StabilityTab.title)
    stab.aboutToShow.emit()  # a tab's submenu lists its plots when it opens
    plot = next(a.menu() for a in stab.actions() if a.text().startswith("Impedance range"))
    next(a for a in plot.actions() if a.text().startswith("CSV")).trigger()
    assert calls == [(win.tab(StabilityTab).range, "csv")]


class _Event:
    """What pyqtgraph's scene asks of a context-menu event."""

    def __init__(self, item):
        self.acceptedItem = item


def check_right_click_menu_has_only_our_export(win) -> None:
    for view in win.plot_views():
        vb = view.plot.getViewBox()
        menu = vb.getMenu(_Event(vb))
        menu = view.plot_widget.scene().addParentContextMenus(vb, menu, _Event(vb))
        texts = [a.text() for a in menu.actions()]
        exports = [t for t in texts if "export" in t.lower()]
        assert exports == ["Export PNG…", "Export SVG…", "Export CSV…"], (view.title, texts)


def read_csv(path) -> tuple[list[str], list[str], list[list[str]]]:
    lines = path.read_text(encoding="utf-8").splitlines()
    notes = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader([line for line in lines if not line.startswith("#")]))
    return notes, rows[0], rows[1:]


def column(header, rows, name) -> np.ndarray:
    j = header.index(name)
    return np.array([float(r[j]) for r in rows if j < len(r) and r[j]])


def test_export_from_a_tab_never_opened_computes_first(win, tmp_path):
    tab = win.tab(DesignTab)
    assert win.tabs.currentWidget() is not tab and tab.stale
    path = tmp_path / "chart.csv"
    assert win.export_view(tab.chart, "csv", str(path))
    notes, header, rows = read_csv(path)
    chart = win.graph.result("design_chart").chart
    kc = column(header, rows, "largest k_c: k_c [N/m]")
    expected = np.asarray(chart.kc, float)
    np.testing.assert_allclose(kc, expected[np.isfinite(expected) & (expected > 0)], rtol=1e-15)
    assert kc.size > 10
    p = win.model.profile
    # the current gains in the units the header names (they were written as log10)
    assert column(header, rows, "current gains: b_c [N·s/m]").tolist() == [p.bc]
    assert column(header, rows, "current gains: k_c [N/m]").tolist() == [p.kc]


def test_exact_limit_chart_export_from_a_tab_never_opened(coarse_grids, win, tmp_path):
    """The export computes the chart first (on the coarse grids: not about the chart's resolution)."""
    view = win.tab(SampledTab).exact_view
    path = tmp_path / "exact.csv"
    assert win.export_view(view, "csv", str(path))
    notes, header, rows = read_csv(path)
    assert any(h.startswith("exact largest k_c") for h in header)
    assert column(header, rows, [h for h in header if h.startswith("exact largest k_c") and h.endswith("k_c [N/m]")][0]).size
    p = win.model.profile
    assert column(header, rows, "current gains: b_c [N·s/m]").tolist() == [p.bc]
    assert column(header, rows, "current gains: k_c [N/m]").tolist() == [p.kc]


def test_export_that_cannot_compute_is_refused_clearly(win, tmp_path, monkeypatch):
    shown = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *a, **k: shown.append(a[2]))

    def broken(*_args):
        raise RuntimeError("no chart today")

    win.graph.replace_function("design_chart", broken)
    path = tmp_path / "chart.csv"
    assert not win.export_view(win.tab(DesignTab).chart, "csv", str(path))
    assert not path.exists()
    assert shown and "not exported" in shown[0] and "no chart today" in shown[0]


@pytest.mark.parametrize("fmt", ["csv", "png"])
def test_empty_design_chart_gui_export_carries_a_note(eom_win, tmp_path, fmt):
    view = eom_win.tab(DesignTab).chart
    path = tmp_path / f"chart.{fmt}"
    assert eom_win.export_view(view, fmt, str(path), width=600)
    assert view.empty_message.startswith("Nothing is feasible")
    if fmt == "csv":
        notes, header, _rows = read_csv(path)
        assert notes == ["# note: " + ascii_numbers(view.empty_message)]  # the GUI's text, ASCII numbers


def test_file_stem_is_plain_ascii():
    from app.window.exports import file_stem

    assert file_stem("J(B<sub>c</sub>), eq. 11 (Fig. 8)") == "j_b_c_eq_11_fig_8"
    assert file_stem("Disturbance to velocity |v/d|") == "disturbance_to_velocity_v_d"
    assert file_stem("‖L‖<sub>∞</sub>(B<sub>c</sub>), eq. 16–17") == "l_inf_b_c_eq_16-17"
    assert file_stem("spectral radius ρ at 0.5 ms, m₁ x²") == "spectral_radius_rho_at_0.5_ms_m1_x2"
    assert file_stem("a &lt; b: c\\d*?") == "a_b_c_d"
    assert file_stem("<b></b> ...") == "plot"
    assert file_stem("Con") == "con_"  # a name Windows reserves gets a suffix


def check_default_export_names_are_valid_everywhere_and_unique(win, monkeypatch) -> None:
    import re

    from PySide6.QtWidgets import QFileDialog

    from app.window.exports import default_export_name

    names = []
    for tab in win.analysis_tabs:
        for view in tab.plot_views():
            name = default_export_name(view, "png", win)
            stem = name[:-len(".png")]
            assert name.endswith(".png") and re.fullmatch(r"[a-z0-9][a-z0-9._-]*[a-z0-9]", stem), name
            assert "__" not in stem and ".." not in stem and len(name) < 200, name
            assert stem.split(".")[0].upper() not in {"CON", "PRN", "AUX", "NUL"}, name
            names.append(name)
    assert len(names) == len(win.plot_views()) >= 20
    assert len({n.lower() for n in names}) == len(names), sorted(names)  # unique, even ignoring case
    wall = {default_export_name(v, "png", win) for v in win.plot_views() if v.title.startswith("Step")}
    assert len(wall) == 2
    # the file dialog is offered that name, in the last directory (accepting it would write there)
    asked = []
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *a, **k: asked.append(a[2]) or ("", ""))
    view = next(v for v in win.plot_views() if "|v/d|" in v.title)
    assert not win.export_view(view, "csv")
    assert asked and os.path.basename(asked[0]) == default_export_name(view, "csv", win)
    assert "|" not in asked[0] and "<" not in asked[0]


def test_every_plot_is_in_the_export_menus_under_a_valid_unique_name(win, monkeypatch):
    """The File > Export tree, every plot's right-click menu and every plot's default file name:
    one test, because each check goes over every tab's plot views and building every tab is most
    of its cost (about 1.2 s of CPU); the checks leave the window as they found it."""
    check_file_export_is_grouped_by_tab_with_readable_unique_names(win)
    check_right_click_menu_has_only_our_export(win)
    check_default_export_names_are_valid_everywhere_and_unique(win, monkeypatch)


@pytest.mark.parametrize("opened", [False, True])
def test_identify_export_before_a_fit_is_refused_at_once(win, qtbot, tmp_path, monkeypatch, opened):
    from app.core.nodes_identify import FIT_NODE
    from app.tabs.identify_tab import IdentifyTab

    shown = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *a, **k: shown.append(a[2]))
    tab = win.tab(IdentifyTab)
    if opened:
        win.tabs.setCurrentWidget(tab)
        qtbot.waitUntil(lambda: not tab.stale, timeout=10000)
    for view in tab.plot_views():
        path = tmp_path / "magnitude.csv"
        assert not win.export_view(view, "csv", str(path))
        assert not path.exists()
    assert not win.graph.runner.is_running(FIT_NODE) and win.graph.calls(FIT_NODE) == 0  # nothing started
    assert len(shown) == 3
    assert all(text.endswith("was not exported: nothing to export yet: run a fit first.") for text in shown), shown
    assert shown[0].startswith("Magnitude")
