"""The verdict: unconditionally stable or not, worst margin, binding frequency, η.  Always visible.

The numbers are the study's :class:`~analysis.study.Headline` of the stability result, printed with
its quantities' one rule (:meth:`~analysis.study.Quantity.format`), so the window, ``zwidth
analyze`` and the report show the same text (the stability reserve in per cent everywhere).
"""

from __future__ import annotations

import math

from PySide6.QtCore import Qt
from PySide6.QtGui import QFont
from PySide6.QtWidgets import QFrame, QGridLayout, QHBoxLayout, QLabel, QVBoxLayout, QWidget

from analysis import StabilityResult
from analysis.study import Headline, format_number

from app.widgets.steady_label import SteadyLabel

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
#: The widest value each cell expects: its label starts that wide, so that the numbers of a slider
#: drag change in place (:class:`~app.widgets.steady_label.SteadyLabel`, no layout pass per step).
_TEMPLATES = {"reserve": "−888.888 %", "freq": "88888.8 rad/s (8888.8 Hz)", "eta": "8.8888",
              "margin": "−8.88888×10<sup>−88</sup> m/(N·s)", "kmax": "8888888 N/m", "bmin": "88.8888 N·s/m"}
#: The badge's texts and colours (white text on them: contrast >= 4.5:1).  The line above the badge
#: (:attr:`question`) says which question it answers (:attr:`analysis.study.Headline.question`): the
#: virtual coupling's two-port test, not the wall controller's robustness on the Transparency tab.
BADGE = {True: ("✔ Unconditionally stable", "#237032"), False: ("✘ Not unconditionally stable", "#c92a2a")}
#: Text colours by theme (light, dark): values and the muted titles, >= 4.5:1 on the window colour.
TEXT_COLORS = {"value": ("#1a1a1a", "#f1f3f5"), "title": ("#50565c", "#b4bbc2")}
_BADGE_PADDING = 12


class VerdictView(QFrame):
    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setFrameShape(QFrame.Shape.StyledPanel)
        self.setObjectName("verdict")
        self.revision = 0
        self.dark = False
        self.badge = QLabel("–")
        self.badge.setAlignment(Qt.AlignmentFlag.AlignCenter)
        font = QFont(self.font())
        font.setPixelSize(15)
        font.setBold(True)
        self.badge.setFont(font)
        # wide enough for either verdict: the badge is never cut
        widest = max(self.badge.fontMetrics().horizontalAdvance(text) for text, _c in BADGE.values())
        self.badge.setMinimumWidth(widest + 2 * _BADGE_PADDING + 8)
        self._stable: bool | None = None
        value_font = QFont(self.font())
        value_font.setPixelSize(14)
        value_font.setWeight(QFont.Weight.DemiBold)
        self.titles: list[QLabel] = []
        self.values: list[QLabel] = []
        lay = QHBoxLayout(self)
        lay.setContentsMargins(8, 4, 8, 4)
        self.question = QLabel("Virtual coupling")  # which question the badge answers
        self.question.setAlignment(Qt.AlignmentFlag.AlignCenter)
        verdict = QVBoxLayout()
        verdict.setSpacing(1)
        verdict.addWidget(self.question)
        verdict.addWidget(self.badge)
        lay.addLayout(verdict)
        grid = QGridLayout()
        grid.setHorizontalSpacing(4)  # the window's minimum width fits 1024 px (the value columns stretch)
        grid.setVerticalSpacing(0)
        cells: dict[str, QLabel] = {}
        for r, row in enumerate(_LAYOUT):
            for c, (key, title) in enumerate(row):
                t = QLabel(title)
                t.setAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
                v = SteadyLabel("–", _TEMPLATES[key])  # rewritten on every drag step: fixed size
                v.setTextFormat(Qt.TextFormat.RichText)
                v.setFont(value_font)
                self.titles.append(t)
                self.values.append(v)
                for w in (t, v):
                    w.setToolTip(_TIPS[key])
                grid.addWidget(t, r, 2 * c)
                grid.addWidget(v, r, 2 * c + 1, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
                cells[key] = v
        for c in range(3):
            grid.setColumnStretch(2 * c + 1, 1)
        # issue 14: whether the current coupling holds for the whole parameter box (hidden without one)
        self.robust = QLabel()
        self.robust.setObjectName("verdictRobust")
        self.robust.hide()
        grid.addWidget(self.robust, len(_LAYOUT), 0, 1, 6)
        lay.addLayout(grid, 1)
        self.reserve, self.frequency, self.eta = cells["reserve"], cells["freq"], cells["eta"]
        self.margin, self.kmax, self.bmin = cells["margin"], cells["kmax"], cells["bmin"]
        self.apply_theme(False)

    def apply_theme(self, dark: bool) -> None:
        """Text colours for the theme (explicit: a palette change alone does not reach every label)."""
        self.dark = dark
        for labels, role in ((self.titles + [self.question], "title"), (self.values, "value")):
            color = TEXT_COLORS[role][1 if dark else 0]
            for label in labels:
                label.setStyleSheet(f"color: {color};")
        self._style_badge()

    def _style_badge(self) -> None:
        if self._stable is None:
            return
        self.badge.setStyleSheet(f"background: {BADGE[self._stable][1]}; color: white; border-radius: 4px;"
                                 f"padding: 6px {_BADGE_PADDING}px;")

    def update_robust(self, text: str | None, holds: bool) -> None:
        """Show ``text`` (:meth:`analysis.study.RobustDesigns.verdict`) in green when the coupling
        holds for the whole box, red when not; ``None`` hides the line."""
        if text is None:
            self.robust.hide()
            return
        self.robust.setText(("✔ " if holds else "✘ ") + text)
        self.robust.setStyleSheet(f"color: {'#237032' if holds else '#c92a2a'}; font-weight: 600;")
        self.robust.show()

    def update_result(self, res: StabilityResult) -> None:
        h = Headline.from_result(res)
        if self.question.text() != h.question:
            self.question.setText(h.question)
        self.badge.setToolTip(h.verdict())
        if h.stable != self._stable:
            self._stable = h.stable
            self.badge.setText(BADGE[h.stable][0])
            self._style_badge()
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
