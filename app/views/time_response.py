"""Time response of a simulated scenario: positions, forces and energy over time, and the verdict.

Positions are drawn in mm (the simulator returns m), forces in N, energy in mJ (the simulator
returns J).  The energy plot shows the energy absorbed by the digital side through the actuator
port (negative = the display generated energy), the same from encoder readings (what a
passivity observer on the hardware would see) and the work of the human on the handle.
"""

from __future__ import annotations

import math

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import QEvent, Qt
from PySide6.QtWidgets import QHBoxLayout, QLabel, QVBoxLayout, QWidget

from analysis.sampled import SimulationResult, Verdict
from analysis.study.quantities import format_number

from app.views.base import PlotView, Series, clean_xy, plain
from app.views.legend_row import sync_legend
from app.widgets.colors import for_theme, is_dark

__all__ = ["TimePlot", "TimeResponse", "verdict_text", "VERDICT_COLORS"]

VERDICT_COLORS = {"stable": "#2b8a3e", "sustained oscillation": "#e67700", "divergent": "#c92a2a"}
#: The same on the dark theme's background (contrast >= 4.5:1 on both themes' window colour).
DARK_VERDICT_COLORS = {"stable": "#69db7c", "sustained oscillation": "#ffa94d", "divergent": "#ff8787"}
#: Curve colours by theme: (light, dark), each with at least 3:1 contrast on its plot background.
_CURVE_COLORS = {"blue": ("#1f5fbf", "#74a7ff"), "orange": ("#d9480f", "#ff922b"), "grey": ("#495057", "#ced4da"),
                 "green": ("#2b8a3e", "#69db7c"), "purple": ("#862e9c", "#e599f7")}
#: Compact legend entries (the curves' full names stay in the CSV export and the tooltips).
_SHORT = {"handle x₁": "x₁ handle", "actuator xₙ": "xₙ actuator", "wall surface": "wall",
          "F_h human": "F<sub>h</sub> human", "F_d actuator": "F<sub>d</sub> actuator",
          "F_e environment": "F<sub>e</sub> environment", "absorbed by controller": "controller",
          "observed (encoder)": "observed", "work of the human": "human", "PO (environment port)": "PO"}


def pc_note(res: SimulationResult) -> str:
    """The passivity observer/controller's summary (Hannaford & Ryu), empty when both are off."""
    if res.passivity_energy is None:
        return ""
    e = np.asarray(res.passivity_energy, float)
    text = f" Passivity observer: final energy {plain(float(e[-1]) * 1e3, 3)} mJ, lowest {plain(float(e.min()) * 1e3, 3)} mJ."
    if res.pc_damping is not None and np.any(res.pc_damping):
        text += f" PC damping up to {plain(float(np.max(res.pc_damping)), 4)} N·s/m."
    return text


def _um(x: float) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{format_number(x * 1e6, 3, rich=True)} µm"


def verdict_text(v: Verdict, dark: bool = False) -> str:
    """The verdict with the detector's numbers (rich text), coloured for the theme."""
    color = (DARK_VERDICT_COLORS if dark else VERDICT_COLORS).get(v.kind, "#adb5bd" if dark else "#495057")
    return (f"<b>Simulation:</b> <span style='color:{color}; font-weight:700; font-size:13pt'>"
            f"{v.kind.capitalize()}</span>"
            f"&nbsp;&nbsp;— {v.reason}.  RMS of the detrended actuator position in the last two windows: "
            f"{_um(v.amplitude_previous)} → {_um(v.amplitude_last)} (rest threshold {_um(v.threshold)})")


class TimePlot(PlotView):
    """One panel of the time response: named curves against time."""

    def __init__(self, title: str, y_name: str, y_unit: str, curves: list[tuple[str, str, Qt.PenStyle]],
                 parent: QWidget | None = None) -> None:
        super().__init__(title, parent)
        self.set_axis_labels("t", "s", y_name, y_unit)
        self._colors = {name: color for name, color, _style in curves}
        self._styles = {name: style for name, _color, style in curves}
        self.curves = {name: self.curve(name, _CURVE_COLORS[color][0], 1.6, style) for name, color, style in curves}
        self.legend_outside()
        for name, item in self.curves.items():
            self.set_legend_text(item, _SHORT.get(name, name))
        self.plot_widget.setMinimumSize(130, 120)
        self._raw: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self.dropped = 0
        self.cursor_label.setMinimumWidth(0)

    def restyle(self, pal: dict) -> None:
        for name, item in self.curves.items():
            color = _CURVE_COLORS[self._colors[name]][1 if self._dark else 0]
            item.setPen(pg.mkPen(color, width=1.6, style=self._styles[name]))

    def set_series(self, t: np.ndarray, values: dict[str, np.ndarray | None]) -> None:
        """Draw the curves; non-finite samples (a diverged run) are not drawn but kept for export,
        and the plot says how many were left out (NaN never reaches a plot silently)."""
        self._raw = {}
        dropped = 0
        for name, item in self.curves.items():
            y = values.get(name)
            if y is None:
                item.setData([], [])
                item.setVisible(False)
            else:
                self._raw[name] = (np.asarray(t, float), np.asarray(y, float))
                x, yy, bad = clean_xy(*self._raw[name])
                dropped += bad
                item.setData(x, yy)
                item.setVisible(True)
        # only the curves drawn: a hidden one (no PO without the observer) would show a crossed-eye icon
        sync_legend(self.legend, [(item, _SHORT.get(name, name)) for name, item in self.curves.items()
                                  if item.isVisible()])
        self.dropped = dropped
        if dropped and not self.warning_text:
            self.set_warning([f"{dropped} non-finite or out-of-range samples (the run diverged) are not drawn; "
                              "the CSV export has them"])
        elif not dropped and self.warning_text.startswith("⚠ ") and "non-finite" in self.warning_text:
            self.set_warning([])
        self.plot.enableAutoRange()
        self.bump()

    def data(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """The curve's full data as set (non-finite samples included; not the downsampled display data)."""
        if name not in self._raw:
            return np.empty(0), np.empty(0)
        return self._raw[name]

    def export_series(self) -> list[Series]:
        return [Series(name, *self.export_axes(), x, y)
                for name, (x, y) in self._raw.items() if len(x)]


class TimeResponse(QWidget):
    """Three linked time plots and the verdict label."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        solid, dash, dot = Qt.PenStyle.SolidLine, Qt.PenStyle.DashLine, Qt.PenStyle.DotLine
        self.positions = TimePlot("Positions", "x", "mm", [
            ("handle x₁", "blue", solid), ("actuator xₙ", "orange", solid), ("wall surface", "grey", dash)])
        self.forces = TimePlot("Forces", "F", "N", [
            ("F_h human", "green", solid), ("F_d actuator", "orange", solid), ("F_e environment", "blue", dash)])
        self.energy = TimePlot("Energy (passivity observer)", "E", "mJ", [
            ("absorbed by controller", "orange", solid), ("observed (encoder)", "purple", dot),
            ("work of the human", "green", dash), ("PO (environment port)", "blue", dash)])
        for p in (self.forces, self.energy):
            p.plot.setXLink(self.positions.plot)
        self.verdict = QLabel("No simulation yet.")
        self.verdict.setTextFormat(Qt.TextFormat.RichText)
        self.verdict.setWordWrap(True)
        self.kind: str | None = None
        self.result: SimulationResult | None = None
        self._dark = is_dark(self.palette())  # built in the dark theme, it gets no palette change
        self._note = ""
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
                                   "work of the human": res.energy_human * 1e3,
                                   "PO (environment port)": None if res.passivity_energy is None
                                   else res.passivity_energy * 1e3})
        e_min = float(np.nanmin(res.energy)) if res.energy.size else math.nan
        self.energy.set_warning([f"passivity observer: controller generated up to {plain(-e_min * 1e3, 3)} mJ "
                                 "(energy < 0: not passive)"] if e_min < -1e-9 else [])
        self.kind = res.verdict.kind
        self._note = note + pc_note(res)
        self._show_verdict()

    def _show_verdict(self) -> None:
        res = self.result
        if res is None:
            return
        muted = "#adb5bd" if self._dark else "#5c636a"  # 4.5:1 on either theme's window colour
        self.verdict.setText(for_theme(verdict_text(res.verdict, self._dark)
                                       + (f"<br><span style='color:{muted}'>{self._note}</span>" if self._note else ""),
                                       self._dark))

    def changeEvent(self, event: QEvent) -> None:  # noqa: N802 - Qt API
        """The theme's palette reached the verdict: its colours follow (no tab passes the theme on:
        the note under the verdict was written for the light theme, 2.1:1 on the dark one)."""
        super().changeEvent(event)
        if event.type() in (QEvent.Type.PaletteChange, QEvent.Type.ApplicationPaletteChange) \
                and is_dark(self.palette()) != self._dark:
            self._dark = is_dark(self.palette())
            self._show_verdict()

    def apply_theme(self, dark: bool) -> None:
        self._dark = dark
        for p in self.plot_views():
            p.apply_theme(dark)
        self._show_verdict()

