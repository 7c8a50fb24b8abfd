"""The report's figures: the app's own plot views, fed with the report's results, offscreen.

The bound plot, the impedance range plot and the design chart are the very
:class:`~app.views.base.PlotView` classes of the main window.  The app has no view yet for
the transparency curves, the sampled-data map and the scenario, so they are small
:class:`~app.report.plots.CurvesPlot` plots, with the same axes, fonts and palette.  The
identification and Z-width figures are built by :mod:`.identify_figures` and :mod:`.zwidth_figures`.
"""

from __future__ import annotations

import html
import math
import os
import sys
from collections.abc import Callable, Iterable

from app import qt_compat  # noqa: F401 - before any Qt call

import numpy as np
from PySide6.QtCore import Qt, qInstallMessageHandler
from PySide6.QtGui import QFont, QGuiApplication
from PySide6.QtWidgets import QApplication

from analysis.study import QUANTITIES, display_kind, rich_numbers, scenario_title
from app.views.base import PlotView, rich_label
from app.views.design_chart import DesignChart
from app.views.range_plot import RangePlot
from app.views.stability_map import StabilityMapView
from app.views.stability_plot import StabilityPlot
from app.report.identify_figures import FIGURE_KEYS as IDENTIFY_FIGURES, identify_figure
from app.report.observer_figures import FIGURE_KEYS as OBSERVER_FIGURES, observer_figure
from app.report.model import Figure, ReportContent, num, symbol_html
from app.report.plots import CurvesPlot
from app.report.zwidth_figures import FIGURE_KEYS as ZWIDTH_FIGURES, zwidth_figure
from app.report.renderable_figures import FIGURE_KEYS as RENDERABLE_FIGURES, renderable_figure
from app.report.workspace_figures import FIGURE_KEYS as WORKSPACE_FIGURES, workspace_figure

__all__ = ["Figure", "build_figures", "ensure_app", "make_view", "FIG_SIZE", "FIGURE_KEYS", "CurvesPlot",
           "quiet_messages", "prepare_view", "figure_parts"]

#: size (px at 96 dpi) the views are laid out at; the PDF scales them to the text width
FIG_SIZE = (658, 350)
#: margins (px: left, top, right, bottom) round a figure's plot, so that no tick label or line label is clipped
FIG_MARGINS = (6, 12, 16, 4)


def ensure_app() -> QApplication:
    """The running QApplication, or a new one (offscreen when there is no display)."""
    app = QApplication.instance()
    if app is None:
        if (not os.environ.get("QT_QPA_PLATFORM") and sys.platform.startswith("linux")
                and not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY")):
            os.environ["QT_QPA_PLATFORM"] = "offscreen"
        app = QApplication(sys.argv[:1])
        if QGuiApplication.platformName() == "offscreen":
            qInstallMessageHandler(quiet_messages)
    return app


def quiet_messages(mode: object, context: object, message: str) -> None:
    """A Qt message handler: drops the offscreen platform's "does not support propagateSizeHints()"
    noise and writes the rest to stderr."""
    if "propagateSizeHints" not in message:
        sys.stderr.write(message + "\n")


_quiet = quiet_messages  # the earlier private name


def _unhinted(view: PlotView) -> None:
    """Lay text out with design metrics, as the PDF and SVG engines draw it (hinted screen metrics
    are up to 15 % narrower at 9 pt, which would make legends overflow their boxes in print)."""
    for item in view.plot_widget.scene().items():
        if hasattr(item, "font") and hasattr(item, "setFont"):
            try:
                f = item.font()
            except TypeError:
                continue
            f.setHintingPreference(QFont.HintingPreference.PreferNoHinting)
            item.setFont(f)


def prepare_view(view: PlotView, size: tuple[int, int] = FIG_SIZE) -> PlotView:
    """Light theme, no header or warning line, laid out at ``size`` without appearing on screen."""
    view.apply_theme(False)
    for _sample, label in view.legend.items:  # legend text in the foreground colour, not pyqtgraph's grey
        label.setText(label.text, color="#222222")
    _unhinted(view)
    view.header.hide()
    # room round the plot for tick labels half outside the axes (a top "10⁷", a right-hand "10⁴"):
    # the page has no header line above them to lend its space
    view.plot.layout.setContentsMargins(*FIG_MARGINS)
    view.cursor_label.hide()
    view.warning.hide()
    view.setAttribute(Qt.WidgetAttribute.WA_DontShowOnScreen, True)
    view.resize(*size)
    view.show()
    QApplication.processEvents()
    view.place_legend()  # at the final size: off the data where the view knows how (top right otherwise)
    QApplication.processEvents()
    return view


def _notes(view: PlotView) -> str:
    text = rich_label(rich_numbers(html.escape(view.warning_text.replace("⚠ ", ""), quote=False)))
    return f" Note: {text}." if text else ""


def _bound(content: ReportContent, key: str) -> Figure:
    stab = content.results["stability"]
    v = StabilityPlot()
    v.update_result(stab)
    cap = (f"Coupling term against the stability bound (eq. {display_kind(stab).bound_equation}) over the band. "
           f"Shaded: negative margin. Worst margin {num(stab.worst_margin, rich=True)} at "
           f"{num(stab.worst_frequency, rich=True)} rad/s.")
    return Figure(key, "Stability bound", cap, v)


def _reserve(content: ReportContent, key: str) -> Figure:
    """The app's ratio view: bound / coupling term, stable below 1; it shows the reserve where
    the bound binds, which the value plot squeezes against zero."""
    stab = content.results["stability"]
    v = StabilityPlot()
    v.update_result(stab, mode="ratio")
    eq = display_kind(stab).bound_equation
    cap = (f"The bound of eq. {eq} divided by the coupling term: unconditionally stable where the curve stays "
           f"below 1. The reserve is 1 minus the highest point: {num(100 * stab.relative_margin, 4, rich=True)} % "
           f"at {num(stab.binding_frequency, rich=True)} rad/s.")
    return Figure(key, "Stability reserve", cap, v)


def _range(content: ReportContent, key: str) -> Figure:
    stab = content.results["stability"]
    v = RangePlot()
    v.update_result(stab)
    cap = (f"Impedance range: |Z<sub>min</sub>| to |Z<sub>max</sub>| (shaded); k<sub>max</sub> = "
           f"{num(stab.k_max, rich=True)} N/m, b<sub>min</sub> = {num(stab.b_min, rich=True)} N&middot;s/m.")
    return Figure(key, "Impedance range (Z-width)", cap, v)


def _chart(content: ReportContent, key: str) -> Figure:
    res = content.results
    v = DesignChart()
    v.update_chart(res["chart"])
    v.update_point(*res["chart_point"], res["stability"].stable)
    cap = ("Largest k<sub>c</sub> satisfying eq. 9 against b<sub>c</sub>; the dot is the profile's coupling."
           if display_kind(res["stability"]).is_impedance else
           "Feasible (m<sub>c</sub>, b<sub>c</sub>) region of eq. 21; the dot is the profile's coupling.")
    return Figure(key, "Design chart", cap, v)


def _tradeoff(content: ReportContent, key: str) -> Figure | None:
    tc, best = content.results.get("tradeoff"), content.results.get("optimum")
    if tc is None:
        return None
    if key == "tradeoff_j":
        index = QUANTITIES["transparency_index"]
        v = CurvesPlot("Transparency index", ("B_c", "N·s/m"), ("J", index.unit), log_y=True)
        v.add("J (eq. 10–11)", tc.bc, tc.index, "#1f5fbf")
        if math.isfinite(best.bc):
            v.add("optimum", [best.bc], [best.index], "#c92a2a", symbol="o")
        cap = (f"Transparency index J against the controller damping B<sub>c</sub>; optimum B<sub>c</sub> = "
               f"{num(best.bc, rich=True)} N&middot;s/m, J = {index.format(best.index, rich=True)}.")
        return Figure(key, "Transparency index", cap, v)
    v = CurvesPlot("Robust stability", ("B_c", "N·s/m"), ("‖L‖∞", "–"))
    v.add("‖L‖∞ (eq. 16)", tc.bc, tc.peak, "#d9480f")
    v.hline(1.0, "limit ‖L‖∞ = 1 (eq. 17)")
    if math.isfinite(best.bc):
        v.add("optimum", [best.bc], [best.peak], "#c92a2a", symbol="o")
    cap = (f"Robustness peak &#8214;L&#8214;<sub>&infin;</sub> against B<sub>c</sub> "
           f"(&alpha; = {num(tc.alpha, rich=True)}, &beta; = {num(tc.beta, rich=True)}); stable for every weighted "
           "uncertainty below the line.")
    return Figure(key, "Robust stability", cap, v)


def _step(content: ReportContent, key: str) -> Figure | None:
    sr = content.results.get("step")
    if sr is None:
        return None
    v = CurvesPlot("Step response", ("t", "s"), ("x", "mm"))
    v.add("handle position", sr.t, sr.position * 1e3, "#1f5fbf")
    v.add("ideal virtual wall", sr.t, sr.wall_position * 1e3, "#868e96", style=Qt.PenStyle.DashLine)
    cap = (f"Handle position for a {num(sr.human_force[0], rich=True)} N force step on the exact sampled loop, "
           f"B<sub>c</sub> = {num(sr.bc, rich=True)} N&middot;s/m, against the ideal wall.")
    return Figure(key, "Virtual wall step response", cap, v)


def _map(content: ReportContent, key: str) -> Figure | None:
    smap = content.results.get("map")
    if smap is None:
        return None
    v = StabilityMapView()  # the app's own map view: same colours, colour bar and ρ = 1 line
    v.update_map(smap)
    v.update_point(*content.results["map_point"], None)
    term = ("hands-off, the paper's penalty wall" if display_kind(content.profile).is_impedance
            else "rigid grasp, free motion")
    cap = (f"Spectral radius &rho; of the exact sampled closed loop ({term}) over {symbol_html(smap.x_name)} "
           f"&times; {symbol_html(smap.y_name)}, as in the app's sampled-data tab; "
           f"{len(smap.x)}&times;{len(smap.y)} grid, the black line is &rho; = 1.")
    return Figure(key, "Sampled-data stability map", cap, v)


def _scenario(content: ReportContent, key: str) -> Figure | None:
    out = content.results.get("simulation")
    if out is None:
        return None
    p = content.profile
    name = scenario_title(p.simulation.scenario.name) if p.simulation else ""
    if key == "scenario_position":
        v = CurvesPlot("Scenario: position", ("t", "s"), ("x", "mm"))
        v.add("handle", out.t, out.positions[:, 0] * 1e3, "#1f5fbf")
        v.add("environment", out.t, np.asarray(out.x_e, float) * 1e3, "#868e96", style=Qt.PenStyle.DashLine)
        cap = (f"Scenario &ldquo;{name}&rdquo;: handle and environment positions. Verdict: "
               f"{out.verdict.kind} ({out.verdict.reason}).")
        return Figure(key, "Scenario time response: position", cap, v)
    v = CurvesPlot("Scenario: forces", ("t", "s"), ("F", "N"))
    v.add("actuator F<sub>d</sub>", out.t, out.f_d, "#1f5fbf")
    v.add("human F<sub>h</sub>", out.t, out.f_h, "#2b8a3e", style=Qt.PenStyle.DashLine)
    v.add("environment F<sub>e</sub>", out.t, out.f_e, "#d9480f", width=1.2)
    cap = f"Scenario &ldquo;{name}&rdquo;: actuator, human and environment forces."
    return Figure(key, "Scenario time response: forces", cap, v)


#: Each figure: the function that draws it and the parts of :func:`app.report.content.gather` whose results it
#: draws (the one definition of what a figure needs: ``zwidth export-plot`` computes only these; every figure also
#: has the stability result).
_BUILDERS: dict[str, tuple[Callable[[ReportContent, str], Figure | None], tuple[str, ...]]] = {
    "bound": (_bound, ()), "reserve": (_reserve, ()), "range": (_range, ()), "chart": (_chart, ("chart",)),
    "tradeoff_j": (_tradeoff, ("wall",)), "tradeoff_l": (_tradeoff, ("wall",)), "step": (_step, ("wall",)),
    "map": (_map, ("sampled",)), "scenario_position": (_scenario, ("sampled",)),
    "scenario_force": (_scenario, ("sampled",)),
    **{k: (observer_figure, ("observer",)) for k in OBSERVER_FIGURES},
    **{k: (identify_figure, ("identification",)) for k in IDENTIFY_FIGURES},
    "zwidth_region": (zwidth_figure, ("zwidth_region",)), "filter_optimum": (zwidth_figure, ("zwidth_optimum",)),
    **{k: (renderable_figure, ("renderable",)) for k in RENDERABLE_FIGURES},
    "workspace_map": (workspace_figure, ("workspace_map",)),
    "workspace_polar": (workspace_figure, ("workspace_point",)),
}


def figure_parts(keys: Iterable[str]) -> frozenset[str]:
    """The parts of :func:`app.report.content.gather` that the figures ``keys`` draw: gather only
    these to draw them (``gather(profile, parts=figure_parts([key]))``)."""
    try:
        return frozenset(part for key in keys for part in _BUILDERS[key][1])
    except KeyError as err:
        raise ValueError(f"unknown plot {err.args[0]!r}") from None


def make_view(content: ReportContent, key: str) -> Figure | None:
    """One figure by key: ``bound``, ``reserve``, ``range``, ``chart``, ``tradeoff_j``, ``tradeoff_l``, ``step``,
    ``map``, ``scenario_position``, ``scenario_force``, ``observer_plant``, ``observer_coupling`` and the
    identification and Z-width keys; ``None`` if the profile has no such data."""
    ensure_app()
    if key not in _BUILDERS:
        raise ValueError(f"unknown plot {key!r}")
    fig = _BUILDERS[key][0](content, key)
    if fig is None:
        return None
    prepare_view(fig.view)
    fig.caption += _notes(fig.view)
    return fig


FIGURE_KEYS = ("bound", "reserve", "range", "chart", "tradeoff_j", "tradeoff_l", "step", "map", "scenario_position",
               "scenario_force", *OBSERVER_FIGURES, *IDENTIFY_FIGURES, *ZWIDTH_FIGURES, *RENDERABLE_FIGURES,
               *WORKSPACE_FIGURES)


def build_figures(content: ReportContent) -> list[Figure]:
    out = []
    for key in FIGURE_KEYS:
        fig = make_view(content, key)
        if fig is not None:
            out.append(fig)
    return out

