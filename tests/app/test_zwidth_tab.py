"""The Z-width tab (issue 15): the filter in the parameter panel drives the region node, undo
restores it; a click on the region sets the wall; imported trials show score_trials' wrong count;
the passivity-control options in the Sampled-data scenario controls."""

from __future__ import annotations

import math

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt

from analysis.sampled import VelocityFilter, load_trials, score_trials
from analysis.study import zwidth_region
from app.core.nodes_zwidth import REGION_NODE
from app.tabs.sampled_tab import SampledTab
from app.tabs.zwidth_tab import ZWidthTab


def show(win, qtbot) -> ZWidthTab:
    tab = win.tab(ZWidthTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh(REGION_NODE) and tab.region_view.region is not None, timeout=60000)
    return tab


def test_filter_kind_in_the_panel_recomputes_the_region_and_undo_restores(zwidth_win, qtbot):
    win = zwidth_win
    tab = show(win, qtbot)
    before = tab.region_view.region
    section = win.model.profile.controller
    assert before.velocity_filter.is_backward and section.velocity_filter.is_backward
    assert len(before.b) == section.b_points < 100  # the coarse grid of the zwidth_win fixture
    calls = win.graph.calls(REGION_NODE)
    fp = win.panel.filter_panel
    assert not fp.cutoff.isEnabled()
    fp.kind.set_value("lowpass1")
    vf = win.model.profile.controller.velocity_filter
    assert vf == VelocityFilter("lowpass1", 2 * math.pi * 30.0) and fp.cutoff.isEnabled()
    qtbot.waitUntil(lambda: tab.region_view.region is not before and win.graph.is_fresh(REGION_NODE), timeout=60000)
    assert win.graph.calls(REGION_NODE) == calls + 1
    after = tab.region_view.region
    assert after.velocity_filter == vf
    np.testing.assert_array_equal(after.k_max, zwidth_region(win.model.profile).k_max)
    assert after.area_linear != before.area_linear
    assert fp.cutoff.write(45.0) is None  # the cut-off slider, in Hz
    assert win.model.profile.controller.velocity_filter.cutoff == pytest.approx(2 * math.pi * 45.0)
    win.undo_stack.undo()
    win.undo_stack.undo()
    assert win.model.profile.controller == section
    qtbot.waitUntil(lambda: tab.region_view.region.velocity_filter.is_backward and win.graph.is_fresh(REGION_NODE),
                    timeout=60000)
    np.testing.assert_array_equal(tab.region_view.region.k_max, before.k_max)


def test_cutoff_above_nyquist_is_refused_with_the_reason(win, qtbot):
    fp = win.panel.filter_panel
    fp.kind.set_value("butter2")
    n = win.undo_stack.count()
    reason = fp.cutoff.write(600.0)  # Nyquist of T = 1 ms is 500 Hz
    assert reason and "Nyquist" in reason
    assert win.undo_stack.count() == n
    assert win.model.profile.controller.velocity_filter.kind == "butter2"


def test_clicking_the_region_sets_the_wall_in_one_undo_step(zwidth_win, qtbot):
    win = zwidth_win
    tab = show(win, qtbot)
    qtbot.wait(50)
    view = tab.region_view
    vb = view.plot.getViewBox()
    target = QPointF(np.log10(20.0), np.log10(3.0e4))  # log-log: view coordinates are log10
    pos = view.plot_widget.mapFromScene(vb.mapViewToScene(target))
    n = win.undo_stack.count()
    qtbot.mouseClick(view.plot_widget.viewport(), Qt.MouseButton.LeftButton, pos=QPoint(pos))
    qtbot.waitUntil(lambda: win.undo_stack.count() == n + 1, timeout=3000)
    p = win.model.profile
    assert p.bc == pytest.approx(20.0, rel=0.05) and p.kc == pytest.approx(3.0e4, rel=0.05)
    win.undo_stack.undo()
    assert (win.model.profile.bc, win.model.profile.kc) == (100.0, 50000.0)


def test_imported_trials_show_the_wrong_count_of_score_trials(win, qtbot, tmp_path):
    tab = show(win, qtbot)
    region = tab.region_view.region
    kmax = region.k_limit(np.array([1.0, 10.0, 50.0]))
    path = tmp_path / "trials.csv"
    path.write_text("# bench, 2026\nb,k,stable\n"
                    f"1,{0.5 * kmax[0]},1\n1,{3 * kmax[0]},1\n10,{0.8 * kmax[1]},0\n"
                    f"10,{2 * kmax[1]},0\n50,{0.9 * kmax[2]},1\n50,{1.5 * kmax[2]},1\n")
    expected = score_trials(region, load_trials(path))
    assert expected.wrong_count == 3
    n = win.undo_stack.count()
    assert tab.import_trials(path) is None
    assert win.undo_stack.count() == n + 1 and win.model.profile.controller.trials == str(path)
    qtbot.waitUntil(lambda: tab.region_view.score is not None, timeout=10000)
    assert tab.region_view.score.wrong_count == 3
    assert list(tab.region_view.score.wrong) == list(expected.wrong)
    assert "3 of 6 predicted wrong" in tab.trials_label.text()
    assert "line 4:" in tab.trials_label.text()  # the file's line numbers (comment and header counted)
    bad = tmp_path / "bad.csv"
    bad.write_text("b,k,stable\n1,2,yes\n")
    reason = tab.import_trials(bad)
    assert reason and "line 2" in reason and win.undo_stack.count() == n + 1
    win.undo_stack.undo()
    assert win.model.profile.controller is None


def test_passivity_control_options_in_the_sampled_data_controls(win, qtbot):
    tab = win.tab(SampledTab)
    panel = tab.panel
    assert not panel.pc.isChecked() and not panel.fields["passivity_max_damping"].isEnabled()
    panel.pc.setChecked(True)
    o = win.model.profile.simulation.options
    assert o.passivity_control and panel.po.isChecked() and not panel.po.isEnabled()
    f = panel.fields["passivity_max_damping"]
    assert f.isEnabled()
    f.setText("250")
    f.setModified(True)
    f.editingFinished.emit()
    assert win.model.profile.simulation.options.passivity_max_damping == 250.0
    win.undo_stack.undo()
    win.undo_stack.undo()
    assert win.model.profile.simulation is None or not win.model.profile.simulation.options.passivity_control


def test_encoder_noise_fields_limit_the_region_in_one_undo_step(zwidth_win, qtbot):
    """The noise criterion from the tab: one undo step, the region recomputed with ``b_noise``
    = F/σ_v (the analysis' own), and undo switches it off again."""
    from analysis.sampled import estimate_noise
    from analysis.study import profile_filter

    win = zwidth_win
    tab = show(win, qtbot)
    section = win.model.profile.controller
    before = tab.region_view.region
    assert math.isinf(before.b_noise) and not tab.noise_box.isChecked() and not tab.encoder.isEnabled()
    depth = win.undo_stack.index()
    assert tab.set_noise(1e-5, 0.1) is None
    assert win.undo_stack.index() == depth + 1
    sec = win.model.profile.controller
    assert (sec.encoder_resolution, sec.force_noise) == (1e-5, 0.1)
    qtbot.waitUntil(lambda: tab.region_view.region is not before and win.graph.is_fresh(REGION_NODE), timeout=60000)
    region = tab.region_view.region
    p = win.model.profile
    sigma = estimate_noise(profile_filter(p), p.device.sample_time, 1e-5).velocity_rms
    assert region.b_noise == pytest.approx(0.1 / sigma, rel=1e-12)
    assert np.all(region.k_max[region.b > region.b_noise] == 0) and region.area_linear < before.area_linear
    assert tab.noise_box.isChecked() and tab.encoder.isEnabled() and tab.encoder.value() == 1e-5
    assert tab.set_noise(-1.0, 0.1) is not None  # refused with the range, nothing changed
    assert win.model.profile.controller.encoder_resolution == 1e-5
    win.undo_stack.undo()
    assert win.model.profile.controller == section
    qtbot.waitUntil(lambda: math.isinf(tab.region_view.region.b_noise) and win.graph.is_fresh(REGION_NODE),
                    timeout=60000)
    assert not tab.noise_box.isChecked()


def _fresh_optimum(win, qtbot, tab):
    """Wait for the optimum node of the current profile, drawn in the tab."""
    from app.core.nodes_zwidth import OPTIMUM_NODE

    def done() -> bool:
        g = win.graph
        return g.is_fresh(OPTIMUM_NODE) and g.result(OPTIMUM_NODE) is not None \
            and tab.optimum_view.optimum is g.result(OPTIMUM_NODE)

    qtbot.waitUntil(done, timeout=180000)
    tab.refresh()
    return tab.optimum_view.optimum


def test_optimum_button_is_disabled_without_noise_and_removes_a_filter(zwidth_win, qtbot):
    """Issue 22: on the HBFD without encoder noise no cut-off beats the unfiltered design, so
    "Use the optimum cut-off" is disabled (the verdict says why); with a filter set it offers to
    remove it, in one undo step."""
    from app.tabs.zwidth_tab import APPLY_TEXT

    win = zwidth_win
    tab = show(win, qtbot)
    assert tab.section.write("b_points", 10, "B points") is None  # a coarse B grid: a quick optimum
    opt = _fresh_optimum(win, qtbot, tab)
    assert opt.current is None and opt.offer is None and opt.area < opt.backward_area
    assert not tab.apply_button.isEnabled() and tab.apply_button.text() == APPLY_TEXT
    assert "without encoder noise nothing is gained" in tab.apply_button.toolTip()
    assert "No filter is best" in tab.optimum_view.summary
    depth = win.undo_stack.index()
    assert tab.apply_optimum() is None and win.undo_stack.index() == depth
    f20 = VelocityFilter("lowpass1", 2 * math.pi * 20.0)
    assert tab.section.write("velocity_filter", f20, "filter") is None
    opt = _fresh_optimum(win, qtbot, tab)
    assert opt.current == f20 and opt.offer is not None and opt.offer.is_backward
    assert tab.apply_button.isEnabled() and tab.apply_button.text() == "Remove the filter"
    depth = win.undo_stack.index()
    qtbot.mouseClick(tab.apply_button, Qt.MouseButton.LeftButton)
    assert win.undo_stack.index() == depth + 1 and win.model.profile.controller.velocity_filter.is_backward


def test_optimum_button_offers_the_interior_optimum_with_noise(zwidth_win, qtbot):
    """With the encoder-noise criterion the noise-limited area has an interior optimum: offered,
    applied in one undo step, and then nothing more is offered."""
    win = zwidth_win
    tab = show(win, qtbot)
    assert tab.section.write_many({"b_points": 10, "encoder_resolution": 1e-5}, "noise") is None
    opt = _fresh_optimum(win, qtbot, tab)
    assert opt.noise_limited and opt.interior and opt.offer == VelocityFilter("lowpass1", opt.cutoff)
    assert tab.apply_button.isEnabled() and "Hz)" in tab.apply_button.text()
    depth = win.undo_stack.index()
    qtbot.mouseClick(tab.apply_button, Qt.MouseButton.LeftButton)
    assert win.undo_stack.index() == depth + 1
    assert win.model.profile.controller.velocity_filter == opt.offer
    after = _fresh_optimum(win, qtbot, tab)
    assert after.current == opt.offer and after.offer is None and not tab.apply_button.isEnabled()
