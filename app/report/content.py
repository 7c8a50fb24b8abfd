"""Everything a report says, gathered from the analysis core (no Qt).

Text is kept as small HTML fragments (``k<sub>c</sub>``), which both the PDF writer (through
``QTextDocument``) and the HTML writer understand.  Numbers are printed by :func:`num`, and
:attr:`ReportContent.numbers` keeps the raw values next to their printed text, so tests can
check that the report says what the analysis computed.  Each section is a function that returns
a :class:`~app.report.model.Part` (its sections, numbers and results); :func:`gather` joins them.

The report asks for every part; ``zwidth export-plot`` asks only for the parts its figure draws
(:data:`PARTS`; :func:`app.report.figures.figure_parts` names them for each figure), so no section
computes what the plot does not show.
"""

from __future__ import annotations

import datetime as _dt
import html
import math
from collections.abc import Callable, Collection
from typing import Any

import numpy as np

from analysis.profiles import Profile
from analysis.study import (
    HEADLINE_KEYS,
    HOLD_LABELS,
    PLANT_LABELS,
    QUANTITIES,
    Quantity,
    Headline,
    citations,
    design_chart,
    designs,
    display_kind,
    filter_optimum,
    map_params,
    map_point,
    scenario_title,
    simulation,
    simulation_section,
    stability_map_result,
)
from app.report.identify_section import identification_part
from app.report.model import (
    DIGITS,
    Numbers,
    Part,
    ReportCancelled,
    ReportContent,
    Row,
    Section,
    num,
    row,
    symbol_html,
)
from app.report.observer_section import observer_part
from app.report.renderable_section import renderable_part
from app.report.workspace_section import workspace_map_alone, workspace_part, workspace_point_alone
from app.report.zwidth_section import zwidth_part, zwidth_results

__all__ = ["ReportContent", "Section", "Row", "ReportCancelled", "gather", "num", "symbol_html", "app_version",
           "METHODS", "DIGITS", "PARTS"]


def app_version() -> str:
    from importlib import metadata

    try:
        return metadata.version("zwidth")
    except metadata.PackageNotFoundError:
        return "unknown (not installed)"


METHODS = (
    "The device is a chain of lumped masses joined by spring-damper elements (eq. 25&ndash;28 of "
    "Adams, Moreyra &amp; Hannaford). The sampled controller and zero-order hold are mapped to the "
    "continuous domain with Tustin's method, <i>s</i> = <i>j</i>(2/<i>T</i>) tan(&omega;<i>T</i>/2), and a "
    "half-sample hold factor (eq. 2, 4, 16). The haptic interface is a two-port network, and Llewellyn's "
    "criterion (eq. 1) gives unconditional stability for every passive human operator and virtual "
    "environment: for the impedance display Re(1/<i>Z</i><sub>c</sub>) must exceed the bound of eq. 9, for "
    "the admittance display Re(<i>Z</i><sub>cA</sub>) the bound of eq. 21. The margin is the coupling term "
    "minus the bound, &eta; is Llewellyn's factor (&ge; 1 where unconditionally stable), and the relative "
    "reserve is the smallest margin relative to the coupling term, 1 &minus; bound/coupling term, over the "
    "band. The impedance range (Z-width) is bounded by "
    "|<i>Z</i><sub>min</sub>| and |<i>Z</i><sub>max</sub>| of eq. 11&ndash;12 (impedance display) or "
    "eq. 23&ndash;24 (admittance display); <i>k</i><sub>max</sub> and <i>b</i><sub>min</sub> are the largest "
    "stiffness and smallest damping rendered, and the apparent mass and damping are those felt in free "
    "motion. Designs are found on a resonance-aware frequency grid with refinement of every local extremum.",
    "Where a profile has a <i>wall</i> section, the virtual-wall controller is evaluated as in Eom, Suh "
    "&amp; Yi: the transparency index <i>J</i> = &#8214;<i>w</i><sub>1</sub>(<i>Y</i><sub>v</sub> &minus; "
    "<i>Y</i><sub>t</sub>)&#8214;<sub>2</sub><sup>2</sup> (eq. 10&ndash;11) and the robust-stability "
    "condition &#8214;<i>L</i>&#8214;<sub>&infin;</sub> &le; 1 (eq. 13&ndash;17) over the controller damping "
    "<i>B</i><sub>c</sub>; with an <i>observer</i> section, the disturbance observer of the same paper "
    "(eq. 2&ndash;5) on one axis and on the two axes of a five-bar device. Where a profile has a <i>simulation</i> section, the exact sampled loop (ZOH, "
    "optional delay) gives the spectral-radius stability map (&rho; &lt; 1 is stable) and the nonlinear "
    "time-domain scenario.",
    "<b>References</b>",
    f"[1] {citations.ADAMS.html()}",
    f"[2] {citations.EOM.html()}",
)


#: report number keys and HTML symbols of the headline quantities (labels and units: the study's)
_VERDICT_ROWS = {
    "stable": ("verdict.stable", ""), "stability_reserve": ("verdict.relative_margin", ""),
    "binding_frequency": ("verdict.binding_frequency", ""), "worst_margin": ("verdict.worst_margin", ""),
    "worst_frequency": ("verdict.worst_frequency", ""), "min_eta": ("verdict.min_eta", "&eta;<sub>min</sub>"),
}
_RANGE_ROWS = {
    "k_max": ("range.k_max", "<i>k</i><sub>max</sub>"), "b_min": ("range.b_min", "<i>b</i><sub>min</sub>"),
    "apparent_mass": ("range.apparent_mass", ""), "apparent_damping": ("range.apparent_damping", ""),
}
_DESIGN_ROWS = {
    "bc": ("design.bc", "<i>b</i><sub>c</sub>"), "kc_max": ("design.kc_max", "<i>k</i><sub>c,max</sub>"),
    "kc_max_frequency": ("design.frequency", ""), "mc": ("design.mc", "<i>m</i><sub>c</sub>"),
    "bc_low": ("design.bc_low", "<i>b</i><sub>c,low</sub>"), "bc_low_frequency": ("design.low_frequency", ""),
    "bc_high": ("design.bc_high", "<i>b</i><sub>c,high</sub>"), "bc_high_frequency": ("design.high_frequency", ""),
    "min_mc": ("design.min_mc", "<i>m</i><sub>c,min</sub>"), "min_mc_bc": ("design.min_mc_bc", "<i>b</i><sub>c</sub>"),
    "min_mc_frequency": ("design.min_mc_frequency", ""),
}



def _unit(value: Any, unit: str) -> str:
    """The Unit cell of ``value``: its unit (HTML), none after a word ("infeasible", "∞", "n/a")."""
    q = Quantity("unit", "", "", unit)  # Quantity.format's rule: no unit after a word
    return html.escape(q.format(value)[len(q.number(value)):].strip())


def _device(profile: Profile) -> Part:
    dev = profile.device
    numbers: Numbers = {}
    rows: list[Row] = []
    for i, m in enumerate(dev.masses):
        rows.append(row(numbers, f"device.mass[{i}]", f"mass {i + 1}", f"<i>m</i><sub>{i + 1}</sub>", m, "kg"))
    for i, k in enumerate(dev.stiffnesses):
        rows.append(row(numbers, f"device.stiffness[{i}]", f"stiffness {i + 1}&ndash;{i + 2}",
                        f"<i>k</i><sub>{i + 1}</sub>", k, "N/m"))
    for i, b in enumerate(dev.dampings):
        rows.append(row(numbers, f"device.damping[{i}]", f"damping {i + 1}&ndash;{i + 2}",
                        f"<i>b</i><sub>{i + 1}</sub>", b, "N&middot;s/m"))
    for i, z in enumerate(dev.damping_ratios):
        rows.append(row(numbers, f"device.damping_ratio[{i}]", f"damping ratio {i + 1}&ndash;{i + 2}",
                        f"&zeta;<sub>{i + 1}</sub>", z, ""))
    for i, g in enumerate(dev.ground_dampings):
        rows.append(row(numbers, f"device.ground_damping[{i}]", f"damping to ground at mass {i + 1}",
                        f"<i>g</i><sub>{i + 1}</sub>", g, "N&middot;s/m"))
    s = int(dev.sensor_element)
    numbers["device.sensor_element"] = (float(s), str(s + 1))
    rows.append(Row("force sensor on element (1 = next to the handle)", "", str(s + 1), ""))
    return Part((Section("Device", ("Masses from the handle (1) to the actuator; element <i>i</i> joins mass "
                                    "<i>i</i> and mass <i>i</i>+1.",), tuple(rows)),), numbers)


def _sampling(profile: Profile) -> Part:
    dev = profile.device
    numbers: Numbers = {}
    rows = (
        row(numbers, "sample_time", "sample period", "<i>T</i>", dev.sample_time, "s"),
        row(numbers, "band.min", "lowest analysed frequency", "&omega;<sub>min</sub>", dev.band_min, "rad/s"),
        row(numbers, "band.max", "Nyquist frequency &pi;/<i>T</i>", "&omega;<sub>N</sub>", dev.nyquist, "rad/s"),
    )
    return Part((Section("Sampling and analysis band", (), rows),), numbers)


def _sampled(profile: Profile) -> Part:
    """The app's sampled-data stability map (:func:`analysis.study.stability_map_result`, its default
    axes and ranges for the display) and the profile's scenario."""
    if profile.simulation is None:
        return Part()
    params = map_params(profile)
    smap = stability_map_result(profile, params)
    sec = simulation_section(profile)
    opt, sc = sec.options, sec.scenario
    out = simulation(profile)
    numbers: Numbers = {}
    stable_share = float(np.mean(smap.spectral_radius <= 1.0))
    rows = (
        Row("scenario", "", html.escape(scenario_title(str(sc.name))), ""),
        row(numbers, "simulation.duration", "duration", "", float(out.t[-1]), "s"),
        Row(f"verdict of the scenario ({html.escape(out.verdict.reason)})", "", html.escape(out.verdict.kind), ""),
        row(numbers, "simulation.peak_position", "largest |handle position|", "",
            float(np.max(np.abs(out.positions[:, 0]))) * 1e3, "mm"),
        row(numbers, "simulation.peak_force", "largest |actuator force|", "", float(np.max(np.abs(out.f_d))), "N"),
        row(numbers, "map.stable_share", "stable share of the map", "", 100.0 * stable_share, "%"),
        Row("delay" + (" (plus the computation delay)" if opt.implementation_delay else ""), "",
            str(opt.delay_samples), "samples"),
    )
    n = params["points"]
    section = Section("Sampled-data checks", (
        "The exact sampled loop (zero-order hold, the profile's delays) on the app's "
        f"{n}&times;{n} stability map ({symbol_html(params['x'])} &times; {symbol_html(params['y'])}), and the "
        "profile's scenario simulated in the time domain.",), rows)
    results = {"map": smap, "map_point": map_point(profile, params["x"], params["y"]), "simulation": out}
    return Part((section,), numbers, results)


def _wall(profile: Profile) -> Part:
    st = profile.wall
    if st is None:
        return Part()
    from analysis.transparency.design import WallDesign

    wd = WallDesign.from_settings(st, profile.device if st.plant == "chain" else None)
    curves = wd.tradeoff()
    best = wd.optimal_damping()
    results: dict[str, Any] = {"tradeoff": curves, "optimum": best}
    if math.isfinite(best.bc):
        results["step"] = wd.step_response(best.bc)
    numbers: Numbers = {}
    index, peak = QUANTITIES["transparency_index"], QUANTITIES["robustness_peak"]
    rows = (
        row(numbers, "wall.mass", "device mass", "<i>m</i>", st.mass, "kg"),
        row(numbers, "wall.damping", "device damping", "<i>b</i>", st.damping, "N&middot;s/m"),
        row(numbers, "wall.wall_stiffness", "virtual wall stiffness", "<i>K</i>", st.wall_stiffness, "N/m"),
        row(numbers, "wall.wall_damping", "virtual wall damping", "<i>B</i>", st.wall_damping, "N&middot;s/m"),
        row(numbers, "wall.alpha", "uncertainty weight (eq. 13)", "&alpha;", st.alpha, ""),
        row(numbers, "wall.beta", "uncertainty weight (eq. 13)", "&beta;", st.beta, ""),
        row(numbers, "wall.optimum.bc", "optimal controller damping", "<i>B</i><sub>c</sub>", best.bc, "N&middot;s/m"),
        row(numbers, "wall.optimum.index", f"{index.name} at the optimum", "<i>J</i>", best.index,
            _unit(best.index, index.unit)),
        row(numbers, "wall.optimum.peak", f"{peak.name} at the optimum",
            "&#8214;<i>L</i>&#8214;<sub>&infin;</sub>", best.peak, _unit(best.peak, peak.unit)),
        row(numbers, "wall.optimum.peak_frequency", "at frequency", "", best.peak_frequency, "rad/s"),
    )
    after = () if best.feasible else (f"No feasible B<sub>c</sub>: {html.escape(best.reason)}",)
    par = (f"Hold model <i>H</i>: {html.escape(HOLD_LABELS.get(st.hold, st.hold))}. Plant: "
           f"{html.escape(PLANT_LABELS.get(st.plant, st.plant))}.")
    return Part((Section("Transparency and robust stability (Eom, Suh &amp; Yi)", (par,), rows, after),), numbers,
                results)


def _headline_part(h: Headline, table: dict[str, tuple[str, str]], keys: tuple[str, ...], title: str,
                   paragraphs: tuple[str, ...] = ()) -> Part:
    """A section of headline quantities, printed by :meth:`analysis.study.Quantity.number`."""
    numbers: Numbers = {}
    rows = []
    for key in keys:
        if key not in table:
            continue
        q, value = h.quantity(key), h.value(key)
        beyond = h.beyond_limits.get(key)  # a design outside its field's physical range: the phrase
        numbers[table[key][0]] = (None if value is None else float(value),
                                  q.number(value) if beyond is None else beyond.text())
        rows.append(Row(q.name, table[key][1], q.number(value, rich=True), _unit(value, q.unit)) if beyond is None
                    else Row(q.name, table[key][1], beyond.text(rich=True), ""))
    return Part((Section(title, paragraphs, tuple(rows)),), numbers)


def _controller(profile: Profile) -> Part:
    kind = display_kind(profile)
    numbers: Numbers = {}
    rows = [Row(f"display type ({kind.causality})", "", kind.name, "")]
    for gain in kind.gains:
        sym = f"<i>{gain.symbol[0]}</i><sub>{gain.symbol[2:]}</sub>"
        rows.append(row(numbers, f"coupling.{gain.symbol.replace('_', '')}", gain.label, sym,
                        getattr(profile, gain.field), html.escape(gain.unit)))
    rows += [
        row(numbers, "pd.kp", "PD position-loop stiffness", "<i>k</i><sub>p</sub>", profile.kp, "N/m"),
        row(numbers, "pd.kd", "PD position-loop damping", "<i>k</i><sub>d</sub>", profile.kd, "N&middot;s/m"),
    ]
    after = ("The PD gains act only in the admittance display (eq. 30).",) if kind.is_impedance else ()
    return Part((Section("Display and controller", (), tuple(rows), after),), numbers)


def _verdict(h: Headline, profile: Profile) -> Part:
    dev = profile.device
    verdict_text = f"<b>{h.question}: {'unconditionally stable' if h.stable else 'NOT unconditionally stable'}</b>"
    return _headline_part(h, _VERDICT_ROWS, HEADLINE_KEYS, "Verdict", (
        f"{verdict_text} for every passive operator and environment, over the band "
        f"[{num(dev.band_min, rich=True)}, {num(dev.nyquist, rich=True)}) rad/s.",))


def _designs(h: Headline) -> Part:
    eq = f"eq. {h.kind.bound_equation}"
    if h.kind.is_impedance:
        par = f"Largest k<sub>c</sub> satisfying {eq} at the profile's b<sub>c</sub> (design chart below)."
    else:
        par = f"Couplings (m<sub>c</sub>, b<sub>c</sub>) satisfying {eq} (design chart below)."
    return _headline_part(h, _DESIGN_ROWS, h.kind.design_keys, "Design results", (par,))


def _if(section: str, results: Callable[[Profile], dict[str, Any]]) -> Callable[[Profile], dict[str, Any]]:
    """``results`` of a profile that has the optional ``section``; nothing (``{}``) without it."""
    return lambda profile: results(profile) if getattr(profile, section) is not None else {}


Alone = Callable[[Profile], dict[str, Any]]
#: The report's computed sections, in its order: the function that writes one whole (its text, numbers and
#: results) and its parts, each with how it is computed alone (the results its figures draw, under the keys
#: the section gives them, without the text), where a section has more than one.  A section is written whole
#: when all its parts are asked (the report); otherwise only its parts asked are computed (export-plot).
_SECTIONS: tuple[tuple[Callable[[Profile], Part], dict[str, Alone | None]], ...] = (
    (_wall, {"wall": None}),
    (observer_part, {"observer": None}),
    (_sampled, {"sampled": None}),
    (identification_part, {"identification": None}),  # issue 14: only with the identification section
    (zwidth_part, {  # issue 15: only with the controller section; the optimum is most of its work
        "zwidth_region": _if("controller", lambda p: zwidth_results(p, optimum=False)),
        "zwidth_optimum": _if("controller", lambda p: {"zwidth_optimum": filter_optimum(p)})}),
    (renderable_part, {"renderable": None}),  # issue 24: only with the renderable section
    (workspace_part, {  # issue 25: only with the multidof section; the polar figure needs no map
        "workspace_map": workspace_map_alone, "workspace_point": workspace_point_alone}),
)
#: Every part :func:`gather` can be asked for, in the report's order: the design chart, then the sections'.
PARTS = ("chart", *(name for _, names in _SECTIONS for name in names))


def _chart_results(profile: Profile) -> dict[str, Any]:
    return {"chart": design_chart(profile), "chart_point": display_kind(profile).chart_point(profile)}


def _computed(profile: Profile, wanted: frozenset[str]) -> list[Part]:
    """The sections of :data:`_SECTIONS` whose parts are all ``wanted``, whole; of the others, the parts
    ``wanted`` alone."""
    out = []
    for whole, names in _SECTIONS:
        if all(n in wanted for n in names):
            out.append(whole(profile))
        else:
            out += [Part(results=alone(profile)) for n, alone in names.items() if n in wanted and alone]
    return out


def gather(profile: Profile, *, source: str | None = None, sampled: bool = True,
           date: str | None = None, parts: Collection[str] | None = None) -> ReportContent:
    """All numbers and results of one report, from :mod:`analysis.study` (no computation here).

    ``parts``: the parts of :data:`PARTS` to compute (``None``: all, the report). The stability result,
    the headline and the tables that only print the profile are always there (they cost milliseconds); a
    section is written when all its parts are asked, otherwise only its parts asked are computed, as
    results for their figures (:func:`app.report.figures.figure_parts` gives a figure's). ``sampled=False``
    leaves the sampled-data map and scenario out.
    """
    wanted = frozenset(PARTS if parts is None else parts)
    if not wanted <= set(PARTS):
        raise ValueError(f"unknown report parts {sorted(wanted - set(PARTS))}; the parts are {', '.join(PARTS)}")
    if not sampled:
        wanted -= {"sampled"}
    kind = display_kind(profile)
    disp = kind.build(profile)
    stab = kind.evaluate(profile, disp)
    h = Headline.from_result(stab, designs(profile, kind, disp))
    pieces = [
        Part(results={"stability": stab, **(_chart_results(profile) if "chart" in wanted else {})}),
        _device(profile), _sampling(profile), _controller(profile), _verdict(h, profile), _designs(h),
        _headline_part(h, _RANGE_ROWS, HEADLINE_KEYS, "Impedance range (Z-width)"),
        *_computed(profile, wanted),
    ]
    numbers: Numbers = {}
    results: dict[str, Any] = {}
    for part in pieces:
        numbers.update(part.numbers)
        results.update(part.results)
    return ReportContent(
        title=f"Haptic interface design report: {html.escape(profile.name)}",
        profile=profile,
        source=source,
        date=date or _dt.datetime.now().strftime("%Y-%m-%d %H:%M"),
        version=app_version(),
        sections=tuple(sec for part in pieces for sec in part.sections),
        methods=METHODS,
        numbers=numbers,
        headline=h,
        results=results,
    )
