"""The report's identification figures (issue 14; needs Qt): measured against model magnitude
(``identify``) and phase (``identify_phase``) of the measurements embedded in the profile, the
model being the profile's device.  The numbers are :mod:`app.report.identify_section`'s.
"""

from __future__ import annotations

from app import qt_compat  # noqa: F401 - before any Qt call

from PySide6.QtCore import Qt

from analysis.study import bode_data
from app.report.model import Figure, ReportContent
from app.report.plots import CurvesPlot

__all__ = ["FIGURE_KEYS", "identify_figure"]

FIGURE_KEYS = ("identify", "identify_phase")


def identify_figure(content: ReportContent, key: str) -> Figure | None:
    """The measured-against-model Bode figure (``identify`` magnitude, ``identify_phase`` phase)."""
    pairs = content.results.get("identify_curves")
    if not pairs:
        return None
    data = bode_data(pairs)
    unit = "N/N" if pairs[0][0].quantity == "gauge" else "m/N"
    if key == "identify":
        v = CurvesPlot("Identification: magnitude", ("ω", "rad/s"), ("|H|", unit), log_x=True, log_y=True)
        v.add("measured", data.w, data.measured_mag, "#868e96", width=3.0)
        v.add("model (profile's device)", data.w, data.model_mag, "#1f5fbf", style=Qt.PenStyle.DashLine)
        cap = ("Measured frequency responses (embedded in the profile) and the response of the profile's "
               "device at the same frequencies: magnitude.")
        return Figure(key, "Identification fit: magnitude", cap, v)
    v = CurvesPlot("Identification: phase", ("ω", "rad/s"), ("∠H", "°"), log_x=True)
    v.add("measured", data.w, data.measured_phase, "#868e96", width=3.0)
    v.add("model (profile's device)", data.w, data.model_phase, "#1f5fbf", style=Qt.PenStyle.DashLine)
    return Figure(key, "Identification fit: phase", "Measured and model phase, unwrapped per measurement.", v)
