"""The text of the transparency tab's summary, and the shaded B_c spans where J is infinite."""

from __future__ import annotations

import html
import math

import numpy as np

from analysis.transparency.settings import WallSettings

from analysis.study.labels import HOLD_LABELS
from analysis.study.quantities import J_UNIT, rich_numbers
from analysis.study.wall import WallPoint, WallTradeoff
from app.views.base import fmt

__all__ = ["wall_summary", "inf_spans"]


def wall_summary(st: WallSettings, point: WallPoint, trade: WallTradeoff | None, device: str = "") -> str:
    """The tab's summary (rich text): which device (``device``, :func:`analysis.study.wall_device_label`),
    J (eq. 11), ‖L‖∞ (eqs. 16-17) and the robust optimum at B_c."""
    pk = point.peak
    bad, good = "#d0312d", "#2b8a3e"
    lines = [f"<b>{html.escape(device)}</b>"] if device else []
    lines += [f"<b>Hold model:</b> {HOLD_LABELS[st.hold]}",
             f"<b>B<sub>c</sub> = {fmt(point.bc)} N·s/m</b>"]
    if point.index.finite:
        lines.append(f"J = {fmt(point.index.index)} {J_UNIT}")
    else:
        lines.append(f"J = ∞: <span style='color:{bad}'>{point.index.reason}</span>")
    where = "ω → ∞" if math.isinf(pk.frequency) else f"ω = {fmt(pk.frequency)} rad/s"
    unstable = not point.index.finite and "unstable" in point.index.reason
    verdict = (f"<span style='color:{bad}'><b>closed loop unstable</b></span>" if unstable else
               f"<span style='color:{good}'><b>robustly stable</b></span> (≤ 0 dB)" if pk.robust else
               f"<span style='color:{bad}'><b>NOT robustly stable</b></span> (eq. 17 needs ≤ 0 dB)")
    lines.append(f"‖L‖<sub>∞</sub> = {rich_numbers(f'{pk.gain_db:+.2f}')} dB at {where}: {verdict}")
    if not pk.certified:
        lines.append("<i>peak not certified above the grid (zoh ripple)</i>")
    if trade is None:
        lines.append("<i>robust optimum: computing…</i>")
    elif trade.optimum.feasible:
        o = trade.optimum
        on = " (on the constraint ‖L‖<sub>∞</sub> = 1)" if o.constrained else ""
        lines.append(f"<b>Robust optimum:</b> B<sub>c</sub> = {fmt(o.bc)} N·s/m, J = {fmt(o.index)} {J_UNIT}, "
                     f"‖L‖<sub>∞</sub> = {rich_numbers(f'{20 * math.log10(o.peak):+.2f}')} dB{on}")
    else:
        lines.append(f"<b>Robust optimum:</b> <span style='color:{bad}'>none in "
                     f"[{fmt(st.bc_min)}, {fmt(st.bc_max)}] N·s/m: {trade.optimum.reason}</span>")
    if st.hold == "discrete":
        lines.append("<i>Discrete hold: J integrates over [0, π/T) only, so it is not comparable "
                     "with the continuous hold models.</i>")
    lines.append(f"Step: F<sub>h</sub> = {fmt(st.step_force)} N for {fmt(st.step_duration)} s "
                 "on the exact sampled loop (whatever the hold model).")
    return "<br>".join(lines)


def inf_spans(x: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
    """The x ranges where ``mask`` holds, each widened to half the spacing of its neighbours."""
    spans = []
    n = x.size
    i = 0
    while i < n:
        if not mask[i]:
            i += 1
            continue
        j = i
        while j + 1 < n and mask[j + 1]:
            j += 1
        lo = x[i] - 0.5 * (x[i] - x[i - 1]) if i > 0 else x[i]
        hi = x[j] + 0.5 * (x[j + 1] - x[j]) if j + 1 < n else x[j]
        spans.append((float(lo), float(hi)))
        i = j + 1
    return spans
