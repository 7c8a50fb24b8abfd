"""Numbers a person reads in the GUI are typeset (issue 22): a true minus "−" and superscript powers
of ten in legends, plot labels, tick labels, the cursor's status text and the tabs' sentences, while
what scripts read (``zwidth analyze``'s text, a view's CSV) keeps ASCII numbers."""

from __future__ import annotations

import dataclasses
import re

import pytest

from analysis.profiles import RenderableSection
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import display_kind, format_number, headline, renderable_study
from app.core.nodes_renderable import RENDERABLE_NODE
from app.tabs.renderable_tab import RenderableTab, width_text
from app.views.export import csv_text
from app.views.stability_plot import StabilityPlot
from cli_runner import run_cli

#: an ASCII hyphen-minus directly before a digit: what a typeset GUI text never shows
ASCII_MINUS = re.compile(r"-\.?\d")
#: a negative rendered mass (the loader accepts -MASS.hi to MASS.hi) on a coarse grid
NEGATIVE_MASS = -0.125
COARSE = RenderableSection(mass_points=9, damping_points=11, qualities=("stable", "passive"),
                           virtual_mass=NEGATIVE_MASS)


def typeset(text: str) -> bool:
    return "−" in text and not ASCII_MINUS.search(text)


def test_binding_label_ticks_and_cursor_typeset_the_minus(qtbot):
    p = load_profile(bundled_profiles()["eom"])  # impedance: reserve -786.1 %, not unconditionally stable
    h = headline(p, with_designs=False)
    assert h.stability_reserve < 0
    view = StabilityPlot()
    qtbot.addWidget(view)
    view.update_result(display_kind(p).evaluate(p), mode="values")
    label = view.worst_line.label.format
    assert "reserve −786 %" in label and typeset(label)
    assert f"reserve {format_number(100 * h.stability_reserve, 3, style='text')} %" in label
    # the cursor's status text: a negative Re(...) value and a 1e-05 frequency
    cursor = view.cursor_text(1e-5, -3.25)
    assert "1×10⁻⁵" in cursor and "−3.25" in cursor and not ASCII_MINUS.search(cursor) and "e-" not in cursor
    # the linear value axis labels its negative ticks with the minus sign, small ones with a power of ten
    ticks = view.plot.getAxis("left").tickStrings([-2e-5, -1e-5, 0.0, 1e-5], 1.0, 1e-5)
    assert ticks[:2] == ["−2×10⁻⁵", "−1×10⁻⁵"] and not any(ASCII_MINUS.search(t) for t in ticks)
    # the CSV of the same view keeps ASCII numbers
    csv = csv_text(view)
    assert "−" not in csv and "×10" not in csv


def test_zwidth_analyze_of_the_same_profile_stays_ascii(capsys):
    r = run_cli(capsys, "analyze", bundled_profiles()["eom"])
    assert r.returncode == 0
    assert "stability reserve -786.1 %" in r.stdout  # the CLI's own digits, a hyphen-minus
    assert "−" not in r.stdout and "×10" not in r.stdout and "⁻" not in r.stdout
    assert re.search(r"\d\.\d+e-\d\d", r.stdout)  # its small numbers in e notation (b_min 1.0478e-09 ...)


def test_the_m_width_in_words_typesets_a_negative_lowest_mass(hbfd_profile):
    study = renderable_study(hbfd_profile.replace(renderable=COARSE))
    assert study.width.m_min < 0
    text = width_text(study)
    assert text.startswith("M-width (all qualities): −") and typeset(text)
    assert f"{format_number(study.width.m_min, style='text')} to" in text


@pytest.fixture
def rwin(qtbot, settings, hbfd_profile):
    from conftest import _main_window

    yield from _main_window(qtbot, settings, hbfd_profile.replace(renderable=COARSE))


def test_the_renderable_tab_shows_a_negative_rendered_mass_with_the_minus_sign(rwin, qtbot):
    tab = next(t for t in rwin.analysis_tabs if isinstance(t, RenderableTab))
    rwin.tabs.setCurrentWidget(tab)
    qtbot.waitUntil(lambda: rwin.graph.is_fresh(RENDERABLE_NODE) and tab.space_view.study is not None,
                    timeout=60000)
    summary = tab.summary.text()
    assert "Rendered (M, B) = (−0.125 kg," in summary and typeset(summary)
    assert f"Rendered (M, B) = ({format_number(NEGATIVE_MASS, style='text')} kg," in summary
    # its CSV export names each curve by its mass in ASCII (negative masses of the grid included)
    csv = csv_text(tab.space_view)
    assert "K_max at M = -" in csv and "−" not in csv


def test_a_profile_with_negative_numbers_keeps_them_ascii_in_analyze(tmp_path, capsys, hbfd_profile):
    """The Renderable tab's profile (a negative rendered mass) through ``zwidth analyze``: ASCII only."""
    from analysis.profiles import save_profile

    path = tmp_path / "negative.json"
    save_profile(dataclasses.replace(hbfd_profile, renderable=COARSE), path)
    r = run_cli(capsys, "analyze", path)
    assert r.returncode == 0 and "−" not in r.stdout and "×10" not in r.stdout
    assert re.search(r"stability reserve -\d", r.stdout)  # the admittance block's negative reserve


def test_status_messages_typeset_their_numbers():
    """The design and robust-design status messages print numbers in the GUI's text form."""
    from analysis.study import RobustDesigns
    from app.window.design_actions import status_number
    from app.window.robust_actions import robust_changes

    assert status_number(-1.25e-5, 6) == "−1.25×10⁻⁵" == format_number(-1.25e-5, 6, style="text")
    from analysis.identify.robust import RobustDamping
    from tests.hbfd_fixtures import make_hbfd

    dev = make_hbfd()
    damping = RobustDamping(mc=0.5, low=2.5e-3, high=4.0e7, low_device=dev, high_device=dev, low_binding={},
                            high_binding={}, nominal=(2.5e-3, 4.0e7), evaluations=2)
    designs = RobustDesigns(impedance=False, intervals={}, stiffness=None, damping=damping, coupling=0.5,
                            holds=True)
    edits, message = robust_changes(designs)
    assert message.endswith("[0.0025, 4×10⁷]") and "e+" not in message and "e-" not in message
