"""The Identify view on the files of the end-to-end path (issue 23; the command line's is
``tests/test_identify_end_to_end.py``): a time-series chirp record and a mixed actuator + gauge +
clamped set, each file of its own kind, fitted on the worker.  The view greys the bins the fit left
out (their own legend entry), says how many bins were used and why, and shows the goodness-of-fit
verdict; a fit that fails it warns and labels the intervals "not trustworthy".  Promises only
(masses within 5 %), never which local optimum a run takes."""

from __future__ import annotations

import html
from pathlib import Path

import numpy as np
import pytest

from analysis.study import UNUSED_BINS_LABEL
from app.core.nodes_identify import FIT_NODE
from app.tabs.identify_tab import IdentifyTab
from app.views.bode_view import NOT_TRUSTWORTHY, UNUSED_KEY
from tests.identify_data import CHIRP_DEVICE
from tests.identify_files import write_chirp_csv, write_frf_csv

TRUE_MASSES = np.array(CHIRP_DEVICE["masses"])
INTERVAL = 6  # the parameter table's interval column


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    d = tmp_path_factory.mktemp("e2e_gui")
    return {"chirp": write_chirp_csv(d / "chirp.csv"), "gauge": write_frf_csv(d / "gauge.csv", "gauge"),
            "clamped": write_frf_csv(d / "clamped.csv", "actuator", "clamped", seed=1)}


def show(win, qtbot) -> IdentifyTab:
    tab = win.tab(IdentifyTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale and tab.refreshes > 0, timeout=10000)
    return tab


def fit(tab: IdentifyTab, qtbot, win, masses: int) -> None:
    tab.panel.masses.setValue(masses)
    tab.panel.max_order.setValue(0)  # the chosen order only
    tab.result = None
    with qtbot.waitSignal(win.graph.ready, timeout=240000, check_params_cb=lambda name: name == FIT_NODE):
        tab.panel.fit_button.click()
    qtbot.waitUntil(lambda: tab.result is not None, timeout=10000)


def legend_texts(view) -> list[str]:
    return [label.text for _sample, label in view.legend.items]


@pytest.mark.numerics
def test_the_view_on_the_mixed_set_greys_unused_bins_and_says_why(win, qtbot, files):
    tab = show(win, qtbot)
    panel = tab.panel
    panel.sampled.setChecked(True)
    panel.sample_time.setValue(1.0)  # ms, as --sample-time 0.001
    assert panel.load_files([files["chirp"], f"{files['gauge']}:gauge", f"{files['clamped']}:actuator:clamped"]) == []
    assert [(m.quantity, m.boundary) for m in panel.measurements] == [
        ("actuator", "free"), ("gauge", "free"), ("actuator", "clamped")]
    assert panel.error.text() == ""
    fit(tab, qtbot, win, 3)
    np.testing.assert_allclose(tab.result.fit.device.masses, TRUE_MASSES, rtol=0.05)
    # the bins left out (the chirp's above 300 Hz) greyed on every plot, with their own entry
    for view in tab.bode.plot_views():
        hz = view.data(UNUSED_KEY)[0] / (2 * np.pi)
        assert np.any(hz > 300.0) and not np.any((hz > 2.0) & (hz < 285.0))  # above the sweep, not inside it
        assert html.escape(UNUSED_BINS_LABEL) in legend_texts(view)
    xm, _ = tab.bode.magnitude.data("measured")  # the fitted bins only, none of the greyed ones
    assert np.intersect1d(xm, tab.bode.magnitude.data(UNUSED_KEY)[0]).size == 0
    summary = tab.summary.text()
    assert "Bins: chirp.csv: " in summary and "gauge.csv: all 300 bins used" in summary
    assert "with input power below" in summary
    assert tab.goodness.isVisibleTo(tab) and "Goodness of fit: the model explains the data" in tab.goodness.text()
    assert not any(NOT_TRUSTWORTHY in row[INTERVAL] for row in tab.parameters.texts())


@pytest.mark.numerics
def test_a_rejected_fit_warns_and_its_intervals_are_not_trustworthy(win, qtbot, files):
    tab = show(win, qtbot)
    assert tab.load_files([files["chirp"]]) == []  # "sampled" unticked: a time series takes its own step
    m = tab.panel.measurements[0]
    assert m.sample_time == pytest.approx(1e-3) and "own step" in tab.panel.files.item(0).text()
    fit(tab, qtbot, win, 1)  # one mass for a 3-mass device
    assert not tab.result.fit.goodness.passed
    assert "Warning: the model does not explain the data" in tab.goodness.text()
    rows = tab.parameters.texts()
    assert rows and all(row[INTERVAL].startswith(NOT_TRUSTWORTHY) for row in rows)
    fit(tab, qtbot, win, 3)  # the right order: the warning and the labels go
    assert tab.result.fit.goodness.passed and "Warning" not in tab.goodness.text()
    assert not any(NOT_TRUSTWORTHY in row[INTERVAL] for row in tab.parameters.texts())


def test_apply_gives_the_selected_file_its_own_kind(win, qtbot, files):
    tab = show(win, qtbot)
    panel = tab.panel
    assert panel.load_files([files["chirp"], files["gauge"]]) == []
    assert panel.measurements[1].quantity == "actuator"  # added with the settings shown
    panel.files.setCurrentRow(1)
    panel.quantity.setCurrentText("gauge")
    panel.apply_button.click()
    assert [m.quantity for m in panel.measurements] == ["actuator", "gauge"]
    assert "gauge" in panel.files.item(1).text() and panel.error.text() == ""
    assert panel.paths == [str(files["chirp"]), str(files["gauge"])]
    assert panel.load_files([f"{files['gauge']}:pressure"])[0].endswith("(FILE[:QUANTITY[:BOUNDARY]])")
