"""Time response of a simulated scenario: positions, forces and energy over time, and the verdict.

Positions are drawn in mm (the simulator returns m), forces in N, energy in mJ (the simulator
returns J).  The energy plot shows the energy absorbed by the digital side through the actuator
port (negative = the display generated energy), the same from encoder readings (what a
passivity observer on the hardware would see) and the work of the human on the handle.
"""

from __future__ import annotations

import math

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QHBoxLayout, QLabel, QVBoxLayout, QWidget

from analysis.sampled import SimulationResult, Verdict

from app.views.base import PlotView, Series, plain

__all__ = ["TimePlot", "TimeResponse", "verdict_text", "VERDICT_COLORS"]

VERDICT_COLORS = {"stable": "#2b8a3e", "sustained oscillation": "#e67700", "divergent": "#c92a2a"}


def _um(x: float) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x * 1e6:.3g} µm"


def verdict_text(v: Verdict) -> str:
    """The verdict with the detector's numbers (rich text)."""
    color = VERDICT_COLORS.get(v.kind, "#495057")
    return (f"<span style='color:{color}; font-weight:700; font-size:13pt'>{v.kind.capitalize()}</span>"
            f"&nbsp;&nbsp;— {v.reason}.  RMS of the detrended actuator position in the last two windows: "
            f"{_um(v.amplitude_previous)} → {_um(v.amplitude_last)} (rest threshold {_um(v.threshold)})")


class TimePlot(PlotView):
    """One panel of the time response: named curves against time."""

    def __init__(self, title: str, y_name: str, y_unit: str, curves: list[tuple[str, str, Qt.PenStyle]],
                 parent: QWidget | None = None) -> None:
        super().__init__(title, parent)
        self.set_axis_labels("t", "s", y_name, y_unit)
        self.curves = {name: self.curve(name, color, 1.6, style) for name, color, style in curves}
        self.plot_widget.setMinimumSize(130, 120)
        self.cursor_label.setMinimumWidth(0)

    def set_series(self, t: np.ndarray, values: dict[str, np.ndarray | None]) -> None:
        for name, item in self.curves.items():
            y = values.get(name)
            if y is None:
                item.setData([], [])
                item.setVisible(False)
            else:
                item.setData(np.asarray(t, float), np.asarray(y, float))
                item.setVisible(True)
        self.plot.enableAutoRange()
        self.bump()

    def data(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """The curve's full data as set (not the downsampled display data)."""
        item = self.curves[name]
        if item.xData is None:
            return np.empty(0), np.empty(0)
        return np.asarray(item.xData), np.asarray(item.yData)

    def export_series(self) -> list[Series]:
        out = []
        for name, item in self.curves.items():
            if item.isVisible() and item.xData is not None and len(item.xData):
                out.append(Series(name, "t (s)", f"{name} ({self.y_unit})", np.asarray(item.xData),
                                  np.asarray(item.yData)))
        return out


class TimeResponse(QWidget):
    """Three linked time plots and the verdict label."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        solid, dash, dot = Qt.PenStyle.SolidLine, Qt.PenStyle.DashLine, Qt.PenStyle.DotLine
        self.positions = TimePlot("Positions", "x", "mm", [
            ("handle x₁", "#1f5fbf", solid), ("actuator xₙ", "#d9480f", solid), ("wall surface", "#495057", dash)])
        self.forces = TimePlot("Forces", "F", "N", [
            ("F_h human", "#2b8a3e", solid), ("F_d actuator", "#d9480f", solid), ("F_e environment", "#1f5fbf", dash)])
        self.energy = TimePlot("Energy (passivity observer)", "E", "mJ", [
            ("absorbed by controller", "#d9480f", solid), ("observed (encoder)", "#862e9c", dot),
            ("work of the human", "#2b8a3e", dash)])
        for p in (self.forces, self.energy):
            p.plot.setXLink(self.positions.plot)
        self.verdict = QLabel("No simulation yet.")
        self.verdict.setTextFormat(Qt.TextFormat.RichText)
        self.verdict.setWordWrap(True)
        self.kind: str | None = None
        self.result: SimulationResult | None = None
        plots = QHBoxLayout()
        plots.setContentsMargins(0, 0, 0, 0)
        for p in self.plot_views():
            plots.addWidget(p, 1)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(2)
        lay.addWidget(self.verdict)
        lay.addLayout(plots, 1)

    def plot_views(self) -> list[PlotView]:
        return [self.positions, self.forces, self.energy]

    def set_busy(self, busy: bool, text: str = "") -> None:
        for p in self.plot_views():
            p.header.setText(f"<b>{p.title}</b>" + (f"  <i>({text or 'updating…'})</i>" if busy else ""))

    def update_result(self, res: SimulationResult | None, wall_position: float | None = None,
                      note: str = "") -> None:
        self.result = res
        if res is None:
            for p in self.plot_views():
                p.set_series(np.empty(0), {})
            self.kind = None
            self.verdict.setText("No simulation yet.")
            return
        t = res.t
        wall = None if wall_position is None else np.full(t.size, wall_position * 1e3)
        self.positions.set_series(t, {"handle x₁": res.handle_position * 1e3,
                                      "actuator xₙ": res.actuator_position * 1e3,
                                      "wall surface": wall})
        self.forces.set_series(t, {"F_h human": res.f_h, "F_d actuator": res.f_d, "F_e environment": res.f_e})
        self.energy.set_series(t, {"absorbed by controller": res.energy * 1e3,
                                   "observed (encoder)": res.energy_observed * 1e3,
                                   "work of the human": res.energy_human * 1e3})
        e_min = float(np.nanmin(res.energy)) if res.energy.size else math.nan
        self.energy.set_warning([f"controller generated up to {plain(-e_min * 1e3, 3)} mJ (energy < 0: "
                                 "not passive)"] if e_min < -1e-9 else [])
        self.kind = res.verdict.kind
        self.verdict.setText(verdict_text(res.verdict) + (f"<br><span style='color:gray'>{note}</span>"
                                                          if note else ""))

    def apply_theme(self, dark: bool) -> None:
        for p in self.plot_views():
            p.apply_theme(dark)

