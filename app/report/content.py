"""Everything a report says, gathered from the analysis core (no Qt).

Text is kept as small HTML fragments (``k<sub>c</sub>``), which both the PDF writer (through
``QTextDocument``) and the HTML writer understand.  Numbers are printed by :func:`num`, and
:attr:`ReportContent.numbers` keeps the raw values next to their printed text, so tests can
check that the report says what the analysis computed.
"""

from __future__ import annotations

import datetime as _dt
import html
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from analysis import AdmittanceDisplay, ImpedanceDisplay
from analysis.profiles.io import Profile
from analysis.study.summary import summarize

__all__ = ["ReportContent", "Section", "Row", "ReportCancelled", "gather", "num", "app_version", "METHODS"]

DIGITS = 6
CHART_POINTS = 40
MAP_POINTS = 31


class ReportCancelled(Exception):
    pass


def num(x: Any, digits: int = DIGITS) -> str:
    """A number as the report prints it (``inf`` -> ``unbounded``, ``None`` -> ``infeasible``)."""
    if x is None:
        return "infeasible"
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    x = float(x)
    if math.isnan(x):
        return "n/a"
    if math.isinf(x):
        return "unbounded" if x > 0 else "-unbounded"
    return f"{x:.{digits}g}"


def app_version() -> str:
    from importlib import metadata

    try:
        return metadata.version("zwidth")
    except metadata.PackageNotFoundError:
        return "unknown (not installed)"


@dataclass(frozen=True)
class Row:
    """One table row: quantity, symbol (HTML), value (printed), unit."""

    label: str
    symbol: str
    value: str
    unit: str = ""


@dataclass(frozen=True)
class Section:
    title: str
    paragraphs: tuple[str, ...] = ()
    rows: tuple[Row, ...] = ()
    after: tuple[str, ...] = ()


@dataclass(frozen=True)
class ReportContent:
    title: str
    profile: Profile
    source: str | None
    date: str
    version: str
    sections: tuple[Section, ...]
    methods: tuple[str, ...]
    numbers: dict[str, tuple[float | None, str]]
    summary: dict[str, Any]
    results: dict[str, Any] = field(default_factory=dict)

    def printed(self, key: str) -> str:
        return self.numbers[key][1]


METHODS = (
    "The device is a chain of lumped masses joined by spring-damper elements (eq. 25&ndash;28 of "
    "Adams, Moreyra &amp; Hannaford). The sampled controller and zero-order hold are mapped to the "
    "continuous domain with Tustin's method, <i>s</i> = <i>j</i>(2/<i>T</i>) tan(&omega;<i>T</i>/2), and a "
    "half-sample hold factor (eq. 2, 4, 16). The haptic interface is a two-port network, and Llewellyn's "
    "criterion (eq. 1) gives unconditional stability for every passive human operator and virtual "
    "environment: for the impedance display Re(1/<i>Z</i><sub>c</sub>) must exceed the bound of eq. 9, for "
    "the admittance display Re(<i>Z</i><sub>cA</sub>) the bound of eq. 21. The margin is the coupling term "
    "minus the bound, &eta; is Llewellyn's factor (&ge; 1 where unconditionally stable), and the relative "
    "reserve is the smallest margin relative to the bound. The impedance range (Z-width) is bounded by "
    "|<i>Z</i><sub>min</sub>| and |<i>Z</i><sub>max</sub>| of eq. 11&ndash;12 (impedance display) or "
    "eq. 23&ndash;24 (admittance display); <i>k</i><sub>max</sub> and <i>b</i><sub>min</sub> are the largest "
    "stiffness and smallest damping rendered, and the apparent mass and damping are those felt in free "
    "motion. Designs are found on a resonance-aware frequency grid with refinement of every local extremum.",
    "Where a profile has a <i>wall</i> section, the virtual-wall controller is evaluated as in Eom, Suh "
    "&amp; Yi: the transparency index <i>J</i> = &#8214;<i>w</i><sub>1</sub>(<i>Y</i><sub>v</sub> &minus; "
    "<i>Y</i><sub>t</sub>)&#8214;<sub>2</sub><sup>2</sup> (eq. 10&ndash;11) and the robust-stability "
    "condition &#8214;<i>L</i>&#8214;<sub>&infin;</sub> &le; 1 (eq. 13&ndash;17) over the controller damping "
    "<i>B</i><sub>c</sub>. Where a profile has a <i>simulation</i> section, the exact sampled loop (ZOH, "
    "optional delay) gives the spectral-radius stability map (&rho; &lt; 1 is stable) and the nonlinear "
    "time-domain scenario.",
    "References: R. J. Adams, M. R. Moreyra and B. Hannaford, &ldquo;Stability and Performance of Haptic "
    "Displays: Theory and Experiments&rdquo;, Proc. ASME IMECE Haptics Symposium, 1998. K.-S. Eom, I. H. Suh "
    "and B.-J. Yi, &ldquo;A Design Method of Haptic Interface Controller Considering Transparency and "
    "Robust Stability&rdquo;, Proc. IEEE/RSJ IROS, 2000.",
)


def _row(numbers: dict, key: str, label: str, symbol: str, value: Any, unit: str = "") -> Row:
    text = num(value)
    numbers[key] = (None if value is None else float(value), text)
    return Row(label, symbol, text, unit)


def _device_rows(profile: Profile, numbers: dict) -> tuple[Row, ...]:
    dev = profile.device
    rows: list[Row] = []
    for i, m in enumerate(dev.masses):
        rows.append(_row(numbers, f"device.mass[{i}]", f"mass {i + 1}", f"<i>m</i><sub>{i + 1}</sub>", m, "kg"))
    for i, k in enumerate(dev.stiffnesses):
        rows.append(_row(numbers, f"device.stiffness[{i}]", f"stiffness {i + 1}&ndash;{i + 2}",
                         f"<i>k</i><sub>{i + 1}</sub>", k, "N/m"))
    for i, b in enumerate(dev.dampings):
        rows.append(_row(numbers, f"device.damping[{i}]", f"damping {i + 1}&ndash;{i + 2}",
                         f"<i>b</i><sub>{i + 1}</sub>", b, "N&middot;s/m"))
    for i, z in enumerate(dev.damping_ratios):
        rows.append(_row(numbers, f"device.damping_ratio[{i}]", f"damping ratio {i + 1}&ndash;{i + 2}",
                         f"&zeta;<sub>{i + 1}</sub>", z, ""))
    for i, g in enumerate(dev.ground_dampings):
        rows.append(_row(numbers, f"device.ground_damping[{i}]", f"damping to ground at mass {i + 1}",
                         f"<i>g</i><sub>{i + 1}</sub>", g, "N&middot;s/m"))
    s = int(dev.sensor_element)
    numbers["device.sensor_element"] = (float(s), str(s + 1))
    rows.append(Row("force sensor on element", "", str(s + 1), "(1 = next to the handle)"))
    return tuple(rows)


def _sampled(profile: Profile, res: dict, numbers: dict, design_kc: float | None) -> Section | None:
    sim = profile.simulation
    if sim is None:
        return None
    from analysis import sampled

    opt = sim.options
    delay = dict(delay_samples=opt.delay_samples, implementation_delay=opt.implementation_delay)
    if profile.display == "impedance":
        bc0 = profile.bc if profile.bc > 0 else 100.0
        kc0 = profile.kc if profile.kc > 0 else (design_kc or 1e4)
        xs = np.geomspace(bc0 / 100, bc0 * 100, MAP_POINTS)
        ys = np.geomspace(kc0 / 100, kc0 * 100, MAP_POINTS)
        smap = sampled.stability_map(profile.device, ("bc", xs), ("kc", ys), display="impedance",
                                     coupling=(profile.kc, profile.bc), pd=(profile.kp, profile.kd), **delay)
        point = (profile.bc, profile.kc)
    else:
        xs = np.geomspace(profile.mc / 100, profile.mc * 100, MAP_POINTS)
        ys = np.geomspace(profile.bc_adm / 100, profile.bc_adm * 100, MAP_POINTS)
        smap = sampled.stability_map(profile.device, ("mc", xs), ("bc", ys), display="admittance",
                                     coupling=(profile.mc, profile.bc_adm), pd=(profile.kp, profile.kd), **delay)
        point = (profile.mc, profile.bc_adm)
    res["map"] = smap
    res["map_point"] = point
    sc = sim.scenario
    out = sampled.simulate(profile, sc, options=opt)
    res["simulation"] = out
    stable_share = float(np.mean(smap.spectral_radius <= 1.0))
    rows = (
        Row("scenario", "", "", html.escape(str(sc.name))),
        _row(numbers, "simulation.duration", "duration", "", float(out.t[-1]), "s"),
        Row("verdict", "", html.escape(out.verdict.kind), html.escape(out.verdict.reason)),
        _row(numbers, "simulation.peak_position", "largest |handle position|", "",
             float(np.max(np.abs(out.positions[:, 0]))) * 1e3, "mm"),
        _row(numbers, "simulation.peak_force", "largest |actuator force|", "", float(np.max(np.abs(out.f_d))), "N"),
        _row(numbers, "map.stable_share", "stable share of the map", "", 100.0 * stable_share, "%"),
        Row("delay", "", str(opt.delay_samples), "sample(s)" + (", plus computation delay"
                                                            if opt.implementation_delay else "")),
    )
    return Section("Sampled-data checks", (
        "The exact sampled loop (zero-order hold, the profile's delays) on a coarse "
        f"{MAP_POINTS}&times;{MAP_POINTS} grid around the current coupling, and the profile's scenario "
        "simulated in the time domain.",), rows)


def _wall(profile: Profile, res: dict, numbers: dict) -> Section | None:
    st = profile.wall
    if st is None:
        return None
    from analysis.transparency.design import WallDesign

    wd = WallDesign.from_settings(st, profile.device if st.plant == "chain" else None)
    curves = wd.tradeoff()
    best = wd.optimal_damping()
    res["tradeoff"] = curves
    res["optimum"] = best
    if math.isfinite(best.bc):
        res["step"] = wd.step_response(best.bc)
    rows = (
        _row(numbers, "wall.mass", "device mass", "<i>m</i>", st.mass, "kg"),
        _row(numbers, "wall.damping", "device damping", "<i>b</i>", st.damping, "N&middot;s/m"),
        _row(numbers, "wall.wall_stiffness", "virtual wall stiffness", "<i>K</i>", st.wall_stiffness, "N/m"),
        _row(numbers, "wall.wall_damping", "virtual wall damping", "<i>B</i>", st.wall_damping, "N&middot;s/m"),
        Row("hold model", "", html.escape(st.hold), ""),
        _row(numbers, "wall.alpha", "uncertainty weight", "&alpha;, &beta;", st.alpha, f"{num(st.beta)}"),
        _row(numbers, "wall.optimum.bc", "optimal controller damping", "<i>B</i><sub>c</sub>", best.bc, "N&middot;s/m"),
        _row(numbers, "wall.optimum.index", "transparency index at the optimum", "<i>J</i>", best.index, ""),
        _row(numbers, "wall.optimum.peak", "robustness peak at the optimum",
             "&#8214;<i>L</i>&#8214;<sub>&infin;</sub>", best.peak, ""),
        _row(numbers, "wall.optimum.peak_frequency", "at frequency", "", best.peak_frequency, "rad/s"),
    )
    after = () if best.feasible else (f"No feasible B<sub>c</sub>: {html.escape(best.reason)}",)
    return Section("Transparency and robust stability (Eom, Suh &amp; Yi)", (), rows, after)


def gather(profile: Profile, *, source: str | None = None, sampled: bool = True,
           date: str | None = None) -> ReportContent:
    """All numbers and results of one report."""
    numbers: dict[str, tuple[float | None, str]] = {}
    res: dict[str, Any] = {}
    dev = profile.device
    summary = summarize(profile)
    imp_disp = profile.display == "impedance"

    if imp_disp:
        disp = ImpedanceDisplay(dev)
        stab = disp.evaluate(profile.kc, profile.bc)
        bcs = np.geomspace(1.0, 1e4, CHART_POINTS)
        res["chart"] = ("impedance", disp.stiffness_chart(bcs))
        res["chart_point"] = (profile.bc, profile.kc)
    else:
        disp = AdmittanceDisplay(dev, profile.kp, profile.kd)
        stab = disp.evaluate(profile.mc, profile.bc_adm)
        mcs = np.geomspace(1e-3, 1e3, CHART_POINTS)
        res["chart"] = ("admittance", disp.mass_chart(mcs))
        res["chart_point"] = (profile.mc, profile.bc_adm)
    res["stability"] = stab

    sampling = Section("Sampling and analysis band", (), (
        _row(numbers, "sample_time", "sample period", "<i>T</i>", dev.sample_time, "s"),
        _row(numbers, "band.min", "lowest analysed frequency", "&omega;<sub>min</sub>", dev.band_min, "rad/s"),
        _row(numbers, "band.max", "Nyquist frequency &pi;/<i>T</i>", "&omega;<sub>N</sub>", dev.nyquist, "rad/s"),
    ))
    if imp_disp:
        ctrl_rows = (
            Row("display type", "", "impedance", "(force out, position in)"),
            _row(numbers, "coupling.kc", "coupling stiffness", "<i>k</i><sub>c</sub>", profile.kc, "N/m"),
            _row(numbers, "coupling.bc", "coupling damping", "<i>b</i><sub>c</sub>", profile.bc, "N&middot;s/m"),
        )
    else:
        ctrl_rows = (
            Row("display type", "", "admittance", "(position out, force in)"),
            _row(numbers, "coupling.mc", "coupling mass", "<i>m</i><sub>c</sub>", profile.mc, "kg"),
            _row(numbers, "coupling.bc", "coupling damping", "<i>b</i><sub>c</sub>", profile.bc_adm, "N&middot;s/m"),
        )
    ctrl_rows += (
        _row(numbers, "pd.kp", "PD position-loop stiffness", "<i>k</i><sub>p</sub>", profile.kp, "N/m"),
        _row(numbers, "pd.kd", "PD position-loop damping", "<i>k</i><sub>d</sub>", profile.kd, "N&middot;s/m"),
    )
    controller = Section("Display and controller", (), ctrl_rows,
                         ("The PD gains act only in the admittance display (eq. 30).",) if imp_disp else ())

    eq = "eq. 9" if imp_disp else "eq. 21"
    margin_unit = "m/(N&middot;s)" if imp_disp else "N&middot;s/m"
    verdict_text = ("<b>Unconditionally stable</b>" if stab.stable else "<b>NOT unconditionally stable</b>")
    verdict = Section("Verdict", (
        f"{verdict_text} ({eq}) for every passive operator and environment, over the band "
        f"[{num(dev.band_min)}, {num(dev.nyquist)}) rad/s.",), (
        _row(numbers, "verdict.stable", "unconditionally stable", "", bool(stab.stable), ""),
        _row(numbers, "verdict.worst_margin", "worst margin", "", stab.worst_margin, margin_unit),
        _row(numbers, "verdict.worst_frequency", "at frequency", "", stab.worst_frequency, "rad/s"),
        _row(numbers, "verdict.relative_margin", "relative stability reserve", "", stab.relative_margin, ""),
        _row(numbers, "verdict.binding_frequency", "binding frequency", "", stab.binding_frequency, "rad/s"),
        _row(numbers, "verdict.min_eta", "smallest Llewellyn factor", "&eta;<sub>min</sub>", stab.min_eta, ""),
    ))
    numbers["verdict.stable"] = (float(stab.stable), "yes" if stab.stable else "no")

    if imp_disp:
        d = summary["impedance"]["design"]
        design_rows: tuple[Row, ...] = (
            _row(numbers, "design.bc", "for coupling damping", "<i>b</i><sub>c</sub>", d["bc"], "N&middot;s/m"),
            _row(numbers, "design.kc_max", "largest stable coupling stiffness", "<i>k</i><sub>c,max</sub>",
                 d["kc_max"], "N/m"),
            _row(numbers, "design.frequency", "binding frequency", "", d["frequency"], "rad/s"),
        )
        design_par = f"Largest k<sub>c</sub> satisfying {eq} at the profile's b<sub>c</sub> (design chart below)."
    else:
        fd = summary["admittance"]["design"]["feasible_damping"]
        mm = summary["admittance"]["design"]["min_mass"]
        design_rows = (
            _row(numbers, "design.mc", "for coupling mass", "<i>m</i><sub>c</sub>", fd["mc"], "kg"),
            _row(numbers, "design.bc_low", "feasible damping, lower edge", "<i>b</i><sub>c,low</sub>", fd["low"],
                 "N&middot;s/m"),
            _row(numbers, "design.low_frequency", "binding frequency (lower)", "", fd["low_frequency"], "rad/s"),
            _row(numbers, "design.bc_high", "feasible damping, upper edge", "<i>b</i><sub>c,high</sub>",
                 fd["high"], "N&middot;s/m"),
            _row(numbers, "design.high_frequency", "binding frequency (upper)", "", fd["high_frequency"], "rad/s"),
            _row(numbers, "design.min_mc", "smallest stable coupling mass", "<i>m</i><sub>c,min</sub>",
                 None if mm is None else mm["mc"], "kg"),
            _row(numbers, "design.min_mc_bc", "with damping", "<i>b</i><sub>c</sub>",
                 None if mm is None else mm["bc"], "N&middot;s/m"),
            _row(numbers, "design.min_mc_frequency", "binding frequency", "",
                 None if mm is None else mm["frequency"], "rad/s"),
        )
        design_par = f"Couplings (m<sub>c</sub>, b<sub>c</sub>) satisfying {eq} (design chart below)."
    designs = Section("Design results", (design_par,), design_rows)

    zrange = Section("Impedance range (Z-width)", (), (
        _row(numbers, "range.k_max", "largest renderable stiffness", "<i>k</i><sub>max</sub>", stab.k_max, "N/m"),
        _row(numbers, "range.b_min", "smallest renderable damping", "<i>b</i><sub>min</sub>", stab.b_min,
             "N&middot;s/m"),
        _row(numbers, "range.apparent_mass", "apparent free-motion mass", "", stab.apparent_mass, "kg"),
        _row(numbers, "range.apparent_damping", "apparent free-motion damping", "", stab.apparent_damping,
             "N&middot;s/m"),
    ))

    sections = [Section("Device", ("Masses from the handle (1) to the actuator; element <i>i</i> joins mass "
                                   "<i>i</i> and mass <i>i</i>+1.",), _device_rows(profile, numbers)),
                sampling, controller, verdict, designs, zrange]
    wall = _wall(profile, res, numbers)
    if wall is not None:
        sections.append(wall)
    if sampled:
        sec = _sampled(profile, res, numbers, None if not imp_disp else summary["impedance"]["design"]["kc_max"])
        if sec is not None:
            sections.append(sec)
    return ReportContent(
        title=f"Haptic interface design report: {html.escape(profile.name)}",
        profile=profile,
        source=source,
        date=date or _dt.datetime.now().strftime("%Y-%m-%d %H:%M"),
        version=app_version(),
        sections=tuple(sections),
        methods=METHODS,
        numbers=numbers,
        summary=summary,
        results=res,
    )
