"""The Transparency and Observer tabs analyse the profile's own device and say which (issue 13):
on the HBFD (no wall or observer section) they used to show the Eom paper's 0.01 kg handle."""

from __future__ import annotations

import math

import pytest

from analysis.study import derived_wall_settings, wall_tradeoff
from app.tabs.observer_tab import ObserverTab
from app.tabs.transparency_tab import TransparencyTab

pytestmark = pytest.mark.gui


def test_hbfd_transparency_tab_shows_the_hbfd(win, qtbot):
    profile = win.model.profile
    assert profile.wall is None and profile.device.total_mass == 5.0
    tab = win.tab(TransparencyTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh("wall_tradeoff") and not tab.stale
                    and tab.tradeoff_drawn is not None, timeout=30000)
    qtbot.waitUntil(lambda: tab.optimum_button.isEnabled(), timeout=30000)
    tab.refresh()
    text = tab.summary.text()
    assert "HBFD" in text and "as a rigid body, m = 5 kg" in text and "m = 0.01 kg" not in text
    fields = tab.panel.fields
    assert fields["mass"].spin.value() == 5.0 and fields["damping"].spin.value() == 5.0
    st = derived_wall_settings(profile)
    assert tab.bc == 7500.0 and st.bc_min < tab.bc < st.bc_max  # the paper's 15 N·s/m times 500
    expected = wall_tradeoff(profile).optimum
    assert tab.tradeoff_drawn.optimum.bc == expected.bc and math.isfinite(expected.bc)
    assert "7638" in tab.optimum_button.text()


def test_hbfd_observer_tab_shows_the_hbfd(win, qtbot):
    tab = win.tab(ObserverTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: not tab.stale and tab.refreshes > 0, timeout=10000)
    assert tab.device_label.text().startswith("Single axis: P_n = 1/(5 s + 5) from HBFD")
    r = win.graph.result("observer_response")
    assert abs(r.nominal[0]) == pytest.approx(abs(1.0 / (5.0 * 1j * r.w[0] + 5.0)), rel=1e-12)


def test_hbfd_admittance_sampled_tab_simulates_its_own_worst_case_and_labels_verdicts(win, qtbot):
    from analysis.sampled import simulate
    from analysis.study import simulation_section
    from app.tabs.sampled_tab import ASYNC_NODES, SampledTab

    win.maybe_save = lambda: True
    assert win.editor.edit("display", "admittance") is None
    tab = win.tab(SampledTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: all(win.graph.is_fresh(n) for n in ASYNC_NODES), timeout=120000)
    qtbot.wait(20)
    p = win.model.profile
    sec = simulation_section(p)
    assert sec.scenario.name == "admittance_worst_case" and sec.options == p.simulation.options
    ref = simulate(p, sec.scenario, options=sec.options)
    assert tab.time_view.kind == ref.verdict.kind
    verdict = tab.time_view.verdict.text()
    assert verdict.startswith("<b>Simulation:</b>") and "a small limit cycle below the rest threshold" in verdict
    summary = tab.summary.text()
    assert summary.startswith("<b>Linear stability</b>") and "no stable m<sub>c</sub>" in summary
    assert "penalty wall" not in verdict
    combo = tab.panel.preset  # the impedance display's worst case is not offered here
    assert combo.currentData() == "admittance_worst_case"
    assert not combo.model().item(combo.findData("impedance_worst_case")).isEnabled()
    assert combo.model().item(combo.findData("wall_push")).isEnabled()
