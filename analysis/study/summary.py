"""Headline figures and designs of a profile, as plain data (``zwidth analyze``).

The dictionary returned by :func:`summarize` has a stable, documented shape (README,
"JSON output").  Both displays are analysed whatever the profile's display type, because
a user comparing the two configurations of one device (as the paper does for the HBFD)
wants both.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from analysis.twoport.admittance import AdmittanceDisplay
from analysis.twoport.impedance import ImpedanceDisplay
from analysis.profiles.io import Profile

__all__ = ["summarize", "format_summary", "design_summary", "format_design", "SUMMARY_VERSION"]

#: bumped whenever a key is removed or changes meaning (adding keys does not bump it)
SUMMARY_VERSION = 1


def _f(x: float | None) -> float | None:
    return None if x is None else float(x)


def summarize(profile: Profile) -> dict[str, Any]:
    """Verdicts, impedance range and conservative designs for both displays."""
    dev = profile.device
    imp = ImpedanceDisplay(dev)
    ri = imp.evaluate(profile.kc, profile.bc)
    di = imp.max_stiffness(profile.bc)
    adm = AdmittanceDisplay(dev, profile.kp, profile.kd)
    ra = adm.evaluate(profile.mc, profile.bc_adm)
    fd = adm.feasible_damping(profile.mc)
    try:
        mm = adm.min_mass()
        min_mass: dict[str, Any] | None = {
            "mc": mm.mc, "bc": mm.bc, "frequency": mm.frequency,
            "low": _f(mm.interval.low), "high": _f(mm.interval.high),
        }
    except ValueError:
        min_mass = None

    def verdict(r) -> dict[str, Any]:
        return {
            "stable": r.stable,
            "worst_margin": r.worst_margin,
            "worst_frequency": r.worst_frequency,
            "min_eta": r.min_eta,
            "k_max": r.k_max,
            "b_min": r.b_min,
            "apparent_mass": r.apparent_mass,
            "apparent_damping": r.apparent_damping,
        }

    return {
        "summary_version": SUMMARY_VERSION,
        "profile": {
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
        },
        "impedance": {
            "coupling": {"kc": profile.kc, "bc": profile.bc},
            **verdict(ri),
            "design": {
                "bc": di.bc,
                "kc_max": _f(di.kc),
                "frequency": di.frequency,
                "margin": di.margin,
            },
        },
        "admittance": {
            "coupling": {"mc": profile.mc, "bc": profile.bc_adm},
            "pd": {"kp": profile.kp, "kd": profile.kd},
            **verdict(ra),
            "design": {
                "feasible_damping": {
                    "mc": fd.mc, "low": _f(fd.low), "high": _f(fd.high),
                    "low_frequency": fd.low_frequency, "high_frequency": fd.high_frequency,
                },
                "min_mass": min_mass,
            },
        },
    }


def _num(x: Any, unit: str = "", fmt: str = ".6g") -> str:
    if x is None:
        return "infeasible"
    if isinstance(x, float) and math.isinf(x):
        return ("unbounded" if x > 0 else "-inf")
    if isinstance(x, float) and math.isnan(x):
        return "n/a"
    return f"{x:{fmt}} {unit}".rstrip()


def format_summary(d: dict[str, Any]) -> str:
    """Readable text version of :func:`summarize`'s dictionary."""
    p, i, a = d["profile"], d["impedance"], d["admittance"]
    lines = [
        f"Profile: {p['name']}  (display: {p['display']})",
        f"  masses {p['masses']} kg, stiffnesses {p['stiffnesses']} N/m",
        f"  dampings {[round(x, 4) for x in p['dampings']]} N s/m, ground {p['ground_dampings']} N s/m",
        f"  T = {p['sample_time']:g} s, band [{p['band'][0]:g}, {p['band'][1]:.6g}) rad/s",
        "",
        f"Impedance display, coupling k_c = {_num(i['coupling']['kc'], 'N/m')}, b_c = {_num(i['coupling']['bc'], 'N s/m')}",
        f"  unconditionally stable (eq. 9): {'yes' if i['stable'] else 'NO'}",
        f"  worst margin {_num(i['worst_margin'], 'm/(N s)')} at {_num(i['worst_frequency'], 'rad/s')}, min eta {_num(i['min_eta'])}",
        f"  k_max {_num(i['k_max'], 'N/m')}, b_min {_num(i['b_min'], 'N s/m')}",
        f"  free motion: mass {_num(i['apparent_mass'], 'kg')}, damping {_num(i['apparent_damping'], 'N s/m')}",
        f"  design: largest k_c for b_c = {_num(i['design']['bc'], 'N s/m')}: {_num(i['design']['kc_max'], 'N/m')}"
        f" (binds at {_num(i['design']['frequency'], 'rad/s')})",
        "",
        f"Admittance display, coupling m_c = {_num(a['coupling']['mc'], 'kg')}, b_c = {_num(a['coupling']['bc'], 'N s/m')},"
        f" PD k_p = {_num(a['pd']['kp'], 'N/m')}, k_d = {_num(a['pd']['kd'], 'N s/m')}",
        f"  unconditionally stable (eq. 21): {'yes' if a['stable'] else 'NO'}",
        f"  worst margin {_num(a['worst_margin'], 'N s/m')} at {_num(a['worst_frequency'], 'rad/s')}, min eta {_num(a['min_eta'])}",
        f"  k_max {_num(a['k_max'], 'N/m')}; free motion: mass {_num(a['apparent_mass'], 'kg')},"
        f" damping {_num(a['apparent_damping'], 'N s/m')}",
    ]
    fd = a["design"]["feasible_damping"]
    lines.append(f"  design: feasible b_c for m_c = {_num(fd['mc'], 'kg')}: "
                 + ("none" if fd["low"] is None else f"[{_num(fd['low'])}, {_num(fd['high'])}] N s/m"))
    mm = a["design"]["min_mass"]
    lines.append("  design: smallest m_c: " + ("not found" if mm is None else
                 f"{_num(mm['mc'], 'kg')} with b_c = {_num(mm['bc'], 'N s/m')} (binds at {_num(mm['frequency'], 'rad/s')})"))
    return "\n".join(lines)


def design_summary(profile: Profile, display: str | None = None, points: int = 25) -> dict[str, Any]:
    """Conservative designs and the design chart of one display (``zwidth design``).

    Impedance display: the largest k_c for the profile's b_c, and the chart of the largest
    k_c over b_c from 1 to 1e4 N s/m.  Admittance display: the feasible b_c interval at the
    profile's m_c, the smallest m_c, and the feasible (m_c, b_c) region from the smallest
    m_c to 100 times it.  Infeasible points are ``None``; unbounded ones ``inf``.
    """
    display = display or profile.display
    dev = profile.device
    if display == "impedance":
        imp = ImpedanceDisplay(dev)
        d = imp.max_stiffness(profile.bc)
        bcs = np.geomspace(1.0, 1e4, points)
        chart = imp.stiffness_chart(bcs)
        return {
            "summary_version": SUMMARY_VERSION,
            "display": "impedance",
            "design": {"bc": d.bc, "kc_max": _f(d.kc), "frequency": d.frequency, "margin": d.margin},
            "chart": {
                "bc": bcs.tolist(),
                "kc_max": [None if not np.isfinite(x) and not np.isinf(x) else float(x) for x in chart.kc],
                "frequency": chart.frequency.tolist(),
            },
        }
    if display != "admittance":
        raise ValueError(f"display must be 'impedance' or 'admittance', got {display!r}")
    adm = AdmittanceDisplay(dev, profile.kp, profile.kd)
    fd = adm.feasible_damping(profile.mc)
    try:
        mm = adm.min_mass()
    except ValueError:
        mm = None
    out: dict[str, Any] = {
        "summary_version": SUMMARY_VERSION,
        "display": "admittance",
        "pd": {"kp": profile.kp, "kd": profile.kd},
        "feasible_damping": {"mc": fd.mc, "low": _f(fd.low), "high": _f(fd.high),
                             "low_frequency": fd.low_frequency, "high_frequency": fd.high_frequency},
        "min_mass": None if mm is None else {
            "mc": mm.mc, "bc": mm.bc, "frequency": mm.frequency,
            "low": _f(mm.interval.low), "high": _f(mm.interval.high),
        },
        "chart": None,
    }
    if mm is not None:
        mcs = np.geomspace(mm.mc, 100.0 * mm.mc, points)
        ch = adm.mass_chart(mcs)
        out["chart"] = {
            "mc": mcs.tolist(),
            "low": [None if np.isnan(x) else float(x) for x in ch.low],
            "high": [None if np.isnan(x) else float(x) for x in ch.high],
        }
    return out


def format_design(d: dict[str, Any]) -> str:
    """Readable text version of :func:`design_summary`."""
    if d["display"] == "impedance":
        g = d["design"]
        lines = [
            "Impedance display: largest coupling stiffness satisfying eq. 9",
            f"  b_c = {_num(g['bc'], 'N s/m')}: k_c <= {_num(g['kc_max'], 'N/m')}"
            f" (binds at {_num(g['frequency'], 'rad/s')})",
            "",
            "  design chart:      b_c (N s/m)     largest k_c (N/m)   binding (rad/s)",
        ]
        for bc, kc, f in zip(d["chart"]["bc"], d["chart"]["kc_max"], d["chart"]["frequency"]):
            lines.append(f"                   {bc:12.5g}   {_num(kc):>18}   {_num(f):>14}")
        return "\n".join(lines)
    fd, mm = d["feasible_damping"], d["min_mass"]
    lines = [
        f"Admittance display (PD k_p = {_num(d['pd']['kp'], 'N/m')}, k_d = {_num(d['pd']['kd'], 'N s/m')}):"
        " couplings satisfying eq. 21",
        f"  m_c = {_num(fd['mc'], 'kg')}: b_c in "
        + ("none" if fd["low"] is None else f"[{_num(fd['low'])}, {_num(fd['high'])}] N s/m"),
        "  smallest m_c: " + ("not found" if mm is None else
                              f"{_num(mm['mc'], 'kg')} with b_c = {_num(mm['bc'], 'N s/m')}"),
    ]
    if d["chart"]:
        lines += ["", "  feasible region:   m_c (kg)        b_c low (N s/m)    b_c high (N s/m)"]
        for mc, lo, hi in zip(d["chart"]["mc"], d["chart"]["low"], d["chart"]["high"]):
            lines.append(f"                   {mc:10.5g}   {_num(lo):>18}   {_num(hi):>18}")
    return "\n".join(lines)
