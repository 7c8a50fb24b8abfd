"""A rich-text pane whose size does not follow its text: for a summary rewritten on every step of a
slider drag.

A word-wrapped ``QLabel`` lays its text out several times per change (it searches a pleasing
width for its size hint) and asks the window to lay itself out again; here a new text is laid out
once, at the pane's width, and only the pane is repainted.  The pane sits in a scroll area
(:func:`scrolling_pane`) that takes whatever room the layout gives it; a text taller than that
scrolls.
"""

from __future__ import annotations

import math

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QAbstractTextDocumentLayout, QPainter, QPalette, QTextDocument
from PySide6.QtWidgets import QFrame, QScrollArea, QSizePolicy, QWidget

__all__ = ["RichTextPane", "scrolling_pane"]


class RichTextPane(QWidget):
    """Rich text (Qt's HTML subset) drawn at the pane's width, in the palette's text colour.

    ``setText``/``text`` as on a ``QLabel``.  The pane's minimum height is the text's height (so
    that a scroll area around it scrolls); it changes only when the number of lines does.
    """

    def __init__(self, parent: QWidget | None = None, margin: int = 6) -> None:
        super().__init__(parent)
        self._text = ""
        self.doc = QTextDocument(self)
        self.doc.setDocumentMargin(margin)
        self.doc.setDefaultFont(self.font())
        self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)

    def text(self) -> str:
        return self._text

    def setText(self, text: str) -> None:  # noqa: N802 - the QLabel name
        if text == self._text:
            return
        self._text = text
        self.doc.setHtml(text)
        self._fit()
        self.update()

    def _fit(self) -> None:
        self.doc.setTextWidth(max(1, self.width()))
        height = int(math.ceil(self.doc.size().height()))
        if height != self.minimumHeight():
            self.setMinimumHeight(height)

    def resizeEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().resizeEvent(event)
        self._fit()

    def changeEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        super().changeEvent(event)
        self.doc.setDefaultFont(self.font())

    def paintEvent(self, event: object) -> None:  # noqa: N802 - Qt API
        painter = QPainter(self)
        ctx = QAbstractTextDocumentLayout.PaintContext()
        pal = QPalette(self.palette())
        pal.setColor(QPalette.ColorRole.Text, self.palette().color(QPalette.ColorRole.WindowText))
        ctx.palette = pal
        ctx.clip = QRectF(self.rect())
        self.doc.documentLayout().draw(painter, ctx)
        painter.end()


def scrolling_pane(pane: QWidget, minimum: tuple[int, int] = (160, 120)) -> QScrollArea:
    """``pane`` in a framed scroll area that takes the room its layout gives (never asks for more:
    a new text never lays the window out again); a taller text scrolls vertically."""
    area = QScrollArea()
    area.setWidget(pane)
    area.setWidgetResizable(True)
    area.setFrameShape(QFrame.Shape.StyledPanel)
    area.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
    area.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Ignored)
    area.setMinimumSize(*minimum)
    return area
