"""The GUI side of a profile's trials file (issue 22).

* A relative ``trials`` path is read from the folder of the opened profile, whatever the working
  directory: the trials node's request carries the resolved absolute path, so the same profile
  opened from another folder reads that folder's file (and only the trials are read again).
* A trials file that cannot be used is an error: File → Export Report… is refused with the
  command line's own message (file, line, column) and writes nothing, and the Z-width tab says
  why no trials are drawn.
"""

from __future__ import annotations

import math
from pathlib import Path

from PySide6.QtWidgets import QMessageBox

from analysis.profiles import ControllerSection, bundled_profiles, load_profile, save_profile
from analysis.sampled import VelocityFilter
from analysis.study import profile_trials, resolve_trials
from app.core.nodes_zwidth import REGION_NODE, TRIALS_NODE
from app.report.action import document_folder, export_report
from app.tabs.zwidth_tab import ZWidthTab
from cli_runner import run_cli

BAD = "b,k,stable\n1,5000,1\n1,abc,0\n"  # line 3, column 'k'


def _bench(folder: Path, trials: str | None) -> Path:
    """A profile ``p.json`` in ``folder`` naming ``trials.csv`` beside it (``trials``: its text) on a
    coarse B grid (12 points: the region is cheap)."""
    folder.mkdir()
    if trials is not None:
        (folder / "trials.csv").write_text(trials, encoding="utf-8")
    p = load_profile(bundled_profiles()["hbfd"])
    p = p.replace(controller=ControllerSection(VelocityFilter("lowpass1", 2 * math.pi * 60), (0.5, 50.0), 12,
                                               "trials.csv"))
    save_profile(p, folder / "p.json")
    return folder / "p.json"


def _rows(stable: list[int]) -> str:
    return "b,k,stable\n" + "".join(f"{1 + i},{1000 * (1 + i)},{s}\n" for i, s in enumerate(stable))


def _show(win, qtbot) -> ZWidthTab:
    tab = win.tab(ZWidthTab)
    win.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: win.graph.is_fresh(REGION_NODE) and tab.region_view.region is not None
                    and not tab.stale, timeout=60000)
    return tab


def _drawn(tab: ZWidthTab) -> tuple[int, int]:
    """How many stable and unstable trial markers the region view draws."""
    view = tab.region_view
    return tuple(len(item.getData()[0] if item.getData()[0] is not None else [])  # type: ignore[return-value]
                 for item in (view.stable_trials, view.unstable_trials))


def test_relative_trials_are_read_from_the_opened_profiles_folder(win, qtbot, tmp_path, monkeypatch):
    a = _bench(tmp_path / "a", _rows([1, 1, 0]))
    b = _bench(tmp_path / "b", _rows([1, 0, 0, 0, 1]))
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    (cwd / "trials.csv").write_text(_rows([0]), encoding="utf-8")  # a decoy of that name where we run
    monkeypatch.chdir(cwd)

    assert win.open_path(str(a), ask=False)
    tab = _show(win, qtbot)
    assert document_folder(win) == str(a.parent)
    assert win.graph.key_of(TRIALS_NODE).path == str(a.parent / "trials.csv")
    trials = tab.region_view.trials
    assert trials is not None and len(trials) == 3 and trials.path == str(a.parent / "trials.csv")
    assert _drawn(tab) == (2, 1) and tab.region_view.score is not None
    assert tab.trials_label.text().startswith("3 trials from trials.csv")
    # the report reads the same file: resolved by the command line's function with the document's folder
    assert len(profile_trials(resolve_trials(win.model.profile, document_folder(win)))) == 3

    # the same profile from another folder: another request, only the trials are read again
    regions, reads = win.graph.calls(REGION_NODE), win.graph.calls(TRIALS_NODE)
    assert win.open_path(str(b), ask=False)
    qtbot.waitUntil(lambda: tab.region_view.trials is not None and len(tab.region_view.trials) == 5, timeout=10000)
    assert win.graph.key_of(TRIALS_NODE).path == str(b.parent / "trials.csv")
    assert _drawn(tab) == (2, 3)
    assert win.graph.calls(TRIALS_NODE) == reads + 1
    assert win.graph.calls(REGION_NODE) == regions  # the region does not read the trials


def test_save_as_into_another_folder_reads_the_trials_from_there(win, qtbot, tmp_path, monkeypatch):
    a = _bench(tmp_path / "a", _rows([1, 1, 0]))
    other = tmp_path / "other"
    other.mkdir()
    (other / "trials.csv").write_text(_rows([0, 0]), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert win.open_path(str(a), ask=False)
    tab = _show(win, qtbot)
    assert _drawn(tab) == (2, 1)
    assert win.save_to(str(other / "p.json"))  # the saved file names trials.csv beside it
    qtbot.waitUntil(lambda: tab.region_view.trials is not None and len(tab.region_view.trials) == 2, timeout=10000)
    assert _drawn(tab) == (0, 2) and win.graph.key_of(TRIALS_NODE).path == str(other / "trials.csv")


def test_a_bad_trials_file_refuses_the_report_and_shows_on_the_tab(win, qtbot, tmp_path, monkeypatch, capfd):
    profile = _bench(tmp_path / "bench", BAD)
    trials = profile.parent / "trials.csv"
    out = tmp_path / "out"
    out.mkdir()
    monkeypatch.chdir(tmp_path)
    cli = run_cli(capfd, "report", profile, "-o", out / "cli.html")
    assert cli.returncode == 1 and cli.stderr.startswith("zwidth: error: ")
    cli_message = cli.stderr.removeprefix("zwidth: error: ").strip()

    assert win.open_path(str(profile), ask=False)
    shown: list[str] = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *a, **k: shown.append(a[2]) or QMessageBox.StandardButton.Ok)
    assert export_report(win, str(out / "gui.pdf")) is False
    assert export_report(win) is False  # refused before the file dialog (the modal guard would fail it)
    assert len(shown) == 2
    message = shown[0]
    assert cli_message in message  # the command line's words: the profile, the file, the line, the column
    assert str(trials) in message and "line 3" in message and "column 'k'" in message
    assert "'abc' is not a number" in message
    assert list(out.iterdir()) == []  # no report, no partial file

    tab = _show(win, qtbot)
    text = tab.trials_label.text()
    assert str(trials) in text and "line 3" in text and "column 'k'" in text and "not drawn" in text
    assert "line 3" in tab.region_view.warning_text and str(trials) in tab.region_view.warning_text
    assert tab.region_view.trials is None and _drawn(tab) == (0, 0)
    assert any("line 3" in n for n in tab.region_view.export_notes())  # a CSV export says why, too

    trials.write_text(_rows([1, 0]), encoding="utf-8")  # the file mended: the next refresh draws it
    tab.update_views()
    assert _drawn(tab) == (1, 1) and "line 3" not in tab.region_view.warning_text
    assert tab.trials_label.text().startswith("2 trials from trials.csv")
