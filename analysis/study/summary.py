"""Headline figures and designs of a profile, as plain data (``zwidth analyze`` and ``zwidth design``).

The dictionary returned by :func:`summarize` has a stable, documented shape (README,
"JSON output").  Both displays are analysed whatever the profile's display type, because
a user comparing the two configurations of one device (as the paper does for the HBFD)
wants both.  Every number comes from :func:`analysis.study.headline.headline` and
:func:`analysis.study.compute.design_chart`; the text versions print through
:class:`analysis.study.quantities.Quantity`, as the GUI and the report do.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from analysis.profiles.model import Profile
from analysis.study.compute import design_chart
from analysis.study.design_limits import design_beyond_limits
from analysis.study.displays import ADMITTANCE, IMPEDANCE, DisplayKind, display_kind
from analysis.study.headline import Headline, designs, headline
from analysis.study.quantities import format_number, quantity

__all__ = ["summarize", "format_summary", "design_summary", "format_design", "SUMMARY_VERSION"]

#: bumped whenever a key is removed or changes meaning (adding keys does not bump it)
SUMMARY_VERSION = 1


def _verdict(h: Headline) -> dict[str, Any]:
    return {
        "stable": h.stable,
        "stability_reserve": h.stability_reserve,
        "binding_frequency": h.binding_frequency,
        "worst_margin": h.worst_margin,
        "worst_frequency": h.worst_frequency,
        "min_eta": h.min_eta,
        "k_max": h.k_max,
        "b_min": h.b_min,
        "apparent_mass": h.apparent_mass,
        "apparent_damping": h.apparent_damping,
    }


def _flagged(out: dict[str, Any], d: dict[str, Any], keys: dict[str, str]) -> dict[str, Any]:
    """``out`` with ``beyond_limit`` (any value outside its field's physical range) and ``beyond``
    (JSON key -> "beyond the physical range (b_c ≤ 1e+08 N·s/m)"); ``keys``: design key -> JSON key.
    The numbers stay as they are (docs/results.md)."""
    found = design_beyond_limits({k: d[k] for k in keys})
    out["beyond_limit"] = bool(found)
    out["beyond"] = {keys[k]: b.text() for k, b in found.items()}
    return out


def _impedance_design(d: dict[str, Any]) -> dict[str, Any]:
    return _flagged({"bc": d["bc"], "kc_max": d["kc_max"], "frequency": d["kc_max_frequency"],
                     "margin": d["kc_max_margin"]}, d, {"kc_max": "kc_max"})


def _feasible_damping(d: dict[str, Any]) -> dict[str, Any]:
    return _flagged({"mc": d["mc"], "low": d["bc_low"], "high": d["bc_high"], "low_frequency": d["bc_low_frequency"],
                     "high_frequency": d["bc_high_frequency"]}, d, {"bc_low": "low", "bc_high": "high"})


def _min_mass(d: dict[str, Any]) -> dict[str, Any] | None:
    if d["min_mc"] is None:
        return None
    return _flagged({"mc": d["min_mc"], "bc": d["min_mc_bc"], "frequency": d["min_mc_frequency"],
                     "low": d["min_mc_bc_low"], "high": d["min_mc_bc_high"]}, d,
                    {"min_mc": "mc", "min_mc_bc": "bc", "min_mc_bc_low": "low", "min_mc_bc_high": "high"})


def _v(d: dict[str, Any], json_key: str, key: str) -> str:
    """``d[json_key]`` printed as the quantity ``key``, or the phrase when it is beyond its limit."""
    beyond = d.get("beyond", {}).get(json_key)
    return beyond.replace("·", " ") if beyond else _q(key, d[json_key])


def _interval(d: dict[str, Any]) -> str:
    """The feasible b_c interval ``[low, high] N s/m``, an end beyond its limit as the phrase."""
    if not d.get("beyond"):
        return f"[{_n(d['low'])}, {_n(d['high'])}] N s/m"
    return f"[{_v(d, 'low', 'bc_low')}, {_v(d, 'high', 'bc_high')}]"


def _profile(profile: Profile) -> dict[str, Any]:
    dev = profile.device
    return {
        "name": profile.name,
        "display": profile.display,
        "sample_time": dev.sample_time,
        "band": [dev.band_min, dev.nyquist],
        "masses": dev.masses.tolist(),
        "stiffnesses": dev.stiffnesses.tolist(),
        "dampings": dev.dampings.tolist(),
        "damping_ratios": dev.damping_ratios.tolist(),
        "ground_dampings": dev.ground_dampings.tolist(),
        "sensor_element": dev.sensor_element,
    }


def summarize(profile: Profile) -> dict[str, Any]:
    """Verdicts, impedance range and conservative designs for both displays.

    The verdicts come with the stability reserve and its binding frequency.

    Parameters
    ----------
    profile : Profile
        The device profile.

    Returns
    -------
    dict of str to Any
        ``summary_version``, ``profile`` (the device's parameters) and, for ``impedance`` and
        ``admittance``, the coupling, the headline values in SI units and the designs (README,
        "JSON output").
    """
    hi = headline(profile, IMPEDANCE)
    ha = headline(profile, ADMITTANCE)
    return {
        "summary_version": SUMMARY_VERSION,
        "profile": _profile(profile),
        "impedance": {
            "coupling": {"kc": profile.kc, "bc": profile.bc},
            **_verdict(hi),
            "design": _impedance_design(hi.designs),
        },
        "admittance": {
            "coupling": {"mc": profile.mc, "bc": profile.bc_adm},
            "pd": {"kp": profile.kp, "kd": profile.kd},
            **_verdict(ha),
            "design": {"feasible_damping": _feasible_damping(ha.designs), "min_mass": _min_mass(ha.designs)},
        },
    }


def _q(key: str, value: Any, margin_unit: str | None = None) -> str:
    """``value`` printed as the quantity ``key`` (units with a plain space, as the CLI prints them)."""
    return quantity(key, margin_unit).format(value).replace("·", " ")


def _n(value: Any) -> str:
    return format_number(value)


def _ns(values: Any) -> str:
    """``[0.08006, 2.3]``: a list of numbers through :func:`format_number` (a fitted mass is not
    printed as 0.08005979194545117)."""
    return "[" + ", ".join(format_number(v) for v in values) + "]"


def _verdict_lines(d: dict[str, Any], kind: DisplayKind) -> list[str]:
    mu = kind.margin_unit
    return [
        f"  virtual coupling (Llewellyn, eq. {kind.bound_equation}) unconditionally stable: "
        f"{'yes' if d['stable'] else 'NO'}",
        f"  stability reserve {_q('stability_reserve', d['stability_reserve'])},"
        f" binding at {_q('binding_frequency', d['binding_frequency'])}",
        f"  worst margin {_q('worst_margin', d['worst_margin'], mu)} at {_q('worst_frequency', d['worst_frequency'])},"
        f" min eta {_q('min_eta', d['min_eta'])}",
        f"  k_max {_q('k_max', d['k_max'])}, b_min {_q('b_min', d['b_min'])}",
        f"  free motion: mass {_q('apparent_mass', d['apparent_mass'])},"
        f" damping {_q('apparent_damping', d['apparent_damping'])}",
    ]


def format_summary(d: dict[str, Any]) -> str:
    """Readable text version of :func:`summarize`'s dictionary.

    Parameters
    ----------
    d : dict of str to Any
        A dictionary as :func:`summarize` returns it.

    Returns
    -------
    str
        The text ``zwidth analyze`` prints, one line per entry.

    Raises
    ------
    KeyError
        When ``d`` lacks a key of :func:`summarize`'s shape.
    """
    p, i, a = d["profile"], d["impedance"], d["admittance"]
    g = i["design"]
    fd, mm = a["design"]["feasible_damping"], a["design"]["min_mass"]
    lines = [
        f"Profile: {p['name']}  (display: {p['display']})",
        f"  masses {_ns(p['masses'])} kg, stiffnesses {_ns(p['stiffnesses'])} N/m",
        f"  dampings {_ns(p['dampings'])} N s/m, ground {_ns(p['ground_dampings'])} N s/m",
        f"  T = {p['sample_time']:g} s, band [{p['band'][0]:g}, {p['band'][1]:.6g}) rad/s",
        "",
        f"Impedance display, coupling k_c = {_q('kc', i['coupling']['kc'])}, b_c = {_q('bc', i['coupling']['bc'])}",
        *_verdict_lines(i, IMPEDANCE),
        f"  design: largest k_c for b_c = {_q('bc', g['bc'])}: {_v(g, 'kc_max', 'kc_max')}"
        f" (binds at {_q('kc_max_frequency', g['frequency'])})",
        "",
        f"Admittance display, coupling m_c = {_q('mc', a['coupling']['mc'])}, b_c = {_q('bc', a['coupling']['bc'])},"
        f" PD k_p = {_q('kp', a['pd']['kp'])}, k_d = {_q('kd', a['pd']['kd'])}",
        *_verdict_lines(a, ADMITTANCE),
        f"  design: feasible b_c for m_c = {_q('mc', fd['mc'])}: "
        + ("none" if fd["low"] is None else _interval(fd)),
        "  design: smallest m_c: " + ("not found" if mm is None else
                                      f"{_v(mm, 'mc', 'min_mc')} with b_c = {_v(mm, 'bc', 'min_mc_bc')}"
                                      f" (binds at {_q('min_mc_frequency', mm['frequency'])})"),
    ]
    return "\n".join(lines)


def _listed(values: np.ndarray) -> list[float | None]:
    """Chart values for JSON: infeasible (NaN) points are ``None``, unbounded ones ``inf``."""
    return [None if np.isnan(x) else float(x) for x in values]


def design_summary(profile: Profile, display: str | None = None, points: int = 25) -> dict[str, Any]:
    """Conservative designs and the design chart of one display (``zwidth design``).

    Impedance display: the largest k_c for the profile's b_c, and the chart of the largest
    k_c over b_c from 1 to 1e4 N s/m.  Admittance display: the feasible b_c interval at the
    profile's m_c, the smallest m_c, and the feasible (m_c, b_c) region from the smallest
    m_c to 100 times it.  Infeasible points are ``None``; unbounded ones ``inf``.

    Parameters
    ----------
    profile : Profile
        The device profile.
    display : str or None, optional
        ``"impedance"`` or ``"admittance"``; ``None`` takes the profile's display.
    points : int, optional
        Number of points of the design chart.

    Returns
    -------
    dict of str to Any
        ``summary_version``, ``display``, the designs and ``chart`` (lists of the chart's grid
        and values in SI units; ``None`` for the admittance display without a smallest m_c).
    """
    kind = display_kind(display or profile)
    found = designs(profile, kind)
    out: dict[str, Any] = {"summary_version": SUMMARY_VERSION, "display": kind.name}
    if kind.is_impedance:
        res = design_chart(profile, kind, bc_range=(1.0, 1e4), points=points)
        assert res is not None
        out["design"] = _impedance_design(found)
        out["chart"] = {"bc": res.chart.bc.tolist(), "kc_max": _listed(res.chart.kc),
                        "frequency": res.chart.frequency.tolist()}
        return out
    mm = _min_mass(found)
    out.update({"pd": {"kp": profile.kp, "kd": profile.kd}, "feasible_damping": _feasible_damping(found),
                "min_mass": mm, "chart": None})
    if mm is not None:
        res = design_chart(profile, kind, mc_range=(mm["mc"], 100.0 * mm["mc"]), points=points)
        assert res is not None
        out["chart"] = {"mc": res.chart.mc.tolist(), "low": _listed(res.chart.low), "high": _listed(res.chart.high)}
    return out


def format_design(d: dict[str, Any]) -> str:
    """Readable text version of :func:`design_summary`.

    Parameters
    ----------
    d : dict of str to Any
        A dictionary as :func:`design_summary` returns it.

    Returns
    -------
    str
        The text ``zwidth design`` prints, with the design chart as a table.

    Raises
    ------
    KeyError
        When ``d`` lacks a key of :func:`design_summary`'s shape.
    """
    if display_kind(d["display"]).is_impedance:
        g = d["design"]
        lines = [
            "Impedance display: largest coupling stiffness satisfying eq. 9",
            f"  b_c = {_q('bc', g['bc'])}: "
            + (f"no k_c satisfies eq. 9 (the bound is exceeded at {_q('kc_max_frequency', g['frequency'])})"
               if g["kc_max"] is None else
               f"k_c <= {_v(g, 'kc_max', 'kc_max')} (binds at {_q('kc_max_frequency', g['frequency'])})"),
            "",
            "  design chart:      b_c (N s/m)     largest k_c (N/m)   binding (rad/s)",
        ]
        for bc, kc, f in zip(d["chart"]["bc"], d["chart"]["kc_max"], d["chart"]["frequency"]):
            lines.append(f"                   {bc:12.5g}   {_n(kc):>18}   {_n(f):>14}")
        return "\n".join(lines)
    fd, mm = d["feasible_damping"], d["min_mass"]
    lines = [
        f"Admittance display (PD k_p = {_q('kp', d['pd']['kp'])}, k_d = {_q('kd', d['pd']['kd'])}):"
        " couplings satisfying eq. 21",
        f"  m_c = {_q('mc', fd['mc'])}: "
        + ("no b_c satisfies eq. 21" if fd["low"] is None else f"b_c in {_interval(fd)}"),
        "  smallest m_c: " + ("not found" if mm is None else
                              f"{_v(mm, 'mc', 'min_mc')} with b_c = {_v(mm, 'bc', 'min_mc_bc')}"),
    ]
    if d["chart"]:
        lines += ["", "  feasible region:   m_c (kg)        b_c low (N s/m)    b_c high (N s/m)"]
        for mc, lo, hi in zip(d["chart"]["mc"], d["chart"]["low"], d["chart"]["high"]):
            lines.append(f"                   {mc:10.5g}   {_n(lo):>18}   {_n(hi):>18}")
    return "\n".join(lines)
