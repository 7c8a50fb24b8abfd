"""The GUI on an identified profile (issue 23): a 3-mass fit on the 4-mass HBFD base, opened from
the file ``zwidth identify`` writes or taken by the Identify tab's "Use this device", runs the
Sampled-data tab (stability map, exact limit, simulation) without an error."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from analysis.chain.device import Device
from analysis.identify import device_response
from analysis.profiles import load_profile, save_profile
from analysis.resources import resource_path
from analysis.study.identify import IdentifyResult, identify_chain, load_measurements, profile_with_fit
from app.core.nodes_sampled import ASYNC_NODES, MAP_NODE, SIM_NODE
from app.tabs.identify_tab import IdentifyTab
from app.tabs.sampled_tab import SampledTab

TRUTH = Device(masses=[0.12, 0.45, 0.30], stiffnesses=[6e4, 1.5e5], dampings=[20.0, 30.0],
               ground_dampings=[0.0, 0.0, 3.0], sample_time=1e-3)


def fitted(folder: Path) -> IdentifyResult:
    """The 3-mass fit of a noise-free actuator FRF of :data:`TRUTH`."""
    w = np.logspace(0, np.log10(0.95 * np.pi / TRUTH.sample_time), 200)
    h = device_response(TRUTH, w, "actuator", "free", TRUTH.sample_time, 0)
    path = folder / "act3.csv"
    path.write_text("frequency_rad_s,real,imag\n"
                    + "\n".join(f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(w, h)) + "\n")
    measurements = load_measurements([path], sample_time=TRUTH.sample_time)
    return identify_chain(measurements, 3, sample_time=TRUTH.sample_time)


@pytest.fixture
def window(coarse_grids, win):
    """The shared main window on the HBFD profile; these tests leave edits behind.  The Sampled-data
    tab's map and exact chart on the coarse grids (``coarse_grids``): the tests check that the tab
    runs on the identified chain, not the grids' resolution."""
    win.maybe_save = lambda: True
    return win


def run_sampled_tab(window, qtbot) -> list[tuple[str, str]]:
    """Show the Sampled-data tab, wait for its computations, and return the failures reported."""
    failures: list[tuple[str, str]] = []
    window.graph.failed.connect(lambda name, message: failures.append((name, message)))
    tab = window.tab(SampledTab)
    tab.ensure_built()
    window.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: bool(failures) or all(window.graph.is_fresh(n) for n in ASYNC_NODES), timeout=120000)
    qtbot.wait(20)
    return failures


def assert_sampled_tab_ok(window, qtbot) -> None:
    failures = run_sampled_tab(window, qtbot)
    assert failures == []
    tab = window.tab(SampledTab)
    assert tab.is_built()
    assert window.graph.result(MAP_NODE) is not None and window.graph.result(SIM_NODE) is not None
    assert "failed" not in tab.time_view.verdict.text()
    assert len(window.graph.result(SIM_NODE).t) > 0


def test_sampled_tab_runs_on_the_profile_identify_writes(window, qtbot, tmp_path):
    base = load_profile(resource_path("profiles", "hbfd.json"))
    result = fitted(tmp_path)
    path = tmp_path / "fit3.json"
    save_profile(profile_with_fit(base, result.fit, result.measurements, name="fit3"), path)
    assert window.open_path(str(path), ask=False)
    p = window.model.profile
    assert p.device.n == 3 and p.simulation.options.friction == ()
    assert "3 masses" in p.notes and "four" not in p.notes.lower()
    assert_sampled_tab_ok(window, qtbot)


def test_use_this_device_drops_the_friction_of_the_old_chain(window, qtbot, tmp_path):
    assert window.model.profile.device.n == 4 and len(window.model.profile.simulation.options.friction) == 4
    tab = window.tab(IdentifyTab)
    tab.result = fitted(tmp_path)
    depth = window.undo_stack.count()
    assert tab.use_device() is None
    assert window.undo_stack.count() == depth + 1  # one undo step
    p = window.model.profile
    assert p.device.n == 3 and p.simulation.options.friction == ()
    assert "3 masses" in p.notes and "four" not in p.notes.lower()
    assert_sampled_tab_ok(window, qtbot)
    window.undo_stack.undo()  # undo restores the base's chain, friction and notes
    q = window.model.profile
    assert q.device.n == 4 and q.simulation.options.friction == (0.0, 1.0, 0.0, 0.5) and "four masses" in q.notes
