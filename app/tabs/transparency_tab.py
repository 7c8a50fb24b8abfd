"""The transparency tab: the wall controller of Eom, Suh & Yi (section 3, Figs. 7-10).

Controls for the wall section of the profile (m, b, K, B, T, the hold model, the weight, α, β)
and for the current controller damping B_c.  Plots: J(B_c) and ‖L‖∞(B_c) (Fig. 8) with the
current B_c and the robust optimum marked, the admittances |Y_v| and |Y_t| (Fig. 9), and the
answer to a human-force step (position and actuator force, Figs. 7 and 10).

The current B_c is not a profile field (``WallSettings`` has none): it is this tab's state,
starting at the paper's B_c = 15 N·s/m, and passed to the graph nodes as a node parameter.
The curves over B_c are an asynchronous node (up to ~0.2 s for the ``zoh`` and ``discrete``
holds); everything at the current B_c is cheap and synchronous.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any

import numpy as np
from PySide6.QtCore import Qt, QTimer, Slot
from PySide6.QtWidgets import (
    QFrame,
    QGridLayout,
    QGroupBox,
    QLabel,
    QPushButton,
    QSizePolicy,
    QVBoxLayout,
    QWidget,
)

from analysis.profiles.io import Profile
from analysis.transparency.design import WallDesign
from analysis.transparency.settings import IndexResult, OptimalDamping, RobustnessPeak, StepResponse, TradeoffCurves, WallSettings

from app.core.compute_graph import ComputeGraph, Node
from app.core.model import DEVICE_FIELDS, ProfileModel
from app.views.base import PlotView, fmt, plain
from app.views.curves_plot import CurvesPlot
from app.widgets.choice_field import ChoiceField
from app.widgets.int_field import IntField
from app.widgets.log_slider_field import LogSliderField
from app.widgets.section_binding import SectionBinding
from app.tabs.base import AnalysisTab, AppContext

__all__ = ["TransparencyTab", "TAB", "wall_settings", "wall_design", "WallPoint", "WallTradeoff",
           "WallAdmittances", "admittance_grid", "DEFAULT_BC"]

DEFAULT_BC = 15.0  # N s/m, the paper's example
HOLD_LABELS = {
    "none": "none: H = 1 (no hold)",
    "pade": "Padé: half-sample delay, 1st order",
    "lowpass2": "2nd-order low-pass at Nyquist (paper)",
    "zoh": "ZOH: (1 − e^(−sT))/(sT)",
    "discrete": "exact sampled loop (discrete)",
}
PLANT_LABELS = {"rigid": "rigid handle: m, b below", "chain": "the profile's device chain"}
_INPUTS = frozenset({"wall"}) | frozenset(DEVICE_FIELDS)
NODES = ("wall_design", "wall_tradeoff", "wall_point", "wall_step", "wall_admittance")


# -- graph nodes ------------------------------------------------------------------------------------
def wall_settings(profile: Profile) -> WallSettings:
    """The profile's wall section, or the paper's example when it has none."""
    return profile.wall if profile.wall is not None else WallSettings()


def wall_design(profile: Profile) -> WallDesign:
    """A fresh :class:`WallDesign` for the profile (the device chain only for ``plant = "chain"``)."""
    st = wall_settings(profile)
    return WallDesign.from_settings(st, profile.device if st.plant == "chain" else None)


def _design_key(p: Profile, params: dict) -> Hashable:
    st = wall_settings(p)
    return st, (p.device.key() if st.plant == "chain" else None)


def _at_bc_key(p: Profile, params: dict) -> Hashable:
    return _design_key(p, params), float(params["bc"])


@dataclass(frozen=True)
class WallTradeoff:
    """Fig. 8 over the settings' B_c range and the robust optimum (same settings)."""

    curves: TradeoffCurves
    optimum: OptimalDamping
    hold: str


@dataclass(frozen=True)
class WallPoint:
    """J and ‖L‖∞ at the current B_c."""

    bc: float
    index: IndexResult
    peak: RobustnessPeak


@dataclass(frozen=True)
class WallAdmittances:
    """|Y_v| and |Y_t| (Fig. 9) at ``w`` (rad/s) and the current B_c."""

    w: np.ndarray
    yv: np.ndarray
    yt: np.ndarray
    bc: float
    nyquist: float


def admittance_grid(st: WallSettings, points: int = 600) -> np.ndarray:
    """1 rad/s to 10 Nyquist (to just below Nyquist for the ``discrete`` hold)."""
    nyq = math.pi / st.sample_time
    hi = 0.999 * nyq if st.hold == "discrete" else 10.0 * nyq
    return np.geomspace(min(1.0, hi / 100.0), hi, points)


def _tradeoff(profile: Profile, params: dict, progress: Callable[[int, int], None],
              cancelled: Callable[[], bool]) -> WallTradeoff | None:
    design = wall_design(profile)  # its own object: the GUI thread's design is never shared
    progress(0, 2)
    curves = design.tradeoff()
    if cancelled():
        return None
    progress(1, 2)
    optimum = design.optimal_damping()
    progress(2, 2)
    return WallTradeoff(curves, optimum, design.settings.hold)


def _point(profile: Profile, pull: Callable[[str], Any], bc: float) -> WallPoint:
    d = pull("wall_design")
    return WallPoint(bc, d.index_result(bc), d.robustness_peak(bc))


def _admittance(profile: Profile, pull: Callable[[str], Any], bc: float) -> WallAdmittances:
    d = pull("wall_design")
    w = admittance_grid(d.settings)
    yv, yt = d.admittances(w, bc)
    return WallAdmittances(w, yv, yt, bc, math.pi / d.settings.sample_time)


def _at_bc_node(name: str, func: Callable[[Profile, Callable[[str], Any], float], Any]) -> Node:
    """A synchronous node evaluated at ``params["bc"]`` (the tab's current B_c)."""
    node = Node(name, _INPUTS, _at_bc_key, lambda p, pull: func(p, pull, float(node.params["bc"])),
                params={"bc": DEFAULT_BC})
    return node


# -- the tab ------------------------------------------------------------------------------------------
class TransparencyTab(AnalysisTab):
    title = "Transparency (wall)"
    order = 30
    nodes = frozenset(NODES)

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        graph.add(Node("wall_design", _INPUTS, _design_key, lambda p, _: wall_design(p)))
        graph.add(Node("wall_tradeoff", _INPUTS, _design_key, _tradeoff, asynchronous=True))
        graph.add(_at_bc_node("wall_point", _point))
        graph.add(_at_bc_node("wall_step", lambda p, pull, bc: pull("wall_design").step_response(bc)))
        graph.add(_at_bc_node("wall_admittance", _admittance))
        try:
            from app.widgets.task_progress import TASK_TITLES

            TASK_TITLES.setdefault("wall_tradeoff", "Computing J(B_c) and ‖L‖∞(B_c)")
        except ImportError:  # pragma: no cover
            pass

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(ctx, parent)
        self.bc = DEFAULT_BC
        self.section = SectionBinding(ctx.model, ctx.editor, "wall", WallSettings, "wall")
        self.fields: dict[str, QWidget] = {}
        controls = self._build_controls(ctx.model)
        self._build_plots()

        self.summary = QLabel()
        self.summary.setObjectName("wallSummary")
        self.summary.setTextFormat(Qt.TextFormat.RichText)
        self.summary.setWordWrap(True)
        self.summary.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        self.summary.setFrameShape(QFrame.Shape.StyledPanel)
        self.summary.setMargin(6)
        self.summary.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)

        grid = QGridLayout()
        grid.setSpacing(6)
        grid.addWidget(self.index_plot, 0, 0)
        grid.addWidget(self.peak_plot, 0, 1)
        grid.addWidget(self.admittance_plot, 0, 2)
        grid.addWidget(self.position_plot, 1, 0)
        grid.addWidget(self.force_plot, 1, 1)
        grid.addWidget(self.summary, 1, 2)
        for i in range(3):
            grid.setColumnStretch(i, 1)
        lay = QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(controls)
        lay.addLayout(grid, 1)
        ctx.graph.ready.connect(self._on_ready)
        self._tradeoff_drawn: WallTradeoff | None = None

    # -- controls ----------------------------------------------------------------------------------
    def _build_controls(self, model: ProfileModel) -> QWidget:
        sec, ed = self.section, self.ctx.editor

        def slider(name: str, label: str, unit: str, lo: float, hi: float, tip: str, log: bool = True,
                   zero: bool = False) -> LogSliderField:
            self.fields[name] = sec.slider(name, label, unit, lo, hi, tip, log=log, allow_zero=zero)
            return self.fields[name]

        box = QGroupBox("Wall controller (Eom, Suh && Yi, eq. 7–17)")
        box.setToolTip("Stored in the profile's wall section (B_c is a design variable of this tab)")
        g = QGridLayout(box)
        g.setContentsMargins(6, 4, 6, 4)
        g.setHorizontalSpacing(10)
        g.setVerticalSpacing(2)
        plant = ChoiceField(model, ("wall",), sec.reader("plant"), sec.writer("plant", "plant"), "Plant",
                            list(PLANT_LABELS.items()),
                            "P(s) = 1/(m s + b), or the handle admittance of the profile's device chain")
        self.fields["plant"] = plant
        hold = ChoiceField(model, ("wall",), sec.reader("hold"), sec.writer("hold", "hold model"), "Hold",
                           list(HOLD_LABELS.items()),
                           "Model of the zero-order hold H(s) in eq. (9), (16).  The paper's J and ‖L‖∞ "
                           "depend on it: under the exact sampled loop B_c = 15 is not robustly stable.")
        self.fields["hold"] = hold
        order = IntField(model, ("wall",), sec.reader("weight_order"), sec.writer("weight_order", "weight order"),
                         "Weight order r", 0, 8, "w₁ = (ω_c/(s + ω_c))^r in eq. (11); r = 0 makes J infinite")
        self.fields["weight_order"] = order
        rows = [
            [plant, slider("mass", "m", "kg", 1e-4, 10.0, "Handle mass (eq. 7)"),
             slider("damping", "b", "N·s/m", 1e-4, 10.0, "Handle damping (eq. 7)", zero=True)],
            [hold, slider("wall_stiffness", "K", "N/m", 1.0, 1e6, "Virtual wall stiffness (eq. 8)", zero=True),
             slider("wall_damping", "B", "N·s/m", 1e-3, 1e3, "Virtual wall damping (eq. 8)", zero=True)],
            [order, slider("weight_cutoff", "ω<sub>c</sub>", "rad/s", 1.0, 1e5, "Cutoff of the weight w₁ (eq. 11)"),
             slider("sample_time", "T", "s", 1e-5, 1e-1, "Sample period of the wall loop")],
            [slider("alpha", "α", "", 0.0, 0.99, "Mass uncertainty of the weight W = α m s + β b (eq. 15)",
                    log=False),
             slider("beta", "β", "", 0.0, 1.0, "Damping uncertainty of the weight W = α m s + β b (eq. 15)",
                    log=False)],
        ]
        for r, row in enumerate(rows):
            for c, w in enumerate(row):
                g.addWidget(w, r, c)
        # the current B_c (tab state, not a profile field)
        self.bc_field = LogSliderField(model, (), lambda _m: self.bc, self._write_bc, ed,
                                       "<b>B<sub>c</sub></b>", "N·s/m", 0.1, 100.0,
                                       tooltip="Controller damping B_c of C(s) = B_c + K_c/s (eq. 12); "
                                               "not stored in the profile")
        self.bc_field.setObjectName("wall_bc")
        self.bc_field.make_compact()
        self.optimum_button = QPushButton("Use robust optimum")
        self.optimum_button.setToolTip("Set B_c to the B_c minimizing J subject to ‖L‖∞ ≤ 1 (section 3)")
        self.optimum_button.clicked.connect(self.use_optimum)
        self.optimum_button.setEnabled(False)
        g.addWidget(self.bc_field, 3, 2)
        g.addWidget(self.optimum_button, 4, 2, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignTop)
        for c in range(3):
            g.setColumnStretch(c, 1)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self._update_enabled)
        self._update_enabled()
        return box

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "wall":
            self._update_enabled()

    @Slot()
    def _update_enabled(self) -> None:
        rigid = self.section.current().plant == "rigid"
        for name in ("mass", "damping"):
            self.fields[name].setEnabled(rigid)

    def _write_bc(self, value: float, drag: int | None = None) -> str | None:
        if not (math.isfinite(value) and value >= 0):
            return "refused: must be >= 0 and finite (N s/m)"
        self.set_bc(value)
        return None

    def set_bc(self, value: float) -> None:
        """Set the current B_c (tab state) and redraw what depends on it if the tab is visible."""
        value = float(value)
        if value == self.bc:
            return
        self.bc = value
        self.bc_field.refresh()
        self.stale = True
        if self.isVisible():
            QTimer.singleShot(0, self._refresh_if_stale)

    @Slot()
    def use_optimum(self) -> None:
        if self._tradeoff_drawn is not None and self._tradeoff_drawn.optimum.feasible:
            self.set_bc(float(f"{self._tradeoff_drawn.optimum.bc:.6g}"))

    @Slot()
    def _refresh_if_stale(self) -> None:
        if self.stale and self.isVisible():
            self.refresh()

    # -- plots ---------------------------------------------------------------------------------------
    def _build_plots(self) -> None:
        bc_axis = ("B<sub>c</sub>", "N·s/m")
        self.index_plot = CurvesPlot("J(B<sub>c</sub>), eq. 11 (Fig. 8)", bc_axis,
                                     ("J", "m²/(N²·s)"), log_y=True)
        self.index_plot.add_curve("J", "J(B<sub>c</sub>)", "a", export_name="J")
        self.index_plot.add_marker("current", "current B<sub>c</sub>", "b", "o", export_name="J at current B_c")
        self.index_plot.add_marker("optimum", "robust optimum", "c", "star", 14, export_name="J at optimum")
        self.index_plot.add_line("bc", True)
        self.index_plot.add_regions("inf")

        self.peak_plot = CurvesPlot("‖L‖<sub>∞</sub>(B<sub>c</sub>), eq. 16–17 (Fig. 8)", bc_axis,
                                    ("‖L‖<sub>∞</sub>", "dB"))
        self.peak_plot.add_curve("peak", "‖L‖<sub>∞</sub>", "a", export_name="||L||inf")
        self.peak_plot.add_curve("peak_invalid", "‖L‖<sub>∞</sub> where J = ∞ (not a valid bound)", "muted", 1.2,
                                 Qt.PenStyle.DotLine, export_name="||L||inf where J = inf")
        self.peak_plot.add_regions("inf")
        self.peak_plot.add_marker("current", "current B<sub>c</sub>", "b", "o",
                                  export_name="||L||inf at current B_c")
        self.peak_plot.add_marker("optimum", "robust optimum", "c", "star", 14, export_name="||L||inf at optimum")
        self.peak_plot.add_line("zero", False, "0 dB: robust limit", "mark", Qt.PenStyle.DashLine)
        self.peak_plot.add_line("bc", True)
        self.peak_plot.set_line("zero", 0.0)

        self.admittance_plot = CurvesPlot("Admittances, eq. 8–9 (Fig. 9)",
                                          ("ω", "rad/s"), ("|Y|", "m/(N·s)"), log_x=True, log_y=True)
        self.admittance_plot.add_curve("yv", "|Y<sub>v</sub>| virtual wall", "muted", 2.0, Qt.PenStyle.DashLine,
                                       export_name="|Y_v|")
        self.admittance_plot.add_curve("yt", "|Y<sub>t</sub>| transmitted", "a", export_name="|Y_t|")
        self.admittance_plot.legend.setOffset((-10, -10))  # bottom right: the resonance is at the top
        self.admittance_plot.add_line("nyquist", True, "π/T", "muted", Qt.PenStyle.DotLine)

        self.position_plot = CurvesPlot("Step: handle position (Figs. 7, 10)", ("t", "s"),
                                        ("x", "mm"))
        self.position_plot.add_curve("wall", "ideal wall F/K (1 − e<sup>−Kt/B</sup>)", "muted", 2.0,
                                     Qt.PenStyle.DashLine, export_name="ideal wall position")
        self.position_plot.add_curve("position", "handle x", "a", export_name="handle position")

        self.force_plot = CurvesPlot("Step: wall force (Figs. 7, 10)", ("t", "s"), ("force", "N"))
        self.force_plot.add_curve("human", "human force F<sub>h</sub>", "muted", 2.0, Qt.PenStyle.DashLine,
                                  export_name="human force")
        self.force_plot.add_curve("force", "actuator force u (held)", "b", export_name="actuator force")

    def plot_views(self) -> list[PlotView]:
        return [self.index_plot, self.peak_plot, self.admittance_plot, self.position_plot, self.force_plot]

    # -- refresh ------------------------------------------------------------------------------------
    def _sync_bc(self) -> None:
        graph = self.ctx.graph
        for name in ("wall_point", "wall_step", "wall_admittance"):
            node = graph.node(name)
            if node.params.get("bc") != self.bc:
                node.params["bc"] = self.bc
                node.dirty = True

    def refresh(self) -> None:
        self._sync_bc()
        graph = self.ctx.graph
        st = wall_settings(self.ctx.model.profile)
        point: WallPoint = graph.get("wall_point")
        step: StepResponse = graph.get("wall_step")
        adm: WallAdmittances = graph.get("wall_admittance")
        trade: WallTradeoff | None = graph.request("wall_tradeoff")
        fresh = graph.is_fresh("wall_tradeoff")
        self._draw_tradeoff(trade, fresh)
        self._draw_point(point, trade if fresh else None)
        self._draw_admittance(adm)
        self._draw_step(step, st)
        self._draw_summary(st, point, trade if fresh else None)
        self.refreshes += 1
        self.stale = False

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == "wall_tradeoff" and self.isVisible():
            self.refresh()

    def _draw_tradeoff(self, trade: WallTradeoff | None, fresh: bool) -> None:
        if trade is None:
            return
        c, o = trade.curves, trade.optimum
        hidden = self.index_plot.set_curve("J", c.bc, c.index)
        finite = np.isfinite(c.index)
        with np.errstate(divide="ignore"):
            db = 20.0 * np.log10(c.peak)
        self.peak_plot.set_curve("peak", c.bc, np.where(finite, db, np.nan), gaps=True)
        # the invalid part joins its finite neighbours so that the curve reads as one line
        near = ~finite | np.convolve(~finite, [1, 1, 1], "same").astype(bool)
        self.peak_plot.set_curve("peak_invalid", c.bc, np.where(near, db, np.nan), gaps=True)
        spans = _runs(c.bc, ~finite)
        self.index_plot.set_regions("inf", spans)
        self.peak_plot.set_regions("inf", spans)
        if o.feasible:
            self.index_plot.set_marker("optimum", o.bc, o.index)
            self.peak_plot.set_marker("optimum", o.bc, 20.0 * math.log10(o.peak))
        else:
            self.index_plot.set_marker("optimum", None, None)
            self.peak_plot.set_marker("optimum", None, None)
        notes = [] if fresh else ["updating the curves…"]
        if hidden:
            notes.append(f"shaded: J = ∞ (closed loop unstable, or J unbounded) at {hidden} of {c.bc.size} "
                         "values of B_c")
        self.index_plot.set_warning(notes)
        self.peak_plot.set_warning([] if fresh else ["updating the curves…"])
        self._tradeoff_drawn = trade
        self.optimum_button.setEnabled(fresh and o.feasible)
        if o.feasible:
            self.optimum_button.setText(f"Use robust optimum ({plain(o.bc, 4)})")
        else:
            self.optimum_button.setText("Use robust optimum (none)")
        self.index_plot.bump()
        self.peak_plot.bump()

    def _draw_point(self, point: WallPoint, trade: WallTradeoff | None) -> None:
        j = point.index.index if point.index.finite else None
        self.index_plot.set_marker("current", point.bc, j)
        self.peak_plot.set_marker("current", point.bc, point.peak.gain_db)
        for v in (self.index_plot, self.peak_plot):
            v.set_line("bc", point.bc)
        self.index_plot.set_legend_text("current", f"B<sub>c</sub> = {fmt(point.bc)}: J = "
                                        f"{fmt(point.index.index) if point.index.finite else '∞'}")
        self.peak_plot.set_legend_text("current", f"B<sub>c</sub> = {fmt(point.bc)}: "
                                       f"{point.peak.gain_db:+.2f} dB")
        if trade is not None and trade.optimum.feasible:
            o = trade.optimum
            self.index_plot.set_legend_text("optimum", f"robust optimum B<sub>c</sub> = {fmt(o.bc)}")
            self.peak_plot.set_legend_text("optimum", f"robust optimum: {20 * math.log10(o.peak):+.2f} dB")

    def _draw_admittance(self, adm: WallAdmittances) -> None:
        self.admittance_plot.set_curve("yv", adm.w, np.abs(adm.yv))
        self.admittance_plot.set_curve("yt", adm.w, np.abs(adm.yt))
        self.admittance_plot.set_line("nyquist", adm.nyquist if adm.nyquist < adm.w[-1] else None)
        self.admittance_plot.set_legend_text("yt", f"|Y<sub>t</sub>| transmitted, B<sub>c</sub> = {fmt(adm.bc)}")
        self.admittance_plot.bump()

    def _draw_step(self, step: StepResponse, st: WallSettings) -> None:
        self.position_plot.set_curve("wall", step.t, 1e3 * step.wall_position)
        self.position_plot.set_curve("position", step.t, 1e3 * step.position)
        self.force_plot.set_curve("human", step.t, step.human_force)
        self.force_plot.set_curve("force", step.t, step.force)
        self.position_plot.set_legend_text("position", f"handle x, B<sub>c</sub> = {fmt(step.bc)}")
        self.force_plot.set_legend_text("human", f"human force F<sub>h</sub> = {fmt(st.step_force)} N")
        self.position_plot.bump()
        self.force_plot.bump()

    def _draw_summary(self, st: WallSettings, point: WallPoint, trade: WallTradeoff | None) -> None:
        pk = point.peak
        bad, good = "#d0312d", "#2b8a3e"
        lines = [f"<b>Hold model:</b> {HOLD_LABELS[st.hold]}",
                 f"<b>B<sub>c</sub> = {fmt(point.bc)} N·s/m</b>"]
        if point.index.finite:
            lines.append(f"J = {fmt(point.index.index)} m²/(N²·s)")
        else:
            lines.append(f"J = ∞: <span style='color:{bad}'>{point.index.reason}</span>")
        where = "ω → ∞" if math.isinf(pk.frequency) else f"ω = {fmt(pk.frequency)} rad/s"
        unstable = not point.index.finite and "unstable" in point.index.reason
        verdict = (f"<span style='color:{bad}'><b>closed loop unstable</b></span>" if unstable else
                   f"<span style='color:{good}'><b>robustly stable</b></span> (≤ 0 dB)" if pk.robust else
                   f"<span style='color:{bad}'><b>NOT robustly stable</b></span> (eq. 17 needs ≤ 0 dB)")
        lines.append(f"‖L‖<sub>∞</sub> = {pk.gain_db:+.2f} dB at {where}: {verdict}")
        if not pk.certified:
            lines.append("<i>peak not certified above the grid (zoh ripple)</i>")
        if trade is None:
            lines.append("<i>robust optimum: computing…</i>")
        elif trade.optimum.feasible:
            o = trade.optimum
            on = " (on the constraint ‖L‖<sub>∞</sub> = 1)" if o.constrained else ""
            lines.append(f"<b>Robust optimum:</b> B<sub>c</sub> = {fmt(o.bc)} N·s/m, J = {fmt(o.index)}, "
                         f"‖L‖<sub>∞</sub> = {20 * math.log10(o.peak):+.2f} dB{on}")
        else:
            lines.append(f"<b>Robust optimum:</b> <span style='color:{bad}'>none in "
                         f"[{fmt(st.bc_min)}, {fmt(st.bc_max)}] N·s/m: {trade.optimum.reason}</span>")
        if st.hold == "discrete":
            lines.append("<i>Discrete hold: J integrates over [0, π/T) only, so it is not comparable "
                         "with the continuous hold models.</i>")
        lines.append(f"Step: F<sub>h</sub> = {fmt(st.step_force)} N for {fmt(st.step_duration)} s "
                     "on the exact sampled loop (whatever the hold model).")
        self.summary.setText("<br>".join(lines))


def _runs(x: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
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


TAB = TransparencyTab
