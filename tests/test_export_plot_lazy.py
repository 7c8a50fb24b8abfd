"""export-plot computes only what its figure draws (the product rule: skip the work the view does not
need), and the report still computes every section, whole and unchanged.

The work is counted, not timed: each section's study function is wrapped, counting its calls, and a
section the figure does not draw must not be called at all.
"""

from __future__ import annotations

import csv
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import PySide6  # noqa: F401 - the figures need Qt: fail loudly, never skip
import pytest

from analysis.profiles import Profile
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.transparency.design import WallDesign
from call_counts import count_calls
from coarse_grids import coarse_sections

ALL_SECTIONS = Path(__file__).parent / "data" / "saved_profiles" / "all_sections.json"


def _all_sections() -> Profile:
    """The profile with every section, its renderable space, workspace map and Z-width region on
    coarse grids: which study a figure calls does not depend on the grids' sizes (the full grids
    cost about 10 s here, issue 21)."""
    return coarse_sections(load_profile(ALL_SECTIONS), "renderable", "multidof", "controller")


def _sentinels() -> dict[str, tuple[tuple[object, str], ...]]:
    """Each part of the report -> the study functions (owner, name) that compute it, where its section
    looks them up."""
    import app.report.content as content
    import app.report.identify_section as identify_section
    import app.report.observer_section as observer_section
    import app.report.renderable_section as renderable_section
    import app.report.workspace_section as workspace_section
    import app.report.zwidth_section as zwidth_section

    return {
        "chart": ((content, "design_chart"),),
        "wall": ((WallDesign, "optimal_damping"), (WallDesign, "tradeoff")),
        "observer": ((observer_section, "observer_response"), (observer_section, "observer_coupling")),
        "sampled": ((content, "stability_map_result"), (content, "simulation")),
        "identification": ((identify_section, "fit_curves"),),
        "zwidth_region": ((zwidth_section, "zwidth_region_result"),),
        "zwidth_optimum": ((zwidth_section, "filter_optimum"), (content, "filter_optimum")),
        "renderable": ((renderable_section, "renderable_study"),),
        "workspace_map": ((workspace_section, "workspace_study"),),
        "workspace_point": ((workspace_section, "workspace_point"),),
    }


@pytest.fixture
def calls(monkeypatch: pytest.MonkeyPatch) -> Iterator[Counter[str]]:
    """Counts the calls of every section's study functions, by part."""
    counter = count_calls(monkeypatch, _sentinels())
    yield counter


@pytest.fixture(scope="module")
def app():
    from app.report.figures import ensure_app

    return ensure_app()


def test_every_part_is_counted_and_every_figure_names_known_parts():
    from app.report.content import PARTS
    from app.report.figures import FIGURE_KEYS, figure_parts

    assert set(_sentinels()) == set(PARTS)
    for key in FIGURE_KEYS:
        assert figure_parts([key]) <= set(PARTS), key
    assert figure_parts(FIGURE_KEYS) == set(PARTS)  # every part is drawn by some figure
    with pytest.raises(ValueError, match="unknown plot"):
        figure_parts(["nope"])


def test_unknown_parts_are_refused():
    from app.report.content import gather

    with pytest.raises(ValueError, match="zwidth_everything"):
        gather(load_profile(bundled_profiles()["hbfd"]), parts={"zwidth_everything"})


@pytest.mark.parametrize("name", ["hbfd", "eom"])
def test_the_report_gathers_every_section_whole(name, calls):
    """The report (parts=None) is the old gather: every section function called whole, in order, with
    its numbers and results, each study function once."""
    from app.report import content as c

    profile = load_profile(bundled_profiles()[name])
    got = c.gather(profile, date="d")
    assert c.gather(profile, date="d", parts=c.PARTS).sections == got.sections
    present = {"chart"} | {p for p in ("wall", "observer") if getattr(profile, p) is not None} \
        | ({"sampled"} if profile.simulation is not None else set())
    assert set(calls) == present
    numbers = got.numbers
    assert len(numbers) > 30
    if name == "eom":
        assert numbers["wall.optimum.bc"][0] == got.results["optimum"].bc
        assert 0 < numbers["wall.optimum.bc"][0] < float("inf")
    else:
        assert 0.0 <= numbers["map.stable_share"][0] <= 100.0


def _parts_of(key: str) -> frozenset[str]:
    from app.report.figures import figure_parts

    return figure_parts([key])


@pytest.mark.parametrize("key", ["bound", "chart", "tradeoff_j", "step", "map", "scenario_force", "observer_plant",
                                 "observer_coupling", "identify", "zwidth_region", "filter_optimum",
                                 "renderable_space", "workspace_polar"])
def test_a_figure_gathers_only_its_parts(key, app, calls):
    """On a profile with every section (coarse grids: :func:`_all_sections`), gathering one figure's
    parts calls only their study functions, and the figure is drawn from them."""
    from app.report.content import gather
    from app.report.figures import make_view

    profile = _all_sections()
    content = gather(profile, parts=_parts_of(key))
    assert set(calls) == set(_parts_of(key)), calls
    fig = make_view(content, key)
    assert fig is not None and fig.view.export_series()
    fig.view.deleteLater()


def test_the_region_alone_has_the_reports_region(calls):
    """The region computed alone is the report's (same area), without the optimum (coarse grids,
    :func:`_all_sections`)."""
    from app.report.content import gather

    profile = _all_sections()
    alone = gather(profile, parts={"zwidth_region"})
    assert "zwidth_optimum" not in alone.results and not any("Z-width region" in s.title for s in alone.sections)
    assert calls == Counter({"zwidth_region": 1})
    from app.report.zwidth_section import zwidth_results

    full = zwidth_results(profile)
    assert alone.results["zwidth_region"].area_linear == full["zwidth_region"].area_linear > 0
    assert alone.results["zwidth_study"].trials == full["zwidth_study"].trials


def _rows(path: Path) -> list[list[str]]:
    with open(path, newline="", encoding="utf-8") as f:
        return [r for r in csv.reader(f) if r and not r[0].startswith("#")]


def test_export_plot_bound_computes_no_other_section(app, calls, tmp_path):
    """`export-plot --plot bound` on a profile with every section: the stability result only."""
    from app.cli import main

    out = tmp_path / "bound.csv"
    assert main(["export-plot", str(ALL_SECTIONS), "--plot", "bound", "-o", str(out)]) == 0
    assert calls == Counter()
    assert len(_rows(out)) > 10


def test_export_plot_zwidth_region_skips_the_filter_optimum(app, calls, tmp_path):
    from app.cli import main

    out = tmp_path / "region.csv"
    assert main(["export-plot", str(bundled_profiles()["hbfd"]), "--plot", "zwidth-region", "-o", str(out)]) == 0
    assert calls == Counter({"zwidth_region": 1})
    assert len(_rows(out)) > 10
