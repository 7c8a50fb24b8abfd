"""Failures found by the GUI state machine's long run, replayed as explicit sequences.

Each test names the run (seed and step of ``tests/benchmarks/bench_state_machine.py``) that found
it, replays the profile and the actions that led to it through :class:`GuiDriver`, and checks the
state machine's invariants after them; a unit test pins the cause.
"""

from __future__ import annotations

import json

import numpy as np
from PySide6.QtCore import Qt

from app.views.time_response import TimePlot

from tests.app.test_state_machine import GuiDriver

#: The profile before step 1095 of the long run (seed 20261201): the Eom device with a second
#: mass, in the admittance display, at gains for which the sampled-data simulation diverges
#: (forces reach 1.5e308).
DIVERGING = {
    "admittance_coupling": {"damping": 10.0, "mass": 0.02871}, "band": {"min": 1.0},
    "device": {"dampings": [4.47213595499958], "ground_dampings": [0.022, 0.0], "masses": [0.01, 0.01],
               "sensor_element": 0, "stiffnesses": [100000.0]},
    "display": "admittance", "impedance_coupling": {"damping": 11202.6, "stiffness": 1000.0},
    "name": "Eom, Suh & Yi device", "notes": "state machine long run, step 1095",
    "observer": {"alpha": 0.5, "beta": 0.5, "cutoff": 200.0, "delta": 1.0, "nominal_damping": 0.022,
                 "nominal_mass": 0.01, "order": 2, "preset": "five_bar_centre", "step_duration": 0.2,
                 "step_force": 1.0},
    "pd_gains": {"damping": 106.794, "stiffness": 933.2}, "sample_time": 0.0004656, "schema_version": 5,
    "wall": {"alpha": 0.5, "bc_count": 100, "bc_max": 40.0, "bc_min": 0.5, "beta": 0.5,
             "controller_stiffness": None, "damping": 0.022, "hold": "lowpass2", "lowpass_damping": 0.7071,
             "mass": 0.01, "plant": "rigid", "sample_time": 0.001, "step_duration": 0.5, "step_force": -5.0,
             "wall_damping": 1.0, "wall_stiffness": 1000.0, "weight_cutoff": 100.0, "weight_order": 1},
}


def _forces_plot(qapp) -> TimePlot:
    solid = Qt.PenStyle.SolidLine
    plot = TimePlot("Forces", "F", "N", [("F_h human", "green", solid), ("F_d actuator", "orange", solid)])
    plot.resize(420, 300)
    plot.show()
    return plot


def test_time_plot_of_a_diverged_run_keeps_a_finite_range(qapp):
    """Finite samples near 1e308 (the forces of step 1095): their span overflows in pyqtgraph's
    auto-range; in the window the y axis then raised "Not setting range to [nan, nan]" in Qt's
    event loop (alone, this plot got a range of +-2.7e12 instead).  They are not drawn (and
    counted, and kept for export); the range is that of the drawable samples."""
    plot = _forces_plot(qapp)
    t = np.linspace(0.0, 0.2, 6)
    plot.set_series(t, {"F_h human": np.array([0.0, 1.0, -7.9e305, 1.02e307, 2.0, np.nan]),
                        "F_d actuator": np.array([0.0, -1.48e308, 1.15e307, 3.0, -1.0, np.inf])})
    for _ in range(3):
        qapp.processEvents()
    lo, hi = plot.plot.getViewBox().viewRange()[1]
    assert plot.dropped == 6
    assert -1.5 < lo <= -1.0 and 3.0 <= hi < 3.5
    assert plot.data("F_d actuator")[1][1] == -1.48e308  # the CSV export keeps every sample
    assert "6 non-finite or out-of-range samples" in plot.warning_text
    plot.close()


def test_drag_on_the_sampled_data_tab_after_a_diverged_run(qapp, tmp_path):
    """Step 1095 of the long run: on the Sampled-data tab (admittance display) the simulation
    diverges; dragging the second mass re-runs it, and an exception reached Qt's event loop."""
    path = tmp_path / "diverging.json"
    path.write_text(json.dumps(DIVERGING))
    driver = GuiDriver(tmp_path)
    try:
        assert driver.win.open_path(str(path), ask=False)
        driver.reset_history()
        tabs = driver.win.tabs
        driver.switch_tab(next(i for i in range(tabs.count()) if tabs.tabText(i) == "Sampled-data"))
        driver.win.runner.wait(60000)
        driver.pump()
        driver.check()
        driver.drag("('masses', 1)", [30, -20, -9])
        for _ in range(3):  # the held-back simulation runs after the release; its result is drawn
            driver.win.runner.wait(60000)
            driver.pump()
        driver.check()
        sim = driver.win.findChildren(TimePlot)
        assert any(p.dropped for p in sim)  # the run did diverge: the case is exercised
        for p in sim:
            assert np.isfinite(p.plot.getViewBox().viewRange()).all(), p.title
    finally:
        driver.close()


class _Payload:
    """Stands for a job's inputs (a profile snapshot): only weak references are kept here."""


def test_finished_jobs_release_their_inputs(qapp):
    """The GUI state machine's memory probe: every background job's runnable stayed alive (about
    one per two steps), and with it the closure and profile snapshot of its job.  After the jobs
    ran, none of their inputs may be alive: superseded, finished and failed jobs alike."""
    import gc
    import weakref

    from app.core.worker import TaskRunner

    runner = TaskRunner()
    refs = []

    def job(payload: _Payload, fail: bool):
        def run(progress, cancelled):
            if fail:
                raise ValueError("a failing job")
            return id(payload)
        return run

    for i in range(120):
        payload = _Payload()
        refs.append(weakref.ref(payload))
        runner.submit(f"job{i % 3}", job(payload, fail=i % 7 == 0))
        del payload
        if i % 10 == 0:
            runner.wait(30000)
            qapp.processEvents()
    runner.wait(30000)
    for _ in range(5):
        qapp.processEvents()
    gc.collect()
    alive = sum(r() is not None for r in refs)
    runner.shutdown()
    assert alive == 0, f"{alive} of {len(refs)} jobs' inputs still alive"
