"""The texts of the sampled-data tab: the map's subtitle, the exact-limit summary, the scenario note.

Rich text for Qt labels; the numbers are the graph's (the exact sampled loop of
``analysis.sampled`` against the two-port bound of eq. 9 / eq. 21).
"""

from __future__ import annotations

import dataclasses
import math

from analysis.profiles.io import Profile
from analysis.profiles.sections import SimulationSection
from analysis.sampled import RIGID_GRASP, SimulationOptions, StabilityMap
from analysis.sampled.terminations import PAPER_WALL_STIFFNESS
from analysis.study import display_kind, map_point

from app.views.base import fmt, plain, rich_label

__all__ = ["map_subtitle", "design_on_map", "exact_summary", "scenario_note", "LINEAR_LABEL", "CATCHING_UP"]

_GOOD, _BAD = "#2b8a3e", "#c92a2a"


def _delay_text(d: int, impl: bool) -> str:
    return f"delay {d} sample(s)" + (" + implementation" if impl else "")


def map_subtitle(p: Profile, m: StabilityMap, d: int, impl: bool) -> str:
    """Who holds the handle, what it touches and which gains are fixed on the map."""
    names = {m.x_name, m.y_name}
    if display_kind(p).is_impedance:
        env = "" if "kobj" in names else f"penalty wall k_obj = {plain(PAPER_WALL_STIFFNESS / 1e3, 6)} kN/m"
        who = "hands-off" if not names & {"grasp_mass", "grasp_stiffness"} else "grasp (other terms 0)"
        fixed = f"k_c = {plain(p.kc, 6)} N/m" if "kc" not in names else f"b_c = {plain(p.bc, 6)} N·s/m"
        if names == {"kc", "bc"}:
            fixed = ""
    else:
        env = "free motion"
        g = RIGID_GRASP
        who = f"rigid grasp ({plain(g.mass, 6)} kg, {plain(g.damping, 6)} N·s/m, {plain(g.stiffness, 6)} N/m)"
        gains = f"k_p = {plain(p.kp, 6)}, k_d = {plain(p.kd, 6)}"
        fixed = f"b_c = {plain(p.bc_adm, 6)} N·s/m, {gains}" if "bc" not in names else gains
    return "; ".join(x for x in (who, env, fixed, _delay_text(d, impl)) if x)


def design_on_map(p: Profile, m: StabilityMap) -> tuple[float, float | None]:
    """Where the current design sits on the map (y is ``None`` when the map's y is not one of its values)."""
    return map_point(p, m.x_name, m.y_name)


#: Said in place of a number that a moving slider drag holds back (computed when it pauses or ends).
CATCHING_UP = "<i>updating after the drag…</i>"


def _impedance_summary(p: Profile, limit: float | None, bound: float | None, delay: str,
                       bound_pending: bool = False) -> str:
    bound_txt = CATCHING_UP if bound_pending else "none" if bound is None else f"{fmt(bound / 1e3, 4)} kN/m"
    if limit is None:
        exact_txt = "computing…"
    elif limit == 0:
        exact_txt = "<b>unstable for every k_c</b>"
    elif math.isinf(limit):
        exact_txt = "no limit below 10⁹ N/m"
    else:
        exact_txt = f"<b>{fmt(limit / 1e3, 4)} kN/m</b>"
    text = (f"Largest stable k_c at b_c = {fmt(p.bc)} N·s/m — exact sampled loop ({delay}, hands-off, "
            f"rigid god-object wall): {exact_txt};  two-port bound (eq. 9, delay-free model): {bound_txt}.  "
            f"Current k_c = {fmt(p.kc / 1e3, 4)} kN/m")
    if limit is not None and math.isfinite(limit):
        ok = p.kc < limit
        text += (f" is <span style='color:{_GOOD}'>below the exact limit</span>." if ok else
                 f" is <span style='color:{_BAD}'><b>above the exact limit: the loop is unstable</b></span>.")
        if bound is not None and limit < bound:
            text += (f"  <span style='color:{_BAD}'>⚠ The two-port bound is not safe here: the exact limit is "
                     f"{100 * (1 - limit / bound):.0f} % lower (the bound assumes no delay).</span>")
        elif bound is not None and limit > bound:
            text += f"  The bound is conservative by a factor {plain(limit / bound, 2)}."
    return text


def _admittance_summary(p: Profile, limit: float | None, delay: str) -> str:
    if limit is None:
        exact_txt = "computing…"
    elif math.isinf(limit):
        exact_txt = "<b>no stable m_c</b>"
    elif limit == 0:
        exact_txt = "every m_c ≥ 1 g stable"
    else:
        exact_txt = f"<b>{fmt(limit, 4)} kg</b>"
    text = (f"Smallest stable m_c at b_c = {fmt(p.bc_adm)} N·s/m — exact sampled loop ({delay}, rigid grasp, "
            f"free motion): {exact_txt}.  Current m_c = {fmt(p.mc)} kg")
    if limit is not None and math.isfinite(limit) and limit > 0:
        text += (f" is <span style='color:{_GOOD}'>above it</span>." if p.mc > limit else
                 f" is <span style='color:{_BAD}'><b>below it: the loop is unstable</b></span>.")
    return text


#: What each verdict of the tab answers (the tab shows two: they can disagree, and say why).
LINEAR_LABEL = "<b>Linear stability</b> (exact sampled loop, no friction, quantization or saturation): "


def exact_summary(p: Profile, limit: float | None, bound: float | None, d: int, impl: bool,
                  bound_pending: bool = False) -> str:
    """The exact limit at the current b_c against the two-port bound (``bound``: largest k_c, eq. 9),
    labelled as the linear loop's answer (:data:`LINEAR_LABEL`).  ``bound_pending``: a slider drag
    holds the bound back (:data:`CATCHING_UP` is said instead)."""
    delay = f"{d}-sample computation delay" if d else "no computation delay"
    if impl:
        delay += " + implementation delay"
    if display_kind(p).is_impedance:
        return LINEAR_LABEL + rich_label(_impedance_summary(p, limit, bound, delay, bound_pending))
    return LINEAR_LABEL + rich_label(_admittance_summary(p, limit, delay))


def scenario_note(sec: SimulationSection, fresh: bool, display: str | None = None) -> str:
    """What was simulated (grasp, environment, effects and delays), and how the simulation's verdict
    relates to the linear limit of ``display`` (the profile's display; default impedance)."""
    sc, o = sec.scenario, sec.options
    ideal = dataclasses.replace(o, delay_samples=0, implementation_delay=False) == SimulationOptions()
    effects = "ideal sensors and actuator" if ideal else "with quantization / friction / saturation"
    grasp = "hands-off" if sc.grasp.hands_off else (
        f"grasp {plain(sc.grasp.mass, 6)} kg, {plain(sc.grasp.damping, 6)} N·s/m, {plain(sc.grasp.stiffness, 6)} N/m"
        f"{f' until {plain(sc.release_time, 6)} s' if math.isfinite(sc.release_time) else ''}")
    env = ("no wall" if not sc.wall else
           f"penalty wall {plain(sc.wall_stiffness, 6)} N/m" if display_kind(sc.causality).is_impedance else "god-object wall")
    linear = ("hands-off against a rigid wall, so a damped grasp can be stable beyond it"
              if display is None or display_kind(display).is_impedance else
              "a rigid grasp in free motion and the linear loop")
    note = (f"Scenario: {sc.name.replace('_', ' ')} ({grasp}; {env}); {effects}; delay {o.delay_samples} sample(s)"
            f"{', implementation delay' if o.implementation_delay else ''}.  The linear limit above is for "
            f"{linear}.")
    if not ideal:
        note += ("  With friction or quantization a small limit cycle below the rest threshold counts as "
                 "stable here even where the linear loop is unstable.")
    if not fresh:
        note += "  (result of the previous inputs)"
    return note
