"""The Z-width tab shows why a profile's trials file cannot be used (issue 22): the file, the line
and the column on the region plot and in the trials line, and a refused import says the same."""

from __future__ import annotations

from app.core.nodes_zwidth import REGION_NODE
from app.tabs.zwidth_tab import ZWidthTab


def test_a_bad_trials_file_is_shown_on_the_region(win, qtbot, tmp_path):
    tab = win.tab(ZWidthTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh(REGION_NODE) and tab.region_view.region is not None, timeout=60000)
    bad = tmp_path / "bad.csv"
    bad.write_text("b,k,stable\n1,5000,1\n1,abc,0\n")
    reason = tab.import_trials(bad)
    assert reason is not None and "line 3" in reason and "column 'k'" in reason and tab.error.isVisible()
    assert win.model.profile.controller is None  # refused: nothing stored
    # a profile that names the file anyway (written by hand, or the file changed since the import)
    assert tab.section.write("trials", str(bad), "trials file") is None
    tab.update_views()
    text = tab.region_view.warning_text
    assert str(bad) in text and "line 3" in text and "column 'k'" in text and "'abc' is not a number" in text
    assert tab.region_view.trials is None and "No trials" not in tab.trials_label.text()
    assert str(bad) in tab.trials_label.text() and "line 3" in tab.trials_label.text()  # not silently dropped
