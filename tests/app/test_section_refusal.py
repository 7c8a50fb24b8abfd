"""A refused setting on the Renderable-space and Workspace panels is said on the panel and the field
goes back to the section's value; the next accepted edit clears the message (SectionBinding.write_shown)."""

from __future__ import annotations

import pytest

from app.tabs.renderable_tab import RenderableTab
from app.tabs.workspace_tab import WorkspaceTab


@pytest.mark.parametrize(("kind", "field", "bad", "good"), [(RenderableTab, "mass_points", 1, 5),
                                                          (WorkspaceTab, "x_points", 1, 5)])
def test_a_refused_setting_is_shown_and_the_next_edit_clears_it(coarse_win, qtbot, kind, field, bad, good):
    tab = coarse_win.tab(kind)
    coarse_win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(tab.is_built, timeout=10000)
    panel = tab.panel
    before = getattr(panel.section.current(), field)
    reason = panel.write(field, bad)
    assert reason and panel.error.text() == f"refused: {reason}" and not panel.error.isHidden()
    assert getattr(panel.section.current(), field) == before  # nothing written
    assert panel.write(field, good) is None
    assert panel.error.text() == "" and panel.error.isHidden()
    assert getattr(panel.section.current(), field) == good
