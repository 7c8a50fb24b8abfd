"""The observer tab: the disturbance observer of Eom, Suh & Yi (section 2, Fig. 1, eq. 2-5).

Controls for the profile's observer section (order r and cutoff ω_Q of Q, the nominal plant, the
α/β/δ perturbation of the real plant, the two-axis five-bar preset).  Plots: the effective plant
through the observer against the nominal and real plants, disturbance to velocity with and
without the observer, the cross-axis coupling |v_y/F_x| of the two-axis device with and without
the observers, and the y answer to a commanded force step on x.  All nodes are synchronous
(< 50 ms together).
"""

from __future__ import annotations

from collections.abc import Hashable

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QGridLayout, QGroupBox, QVBoxLayout, QWidget

from analysis.transparency.observer import PRESETS, DisturbanceObserver, ObserverResponse, ObserverSettings, TwoAxisObserver
from analysis.profiles.io import Profile

from app.core.compute_graph import ComputeGraph, Node
from app.core.model import ProfileModel
from app.views.base import PlotView, fmt
from app.views.curves_plot import CurvesPlot
from app.widgets.choice_field import ChoiceField
from app.widgets.int_field import IntField
from app.widgets.log_slider_field import LogSliderField
from app.widgets.section_binding import SectionBinding
from app.tabs.base import AnalysisTab, AppContext

__all__ = ["ObserverTab", "TAB", "observer_settings", "OBSERVER_W"]

#: The frequency grid of the observer plots (rad/s).
OBSERVER_W = np.geomspace(0.1, 1e5, 500)
PRESET_LABELS = {"five_bar_centre": "five-bar, workspace centre (unequal distal links)",
                 "five_bar_offset": "five-bar, handle 60 mm right of centre"}
NODES = ("observer_response", "observer_coupling", "observer_step")


def observer_settings(profile: Profile) -> ObserverSettings:
    """The profile's observer section, or the defaults when it has none."""
    return profile.observer if profile.observer is not None else ObserverSettings()


def _two_axis_key(p: Profile, params: dict) -> Hashable:
    st = observer_settings(p)
    return st.preset, st.order, st.cutoff


def _response(p: Profile, pull) -> ObserverResponse:
    st = observer_settings(p)
    return DisturbanceObserver.from_settings(st).response(OBSERVER_W, None, st.alpha, st.beta, st.delta)


class ObserverTab(AnalysisTab):
    title = "Disturbance observer"
    order = 40
    nodes = frozenset(NODES)

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        inputs = frozenset({"observer"})
        graph.add(Node("observer_response", inputs, lambda p, _: observer_settings(p), _response))
        graph.add(Node("observer_coupling", inputs, _two_axis_key,
                       lambda p, _: TwoAxisObserver.from_settings(observer_settings(p)).coupling(OBSERVER_W)))
        graph.add(Node("observer_step", inputs,
                       lambda p, prm: (_two_axis_key(p, prm), observer_settings(p).step_force,
                                       observer_settings(p).step_duration),
                       lambda p, _: TwoAxisObserver.from_settings(observer_settings(p)).step_response(
                           observer_settings(p).step_force, observer_settings(p).step_duration)))

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(ctx, parent)
        self.section = SectionBinding(ctx.model, ctx.editor, "observer", ObserverSettings, "observer")
        self.fields: dict[str, QWidget] = {}
        controls = self._build_controls(ctx.model)
        self._build_plots()
        grid = QGridLayout()
        grid.setSpacing(6)
        grid.addWidget(self.plant_plot, 0, 0)
        grid.addWidget(self.disturbance_plot, 0, 1)
        grid.addWidget(self.coupling_plot, 1, 0)
        grid.addWidget(self.step_plot, 1, 1)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(controls)
        lay.addLayout(grid, 1)

    def _build_controls(self, model: ProfileModel) -> QWidget:
        sec = self.section

        def slider(name: str, label: str, unit: str, lo: float, hi: float, tip: str, log: bool = True,
                   zero: bool = False) -> LogSliderField:
            self.fields[name] = sec.slider(name, label, unit, lo, hi, tip, log=log, allow_zero=zero)
            return self.fields[name]

        box = QGroupBox("Disturbance observer (Eom, Suh && Yi, Fig. 1, eq. 3–5)")
        box.setToolTip("Stored in the profile's observer section")
        g = QGridLayout(box)
        g.setContentsMargins(6, 4, 6, 4)
        g.setHorizontalSpacing(10)
        g.setVerticalSpacing(2)
        order = IntField(model, ("observer",), sec.reader("order"), sec.writer("order", "order"), "Q order r", 1, 8,
                         "Q = (ω_Q/(s + ω_Q))^r, binomial low-pass (r ≥ 1 so that Q/P_n is proper)")
        preset = ChoiceField(model, ("observer",), sec.reader("preset"), sec.writer("preset", "preset"),
                             "Two-axis device", [(p, PRESET_LABELS.get(p, p)) for p in PRESETS],
                             "Cartesian inertia and damping of a five-bar linkage (eq. 2)")
        self.fields["order"], self.fields["preset"] = order, preset
        rows = [
            [order, slider("cutoff", "ω<sub>Q</sub>", "rad/s", 1.0, 1e5, "Cutoff of the Q filter"),
             slider("nominal_mass", "M̄", "kg", 1e-4, 10.0, "Nominal mass of P_n = 1/(M̄ s + B̄) (eq. 3)")],
            [preset, slider("delta", "δ", "", -1.0, 1.0, "Δ of eq. (13): the real plant's mass is M̄(1 + αδ), "
                                                        "its damping B̄(1 + βδ)", log=False),
             slider("nominal_damping", "B̄", "N·s/m", 1e-4, 10.0, "Nominal damping of P_n (eq. 3)", zero=True)],
            [slider("alpha", "α", "", 0.0, 0.99, "Mass uncertainty of the real plant (eq. 13)", log=False),
             slider("beta", "β", "", 0.0, 1.0, "Damping uncertainty of the real plant (eq. 13)", log=False)],
        ]
        for r, row in enumerate(rows):
            for c, w in enumerate(row):
                g.addWidget(w, r, c)
        for c in range(3):
            g.setColumnStretch(c, 1)
        return box

    def _build_plots(self) -> None:
        w_axis, y_axis = ("ω", "rad/s"), ("|v/u|", "m/(N·s)")
        self.plant_plot = CurvesPlot("Effective plant through the observer (eq. 3–5)", w_axis, y_axis, True, True)
        self.plant_plot.add_curve("plant", "real plant P̃ (eq. 13)", "muted", 2.0, Qt.PenStyle.DashLine,
                                  export_name="|P real|")
        self.plant_plot.add_curve("nominal", "nominal P<sub>n</sub>", "c", 2.0, Qt.PenStyle.DotLine,
                                  export_name="|P_n|")
        self.plant_plot.add_curve("effective", "effective plant with observer", "a", export_name="|P effective|")
        self.plant_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.disturbance_plot = CurvesPlot("Disturbance to velocity |v/d|", w_axis, ("|v/d|", "m/(N·s)"),
                                           True, True)
        self.disturbance_plot.add_curve("without", "without observer", "muted", 2.0, Qt.PenStyle.DashLine,
                                        export_name="|v/d| without observer")
        self.disturbance_plot.add_curve("with", "with observer", "a", export_name="|v/d| with observer")
        self.disturbance_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.coupling_plot = CurvesPlot("Cross-axis coupling |v<sub>y</sub>/F<sub>x</sub>| (two axes, eq. 2)",
                                        w_axis, ("|v<sub>y</sub>/F<sub>x</sub>|", "m/(N·s)"), True, True)
        self.coupling_plot.add_curve("without", "without observers", "muted", 2.0, Qt.PenStyle.DashLine,
                                     export_name="|v_y/F_x| without observers")
        self.coupling_plot.add_curve("with", "with observers", "b", export_name="|v_y/F_x| with observers")
        self.coupling_plot.add_line("cutoff", True, "ω_Q", "muted", Qt.PenStyle.DotLine)

        self.step_plot = CurvesPlot("Force step on x: y displacement", ("t", "s"), ("y", "mm"))
        self.step_plot.add_curve("without", "without observers", "muted", 2.0, Qt.PenStyle.DashLine,
                                 export_name="y without observers")
        self.step_plot.add_curve("with", "with observers", "b", export_name="y with observers")

    def plot_views(self) -> list[PlotView]:
        return [self.plant_plot, self.disturbance_plot, self.coupling_plot, self.step_plot]

    def refresh(self) -> None:
        graph = self.ctx.graph
        st = observer_settings(self.ctx.model.profile)
        r = graph.get("observer_response")
        c = graph.get("observer_coupling")
        s = graph.get("observer_step")
        self.plant_plot.set_curve("plant", r.w, np.abs(r.plant))
        self.plant_plot.set_curve("nominal", r.w, np.abs(r.nominal))
        self.plant_plot.set_curve("effective", r.w, np.abs(r.effective))
        self.plant_plot.set_legend_text("plant", f"real plant P̃: α = {fmt(st.alpha)}, β = {fmt(st.beta)}, "
                                                 f"δ = {fmt(st.delta)}")
        self.disturbance_plot.set_curve("without", r.w, np.abs(r.disturbance_without))
        self.disturbance_plot.set_curve("with", r.w, np.abs(r.disturbance_with))
        self.coupling_plot.set_curve("without", c.w, np.abs(c.coupling_without))
        self.coupling_plot.set_curve("with", c.w, np.abs(c.coupling_with))
        for v in (self.plant_plot, self.disturbance_plot, self.coupling_plot):
            v.set_line("cutoff", st.cutoff)
        self.step_plot.set_curve("without", s.t, 1e3 * s.y_without)
        self.step_plot.set_curve("with", s.t, 1e3 * s.y_with)
        self.step_plot.header.setText(f"<b>Force step F<sub>x</sub> = {fmt(s.force)} N on x: "
                                      "y displacement</b>")
        for v in self.plot_views():
            v.bump()
        self.refreshes += 1
        self.stale = False


TAB = ObserverTab
