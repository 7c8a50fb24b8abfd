"""The verdict: unconditionally stable or not, worst margin, binding frequency, η.  Always visible.

The numbers are the study's :class:`~analysis.study.Headline` of the stability result, printed with
its quantities' one rule (:meth:`~analysis.study.Quantity.format`), so the window, ``zwidth
analyze`` and the report show the same text (the stability reserve in per cent everywhere).
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QFrame, QGridLayout, QHBoxLayout, QLabel, QWidget

from analysis import StabilityResult
from analysis.study import Headline, format_number

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
        h = Headline.from_result(res)
        if h.stable:
            text, color = "✔ Unconditionally stable", "#2b8a3e"
        else:
            text, color = "✘ Not unconditionally stable", "#c92a2a"
        self.badge.setText(text)
        self.badge.setStyleSheet(f"background: {color}; color: white; font-size: 15px; font-weight: 700;"
                                 "border-radius: 4px; padding: 6px 12px;")
        self.reserve.setText(h.text("stability_reserve", rich=True))
        key = "binding_frequency" if math.isfinite(h.binding_frequency) else "worst_frequency"
        wf = h.value(key)
        hz = f" ({format_number(wf / (2 * math.pi), 3, rich=True)} Hz)" if math.isfinite(wf) else ""
        self.frequency.setText(h.text(key, rich=True) + hz)
        self.margin.setText(h.text("worst_margin", rich=True))
        self.margin.setToolTip(f"{_TIPS['margin'].split(';')[0]}; here at {h.text('worst_frequency')}")
        self.eta.setText(h.text("min_eta", rich=True))
        self.kmax.setText(h.text("k_max", rich=True))
        self.bmin.setText(h.text("b_min", rich=True))
        self.revision += 1
