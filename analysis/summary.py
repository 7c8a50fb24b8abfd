"""Headline figures and designs of a profile, as plain data (``zwidth analyze``).

The dictionary returned by :func:`summarize` has a stable, documented shape (README,
"JSON output").  Both displays are analysed whatever the profile's display type, because
a user comparing the two configurations of one device (as the paper does for the HBFD)
wants both.
"""

from __future__ import annotations

import math
from typing import Any

from .admittance import AdmittanceDisplay
from .impedance import ImpedanceDisplay
from .profiles import Profile

__all__ = ["summarize", "format_summary", "SUMMARY_VERSION"]

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
