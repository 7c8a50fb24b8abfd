"""The report's renderable-space part (issue 24), when the profile has a ``renderable`` section.

Qt-free: :func:`renderable_part` (called by :func:`app.report.content.gather`) gives the M-width of
Colonnese & Okamura (RSS 2012) for all the qualities asked and for each, the volume of the renderable
(M, B, K) space of Colonnese & Chan (IEEE Haptics Symposium 2016) and the largest K at the rendered
(M, B), all from :func:`analysis.study.renderable_study`.  When the profile's identified intervals bound
a parameter box (:func:`analysis.study.robust_box_reason` is ``None``), the section adds the robust space
over the box's corners (or 16 seeded samples of a box of more than four parameters), as the tab's
"Robust over" overlay computes it
(``RenderableRequest.of(profile, robust="corners")``, :func:`analysis.study.robust_study`): its volume,
its largest K at the rendered (M, B) and the M-width every corner renders
(:func:`analysis.study.renderable.robust_m_width`); without a box, one sentence says why.  Its figures
(needing Qt) are in :mod:`app.report.renderable_figures`; :func:`renderable_results` are the results they
draw, computed alone by ``zwidth export-plot --plot space --robust ...``.
"""

from __future__ import annotations

import html
from typing import Any

from analysis.profiles import Profile
from analysis.profiles.schema import GRASP_SETS
from analysis.study import (
    QUALITY_LABELS,
    ROBUST_SAMPLES,
    RenderableRequest,
    format_number,
    k_max_at,
    renderable_section,
    renderable_study,
    robust_box_reason,
    robust_study,
)
from analysis.study.renderable import robust_m_width
from app.report.model import Numbers, Part, Row, Section

__all__ = ["renderable_part", "renderable_results", "REPORT_ROBUST", "report_robust_kind"]

#: How the report takes the identified box for its robust space (a key of ``ROBUST_KINDS``): its
#: corners while there are at most :data:`ROBUST_SAMPLES` of them (four boxed parameters), else that
#: many seeded samples (an identified HBFD boxes 14 parameters: 16384 corners, each a whole space).
REPORT_ROBUST = "corners"


def report_robust_kind(profile: Profile) -> str:
    """The batch the report's robust space takes: ``"off"`` without a box (:func:`robust_box_reason`),
    ``"corners"`` for a box of at most :data:`ROBUST_SAMPLES` corners, else ``"samples"``
    (:data:`ROBUST_SAMPLES` seeded devices, as the tab's "samples of the box")."""
    if robust_box_reason(profile) is not None:
        return "off"
    req = RenderableRequest.of(profile, robust=REPORT_ROBUST)
    return REPORT_ROBUST if 2 ** len(req.robust.intervals) <= ROBUST_SAMPLES else "samples"


def _row(numbers: Numbers, key: str, label: str, value: float, unit: str) -> Row:
    numbers[key] = (value, format_number(value))  # the number table: ASCII, as the CLI prints it
    return Row(label, "", format_number(value, rich=True), unit)


def renderable_results(profile: Profile, robust: str = "off", samples: int = ROBUST_SAMPLES) -> dict[str, Any]:
    """The results the section's figures draw: ``renderable_study`` and, when ``robust`` (a key of
    ``ROBUST_KINDS``) is not ``"off"`` and the profile has a box, ``renderable_robust`` (the robust
    space, :func:`analysis.study.robust_study`) and ``renderable_robust_label`` (its batch in words,
    as the tab's overlay labels it); ``samples`` for ``robust="samples"``."""
    out: dict[str, Any] = {"renderable_study": renderable_study(profile)}
    req = RenderableRequest.of(profile, robust=robust, samples=samples)
    if req.robust is not None:
        out["renderable_robust"] = robust_study(req)
        out["renderable_robust_label"] = req.robust.label(req.device)
    return out


def _robust_rows(profile: Profile, results: dict[str, Any], numbers: Numbers) -> tuple[list[Row], str]:
    """The robust space's rows (M-width, volume, largest K at the rendered (M, B)) and its sentence."""
    sec = renderable_section(profile)
    robust, label = results["renderable_robust"], results["renderable_robust_label"]
    w = robust_m_width(RenderableRequest.of(profile, robust=report_robust_kind(profile)))
    rows = [_row(numbers, "renderable.robust.m_min", f"robust M-width, lowest mass ({label})", w.m_min, "kg"),
            _row(numbers, "renderable.robust.m_max", f"robust M-width, highest mass ({label})", w.m_max, "kg"),
            _row(numbers, "renderable.robust.m_width", f"robust M-width ({label})", w.width, "kg"),
            _row(numbers, "renderable.robust.volume", f"robust volume ({label})", robust.volume,
                 "kg&middot;decades&sup2;"),
            _row(numbers, "renderable.robust.k_max_at_environment",
                 f"robust largest K at the rendered (M, B), nearest grid point ({label})",
                 k_max_at(robust, sec.virtual_mass, sec.virtual_damping), "N/m")]
    text = (f"The robust space is the space that every device of the identified parameter box renders, taken "
            f"over the {html.escape(label)}: the smallest K<sub>max</sub> over them at each (M, B) of the same grid "
            f"(dashed in the figure; hatched where this device renders K and the box does not); the robust M-width "
            f"is the interval of the masses that every one of them renders at B = K = 0.")
    return rows, text


def renderable_part(profile: Profile) -> Part:
    """The report's section on the renderable space (empty without a ``renderable`` section), with
    the study as its result (``renderable_study``)."""
    if profile.renderable is None:
        return Part()
    sec = renderable_section(profile)
    reason = robust_box_reason(profile)
    results = renderable_results(profile, report_robust_kind(profile))
    study = results["renderable_study"]
    w, sp = study.width, study.space
    numbers: Numbers = {}
    rows = [_row(numbers, "renderable.m_min", "M-width, lowest mass (all qualities)", w.m_min, "kg"),
            _row(numbers, "renderable.m_max", "M-width, highest mass (all qualities)", w.m_max, "kg"),
            _row(numbers, "renderable.m_width", "M-width (all qualities)", w.width, "kg")]
    for q in w.qualities if len(w.qualities) > 1 else ():
        lo, hi = w.by_quality[q]
        rows.append(_row(numbers, f"renderable.m_min.{q}", f"M-width, lowest mass ({q})", lo, "kg"))
        rows.append(_row(numbers, f"renderable.m_max.{q}", f"M-width, highest mass ({q})", hi, "kg"))
    rows.append(_row(numbers, "renderable.volume", "volume of the space (M linear, B and K on log axes)", sp.volume,
                     "kg&middot;decades&sup2;"))
    k = k_max_at(sp, sec.virtual_mass, sec.virtual_damping)
    rows.append(_row(numbers, "renderable.k_max_at_environment", "largest K at the rendered (M, B), nearest grid point",
                     k, "N/m"))
    names = ", ".join(QUALITY_LABELS[q] for q in w.qualities)

    def num(x: float) -> str:  # a number of the page's HTML
        return format_number(x, rich=True)

    par = (f"The impedance display renders F = M&nbsp;&acirc; + B&nbsp;v&#770; + K&nbsp;x with the acceleration "
           f"estimate {html.escape(sec.acceleration.label())}. Qualities asked: {html.escape(names)} (grasps: "
           f"{html.escape(GRASP_SETS[sec.grasps])}). The M-width (Colonnese &amp; Okamura) is the interval of "
           f"virtual masses rendered with them at B = K = 0; the renderable space (Colonnese &amp; Chan) is the "
           f"largest K for each (M, B) of a {sp.mass.size} &times; {sp.damping.size} grid, M from "
           f"{num(sp.mass[0])} to {num(sp.mass[-1])} kg, B from {num(sp.damping[0])} "
           f"to {num(sp.damping[-1])} N&middot;s/m. The rendered environment is M = "
           f"{num(sec.virtual_mass)} kg, B = {num(sec.virtual_damping)} N&middot;s/m, K = "
           f"{num(sec.virtual_stiffness)} N/m.")
    if reason is None:
        more, after = _robust_rows(profile, results, numbers)
        rows += more
    else:
        after = f"No robust space over an identified box: {html.escape(reason)}."
    return Part((Section("Renderable space and M-width", (par,), tuple(rows), (after,)),), numbers, results)
