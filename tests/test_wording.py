"""Words and numbers a new user reads (issue 13, "Limits and messages"): each verdict says which
question it answers, the default scenario follows the display, messages give reasons."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from analysis.profiles.files import unwritable_reason
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.study import (
    design_summary,
    format_design,
    format_number,
    headline,
    scenario_matches,
    simulation,
    simulation_section,
)
from cli_runner import run_cli

REPO = Path(__file__).resolve().parent.parent


def profile(name: str, **changes):
    p = load_profile(bundled_profiles()[name])
    return p.replace(**changes) if changes else p


def test_the_headline_names_its_question():
    h = headline(profile("eom"), with_designs=False)
    assert not h.stable
    assert h.question == "Virtual coupling (Llewellyn, eq. 9)"
    assert h.verdict() == "Virtual coupling (Llewellyn, eq. 9): not unconditionally stable"
    a = headline(profile("hbfd", display="admittance"), with_designs=False)
    assert a.question == "Virtual coupling (Llewellyn, eq. 21)"


def test_the_default_scenario_follows_the_display():
    hb = profile("hbfd")
    assert hb.simulation.scenario.name == "impedance_worst_case"
    assert simulation_section(hb) is hb.simulation
    adm = hb.replace(display="admittance")
    assert not scenario_matches(adm, hb.simulation.scenario)
    sec = simulation_section(adm)
    assert sec.scenario.name == "admittance_worst_case" and not sec.scenario.wall
    assert sec.options == hb.simulation.options  # the saved effects are kept
    custom = hb.simulation.scenario.replace(name="custom")
    assert scenario_matches(adm, custom)  # the user's own scenario is never replaced
    # with ideal sensors the simulation agrees with the exact linear limit ("no stable m_c")
    ideal = adm.replace(simulation=None)
    assert simulation(ideal).verdict.kind == "divergent"


def test_design_text_has_no_empty_ranges():
    text = format_design(design_summary(profile("eom"), "admittance", points=3))
    assert "b_c in none" not in text and "m_c = 0.1 kg: no b_c satisfies eq. 21" in text
    text = format_design(design_summary(profile("eom"), points=3))
    assert "k_c <= infeasible" not in text
    assert "b_c = 1 N s/m: no k_c satisfies eq. 9 (the bound is exceeded at 624.282 rad/s)" in text
    text = format_design(design_summary(profile("hbfd"), points=3))
    assert "b_c = 100 N s/m: k_c <= 117118 N/m (binds at 79.0744 rad/s)" in text


def test_cannot_write_says_why(tmp_path, capsys):
    missing = tmp_path / "no" / "such" / "r.html"
    assert unwritable_reason(missing) == f"No such folder: {tmp_path / 'no'}"
    assert unwritable_reason(tmp_path / "ok.html") is None
    (tmp_path / "file").write_text("x")
    assert unwritable_reason(tmp_path / "file" / "r.pdf") == f"Not a folder: {tmp_path / 'file'}"
    assert unwritable_reason(tmp_path) == f"Is a folder: {tmp_path}"
    rigid = bundled_profiles()["rigid"]
    r = run_cli(capsys, "report", rigid, "-o", missing, "--no-sampled")
    assert r.returncode == 1
    assert r.stderr == f"zwidth: error: cannot write {missing}: No such folder: {tmp_path / 'no'}\n"


def test_reserve_is_printed_by_the_one_rule():
    assert format_number(-452.0, 4, scale=100.0, rich=True) == "−4.52×10<sup>4</sup>"
    assert format_number(1.62e-9, 4, scale=100.0, rich=True) == "1.62×10<sup>−7</sup>"
    assert format_number(math.inf) == "∞"


def test_one_year_for_the_adams_paper():
    """The paper is Proc. ASME IMECE, Anaheim, November 1998 (its own references go up to 1998)."""
    years = set()
    files = [REPO / "README.md", *(REPO / "docs").rglob("*.md"), *(REPO / "app").rglob("*.py"),
             *(REPO / "analysis").rglob("*.py")]
    for f in files:
        if "_build" in f.parts:
            continue
        text = f.read_text(encoding="utf-8")
        years |= set(re.findall(r"Adams[^()\n]{0,80}\((19\d\d)\)", text))
        years |= set(re.findall(r"Hannaford[^\n]{0,200}?(19\d\d)", text))
    assert years == {"1998"}


@pytest.mark.parametrize("symbol, rich", [("Re(1/Z_c)", "Re(1/Z<sub>c</sub>)"), ("k_c", "k<sub>c</sub>"),
                                          ("ω", "ω")])
def test_axis_titles_use_subscripts(symbol, rich):
    from app.views.base import rich_label

    assert rich_label(symbol) == rich


def test_rich_numbers_typesets_every_e_number_as_format_number_does():
    from analysis.study import format_number, rich_numbers

    for x in (3.804e7, -4.5e-8, 1.62e-7, 2.55e11):
        plain, rich = format_number(x, 4), format_number(x, 4, rich=True)
        assert "e" in plain
        assert rich_numbers(f"area {plain} N") == f"area {rich} N"
    assert rich_numbers("k1e5 and b_2e3 stay") == "k1e5 and b_2e3 stay"  # names, not numbers


def test_superscript_numbers_is_plain_text_typesetting():
    from analysis.study import superscript_numbers

    assert superscript_numbers("rises to 2.55e+11 N·s/m above 3058 rad/s") == "rises to 2.55×10¹¹ N·s/m above 3058 rad/s"
    assert superscript_numbers("-4.5e-08") == "−4.5×10⁻⁸"
