"""The report's identification figures (issue 14; needs Qt): measured against model magnitude
(``identify``) and phase (``identify_phase``) of the measurements embedded in the profile, the
model being the profile's device.  The bins a fit leaves out (coherence below the analysis
module's threshold) are drawn apart as small grey points, with their own legend entry
(:data:`analysis.study.UNUSED_BINS_LABEL`; issue 23).  The numbers are
:mod:`app.report.identify_section`'s.
"""

from __future__ import annotations

import html

from app import qt_compat  # noqa: F401 - before any Qt call

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt

from analysis.study import UNUSED_BINS_LABEL, BodeData, bode_data
from app.report.model import Figure, ReportContent
from app.report.plots import CurvesPlot

__all__ = ["FIGURE_KEYS", "UNUSED_COLOR", "identify_figure"]

FIGURE_KEYS = ("identify", "identify_phase")
#: The greyed bins: a pale grey, apart from the measured curve's colour.
UNUSED_COLOR = "#adb5bd"
_MEASURED = "#495057"


def _measured(v: CurvesPlot, data: BodeData, values: np.ndarray) -> None:
    """The measured curve at the fitted bins and, when some were left out, those bins greyed."""
    v.add("measured" if not data.has_unused else "measured (bins fitted)", data.w, data.where_used(values),
          _MEASURED, width=3.0)
    if data.has_unused:
        # (the legend is rich text: "<" escaped)
        v.add(html.escape(UNUSED_BINS_LABEL), data.w, data.where_used(values, False), UNUSED_COLOR, symbol="o")
        item = v.plot.listDataItems()[-1]  # small grey points, no outline: they are not the data fitted
        item.setSymbolSize(4)
        item.setSymbolPen(pg.mkPen(None))
        item.setZValue(-1)


def identify_figure(content: ReportContent, key: str) -> Figure | None:
    """The measured-against-model Bode figure (``identify`` magnitude, ``identify_phase`` phase)."""
    pairs = content.results.get("identify_curves")
    if not pairs:
        return None
    data = bode_data(pairs)
    unit = "N/N" if pairs[0][0].quantity == "gauge" else "m/N"
    grey = " Bins the fit leaves out are grey points." if data.has_unused else ""
    if key == "identify":
        v = CurvesPlot("Identification: magnitude", ("ω", "rad/s"), ("|H|", unit), log_x=True, log_y=True)
        _measured(v, data, data.measured_mag)
        v.add("model (profile's device)", data.w, data.model_mag, "#1f5fbf", style=Qt.PenStyle.DashLine)
        cap = ("Measured frequency responses (embedded in the profile) and the response of the profile's "
               "device at the same frequencies: magnitude." + grey)
        return Figure(key, "Identification fit: magnitude", cap, v)
    v = CurvesPlot("Identification: phase", ("ω", "rad/s"), ("∠H", "°"), log_x=True)
    _measured(v, data, data.measured_phase)
    v.add("model (profile's device)", data.w, data.model_phase, "#1f5fbf", style=Qt.PenStyle.DashLine)
    return Figure(key, "Identification fit: phase", "Measured and model phase, unwrapped per measurement." + grey, v)
