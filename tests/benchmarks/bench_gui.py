"""GUI latency: slider value change to repainted plots, on the real app, offscreen, on every tab.

For each sample the benchmark moves a real ``QSlider`` (held down, as in a drag: one drag token,
one undo step) and runs the event loop until the visible tab has refreshed and its plots have
repainted: the undo command, model signal, graph invalidation, verdict and view refresh and the
paint events.  The time from ``setValue`` to the last paint of a plot of the visible tab (or to the
tab's refresh, if no plot needed a repaint) is the latency a user sees.  One drag per tab: the
coupling stiffness k_c on Stability, Design and Sampled-data (the device two-port is cached, only
the coupling side is recomputed), the handle mass m_1 on Stability and Sampled-data (the device
response is recomputed), the wall stiffness K on Transparency and the Q-filter cutoff on Observer.
Target: median <= 16 ms and p95 <= 33 ms (60 fps) on every tab.

During a drag the expensive results are not recomputed: the sampled-data map, exact limit chart
and simulation, the transparency curves over B_c and step response, the observer's two-axis
coupling and step.  They catch up on the worker when the drag pauses or ends
(:mod:`app.core.compute_graph`); what the drag moves directly (the design point, the exact value
at the current gains, the admittances, the single-axis observer response) follows every step.  The
row after a drag that held results back is the time from the release to those results being fresh
again.

The last row is the watchdog of the GUI issue: the longest time the GUI thread was busy while a
long design chart ran on the worker and the user kept editing.

``quick`` (the crash check of ``zwidth bench --quick``): 3 steps a drag, a 10-point chart, and the
Sampled-data tab's map and exact chart on :data:`QUICK_MAP_POINTS` and :data:`QUICK_EXACT_POINTS`.
"""

from __future__ import annotations

import os
import tempfile
import time

# The GUI's setting (app/cli.py): BLAS threads would oversubscribe the worker pool's cores.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: Settle: this many event-loop rounds without a new paint end a sample.
_QUIET_ROUNDS = 5


def _window():
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide6.QtCore import QSettings
    from PySide6.QtWidgets import QApplication

    QSettings.setDefaultFormat(QSettings.Format.IniFormat)
    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, tempfile.mkdtemp())
    from analysis.profiles.io import load_profile
    from analysis.resources import resource_path
    from app.window.main_window import MainWindow, make_application

    app = QApplication.instance() or make_application([])
    win = MainWindow(profile=load_profile(resource_path("profiles", "hbfd.json")))
    win.resize(1400, 900)
    win.show()
    for _ in range(20):
        app.processEvents()
    return app, win


class _PaintClock:
    """Counts the paint events of the visible tab's plot viewports and stamps the last one."""

    def __init__(self, win) -> None:
        from PySide6.QtCore import QEvent, QObject

        views = list(win.tabs.currentWidget().plot_views())
        self.count = 0
        self.last = 0.0
        clock = self
        paint = QEvent.Type.Paint

        class Filter(QObject):
            def eventFilter(self, obj, event) -> bool:  # noqa: N802 - Qt API
                if event.type() == paint:
                    clock.count += 1
                    clock.last = time.perf_counter()
                return False

        self._filter = Filter()
        self._views = views
        for v in views:
            v.plot_widget.viewport().installEventFilter(self._filter)

    def remove(self) -> None:
        for v in self._views:
            v.plot_widget.viewport().removeEventFilter(self._filter)


def _positions(slider, samples: int) -> list[int]:
    """Three swings of 60 slider steps that end away from the start (so the end needs new results)."""
    lo, hi = slider.minimum(), slider.maximum()
    start = slider.value()
    return [int(p) for p in np.clip(start + np.round(60 * np.sin(np.linspace(0, 5.5 * np.pi, samples))), lo, hi)]


def _step(app, tab, clock: _PaintClock, slider, position: int) -> float | None:
    """One drag step: ms from ``setValue`` to the tab refreshed and its plots painted."""
    refreshes, paints = tab.refreshes, clock.count
    t0 = time.perf_counter()
    slider.setValue(position)
    seen, quiet, end = None, 0, t0
    while quiet < _QUIET_ROUNDS:
        before = clock.count
        app.processEvents()
        now = time.perf_counter()
        if seen is None and tab.refreshes != refreshes:
            seen = end = now
        quiet = quiet + 1 if (seen is not None and clock.count == before) else 0
        if now - t0 > 5.0:
            return None  # nothing to refresh (the value did not change the model)
    if clock.count != paints:
        end = max(end, clock.last)
    return (end - t0) * 1e3


def _drag(app, win, field, samples: int) -> tuple[list[float], int]:
    """Latencies of one drag of ``field`` on the visible tab; also how many steps changed nothing."""
    tab = win.tabs.currentWidget()
    clock = _PaintClock(win)
    slider = field.slider
    out, skipped = [], 0
    slider.setSliderDown(True)
    try:
        for p in _positions(slider, samples):
            if p == slider.value():
                p = p + 1 if p < slider.maximum() else p - 1
            ms = _step(app, tab, clock, slider, p)
            if ms is None:
                skipped += 1
            else:
                out.append(ms)
    finally:
        slider.setSliderDown(False)
        clock.remove()
    return out, skipped


def _drags(win) -> list[tuple[str, type, object]]:
    """(label, tab class, slider field) of the drags, one or two per tab."""
    from app.tabs.design_tab import DesignTab
    from app.tabs.observer_tab import ObserverTab
    from app.tabs.sampled_tab import SampledTab
    from app.tabs.stability_tab import StabilityTab
    from app.tabs.transparency_tab import TransparencyTab

    kc, m1 = win.panel.fields["kc"], win.panel.chain.fields[("masses", 0)]
    return [("k_c (coupling)", StabilityTab, kc), ("m_1 (device)", StabilityTab, m1),
            ("k_c (coupling)", DesignTab, kc),
            ("K (wall stiffness)", TransparencyTab, win.tab(TransparencyTab).fields["wall_stiffness"]),
            ("ω_Q (Q-filter cutoff)", ObserverTab, win.tab(ObserverTab).fields["cutoff"]),
            ("k_c (coupling)", SampledTab, kc), ("m_1 (device)", SampledTab, m1)]


#: The results a drag on the tab holds back (by tab title): a row says how long they take to catch up.
_CAUGHT_UP = {"Sampled-data": "map, limits and simulation", "Transparency (wall)": "curves over B_c and step",
              "Disturbance observer": "two-axis coupling and step"}


def _settled(app, win, tab, seconds: float = 180.0) -> float:
    """Run the event loop until the tab is refreshed and no job runs; returns the seconds it took."""
    t0 = time.perf_counter()
    _spin(app, lambda: not tab.stale and not win.runner.is_running() and not win.graph.waiting(), seconds)
    return time.perf_counter() - t0


def _tab_rows(app, win, samples: int) -> list[dict]:
    rows = []
    for label, cls, field in _drags(win):
        tab = win.tab(cls)
        win.tabs.setCurrentWidget(tab)
        _settled(app, win, tab)
        ts, skipped = _drag(app, win, field, samples)
        arr = np.array(ts) if ts else np.array([np.nan])
        rows.append({"name": f"{tab.title}: drag {label} -> plots repainted (HBFD, offscreen)",
                     "median_ms": float(np.median(arr)), "p95_ms": float(np.percentile(arr, 95)),
                     "max_ms": float(arr.max()), "samples": len(ts), "unchanged": skipped,
                     "target_median_ms": 16.0, "target_p95_ms": 33.0})
        caught = _CAUGHT_UP.get(tab.title)
        if caught:
            rows.append({"name": f"{tab.title}: after the {label} drag, {caught} caught up",
                         "median_ms": 1e3 * _settled(app, win, tab), "samples": 1})
    return rows


def _watchdog(app, win, points: int) -> dict:
    """GUI-thread gaps while a long design chart runs on the worker and the user keeps editing.

    A 5 ms timer records the time between its ticks; a gap is how long the GUI thread was busy
    (with the edits' own synchronous work and repaints included).  Target: no gap over 50 ms.
    """
    from PySide6.QtCore import QElapsedTimer, Qt, QTimer

    from app.tabs.design_tab import DesignTab

    g = win.graph
    win.tabs.setCurrentWidget(win.tab(DesignTab))
    _spin(app, lambda: g.is_fresh("design_chart"), 60.0)
    g.node("design_chart").params["points"] = points
    gaps: list[float] = []
    clock = QElapsedTimer()
    clock.start()
    last = [clock.nsecsElapsed()]

    def tick() -> None:
        now = clock.nsecsElapsed()
        gaps.append((now - last[0]) / 1e6)
        last[0] = now

    timer = QTimer()
    timer.setTimerType(Qt.TimerType.PreciseTimer)
    timer.timeout.connect(tick)
    timer.start(5)
    t0 = time.perf_counter()
    win.panel.chain.fields[("masses", 0)].spin.setValue(0.25)
    kc = 50e3
    while not g.is_fresh("design_chart") and time.perf_counter() - t0 < 120:
        deadline = time.perf_counter() + 0.1
        while time.perf_counter() < deadline:
            app.processEvents()
            time.sleep(0.001)
        kc = 55e3 if kc != 55e3 else 60e3
        win.panel.fields["kc"].spin.setValue(kc)
    timer.stop()
    arr = np.array(gaps[1:]) if len(gaps) > 1 else np.array([np.nan])
    return {"name": f"GUI-thread gaps during a {points}-point design chart with edits every 100 ms",
            "median_ms": float(np.median(arr)), "p95_ms": float(np.percentile(arr, 95)),
            "max_ms": float(arr.max()), "samples": int(arr.size), "target_max_ms": 50.0,
            "chart_s": time.perf_counter() - t0}


def _spin(app, done, seconds: float) -> None:
    t0 = time.perf_counter()
    while not done() and time.perf_counter() - t0 < seconds:
        app.processEvents()
        time.sleep(0.001)


#: ``quick``: the Sampled-data tab's stability map points per axis and exact-chart b_c points (the
#: app's are 48 and 24): every drag and catch-up runs, on the smallest grids the GUI tests use
QUICK_MAP_POINTS, QUICK_EXACT_POINTS = 12, 8


def run(quick: bool = False) -> list[dict]:
    import app.core.nodes_sampled as nodes_sampled

    saved = nodes_sampled.MAP_POINTS, nodes_sampled.EXACT_POINTS
    if quick:  # the graph reads both when the window registers its nodes
        nodes_sampled.MAP_POINTS, nodes_sampled.EXACT_POINTS = QUICK_MAP_POINTS, QUICK_EXACT_POINTS
    try:
        return _run(quick)
    finally:
        nodes_sampled.MAP_POINTS, nodes_sampled.EXACT_POINTS = saved


def _run(quick: bool) -> list[dict]:
    import subprocess

    from app.allocator import tune_allocator

    tune_allocator()
    app, win = _window()
    samples = 3 if quick else 200  # quick: a crash check of every drag, not a latency figure
    load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip() if os.name == "posix" else ""
    rows = _tab_rows(app, win, samples)
    rows.append(_watchdog(app, win, 10 if quick else 400))
    if load:
        rows.append({"name": f"machine load during this run: {load.split('load average:')[-1].strip()}"})
    win.undo_stack.setClean()  # no unsaved-changes question on close
    win.runner.shutdown()
    win.close()
    return rows


if __name__ == "__main__":
    for r in run(quick=False):
        print(r)
