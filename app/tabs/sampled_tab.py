"""The sampled-data tab: the exact loop behind the two-port bounds.

* a stability map -- the spectral radius of the real sampled loop over two parameters;
* the exact stability limit over b_c overlaid on the two-port design chart;
* the scenario runner -- the nonlinear simulator's positions, forces and energy, and its verdict.

All three run as asynchronous graph nodes (registered here) on the worker, with progress and
Cancel; like every tab, nothing is pulled while the tab is hidden.  The delays, the scenario and
the simulator options are the profile's ``simulation`` section (edited through undo commands);
the map's axes and ranges are view settings of this tab (node parameters).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Hashable
from typing import Any

import numpy as np
from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QComboBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QScrollArea,
    QSpinBox,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from analysis.profiles.io import Profile
from analysis.sampled import (
    HANDS_OFF,
    RIGID_GRASP,
    CriticalChart,
    CriticalMassChart,
    SimulationOptions,
    StabilityMap,
    critical_mass,
    critical_stiffness,
    simulate,
    stability_map,
)
from analysis.sampled.terminations import PAPER_WALL_STIFFNESS

from app.core.compute_graph import GAIN_FIELDS, ComputeGraph, Node
from app.core.model import DEVICE_FIELDS
from app.views.base import PlotView, plain
from app.views.exact_limit_chart import ExactLimitChart
from app.views.stability_map import PARAMETER_LABELS, StabilityMapView
from app.views.time_response import TimeResponse
from app.widgets.node_progress import NodeProgress
from app.widgets.sci_spin_box import SciSpinBox
from app.panels.simulation_panel import SimulationPanel, current_section
from app.widgets.task_progress import TASK_TITLES
from app.tabs.base import AnalysisTab, AppContext

__all__ = ["SampledTab", "TAB", "MAP_AXES", "DEFAULT_RANGES", "map_arguments", "exact_grid"]

MAP_NODE, EXACT_NODE, LIMIT_NODE, SIM_NODE = "sampled_map", "sampled_exact_chart", "sampled_limit", "sampled_simulation"
ASYNC_NODES = (MAP_NODE, EXACT_NODE, LIMIT_NODE, SIM_NODE)
TITLES = {MAP_NODE: "Stability map", EXACT_NODE: "Exact limit chart", LIMIT_NODE: "Exact limit at current b_c",
          SIM_NODE: "Simulation"}

#: The map axes offered for each display type (x, y) -- names of analysis.sampled.MAP_PARAMETERS.
MAP_AXES = {
    "impedance": [("kc", "kobj"), ("kc", "bc"), ("kc", "grasp_mass"), ("kc", "grasp_stiffness")],
    "admittance": [("mc", "bc"), ("mc", "grasp_mass"), ("mc", "grasp_stiffness"), ("mc", "kd")],
}
DEFAULT_RANGES = {
    ("impedance", "kc"): (1e3, 1e6), ("impedance", "kobj"): (1e3, 1e7), ("impedance", "bc"): (1.0, 1e4),
    ("impedance", "grasp_mass"): (1e-2, 10.0), ("impedance", "grasp_stiffness"): (10.0, 1e6),
    ("admittance", "mc"): (1e-2, 1e2), ("admittance", "bc"): (10.0, 1e4), ("admittance", "grasp_mass"): (0.1, 10.0),
    ("admittance", "grasp_stiffness"): (1e2, 1e6), ("admittance", "kd"): (1.0, 1e4),
}
MAP_POINTS = 48
EXACT_BC_RANGE, EXACT_POINTS = (1.0, 1e4), 24
_DEVICE = frozenset(DEVICE_FIELDS)


# -- the node functions (Qt-free; each builds its own objects, never shares across threads) -------------

def _coupling(p: Profile) -> tuple[float, float]:
    return (p.kc, p.bc) if p.display == "impedance" else (p.mc, p.bc_adm)


def _delays(p: Profile) -> tuple[int, bool]:
    o = current_section(p).options
    return o.delay_samples, o.implementation_delay


def map_arguments(p: Profile, params: dict) -> dict[str, Any]:
    """The keyword arguments of :func:`analysis.sampled.stability_map` for the tab's map.

    The termination is the analysis default (impedance: hands-off against the paper's
    500 kN/m penalty wall; admittance: rigid grasp in free motion).
    """
    n = int(params["points"])
    d, impl = _delays(p)
    return dict(x=(params["x"], np.geomspace(*params["x_range"], n)),
                y=(params["y"], np.geomspace(*params["y_range"], n)),
                display=p.display, coupling=_coupling(p), pd=(p.kp, p.kd), delay_samples=d,
                implementation_delay=impl)


def _map_key(p: Profile, params: dict) -> Hashable:
    return (p.device.key(), p.display, _coupling(p), (p.kp, p.kd), _delays(p),
            tuple(sorted((k, v) for k, v in params.items())))


def _map(p: Profile, params: dict, progress: Callable[[int, int], None], cancelled: Callable[[], bool]
         ) -> StabilityMap | None:
    """The map in row blocks (one batched sweep each) so that it can report and stop."""
    args = map_arguments(p, params)
    yn, yv = args.pop("y")
    blocks = np.array_split(np.arange(yv.size), min(8, yv.size))
    rows, x_name, x = [], args["x"][0], args["x"][1]
    for i, idx in enumerate(blocks):
        if cancelled():
            return None
        rows.append(stability_map(p.device, y=(yn, yv[idx]), **args).spectral_radius)
        progress(i + 1, len(blocks))
    return StabilityMap(x_name=x_name, x=x, y_name=yn, y=yv, spectral_radius=np.vstack(rows))


def exact_grid(params: dict) -> np.ndarray:
    return np.geomspace(*params["bc_range"], int(params["points"]))


def _exact_key(p: Profile, params: dict) -> Hashable:
    pd = (p.kp, p.kd) if p.display == "admittance" else None
    return (p.device.key(), p.display, pd, _delays(p), params["bc_range"], params["points"])


def _exact_chart(p: Profile, params: dict, progress: Callable[[int, int], None], cancelled: Callable[[], bool]
                 ) -> CriticalChart | CriticalMassChart | None:
    """:func:`critical_stiffness_chart` / :func:`critical_mass_chart`, one b_c at a time."""
    bcs = exact_grid(params)
    d, impl = _delays(p)
    out = np.empty(bcs.size)
    for i, bc in enumerate(bcs):
        if cancelled():
            return None
        if p.display == "impedance":
            out[i] = critical_stiffness(p.device, float(bc), d, implementation_delay=impl)
        else:
            out[i] = critical_mass(p.device, float(bc), (p.kp, p.kd), d, implementation_delay=impl)
        progress(i + 1, bcs.size)
    if p.display == "impedance":
        return CriticalChart(bc=bcs, kc=out, delay_samples=d)
    return CriticalMassChart(bc=bcs, mc=out, delay_samples=d)


def _limit_key(p: Profile, params: dict) -> Hashable:
    c = p.bc if p.display == "impedance" else (p.bc_adm, p.kp, p.kd)
    return (p.device.key(), p.display, c, _delays(p))


def _limit(p: Profile, params: dict, progress: Callable[[int, int], None], cancelled: Callable[[], bool]) -> float:
    """The exact limit at the current b_c: largest stable k_c or smallest stable m_c."""
    d, impl = _delays(p)
    progress(0, 1)
    if p.display == "impedance":
        v = critical_stiffness(p.device, float(p.bc), d, implementation_delay=impl)
    else:
        v = critical_mass(p.device, float(p.bc_adm), (p.kp, p.kd), d, implementation_delay=impl)
    progress(1, 1)
    return v


def _sim_key(p: Profile, params: dict) -> Hashable:
    return (p.device.key(), p.display, _coupling(p), (p.kp, p.kd), current_section(p))


def _simulation(p: Profile, params: dict, progress: Callable[[int, int], None], cancelled: Callable[[], bool]):
    """One run of the simulator.  It has no progress hook: reports 0/1 and 1/1, and a cancel drops it."""
    sec = current_section(p)
    progress(0, 1)
    if cancelled():
        return None
    res = simulate(p, sec.scenario, options=sec.options)
    progress(1, 1)
    return None if cancelled() else res


# -- the tab ------------------------------------------------------------------------------------------------

class SampledTab(AnalysisTab):
    title = "Sampled-data"
    order = 30
    nodes = frozenset({*ASYNC_NODES, "design_chart", "stability", "max_stiffness"})

    @classmethod
    def register_nodes(cls, graph: ComputeGraph) -> None:
        sim_inputs = _DEVICE | GAIN_FIELDS | {"simulation"}
        graph.add(Node(MAP_NODE, sim_inputs, _map_key, _map, asynchronous=True,
                       params={"x": "kc", "x_range": DEFAULT_RANGES[("impedance", "kc")], "y": "kobj",
                               "y_range": DEFAULT_RANGES[("impedance", "kobj")], "points": MAP_POINTS}))
        graph.add(Node(EXACT_NODE, _DEVICE | {"display", "kp", "kd", "simulation"}, _exact_key, _exact_chart,
                       asynchronous=True, params={"bc_range": EXACT_BC_RANGE, "points": EXACT_POINTS}))
        graph.add(Node(LIMIT_NODE, _DEVICE | GAIN_FIELDS | {"simulation"}, _limit_key, _limit, asynchronous=True))
        graph.add(Node(SIM_NODE, sim_inputs, _sim_key, _simulation, asynchronous=True))
        for name in ASYNC_NODES:
            TASK_TITLES.setdefault(name, f"Computing {TITLES[name].lower()}")

    def __init__(self, ctx: AppContext, parent: QWidget | None = None) -> None:
        super().__init__(ctx, parent)
        g = ctx.graph
        self._held: dict[str, Hashable] = {}  # node -> key not to restart (cancelled or failed)
        self._errors: dict[str, str] = {}
        self.map_settings = {disp: {"x": axes[0][0], "x_range": DEFAULT_RANGES[(disp, axes[0][0])],
                                    "y": axes[0][1], "y_range": DEFAULT_RANGES[(disp, axes[0][1])],
                                    "points": MAP_POINTS} for disp, axes in MAP_AXES.items()}
        self.map_view = StabilityMapView()
        self.exact_view = ExactLimitChart()
        self.time_view = TimeResponse()
        self.summary = QLabel("")
        self.summary.setWordWrap(True)
        self.summary.setTextFormat(Qt.TextFormat.RichText)
        self.progress = {name: NodeProgress(g, name, TITLES[name]) for name in ASYNC_NODES}
        for w in self.progress.values():
            w.rerun.connect(self.run_again)

        # -- controls ------------------------------------------------------------------------------
        self.panel = SimulationPanel(ctx.model, ctx.editor)
        self.axes_box = QComboBox()
        self.axes_box.activated.connect(self._on_axes)
        self.range_fields = {k: SciSpinBox() for k in ("x_lo", "x_hi", "y_lo", "y_hi")}
        for f in self.range_fields.values():
            f.setMaximumWidth(100)
            f.editingFinished.connect(self._on_range)
        self.points = QSpinBox()
        self.points.setRange(4, 400)
        self.points.setKeyboardTracking(False)
        self.points.setToolTip("Grid points per axis (the map costs points² eigenvalue problems)")
        self.points.valueChanged.connect(self._on_points)
        self.map_error = QLabel("")
        self.map_error.setStyleSheet("color: #c92a2a;")
        self.map_error.hide()
        mg = QGroupBox("Stability map")
        mf = QFormLayout(mg)
        mf.addRow("Axes (x × y)", self.axes_box)
        self.x_label, self.y_label = QLabel("x range"), QLabel("y range")
        for label, lo, hi in ((self.x_label, "x_lo", "x_hi"), (self.y_label, "y_lo", "y_hi")):
            row = QHBoxLayout()
            row.addWidget(self.range_fields[lo])
            row.addWidget(QLabel("to"))
            row.addWidget(self.range_fields[hi])
            mf.addRow(label, row)
        mf.addRow("Points per axis", self.points)
        mf.addRow(self.map_error)
        controls = QWidget()
        cl = QVBoxLayout(controls)
        cl.setContentsMargins(0, 0, 4, 0)
        cl.addWidget(self.panel)
        cl.addWidget(mg)
        cl.addStretch(1)
        scroll = QScrollArea()
        scroll.setWidget(controls)
        scroll.setWidgetResizable(True)
        scroll.setMinimumWidth(270)
        scroll.setMaximumWidth(380)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)

        # -- views ----------------------------------------------------------------------------------
        def column(*widgets: QWidget) -> QWidget:
            w = QWidget()
            lay = QVBoxLayout(w)
            lay.setContentsMargins(0, 0, 0, 0)
            lay.setSpacing(2)
            for x in widgets:
                lay.addWidget(x, 1 if isinstance(x, (PlotView, TimeResponse)) else 0)
            return w

        top = QSplitter(Qt.Orientation.Horizontal)
        top.addWidget(column(self.map_view, self.progress[MAP_NODE]))
        top.addWidget(column(self.exact_view, self.progress[EXACT_NODE], self.progress[LIMIT_NODE]))
        top.setChildrenCollapsible(False)
        split = QSplitter(Qt.Orientation.Vertical)
        split.addWidget(top)
        split.addWidget(column(self.summary, self.time_view, self.progress[SIM_NODE]))
        split.setChildrenCollapsible(False)
        split.setSizes([1, 1])
        lay = QHBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(scroll)
        lay.addWidget(split, 1)

        g.ready.connect(self._on_ready)
        g.cancelled.connect(self._on_cancelled)
        g.failed.connect(self._on_failed)
        self._sync_map_controls(ctx.model.profile.display)

    # -- map settings (view state, not the profile) --------------------------------------------------
    def _sync_map_controls(self, display: str) -> None:
        s = self.map_settings[display]
        self.axes_box.blockSignals(True)
        self.axes_box.clear()
        for x, y in MAP_AXES[display]:
            self.axes_box.addItem(f"{PARAMETER_LABELS[x][0]} × {PARAMETER_LABELS[y][0]}", (x, y))
        self.axes_box.setCurrentIndex(MAP_AXES[display].index((s["x"], s["y"])))
        self.axes_box.blockSignals(False)
        for key, (lo, hi) in (("x", s["x_range"]), ("y", s["y_range"])):
            self.range_fields[f"{key}_lo"].setValue(lo)
            self.range_fields[f"{key}_hi"].setValue(hi)
            name, unit = PARAMETER_LABELS[s[key]]
            for k in ("lo", "hi"):
                self.range_fields[f"{key}_{k}"].setSuffix(f" {unit}")
            (self.x_label if key == "x" else self.y_label).setText(f"{name} range")
        self.points.blockSignals(True)
        self.points.setValue(int(s["points"]))
        self.points.blockSignals(False)

    def set_map(self, x: str | None = None, y: str | None = None, x_range: tuple[float, float] | None = None,
                y_range: tuple[float, float] | None = None, points: int | None = None) -> str | None:
        """Change the map's axes, ranges or resolution; returns the reason if refused."""
        display = self.ctx.model.profile.display
        s = dict(self.map_settings[display])
        if x is not None or y is not None:
            x, y = x or s["x"], y or s["y"]
            if (x, y) not in MAP_AXES[display]:
                return self._map_refused(f"axes {x} × {y} are not offered for the {display} display")
            if x != s["x"]:
                s["x_range"] = DEFAULT_RANGES[(display, x)]
            if y != s["y"]:
                s["y_range"] = DEFAULT_RANGES[(display, y)]
            s["x"], s["y"] = x, y
        for key, rng in (("x_range", x_range), ("y_range", y_range)):
            if rng is not None:
                lo, hi = float(rng[0]), float(rng[1])
                if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
                    return self._map_refused(f"{key.replace('_', ' ')}: must satisfy 0 < low < high (log axis)")
                s[key] = (lo, hi)
        if points is not None:
            s["points"] = int(points)
        self.map_error.hide()
        self.map_settings[display] = s
        self._sync_map_controls(display)
        self._held.pop(MAP_NODE, None)
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True
        return None

    def _map_refused(self, reason: str) -> str:
        self.map_error.setText(f"refused: {reason}")
        self.map_error.show()
        self._sync_map_controls(self.ctx.model.profile.display)
        return reason

    @Slot(int)
    def _on_axes(self, _i: int) -> None:
        x, y = self.axes_box.currentData()
        self.set_map(x=x, y=y)

    @Slot()
    def _on_range(self) -> None:
        f = self.range_fields
        self.set_map(x_range=(f["x_lo"].value(), f["x_hi"].value()), y_range=(f["y_lo"].value(), f["y_hi"].value()))

    @Slot(int)
    def _on_points(self, n: int) -> None:
        self.set_map(points=n)

    # -- pulling ---------------------------------------------------------------------------------------
    def _pull(self, name: str) -> Any:
        """Request ``name`` unless the user cancelled it (or it failed) for the same inputs."""
        g = self.ctx.graph
        held = self._held.get(name)
        if held is not None:
            if held == g.key_of(name):
                return g.node(name).value
            del self._held[name]
            self._errors.pop(name, None)
        return g.request(name)

    def _busy(self, name: str) -> bool:
        return not self.ctx.graph.is_fresh(name) and name not in self._held

    def refresh(self) -> None:
        g, p = self.ctx.graph, self.ctx.model.profile
        self._sync_map_controls(p.display)
        g.node(MAP_NODE).params.update(self.map_settings[p.display])
        m = self._pull(MAP_NODE)
        chart = self._pull(EXACT_NODE)
        limit = self._pull(LIMIT_NODE)
        sim = self._pull(SIM_NODE)
        bound = g.request("design_chart")
        stable = g.get("stability").stable
        sec = current_section(p)
        d, impl = sec.options.delay_samples, sec.options.implementation_delay

        # the map ----------------------------------------------------------------------------
        if m is not None and m.x_name == self.map_settings[p.display]["x"]:
            self.map_view.update_map(m, self._map_subtitle(p, m))
            px, py = self._design_on_map(p, m)
            inside = (m.x[0] <= px <= m.x[-1]) and py is not None and (m.y[0] <= py <= m.y[-1])
            rho = self.map_view.value_at(px, py) if inside else math.nan
            self.map_view.update_point(px, py, None if math.isnan(rho) else rho <= 1 + 1e-12)
        elif m is not None:
            self.map_view.update_map(None)
        self.map_view.set_busy(self._busy(MAP_NODE))
        if MAP_NODE in self._errors:
            self.map_view.set_warning([self._errors[MAP_NODE]])

        # the exact limit chart -----------------------------------------------------------------
        kind = CriticalChart if p.display == "impedance" else CriticalMassChart
        if bound is not None and bound.display == p.display:
            self.exact_view.update_bound(bound)
        else:
            self.exact_view.update_bound(None)
        self.exact_view.update_exact(chart if isinstance(chart, kind) else None, p.display)
        if p.display == "impedance":
            self.exact_view.update_point(p.bc, p.kc, stable)
        else:
            self.exact_view.update_point(p.mc, p.bc_adm, stable)
        self.exact_view.set_busy(self._busy(EXACT_NODE) or not g.is_fresh("design_chart"))
        if EXACT_NODE in self._errors:
            self.exact_view.set_warning([self._errors[EXACT_NODE]])
        self.summary.setText(self._summary(p, limit if g.is_fresh(LIMIT_NODE) else None, d, impl))

        # the simulation --------------------------------------------------------------------------
        if sim is not None:
            sc = sec.scenario
            ideal = dataclasses.replace(sec.options, delay_samples=0, implementation_delay=False) == SimulationOptions()
            effects = "ideal sensors and actuator" if ideal else "with quantization / friction / saturation"
            grasp = "hands-off" if sc.grasp.hands_off else (
                f"grasp {sc.grasp.mass:g} kg, {sc.grasp.damping:g} N·s/m, {sc.grasp.stiffness:g} N/m"
                f"{f' until {sc.release_time:g} s' if math.isfinite(sc.release_time) else ''}")
            env = ("no wall" if not sc.wall else
                   f"penalty wall {sc.wall_stiffness:g} N/m" if sc.causality == "impedance" else "god-object wall")
            note = (f"Scenario: {sc.name.replace('_', ' ')} ({grasp}; {env}); {effects}; delay {d} sample(s)"
                    f"{', implementation delay' if impl else ''}.  The exact limit above is for hands-off "
                    "against a rigid wall, so a damped grasp can be stable beyond it.")
            if not g.is_fresh(SIM_NODE):
                note += "  (result of the previous inputs)"
            self.time_view.update_result(sim, sc.wall_position if sc.wall else None, note)
        if SIM_NODE in self._errors:
            self.time_view.verdict.setText(f"<span style='color:#c92a2a'>{self._errors[SIM_NODE]}</span>")
        self.time_view.set_busy(self._busy(SIM_NODE))
        self.refreshes += 1
        self.stale = False

    @staticmethod
    def _map_subtitle(p: Profile, m: StabilityMap) -> str:
        names = {m.x_name, m.y_name}
        if p.display == "impedance":
            env = "" if "kobj" in names else f"penalty wall k_obj = {PAPER_WALL_STIFFNESS / 1e3:g} kN/m"
            who = "hands-off" if not names & {"grasp_mass", "grasp_stiffness"} else "grasp (other terms 0)"
            fixed = f"k_c = {p.kc:g} N/m" if "kc" not in names else f"b_c = {p.bc:g} N·s/m"
            if names == {"kc", "bc"}:
                fixed = ""
        else:
            env = "free motion"
            g = RIGID_GRASP
            who = f"rigid grasp ({g.mass:g} kg, {g.damping:g} N·s/m, {g.stiffness:g} N/m)"
            fixed = f"b_c = {p.bc_adm:g} N·s/m, k_p = {p.kp:g}, k_d = {p.kd:g}" if "bc" not in names else \
                f"k_p = {p.kp:g}, k_d = {p.kd:g}"
        d, impl = _delays(p)
        parts = [x for x in (who, env, fixed, f"delay {d} sample(s)" + (" + implementation" if impl else "")) if x]
        return "; ".join(parts)

    @staticmethod
    def _design_on_map(p: Profile, m: StabilityMap) -> tuple[float, float | None]:
        x = p.kc if m.x_name == "kc" else p.mc
        y = {"kobj": PAPER_WALL_STIFFNESS, "bc": p.bc if p.display == "impedance" else p.bc_adm, "kd": p.kd,
             "grasp_mass": (HANDS_OFF if p.display == "impedance" else RIGID_GRASP).mass,
             "grasp_stiffness": (HANDS_OFF if p.display == "impedance" else RIGID_GRASP).stiffness}.get(m.y_name)
        return float(x), (None if y is None else float(y))

    def _summary(self, p: Profile, limit: float | None, d: int, impl: bool) -> str:
        delay = f"{d}-sample computation delay" if d else "no computation delay"
        if impl:
            delay += " + implementation delay"
        if p.display == "impedance":
            bound = self.ctx.graph.get("max_stiffness").kc
            bound_txt = "none" if bound is None else f"{plain(bound / 1e3, 4)} kN/m"
            if limit is None:
                exact_txt = "computing…"
            elif limit == 0:
                exact_txt = "<b>unstable for every k_c</b>"
            elif math.isinf(limit):
                exact_txt = "no limit below 10⁹ N/m"
            else:
                exact_txt = f"<b>{plain(limit / 1e3, 4)} kN/m</b>"
            text = (f"Largest stable k_c at b_c = {plain(p.bc)} N·s/m — exact sampled loop ({delay}, hands-off, "
                    f"rigid god-object wall): {exact_txt};  two-port bound (eq. 9, delay-free model): {bound_txt}.  "
                    f"Current k_c = {plain(p.kc / 1e3, 4)} kN/m")
            if limit is not None and math.isfinite(limit):
                ok = p.kc < limit
                text += (" is <span style='color:#2b8a3e'>below the exact limit</span>." if ok else
                         " is <span style='color:#c92a2a'><b>above the exact limit: the loop is unstable</b></span>.")
                if bound is not None and limit < bound:
                    text += (f"  <span style='color:#c92a2a'>⚠ The two-port bound is not safe here: the exact limit is "
                             f"{100 * (1 - limit / bound):.0f} % lower (the bound assumes no delay).</span>")
                elif bound is not None and limit > bound:
                    text += f"  The bound is conservative by a factor {limit / bound:.2g}."
            return text
        if limit is None:
            exact_txt = "computing…"
        elif math.isinf(limit):
            exact_txt = "<b>no stable m_c</b>"
        elif limit == 0:
            exact_txt = "every m_c ≥ 1 g stable"
        else:
            exact_txt = f"<b>{plain(limit, 4)} kg</b>"
        text = (f"Smallest stable m_c at b_c = {plain(p.bc_adm)} N·s/m — exact sampled loop ({delay}, rigid grasp, "
                f"free motion): {exact_txt}.  Current m_c = {plain(p.mc)} kg")
        if limit is not None and math.isfinite(limit) and limit > 0:
            text += (" is <span style='color:#2b8a3e'>above it</span>." if p.mc > limit else
                     " is <span style='color:#c92a2a'><b>below it: the loop is unstable</b></span>.")
        return text

    # -- worker reports -------------------------------------------------------------------------------
    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name in self.nodes and self.isVisible():
            self.refresh()

    @Slot(str)
    def _on_cancelled(self, name: str) -> None:
        if name in ASYNC_NODES:
            self._held[name] = self.ctx.graph.key_of(name)
            if self.isVisible():
                self.refresh()

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name in ASYNC_NODES:
            self._held[name] = self.ctx.graph.key_of(name)
            self._errors[name] = f"{TITLES[name]} failed: {message}"
            if self.isVisible():
                self.refresh()

    @Slot(str)
    def run_again(self, name: str) -> None:
        """Restart a cancelled (or failed) computation."""
        self._held.pop(name, None)
        self._errors.pop(name, None)
        self.progress[name].hide()
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True

    def cancel(self, name: str) -> None:
        self.ctx.graph.cancel(name)

    def plot_views(self) -> list[PlotView]:
        return [self.map_view, self.exact_view, *self.time_view.plot_views()]


TAB = SampledTab
