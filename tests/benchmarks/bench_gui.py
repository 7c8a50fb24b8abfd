"""GUI latency: slider value change to repainted plots, on the real app, offscreen.

For each sample the benchmark moves a real ``QSlider`` of the parameter panel (held down, as
in a drag) and runs the event loop until every plot of the visible tab has received its paint
event: the undo command, model signal, graph invalidation, view refresh and paint.  The time
from ``setValue`` to the last plot's paint is the latency a user sees.  Two sliders: the coupling stiffness k_c (the device two-port is cached, only the
coupling side is recomputed) and the handle mass m_1 (the device response is recomputed).

The third row is the watchdog of the GUI issue: the longest time the GUI thread was busy while a
long design chart ran on the worker and the user kept editing.
"""

from __future__ import annotations

import os
import tempfile
import time

import numpy as np


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


class _PaintCounter:
    """Counts the paint events of the visible plots' viewports (an event filter)."""

    def __init__(self, win) -> None:
        from PySide6.QtCore import QEvent, QObject

        views = [v for v in win.tabs.currentWidget().plot_views()]
        self.counts = [0] * len(views)
        counts = self.counts
        paint = QEvent.Type.Paint

        class Filter(QObject):
            def __init__(self, i: int) -> None:
                super().__init__()
                self.i = i

            def eventFilter(self, obj, event) -> bool:  # noqa: N802 - Qt API
                if event.type() == paint:
                    counts[self.i] += 1
                return False

        self._filters = [Filter(i) for i in range(len(views))]
        for f, v in zip(self._filters, views):
            v.plot_widget.viewport().installEventFilter(f)


def _drag(app, win, field, samples: int) -> list[float]:
    """Time from ``setValue`` until every visible plot has painted the new data.

    The event loop runs until each plot viewport of the visible tab received a paint event after
    the change (what the user sees), without forcing extra paints of the rest of the window.
    """
    painted = _PaintCounter(win)
    slider = field.slider
    lo, hi = slider.minimum(), slider.maximum()
    start = slider.value()
    positions = [int(p) for p in np.clip(start + np.round(60 * np.sin(np.linspace(0, 6 * np.pi, samples))), lo, hi)]
    out = []
    slider.setSliderDown(True)
    try:
        for p in positions:
            if p == slider.value():
                p = p + 1 if p < hi else p - 1
            before = list(painted.counts)
            t0 = time.perf_counter()
            slider.setValue(p)
            while any(a == b for a, b in zip(painted.counts, before)):
                app.processEvents()
                if time.perf_counter() - t0 > 5.0:
                    raise RuntimeError("the plots were not repainted within 5 s")
            out.append((time.perf_counter() - t0) * 1e3)
    finally:
        slider.setSliderDown(False)
    return out


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


def run(quick: bool = False) -> list[dict]:
    from app.allocator import tune_allocator

    tune_allocator()
    app, win = _window()
    samples = 30 if quick else 200
    rows = []
    targets = (("k_c (coupling)", win.panel.fields["kc"]), ("m_1 (device)", win.panel.chain.fields[("masses", 0)]))
    for label, field in targets:
        ts = np.array(_drag(app, win, field, samples))
        rows.append({"name": f"slider {label} -> plots repainted (HBFD, offscreen)", "median_ms": float(np.median(ts)),
                     "p95_ms": float(np.percentile(ts, 95)), "max_ms": float(ts.max()), "samples": samples,
                     "target_median_ms": 16.0})
    rows.append(_watchdog(app, win, 100 if quick else 400))
    win.undo_stack.setClean()  # no unsaved-changes question on close
    win.runner.shutdown()
    win.close()
    return rows


if __name__ == "__main__":
    for r in run(quick=False):
        print(r)
