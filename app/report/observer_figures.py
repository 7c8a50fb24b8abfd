"""The report's disturbance-observer figures (needs Qt): the plants and the disturbance response of
one axis (``observer_plant``) and the cross-axis coupling of the two-axis device
(``observer_coupling``), drawing the results of :mod:`app.report.observer_section`.
"""

from __future__ import annotations

from app import qt_compat  # noqa: F401 - before any Qt call

import numpy as np
from PySide6.QtCore import Qt

from app.report.model import Figure, ReportContent
from app.report.plots import CurvesPlot

__all__ = ["FIGURE_KEYS", "observer_figure"]

FIGURE_KEYS = ("observer_plant", "observer_coupling")

_ADMITTANCE = "m/(N·s)"


def observer_figure(content: ReportContent, key: str) -> Figure | None:
    """The single-axis plants (``observer_plant``) or the two-axis coupling (``observer_coupling``)."""
    res = content.results
    if "observer_response" not in res:
        return None
    if key == "observer_plant":
        r = res["observer_response"]
        v = CurvesPlot("Observer: plants", ("ω", "rad/s"), ("|P|", _ADMITTANCE), log_x=True, log_y=True)
        v.add("real plant P", r.w, np.abs(r.plant), "#868e96", width=3.0)
        v.add("nominal P<sub>n</sub>", r.w, np.abs(r.nominal), "#2b8a3e", style=Qt.PenStyle.DashLine)
        v.add("through the observer", r.w, np.abs(r.effective), "#1f5fbf")
        v.add("v/d with the observer", r.w, np.abs(r.disturbance_with), "#d9480f", width=1.5)
        cap = ("Single axis (eq. 3&ndash;5): the real plant <i>P</i>, the nominal <i>P</i><sub>n</sub>, the plant "
               "seen through the observer, and the disturbance-to-velocity response with the observer (without "
               "it, it is <i>P</i>).")
        return Figure(key, "Disturbance observer: plants", cap, v)
    c = res["observer_coupling"]
    v = CurvesPlot("Observer: coupling", ("ω", "rad/s"), ("|v_y/F_x|", _ADMITTANCE), log_x=True, log_y=True)
    v.add("without the observers", c.w, np.abs(c.coupling_without), "#868e96", width=3.0)
    v.add("with the observers", c.w, np.abs(c.coupling_with), "#1f5fbf")
    cap = ("Cross-axis coupling |v<sub>y</sub>/F<sub>x</sub>| of the two-axis five-bar device (eq. 2) without "
           "and with an observer on each axis.")
    return Figure(key, "Disturbance observer: cross-axis coupling", cap, v)
