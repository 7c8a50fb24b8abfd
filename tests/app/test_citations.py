"""Every analysis tab names the paper of its equation numbers in full (a citation note).

The tabs' titles, legends and tooltips say "eq. 9" or "eq. 16"; the note at the bottom of each tab
cites the paper those numbers refer to, from the one definition in analysis.study.citations.
"""

from __future__ import annotations

import pytest
from PySide6.QtCore import Qt
from PySide6.QtGui import QPalette

from analysis.study import citation_text
from analysis.study.citations import (
    ADAMS,
    COLGATE_BROWN,
    COLGATE_SCHENKEL,
    COLONNESE_CHAN,
    COLONNESE_OKAMURA,
    EOM,
    HANNAFORD_RYU,
    REFERENCES,
)
from app.widgets.citation_note import CitationNote

pytestmark = pytest.mark.gui

#: tab title -> the paper whose equation numbers the tab shows, and papers it also names
EXPECTED = {
    "Stability and Z-width": (ADAMS, ()),
    "Design chart": (ADAMS, ()),
    "Sampled-data": (ADAMS, (HANNAFORD_RYU,)),
    "Z-width": (ADAMS, (COLGATE_SCHENKEL,)),
    "Transparency (wall)": (EOM, ()),
    "Disturbance observer": (EOM, ()),
    "Identify": (ADAMS, ()),
    "Renderable space": (COLONNESE_CHAN, (COLONNESE_OKAMURA,)),
    "Workspace": (ADAMS, (COLGATE_BROWN,)),
}


def _notes(tab) -> list[CitationNote]:
    return tab.findChildren(CitationNote)


def test_every_tab_carries_the_full_citation_of_its_equation_numbers(win):
    titles = [win.tabs.tabText(i) for i in range(win.tabs.count())]
    assert {"Stability and Z-width", "Design chart", "Sampled-data", "Transparency (wall)",
            "Disturbance observer"} <= set(titles)
    for i, title in enumerate(titles):
        tab = win.tabs.widget(i)
        tab.ensure_built()  # a tab never shown has no widgets yet
        notes = _notes(tab)
        assert len(notes) == 1, f"{title}: {len(notes)} citation notes"
        note = notes[0]
        primary, others = EXPECTED[title]
        assert note.references[0] is primary, title
        assert set(others) <= set(note.references), title
        text = note.text()
        # the full citation: authors, year, title and venue of the paper
        assert text.startswith("Equation numbers refer to " + primary.authors), title
        for part in (f"({primary.year})", primary.title, primary.venue):
            assert part in text, (title, part)
        assert text == citation_text(*note.references)


def test_the_note_is_small_selectable_wrapped_plain_text_in_the_theme_colour(win):
    note = _notes(win.tabs.widget(0))[0]
    assert note.wordWrap()
    assert note.textFormat() == Qt.TextFormat.PlainText
    assert note.textInteractionFlags() & Qt.TextInteractionFlag.TextSelectableByMouse
    assert note.foregroundRole() == QPalette.ColorRole.WindowText
    assert note.font().pointSizeF() < win.tabs.widget(0).font().pointSizeF()
    assert note.styleSheet() == ""  # the colour comes from the theme's palette
    assert note.names() == ("Adams, Moreyra & Hannaford",)


def test_citation_text_spells_out_each_reference():
    assert citation_text(EOM) == (
        "Equation numbers refer to Eom, K. S., Suh, I. H., & Yi, B.-J. (2000). A Design Method of Haptic "
        "Interface Controller Considering Transparency and Robust Stability. Proceedings of the IEEE/RSJ "
        "International Conference on Intelligent Robots and Systems (IROS 2000), Takamatsu, Japan.")
    both = citation_text(ADAMS, COLGATE_SCHENKEL)
    assert both.startswith("Equation numbers refer to Adams, R. J., Moreyra, M. R., & Hannaford, B. (1998).")
    assert " Also cited: Colgate, J. E., & Schenkel, G. G. (1997). Passivity of a Class of Sampled-Data " in both
    assert ADAMS.html().startswith("Adams, R. J., Moreyra, M. R., &amp; Hannaford, B. (1998). <i>Stability")
    assert len({r.short for r in REFERENCES}) == len(REFERENCES) == 11
