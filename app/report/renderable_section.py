"""The report's renderable-space part (issue 24), when the profile has a ``renderable`` section.

Qt-free: :func:`renderable_part` (called by :func:`app.report.content.gather`) gives the M-width of
Colonnese & Okamura (RSS 2012) for all the qualities asked and for each, the volume of the renderable
(M, B, K) space of Colonnese & Chan (IEEE Haptics Symposium 2016) and the largest K at the rendered
(M, B), all from :func:`analysis.study.renderable_study`.  Its figures (needing Qt) are in
:mod:`app.report.renderable_figures`.
"""

from __future__ import annotations

import html

from analysis.profiles import Profile
from analysis.profiles.schema import GRASP_SETS
from analysis.study import QUALITY_LABELS, format_number, k_max_at, renderable_section, renderable_study
from app.report.model import Numbers, Part, Row, Section

__all__ = ["renderable_part"]


def _row(numbers: Numbers, key: str, label: str, value: float, unit: str) -> Row:
    numbers[key] = (value, format_number(value))  # the number table: ASCII, as the CLI prints it
    return Row(label, "", format_number(value, rich=True), unit)


def renderable_part(profile: Profile) -> Part:
    """The report's section on the renderable space (empty without a ``renderable`` section), with
    the study as its result (``renderable_study``)."""
    if profile.renderable is None:
        return Part()
    sec = renderable_section(profile)
    study = renderable_study(profile)
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
    return Part((Section("Renderable space and M-width", (par,), tuple(rows)),), numbers,
                {"renderable_study": study})
