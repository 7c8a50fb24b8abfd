"""One study, three front ends (issue 12): ``zwidth analyze --json``, the HTML report and the GUI
verdict give the same headline numbers and designs as :func:`analysis.study.headline`, for
every bundled profile.  The JSON carries full precision; the report and the verdict are parsed
back from their printed text and must agree to the digits they print."""

from __future__ import annotations

import json
import math
import os
import re

import numpy as np
import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from analysis.profiles.io import bundled_profiles, load_profile  # noqa: E402
from analysis.study import HEADLINE_KEYS, Headline, display_kind, headline  # noqa: E402
from cli_runner import run_cli  # noqa: E402

PROFILES = sorted(bundled_profiles().items())
IDS = [name for name, _ in PROFILES]
#: the verdict numbers compared everywhere (``stable`` is compared as a yes/no)
NUMBERS = ("stability_reserve", "binding_frequency", "worst_margin", "min_eta", "k_max", "b_min")


@pytest.fixture(scope="module")
def reference() -> dict[str, Headline]:
    return {name: headline(load_profile(path)) for name, path in PROFILES}


def parse_printed(text: str) -> tuple[float | None, int]:
    """A printed number back as (value, significant digits printed): plain or Qt rich text,
    with or without a unit; "%" divides by 100; words for infinite and missing values."""
    t = re.sub(r"×10<sup>([^<]+)</sup>", r"e\1", text).replace("−", "-")
    t = re.sub(r"<[^>]+>", "", t).strip()
    word = t.split()[0] if t.split() else t
    special = {"unbounded": math.inf, "∞": math.inf, "-unbounded": -math.inf, "-∞": -math.inf, "n/a": math.nan,
               "–": math.nan, "infeasible": None}
    if word in special:
        return special[word], 0
    mant = word.split("e")[0].lstrip("-").replace(".", "").lstrip("0")
    value = float(word)
    return (value / 100.0 if "%" in t else value), max(len(mant), 1)


def assert_printed(text: str, expected: float | None, what: str) -> None:
    value, digits = parse_printed(text)
    if expected is None or value is None:
        assert value is None and expected is None, (what, text, expected)
    elif not math.isfinite(expected):
        assert value == expected or (math.isnan(value) and math.isnan(expected)), (what, text, expected)
    else:
        assert value == pytest.approx(expected, rel=0.51 * 10.0 ** (1 - digits), abs=1e-300), (what, text, expected)


def _json_number(x: object) -> float | None:
    return None if x is None else float(x)  # "inf", "-inf" and "nan" parse as floats too


# -- the CLI ---------------------------------------------------------------------------------------

def _json_designs(kind_name: str, section: dict) -> dict[str, float | None]:
    d = section["design"]
    if display_kind(kind_name).is_impedance:
        return {"bc": d["bc"], "kc_max": d["kc_max"], "kc_max_frequency": d["frequency"]}
    fd, mm = d["feasible_damping"], d["min_mass"] or {}
    return {"mc": fd["mc"], "bc_low": fd["low"], "bc_low_frequency": fd["low_frequency"], "bc_high": fd["high"],
            "bc_high_frequency": fd["high_frequency"], "min_mc": mm.get("mc"), "min_mc_bc": mm.get("bc"),
            "min_mc_frequency": mm.get("frequency")}


@pytest.mark.parametrize("name,path", PROFILES, ids=IDS)
def test_cli_json_equals_study(capsys, reference, name, path):
    proc = run_cli(capsys, "analyze", path, "--json")
    assert proc.returncode == 0, proc.stderr
    h = reference[name]
    section = json.loads(proc.stdout)[h.kind.name]
    assert section["stable"] is h.stable
    for key in HEADLINE_KEYS[1:]:
        assert _json_number(section[key]) == pytest.approx(h.value(key), rel=1e-12, nan_ok=True), key
    designs = _json_designs(h.kind.name, section)
    for key in h.kind.design_keys:
        want, got = h.designs[key], _json_number(designs[key])
        assert (got is None and want is None) or got == pytest.approx(want, rel=1e-12, nan_ok=True), key


@pytest.mark.parametrize("name,path", PROFILES, ids=IDS)
def test_cli_text_headline(capsys, reference, name, path):
    """The text output leads with the reserve and the binding frequency, printed as everywhere."""
    proc = run_cli(capsys, "analyze", path)
    assert proc.returncode == 0, proc.stderr
    h = reference[name]
    block = proc.stdout.split(f"{h.kind.title}, coupling")[1]
    line = next(x for x in block.splitlines() if "stability reserve" in x)
    assert h.text("stability_reserve") in line
    assert h.text("binding_frequency") in line
    assert_printed(line.split("stability reserve")[1], h.stability_reserve, "reserve")
    assert_printed(line.split("binding at")[1], h.binding_frequency, "binding frequency")


# -- the HTML report -------------------------------------------------------------------------------

def _report_tables(page: str) -> dict[str, dict[str, list[str]]]:
    """{section title: {quantity label: [printed values, in order]}} from the report's tables."""
    out: dict[str, dict[str, list[str]]] = {}
    for chunk in page.split("<h2>")[1:]:
        title = chunk.split("</h2>")[0]
        rows = re.findall(r"<tr[^>]*><td>(.*?)</td><td>.*?</td><td class=\"v\">(.*?)</td>", chunk)
        table: dict[str, list[str]] = {}
        for label, value in rows:
            table.setdefault(label, []).append(value)
        out[title] = table
    return out


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> dict[str, str]:
    from app.report import build_report
    from app.report.figures import ensure_app

    ensure_app()
    tmp = tmp_path_factory.mktemp("consistency")
    out = {}
    for name, path in PROFILES:
        page = tmp / f"{name}.html"
        build_report(load_profile(path), page, source=str(path), sampled=False)
        out[name] = page.read_text(encoding="utf-8")
    return out


@pytest.mark.parametrize("name", IDS)
def test_html_report_equals_study(reference, reports, name):
    h = reference[name]
    tables = _report_tables(reports[name])
    verdict, zrange, design = tables["Verdict"], tables["Impedance range (Z-width)"], tables["Design results"]
    assert verdict[h.quantity("stable").name] == ["yes" if h.stable else "no"]
    for key in NUMBERS + ("worst_frequency",):
        table = zrange if key in ("k_max", "b_min") else verdict
        (printed,) = table[h.quantity(key).name]
        assert printed == h.quantity(key).number(h.value(key), rich=True), key  # the page typesets
        assert_printed(printed + (" %" if key == "stability_reserve" else ""), h.value(key), key)
    for key in h.kind.design_keys:
        (printed,) = design[h.quantity(key).name]
        assert printed == h.quantity(key).number(h.designs[key], rich=True), key
        assert_printed(printed, h.designs[key], key)


# -- the GUI verdict -------------------------------------------------------------------------------

def _verdict_texts(h: Headline, profile) -> dict[str, str]:
    from app.report.figures import ensure_app
    from app.views.verdict import VerdictView

    ensure_app()
    view = VerdictView()
    view.update_result(h.kind.evaluate(profile))
    texts = {"badge": view.badge.text(), "stability_reserve": view.reserve.text(),
             "binding_frequency": view.frequency.text(), "worst_margin": view.margin.text(),
             "min_eta": view.eta.text(), "k_max": view.kmax.text(), "b_min": view.bmin.text()}
    view.deleteLater()
    return texts


@pytest.mark.parametrize("name,path", PROFILES, ids=IDS)
def test_gui_verdict_equals_study(reference, name, path):
    h = reference[name]
    texts = _verdict_texts(h, load_profile(path))
    assert ("Not" not in texts["badge"]) is h.stable
    for key in NUMBERS:
        assert_printed(texts[key], h.value(key), key)
        assert texts[key].startswith(h.text(key, rich=True)), (key, texts[key])  # the study's one rule


# -- the study's own contracts (Qt-free) -----------------------------------------------------------

def test_display_kinds_are_the_one_mapping():
    from analysis.study import ADMITTANCE, IMPEDANCE

    profile = load_profile(bundled_profiles()["hbfd"])
    assert display_kind("impedance") is IMPEDANCE and display_kind("admittance") is ADMITTANCE
    assert display_kind(profile) is display_kind(profile.display)
    assert display_kind(IMPEDANCE.evaluate(profile)) is IMPEDANCE
    assert IMPEDANCE.coupling(profile) == (profile.kc, profile.bc)
    assert ADMITTANCE.coupling(profile) == (profile.mc, profile.bc_adm)
    assert IMPEDANCE.edits_from_chart(10.0, 2e4) == {"bc": 10.0, "kc": 2e4}
    assert ADMITTANCE.chart_point(profile) == (profile.mc, profile.bc_adm)
    with pytest.raises(ValueError):
        display_kind("hybrid")


def test_quantity_formatting_rule():
    from analysis.study import QUANTITIES, quantity

    reserve = QUANTITIES["stability_reserve"]
    assert reserve.format(0.123456) == "12.35 %" and reserve.parse("12.35 %") == pytest.approx(0.1235)
    assert quantity("k_max").format(117118.4) == "117118 N/m"
    assert quantity("k_max").format(1.5e7, rich=True) == "1.5×10<sup>7</sup> N/m"
    assert quantity("worst_margin", "m/(N·s)").format(-2.5e-6) == "-2.5e-06 m/(N·s)"
    assert quantity("kc_max").format(None) == "infeasible"
    assert quantity("kc_max").format(math.inf) == "∞"
    assert quantity("min_eta").format(math.nan) == "n/a"


@pytest.mark.parametrize("display", ["impedance", "admittance"])
def test_design_chart_progress_and_cancel(display):
    """The chart reports each point and stops at a cancel; the values are the analysis chart's."""
    from analysis.study import design_chart

    profile = load_profile(bundled_profiles()["rigid"])
    kind = display_kind(display)
    seen: list[tuple[int, int]] = []
    full = design_chart(profile, kind, points=5, progress=lambda d, t: seen.append((d, t)))
    assert seen == [(i, 5) for i in range(1, 6)] and full.display == display
    disp = kind.build(profile)
    if kind.is_impedance:
        direct = disp.stiffness_chart(np.geomspace(1.0, 1e4, 5))
        np.testing.assert_array_equal(full.chart.kc, direct.kc)
    else:
        direct = disp.mass_chart(np.geomspace(1e-3, 1e3, 5))
        np.testing.assert_array_equal(full.chart.low, direct.low)
    calls = []
    assert design_chart(profile, kind, points=5, cancelled=lambda: len(calls) >= 2,
                        progress=lambda d, t: calls.append(d)) is None
    assert calls == [1, 2]


def test_exact_chart_and_map_hooks():
    from analysis.sampled import critical_stiffness
    from analysis.study import exact_chart, map_params, map_point, stability_map

    profile = load_profile(bundled_profiles()["rigid"])
    steps: list[int] = []
    chart = exact_chart(profile, bc_range=(1.0, 100.0), points=3, progress=lambda d, t: steps.append(d))
    assert steps == [1, 2, 3]
    assert chart.kc[1] == critical_stiffness(profile.device, 10.0)
    assert exact_chart(profile, points=3, cancelled=lambda: True) is None
    params = {**map_params(profile), "points": 6}
    assert (params["x"], params["y"]) == display_kind(profile).map_axes[0]
    m = stability_map(profile, params)
    assert m.spectral_radius.shape == (6, 6) and np.all(m.spectral_radius > 0)
    assert stability_map(profile, params, cancelled=lambda: True) is None
    x, y = map_point(profile, params["x"], params["y"])
    assert x == display_kind(profile).coupling(profile)[0] and y is not None
