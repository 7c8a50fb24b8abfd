"""The verdict: unconditionally stable or not, worst margin, binding frequency, η.  Always visible."""

from __future__ import annotations

import math

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QFrame, QGridLayout, QHBoxLayout, QLabel, QWidget

from analysis import StabilityResult

from app.views.base import fmt

__all__ = ["VerdictView"]


_TIPS = {
    "reserve": "Smallest 1 − bound/coupling term over the band: the fraction of the coupling term left "
               "over where the bound comes closest (negative: the bound is exceeded)",
    "freq": "Where the stability reserve is smallest: the bound binds there first",
    "margin": "Smallest coupling term − bound over the band (absolute, in the bound's units); the "
              "frequency where it occurs is in this tooltip once computed",
    "eta": "Smallest Llewellyn/Rollett factor η of the coupled interface (≥ 1: unconditionally stable)",
    "kmax": "k_max: the low-frequency stiffness of Z_max (eq. 12 / 24)",
    "bmin": "b_min: the low-frequency damping of Z_min (eq. 11 / 23)",
}
# two rows of three "title value" pairs: everything visible without widening the window
_LAYOUT = ((("reserve", "stability reserve"), ("freq", "binds at"), ("eta", "min η")),
           (("margin", "worst margin"), ("kmax", "k_max"), ("bmin", "b_min")))


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
        lay.setContentsMargins(8, 4, 8, 4)
        lay.addWidget(self.badge)
        grid = QGridLayout()
        grid.setHorizontalSpacing(8)
        grid.setVerticalSpacing(0)
        cells: dict[str, QLabel] = {}
        for r, row in enumerate(_LAYOUT):
            for c, (key, title) in enumerate(row):
                t = QLabel(title)
                t.setEnabled(False)
                t.setAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
                v = QLabel("–")
                v.setTextFormat(Qt.TextFormat.RichText)
                v.setStyleSheet("font-size: 14px; font-weight: 600;")
                for w in (t, v):
                    w.setToolTip(_TIPS[key])
                grid.addWidget(t, r, 2 * c)
                grid.addWidget(v, r, 2 * c + 1)
                cells[key] = v
        for c in range(3):
            grid.setColumnStretch(2 * c + 1, 1)
        lay.addLayout(grid, 1)
        self.reserve, self.frequency, self.eta = cells["reserve"], cells["freq"], cells["eta"]
        self.margin, self.kmax, self.bmin = cells["margin"], cells["kmax"], cells["bmin"]

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
        self.margin.setText(f"{fmt(res.worst_margin, 3)} {unit}")
        self.margin.setToolTip(f"{_TIPS['margin'].split(';')[0]}; here at {fmt(res.worst_frequency)} rad/s")
        self.eta.setText(fmt(res.min_eta, 6))
        self.kmax.setText(f"{fmt(res.k_max)} N/m")
        self.bmin.setText(f"{fmt(res.b_min)} N·s/m")
        self.revision += 1
