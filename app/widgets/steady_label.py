"""A label whose new texts do not lay the window out again: for numbers rewritten on every step of a
slider drag (the verdict's values).

``QLabel.setText`` asks its layout for a new geometry, and the layout then recomputes the window's
whole layout (and repaints what moved) -- on every step of a drag.  Qt skips that for a widget of
fixed size (``QWidget::updateGeometry`` only invalidates the layout when the minimum and maximum
sizes differ), so a :class:`SteadyLabel` has a fixed size: that of the widest and tallest text it
has shown, and at least that of a template text.  A text that needs more grows it, once (one
layout pass); it never shrinks, so a number whose width changes from step to step lays nothing out.
Place it in its layout cell with an alignment (e.g. left, vertically centred): the cell may be
larger than the label.

A word-wrapped paragraph follows its layout's width instead: that is
:class:`~app.widgets.rich_text_pane.RichTextPane`.
"""

from __future__ import annotations

import html
import re

from PySide6.QtCore import QEvent, QSize
from PySide6.QtWidgets import QLabel, QWidget

__all__ = ["SteadyLabel"]

_TAG = re.compile(r"<[^>]*>")
#: px kept free beyond the plain text's width (the label's margins and rounding)
_SLACK = 8


class SteadyLabel(QLabel):
    """A fixed-size ``QLabel`` that grows to fit a longer text and never shrinks.

    ``template`` (same text format as the label) sets the size it starts with: the widest text
    expected, so that a drag does not grow it step by step.  :attr:`relayouts` counts the
    growths (each lays the window out once; tests).
    """

    def __init__(self, text: str = "", template: str = "", parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.template = template
        self.relayouts = 0
        self._size = QSize(0, 0)
        self._template_size: QSize | None = None  # measured once per font
        super().setText(text)
        self.fit()

    def setText(self, text: str) -> None:  # noqa: N802 - the QLabel name
        if text == self.text():
            return
        super().setText(text)
        if not self.fits(text):
            self.fit()

    def fits(self, text: str) -> bool:
        """Whether one line of ``text`` surely fits the present size, without laying it out: its plain
        characters in the label's font (an upper bound: sub- and superscripts are smaller) plus a
        margin.  A rich text's size hint costs a document layout; this, a few microseconds."""
        if not self._size.width() or "<br" in text or "\n" in text or "<b" in text:
            return False
        plain = html.unescape(_TAG.sub("", text))
        return self.fontMetrics().horizontalAdvance(plain) + _SLACK <= self._size.width()

    def needed(self) -> QSize:
        """The size the current text (or the template, if larger) needs."""
        need = self.sizeHint()
        if self.template and self._template_size is None:
            text = self.text()
            super().setText(self.template)
            self._template_size = self.sizeHint()
            super().setText(text)
        return need.expandedTo(self._template_size) if self._template_size is not None else need

    def fit(self, shrink: bool = False) -> None:
        """Grow the fixed size to the text's needs (``shrink``: fit it exactly, after a font change)."""
        need = self.needed()
        size = need if shrink else need.expandedTo(self._size)
        if size != self._size or self.minimumSize() != self.maximumSize():
            self._size = size
            self.relayouts += 1
            self.setFixedSize(size)

    def changeEvent(self, event: QEvent) -> None:  # noqa: N802 - Qt API
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:
            self._template_size = None
            self.fit(shrink=True)
