"""The verdict: unconditionally stable or not, worst margin, binding frequency, η.  Always visible."""

from __future__ import annotations

import math

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QFrame, QHBoxLayout, QLabel, QVBoxLayout, QWidget

from analysis import StabilityResult

from .base import fmt

__all__ = ["VerdictView"]


def _cell(title: str) -> tuple[QWidget, QLabel]:
    w = QWidget()
    lay = QVBoxLayout(w)
    lay.setContentsMargins(6, 0, 6, 0)
    lay.setSpacing(0)
    t = QLabel(title)
    t.setStyleSheet("font-size: 11px;")
    t.setEnabled(False)
    v = QLabel("–")
    v.setTextFormat(Qt.TextFormat.RichText)
    v.setStyleSheet("font-size: 15px; font-weight: 600;")
    lay.addWidget(t)
    lay.addWidget(v)
    return w, v


class VerdictView(QFrame):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setFrameShape(QFrame.Shape.StyledPanel)
        self.setObjectName("verdict")
        self.revision = 0
        self.badge = QLabel("–")
        self.badge.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.badge.setMinimumWidth(200)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(8, 6, 8, 6)
        lay.addWidget(self.badge)
        cells = {}
        tips = {
            "reserve": "Smallest 1 − bound/coupling term over the band: the fraction of the coupling "
                       "term left over where the bound comes closest (negative: the bound is exceeded)",
            "freq": "Where the stability reserve is smallest (the bound binds there first)",
            "margin": "Smallest coupling term − bound over the band (absolute, in the bound's units) "
                      "and where it occurs",
            "eta": "Smallest Llewellyn/Rollett factor η of the coupled interface (≥ 1: unconditionally stable)",
        }
        tips["kmax"] = "k_max: the low-frequency stiffness of Z_max (eq. 12 / 24)"
        tips["bmin"] = "b_min: the low-frequency damping of Z_min (eq. 11 / 23)"
        for key, title in (("reserve", "stability reserve"), ("freq", "binds at"),
                           ("eta", "min η (Llewellyn)"),
                           ("kmax", "k_max (stiffness)"), ("bmin", "b_min (damping)")):
            w, v = _cell(title)
            w.setToolTip(tips.get(key, ""))
            cells[key] = v
            lay.addWidget(w)
        lay.addStretch(1)
        self.reserve = cells["reserve"]
        self.frequency, self.eta = cells["freq"], cells["eta"]
        self.margin = self.reserve  # the absolute worst margin is in the reserve's tooltip
        self.kmax, self.bmin = cells["kmax"], cells["bmin"]

    def update_result(self, res: StabilityResult) -> None:
        unit = "m/(N·s)" if res.display == "impedance" else "N·s/m"
        if res.stable:
            text, color = "✔ Unconditionally stable", "#2b8a3e"
        else:
            text, color = "✘ Not unconditionally stable", "#c92a2a"
        self.badge.setText(text)
        self.badge.setStyleSheet(f"background: {color}; color: white; font-size: 15px; font-weight: 700;"
                                 "border-radius: 4px; padding: 6px 12px;")
        rel = res.relative_margin
        self.reserve.setText(f"{100 * rel:.3g} %" if math.isfinite(rel) else fmt(rel))
        wf = res.binding_frequency if math.isfinite(res.binding_frequency) else res.worst_frequency
        hz = f" ({fmt(wf / (2 * math.pi), 3)} Hz)" if math.isfinite(wf) else ""
        self.frequency.setText(f"{fmt(wf)} rad/s{hz}")
        self.reserve.setToolTip(f"worst margin {fmt(res.worst_margin, 3)} {unit} at {fmt(res.worst_frequency)} rad/s")
        self.eta.setText(fmt(res.min_eta, 6))
        self.kmax.setText(f"{fmt(res.k_max)} N/m")
        self.bmin.setText(f"{fmt(res.b_min)} N·s/m")
        self.revision += 1
