"""The full citation under a tab whose texts name a paper's equation numbers.

A tab's titles, legends and tooltips say "eq. 9" or "Eom, eq. 16"; :class:`CitationNote` at the
bottom of the tab names the paper(s) in full, from the one definition
(:mod:`analysis.study.citations`), so every page of the app carries the full citation for its
equation numbers.  A small, word-wrapped, selectable plain-text label in the theme's text colour
(the palette's window text, which the theme sets on the application).
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QPalette
from PySide6.QtWidgets import QLabel, QWidget

from analysis.study.citations import Reference, citation_text

__all__ = ["CitationNote"]

#: The note's font size relative to the tab's.
FONT_SCALE = 0.85


class CitationNote(QLabel):
    """``CitationNote(ADAMS, COLGATE_SCHENKEL)``: "Equation numbers refer to <Adams et al. in full>.
    Also cited: <Colgate & Schenkel in full>" (the first paper is the one whose equation numbers
    the tab shows)."""

    def __init__(self, primary: Reference, *others: Reference, parent: QWidget | None = None) -> None:
        super().__init__(citation_text(primary, *others), parent)
        self.references: tuple[Reference, ...] = (primary, *others)
        self.setObjectName("citationNote")
        self.setTextFormat(Qt.TextFormat.PlainText)
        self.setWordWrap(True)
        self.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.setForegroundRole(QPalette.ColorRole.WindowText)
        self.setContentsMargins(4, 2, 4, 2)
        font = self.font()
        if font.pointSizeF() > 0:
            font.setPointSizeF(font.pointSizeF() * FONT_SCALE)
        else:
            font.setPixelSize(max(8, round(font.pixelSize() * FONT_SCALE)))
        self.setFont(font)

    def names(self) -> tuple[str, ...]:
        """The short names of the cited papers ("Adams, Moreyra & Hannaford", ...)."""
        return tuple(r.short for r in self.references)
