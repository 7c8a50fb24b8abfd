"""The robust renderable space in the report and in ``zwidth export-plot --plot space --robust`` (issue 24).

A profile whose identified intervals bound a box: the report's renderable section adds the robust
space over the box's corners (rows whose numbers are :func:`analysis.study.robust_study`'s and the
intersection of the corners' M-widths) and its heat map overlays it with the tab's legend entry; a
profile without a box says why in one sentence and computes no robust space.  ``export-plot``
draws the robust space only when asked (``--robust corners|samples``), writes its series in the CSV,
and refuses it (status 2, with the reason) on a profile without a box.

The rigid profile on a coarse grid (:mod:`coarse_grids`): these tests check what is shown and where its
numbers come from, not the space's resolution.
"""

from __future__ import annotations

import csv
from collections import Counter
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from cli_runner import run_cli
from call_counts import count_calls
from coarse_grids import coarse_sections

from analysis.identify import parameter_box
from analysis.profiles import Profile, save_profile
from analysis.profiles.identification import IdentificationSection
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.sampled import box_corners, m_width
from analysis.study import (
    ROBUST_KINDS,
    ROBUST_SAMPLES,
    RenderableRequest,
    format_number,
    k_max_at,
    renderable_study,
    robust_study,
)
from analysis.study.renderable import robust_box_reason

#: the handle's mass and the first ground damping: a box of four corners around the rigid profile's device
INTERVALS = {"masses[0]": (0.4, 0.6), "ground_dampings[0]": (1.0, 3.0)}
#: the legend entry of the tab's overlay (RenderableSpaceView) over the corners
LEGEND = "robust over 4 corners of the identified box"


def _rigid() -> Profile:
    return coarse_sections(load_profile(bundled_profiles()["rigid"]), "renderable")


@pytest.fixture(scope="module")
def boxed() -> Profile:
    """The rigid profile with identified intervals that bound a box, as ``zwidth identify`` writes them."""
    return _rigid().replace(identification=IdentificationSection(INTERVALS))


@pytest.fixture(scope="module")
def robust_ref(boxed: Profile):
    """The robust space over the box's corners, as the tab's robust node computes it."""
    return robust_study(RenderableRequest.of(boxed, robust="corners"))


@pytest.fixture
def robust_calls(monkeypatch: pytest.MonkeyPatch) -> Iterator[Counter[str]]:
    """Counts the robust computations where the report's section looks them up."""
    import app.report.renderable_section as section

    counter = count_calls(monkeypatch, {name: ((section, name),) for name in ("robust_study", "robust_m_width")})
    yield counter


@pytest.fixture(scope="module")
def app():
    from app.report.figures import ensure_app

    return ensure_app()


def test_the_clis_robust_choices_are_the_studys():
    """The parser spells them out (it loads no analysis.study): they must stay the tab's."""
    from app import cli

    assert cli.ROBUST_CHOICES == tuple(ROBUST_KINDS)
    assert cli.ROBUST_SAMPLES == ROBUST_SAMPLES


# -- the report ------------------------------------------------------------------------------------
def test_the_section_has_the_robust_rows_of_the_box(boxed, robust_ref, robust_calls):
    from app.report.renderable_section import renderable_part

    assert robust_box_reason(boxed) is None
    part = renderable_part(boxed)
    (sec,) = part.sections
    labels = [row.label for row in sec.rows]
    for words in ("robust M-width, lowest mass", "robust M-width, highest mass", "robust M-width (", "robust volume",
                  "robust largest K at the rendered (M, B)"):
        assert any(label.startswith(words) and "4 corners of the identified box" in label for label in labels), words
    n = part.numbers
    assert n["renderable.robust.volume"][0] == robust_ref.volume
    env = boxed.renderable
    assert n["renderable.robust.k_max_at_environment"][0] == k_max_at(robust_ref, env.virtual_mass,
                                                                       env.virtual_damping)
    np.testing.assert_array_equal(part.results["renderable_robust"].k_max, robust_ref.k_max)
    # the robust M-width: the masses every corner renders at B = K = 0, the intersection of their M-widths
    req = RenderableRequest.of(boxed)
    widths = [m_width(d, req.delay_samples, req.velocity_filter, req.acceleration, req.qualities,
                      settings=req.settings) for d in box_corners(parameter_box(boxed.device, INTERVALS))]
    lo, hi = max(w.m_min for w in widths), min(w.m_max for w in widths)
    assert n["renderable.robust.m_min"][0] == lo < 0 < hi == n["renderable.robust.m_max"][0]
    assert n["renderable.robust.m_width"][0] == pytest.approx(hi - lo, rel=1e-12)
    # the box holds devices lighter and heavier than the profile's: they render less than it alone
    assert n["renderable.robust.volume"][0] < n["renderable.volume"][0]
    assert n["renderable.robust.m_width"][0] < n["renderable.m_width"][0]
    assert "every device of the identified parameter box renders" in sec.after[0]
    assert robust_calls == Counter({"robust_study": 1, "robust_m_width": 1})


@pytest.mark.parametrize("intervals", [None, {"masses[0]": (0.4, float("inf"))}],
                         ids=["no-intervals", "open-interval"])
def test_without_a_box_one_sentence_says_why(intervals, robust_calls):
    from app.report.renderable_section import renderable_part

    profile = _rigid()
    if intervals is not None:
        profile = profile.replace(identification=IdentificationSection(intervals))
    reason = robust_box_reason(profile)
    assert reason is not None and ("no identified intervals" in reason or "masses[0] open" in reason)
    part = renderable_part(profile)
    (sec,) = part.sections
    assert not any("robust" in row.label for row in sec.rows)
    assert not any(key.startswith("renderable.robust") for key in part.numbers)
    assert "renderable_robust" not in part.results
    assert sec.after == (f"No robust space over an identified box: {reason}.",)
    assert robust_calls == Counter()


def test_the_report_leaves_the_robust_space_out_when_the_section_is_not_asked(boxed, robust_calls):
    """Lazy: only the renderable section computes it."""
    from app.report.content import gather

    content = gather(boxed, parts=())
    assert "renderable_robust" not in content.results
    assert robust_calls == Counter()


def test_the_reports_figure_and_html_overlay_the_robust_space(boxed, robust_ref, app):
    from app.report.content import gather
    from app.report.figures import make_view
    from app.report.html import report_html

    content = gather(boxed, date="d", parts={"renderable"})  # the renderable section whole, as the report's
    fig = make_view(content, "renderable_space")
    assert fig.view.robust_drawn
    np.testing.assert_array_equal(fig.view.robust_shown(), robust_ref.k_max)
    assert LEGEND in fig.view.legend.getLabel(fig.view.robust_legend).text
    assert "Dashed: the robust space over the 4 corners of the identified box" in fig.caption
    page = report_html(content, [fig])
    svg = page[page.index("<figure"):]
    assert LEGEND in svg  # the legend entry in the inline SVG
    assert "robust volume (4 corners of the identified box)" in page
    assert format_number(robust_ref.volume, rich=True) in page  # the row's number, as the page prints it
    fig.view.deleteLater()


# -- export-plot -----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def boxed_path(boxed: Profile, tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("robust") / "boxed.json"
    save_profile(boxed, path)
    return path


@pytest.fixture(scope="module")
def plain_path(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("plain") / "plain.json"
    save_profile(_rigid(), path)
    return path


def _robust_columns(path: Path) -> tuple[list[str], np.ndarray]:
    """The CSV's robust K_max columns (headers and values, one column per mass)."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    cols = [i for i, h in enumerate(rows[0]) if h.startswith("robust K_max at M = ") and h.endswith("K_max [N/m]")]
    return [rows[0][i] for i in cols], np.array([[float(r[i]) for i in cols] for r in rows[1:]])


def test_export_plot_robust_corners_svg_and_csv(capfd, tmp_path, boxed_path, robust_ref, app):
    svg = tmp_path / "space.svg"
    r = run_cli(capfd, "export-plot", boxed_path, "--plot", "space", "--robust", "corners", "-o", svg)
    assert r.returncode == 0, r.stderr
    assert LEGEND in svg.read_text(encoding="utf-8")
    out = tmp_path / "space.csv"
    r = run_cli(capfd, "export-plot", boxed_path, "--plot", "space", "--robust", "corners", "-o", out)
    assert r.returncode == 0, r.stderr
    headers, k = _robust_columns(out)
    assert len(headers) == robust_ref.mass.size and all("4 corners of the identified box" in h for h in headers)
    np.testing.assert_array_equal(k.T, robust_ref.k_max)  # one column per mass, B down the rows


def test_export_plot_robust_samples(capfd, tmp_path, boxed_path, boxed):
    out = tmp_path / "samples.csv"
    r = run_cli(capfd, "export-plot", boxed_path, "--plot", "space", "--robust", "samples", "--samples", "3",
                "-o", out)
    assert r.returncode == 0, r.stderr
    headers, k = _robust_columns(out)
    assert all("3 samples of the identified box" in h for h in headers)
    ref = robust_study(RenderableRequest.of(boxed, robust="samples", samples=3))
    assert ref.devices == 3
    np.testing.assert_array_equal(k.T, ref.k_max)


def test_export_plot_without_robust_computes_none(capfd, tmp_path, boxed_path, boxed, robust_calls, app):
    """The default is off: on a profile with a box, no robust space is computed or drawn."""
    out = tmp_path / "space.csv"
    r = run_cli(capfd, "export-plot", boxed_path, "--plot", "space", "-o", out)
    assert r.returncode == 0, r.stderr
    assert robust_calls == Counter()
    headers, _ = _robust_columns(out)
    assert headers == []
    with open(out, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    own = renderable_study(boxed).space.k_max
    assert len(rows[0]) == 2 * own.shape[0]  # the device's own K_max against B, one column pair per mass


def test_export_plot_refuses_the_robust_space_without_a_box(capfd, tmp_path, plain_path):
    out = tmp_path / "space.svg"
    r = run_cli(capfd, "export-plot", plain_path, "--plot", "space", "--robust", "corners", "-o", out)
    assert r.returncode == 2
    reason = robust_box_reason(load_profile(plain_path))
    assert f"--robust corners: no robust space: {reason}" in r.stderr
    assert not out.exists()


@pytest.mark.parametrize(("args", "words"), [
    (["--plot", "m-width", "--robust", "corners"], "only --plot space draws the robust space"),
    (["--plot", "space", "--samples", "3"], "--samples needs --robust samples"),
    (["--plot", "space", "--robust", "samples", "--samples", "0"], "--samples must be between 1 and"),
    (["--plot", "space", "--robust", "edges"], "invalid choice: 'edges'"),
])
def test_export_plot_robust_usage_errors(capfd, tmp_path, boxed_path, args, words):
    out = tmp_path / "x.png"
    r = run_cli(capfd, "export-plot", boxed_path, *args, "-o", out)
    assert r.returncode == 2 and words in r.stderr, r.stderr
    assert not out.exists()


def test_the_report_takes_corners_of_a_small_box_and_samples_of_a_large_one(boxed: Profile):
    """Four corners (two boxed parameters) are taken whole; an identified HBFD boxes up to 14
    parameters (16384 corners, each a whole space), so a box of more than four parameters is taken
    as ROBUST_SAMPLES seeded samples; without a box nothing robust is asked."""
    from app.report.renderable_section import report_robust_kind

    assert report_robust_kind(boxed) == "corners"
    assert report_robust_kind(_rigid()) == "off"
    hbfd = coarse_sections(load_profile(bundled_profiles()["hbfd"]), "renderable")
    keys = ("masses[0]", "masses[1]", "stiffnesses[0]", "dampings[0]", "ground_dampings[3]")
    box = {k: (0.9 * v, 1.1 * v) for k, v in ((k, _value(hbfd, k)) for k in keys)}
    five = hbfd.replace(identification=IdentificationSection(box))
    assert report_robust_kind(five) == "samples"
    assert RenderableRequest.of(five, robust="samples").robust.label(five.device) == \
        f"{ROBUST_SAMPLES} samples of the identified box"
    four = hbfd.replace(identification=IdentificationSection({k: box[k] for k in keys[:4]}))
    assert report_robust_kind(four) == "corners" and 2 ** 4 == ROBUST_SAMPLES


def _value(profile: Profile, key: str) -> float:
    from analysis.identify import device_value

    return device_value(profile.device, key)
