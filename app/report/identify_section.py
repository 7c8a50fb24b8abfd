"""The report's identification part (issue 14), when the profile has an ``identification`` section.

:func:`identification_part` (Qt-free, called by :func:`app.report.content.gather`): the
measurements with the bins used of each and why the others were left out, the goodness of fit of
the profile's device to them (:func:`analysis.study.curves_goodness`: a warning when it fails, and
the intervals are then labelled "not trustworthy"), the parameter table with the 95 % intervals,
and the robust designs (robust largest
k_c at the current b_c against the nominal one, with the binding device; or the robust b_c interval
on the admittance display), computed by :mod:`analysis.study.identify`.  Its figures (needing Qt)
are in :mod:`app.report.identify_figures`.
"""

from __future__ import annotations

import html
import re
from typing import Any

from analysis.profiles import Profile
from analysis.identify import Goodness
from analysis.study import BeyondLimit, RobustDesigns, curves_goodness, fit_curves, format_number, robust_designs
from app.report.model import Numbers, Part, Row, Section

__all__ = ["identification_part", "parameter_label"]

_NAMES = {"masses": ("mass {}", "kg"), "stiffnesses": ("stiffness {}&ndash;{}", "N/m"),
          "dampings": ("damping {}&ndash;{}", "N&middot;s/m"),
          "ground_dampings": ("damping to ground at mass {}", "N&middot;s/m")}
_KEY = re.compile(r"^(\w+)\[(\d+)\]$")


def parameter_label(key: str) -> tuple[str, str]:
    """``"masses[0]"`` -> ``("mass 1", "kg")`` (the report's 1-based names) and its unit."""
    match = _KEY.match(key)
    name, i = match.group(1), int(match.group(2))
    text, unit = _NAMES[name]
    return text.format(i + 1, i + 2), unit


def _value(profile: Profile, key: str) -> float:
    match = _KEY.match(key)
    return float(getattr(profile.device, match.group(1))[int(match.group(2))])


def _rows(profile: Profile, numbers: Numbers, trusted: bool = True) -> tuple[Row, ...]:
    rows = []
    what = "95&nbsp;% interval" if trusted else "interval (<b class='bad'>not trustworthy</b>)"
    for key, (lo, hi) in profile.identification.intervals.items():
        label, unit = parameter_label(key)
        value = _value(profile, key)
        numbers[f"identify.{key}"] = (value, format_number(value))
        numbers[f"identify.{key}.low"] = (lo, format_number(lo))
        numbers[f"identify.{key}.high"] = (hi, format_number(hi))
        rows.append(Row(f"{label} <code>{html.escape(key)}</code>, {what} "
                        f"[{format_number(lo, rich=True)}, {format_number(hi, rich=True)}]", "", format_number(value, rich=True),
                        unit))
    return tuple(rows)


def _robust_row(numbers: Numbers, key: str, label: str, value: float | None, beyond: BeyondLimit | None,
                unit: str) -> Row:
    """One robust design row: the number, or the phrase when it is beyond its field's physical range."""
    text = format_number(value) if beyond is None else beyond.text()
    numbers[key] = (value, text)
    return Row(label, "", format_number(value, rich=True) if beyond is None else beyond.text(rich=True),
               unit if beyond is None else "")


def _robust_rows(rd: RobustDesigns | None, numbers: Numbers) -> tuple[tuple[Row, ...], str]:
    if rd is None:
        return (), ""
    rows = []
    if rd.unbounded:
        return (), f"<b class='bad'>{html.escape(rd.verdict())}</b>"
    beyond = rd.beyond_limits  # a robust design outside its field's physical range: the phrase
    if rd.impedance:
        s = rd.stiffness
        for key, label, value, design in (("robust.kc", "robust largest k<sub>c</sub> (eq. 9, whole box)", s.kc,
                                           "kc_max"),
                                          ("robust.nominal_kc", "nominal largest k<sub>c</sub> (profile's device)",
                                           s.nominal_kc, "")):
            rows.append(_robust_row(numbers, key, label, value, beyond.get(design), "N/m"))
        numbers["robust.bc"] = (s.bc, format_number(s.bc))
        rows.append(Row("at coupling damping b<sub>c</sub>", "", format_number(s.bc, rich=True), "N&middot;s/m"))
        binding = s.binding
    else:
        d = rd.damping
        for key, label, value, design in (("robust.bc_low", "robust b<sub>c</sub>, lower edge (eq. 21)", d.low,
                                           "bc_low"),
                                          ("robust.bc_high", "robust b<sub>c</sub>, upper edge (eq. 21)", d.high,
                                           "bc_high")):
            rows.append(_robust_row(numbers, key, label, value, beyond.get(design), "N&middot;s/m"))
        binding = {**d.low_binding}
    for key, value in binding.items():
        label, unit = parameter_label(key)
        rows.append(Row(f"binding device: {label}", "", format_number(value, rich=True), unit))
    verdict = html.escape(rd.verdict())
    cls = "ok" if rd.holds else "bad"
    return tuple(rows), f"<b class='{cls}'>{verdict}</b>"


def _bins_and_goodness(pairs: list, goodness: Goodness | None, numbers: Numbers) -> tuple[str, ...]:
    """The bins used of each measurement and why (greyed in the figures), and the goodness-of-fit
    verdict of the profile's device on them."""
    out = []
    if pairs:
        out.append("<b>Bins used</b> (the others are greyed in the figures):")
        out += [f"&bull;&nbsp;{html.escape(m.bins.summary)}" for m, _ in pairs]
        numbers["identify.bins_used"] = (sum(m.bins.used for m, _ in pairs), str(sum(m.bins.used for m, _ in pairs)))
    if goodness is not None:
        numbers["identify.goodness"] = (goodness.statistic, format_number(goodness.statistic, 3))
        if goodness.passed:
            out.append(f"<b class='ok'>Goodness of fit</b> of the profile's device: {html.escape(goodness.message)}.")
        else:
            out.append(f"<b class='bad'>Warning: {html.escape(goodness.message)}.</b> The intervals below are "
                       "not trustworthy.")
    return tuple(out)


def identification_part(profile: Profile) -> Part:
    """The report's sections on the profile's identification (empty without one); results
    ``identify_curves`` (the measured and model responses), ``identify_goodness`` (the
    goodness-of-fit test of the profile's device on the informative bins, or ``None``) and
    ``robust``."""
    sec = profile.identification
    if sec is None:
        return Part()
    numbers: Numbers = {}
    results: dict[str, Any] = {"identify_curves": fit_curves(profile), "robust": robust_designs(profile)}
    names = ", ".join(f"{html.escape(m.source or f'measurement {i + 1}')} ({m.quantity}, handle {m.boundary}, "
                      f"{m.frequency.size} points, {'continuous' if m.sample_time is None else 'sampled'})"
                      for i, m in enumerate(sec.measurements))
    par = ("The device model was identified from measured frequency responses"
           + (f": {names}." if names else " (no measurements embedded).")
           + " The table gives each parameter of the profile's device with its 95&nbsp;% interval "
           "(from the Jacobian or the profile likelihood of the weighted log-response fit, or typed by the "
           "user; &infin; where the measurements do not bound it).")
    pairs = results["identify_curves"]
    goodness = curves_goodness(pairs, len(sec.intervals))
    results["identify_goodness"] = goodness
    trusted = goodness is None or goodness.passed
    notes: tuple[str, ...] = ()
    if sec.notes:
        notes = ("<b>What the fit said</b> about these measurements:",
                 *(f"&bull;&nbsp;{html.escape(t)}" for t in sec.notes))
    notes += _bins_and_goodness(pairs, goodness, numbers)
    out = [Section("Identification", (par,), _rows(profile, numbers, trusted), notes)]
    rows, verdict = _robust_rows(results["robust"], numbers)
    if verdict and not rows:  # unbounded intervals: no box, and the reason
        out.append(Section("Designs that hold for the whole parameter box", (
            "A robust design needs every interval bounded; these measurements leave some open.",),
            (), (verdict,)))
    if rows:
        out.append(Section("Designs that hold for the whole parameter box", (
            "The worst case over every device in the box of intervals above (screening, corners, a seeded "
            "random sample and a bounded local search; the worst case is not always a corner).",),
            rows, (verdict,)))
    return Part(tuple(out), numbers, results)
