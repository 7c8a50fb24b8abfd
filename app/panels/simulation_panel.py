"""Controls of the profile's ``simulation`` section: delays, scenario and nonlinear effects.

Every edit builds a new :class:`~analysis.profile_sections.SimulationSection` (from the defaults
when the profile has none) and goes through the :class:`~app.commands.Editor` as one undo step.
A value the analysis core refuses is shown with its reason and changes nothing.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from analysis import ValidationError
from analysis.profiles.sections import SimulationSection
from analysis.study import SCENARIO_TIPS, SCENARIO_TITLES, scenario_matches
from analysis.sampled import CLAMPED, FIRM_GRASP, HANDS_OFF, RIGID_GRASP, SCENARIOS, SimulationOptions, hbfd_options
from analysis.sampled import scenario as preset

from app.widgets.colors import ERROR_STYLE
from app.core.commands import Editor, describe_error
from app.core.model import ProfileModel
from app.core.nodes_sampled import current_section

__all__ = ["SimulationPanel", "current_section", "GRASPS", "SCENARIO_TITLES", "with_options", "with_scenario",
           "hbfd_section", "ideal_section"]

GRASPS = {"hands-off": HANDS_OFF, "firm grasp": FIRM_GRASP, "rigid grasp": RIGID_GRASP, "clamped": CLAMPED}



def _fmt(x: float) -> str:
    return "inf" if math.isinf(x) else f"{x:.6g}"


def _parse_float(text: str) -> float:
    return float(text.strip().replace("∞", "inf"))


def with_options(s: SimulationSection, **changes: object) -> SimulationSection:
    """``s`` with some simulator options changed (validated by ``SimulationOptions``)."""
    return SimulationSection(options=dataclasses.replace(s.options, **changes), scenario=s.scenario)


def with_scenario(s: SimulationSection, **changes: object) -> SimulationSection:
    """``s`` with some scenario fields changed; a changed preset is renamed ``custom``."""
    sc = s.scenario.replace(**changes)
    if sc != SCENARIOS.get(sc.name):
        sc = sc.replace(name="custom")
    return SimulationSection(options=s.options, scenario=sc)


def hbfd_section(s: SimulationSection, masses: int) -> SimulationSection:
    """The HBFD's sensors, actuator and friction (friction dropped unless one value per mass); keeps the delays."""
    o = s.options
    base = hbfd_options(delay_samples=o.delay_samples, implementation_delay=o.implementation_delay)
    if len(base.friction) != masses:
        base = dataclasses.replace(base, friction=())
    return SimulationSection(options=base, scenario=s.scenario)


def ideal_section(s: SimulationSection) -> SimulationSection:
    """Ideal sensors and actuator; keeps the delays."""
    o = s.options
    return SimulationSection(options=SimulationOptions(delay_samples=o.delay_samples,
                                                       implementation_delay=o.implementation_delay),
                             scenario=s.scenario)


class _Field(QLineEdit):
    """A number field: parsed with ``float`` (``inf`` allowed), applied on Enter or focus loss."""

    def __init__(self, tip: str) -> None:
        super().__init__()
        self.setToolTip(tip)
        self.setMaximumWidth(110)


class PassivityControls(QGroupBox):
    """The passivity observer and controller of Hannaford & Ryu (IEEE T-RO 18(1), 2002), issue 15:
    two check boxes and the PC damping cap (``max_damping``, a field of the panel)."""

    def __init__(self, edit_options: Callable[..., str | None], max_damping: QLineEdit) -> None:
        super().__init__("Passivity control (Hannaford && Ryu, simulation only)")
        self.max_damping = max_damping
        self.po = QCheckBox("passivity observer (energy into the virtual environment)")
        self.po.setToolTip("Records the energy flowing into the virtual environment port from the sampled "
                           "force and velocity (simulation only)")
        self.po.toggled.connect(lambda on: edit_options("passivity observer", passivity_observer=bool(on)))
        self.pc = QCheckBox("passivity controller (variable damping)")
        self.pc.setToolTip("Adds the damping that removes the observed energy excess (impedance causality, "
                           "Hannaford & Ryu); implies the observer")
        self.pc.toggled.connect(lambda on: edit_options("passivity controller", passivity_control=bool(on)))
        form = QFormLayout(self)
        form.addRow(self.po)
        form.addRow(self.pc)
        form.addRow("Max PC damping [N·s/m]", max_damping)

    def sync(self, o: SimulationOptions) -> None:
        """Show ``o``'s passivity options (the caller blocks the edits)."""
        self.po.setChecked(o.passivity_observer or o.passivity_control)
        self.po.setEnabled(not o.passivity_control)  # the controller needs the observer
        self.pc.setChecked(o.passivity_control)
        self.max_damping.setEnabled(o.passivity_control)


class SimulationPanel(QWidget):
    def __init__(self, model: ProfileModel, editor: Editor, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.model, self.editor = model, editor
        self._syncing = False
        self.error = QLabel("")
        self.error.setWordWrap(True)
        self.error.setStyleSheet(ERROR_STYLE)
        self.error.hide()
        self.fields: dict[str, _Field] = {}
        lay = QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        self.passivity = PassivityControls(self._edit_options, self._option_field("passivity_max_damping", (
            "Cap of the PC damping (0 = uncapped, as in Hannaford & Ryu)")))
        self.po, self.pc = self.passivity.po, self.passivity.pc
        for box in (self._loop_box(), self._scenario_box(), self._effects_box(), self.passivity):
            lay.addWidget(box)
        lay.addWidget(self.error)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.sync)
        editor.refused.connect(self._on_refused)
        self.sync()

    # -- construction ----------------------------------------------------------------------------
    def _loop_box(self) -> QGroupBox:
        """The computation and implementation delays."""
        self.delay = QSpinBox()
        self.delay.setRange(0, 1000)
        self.delay.setSuffix(" sample(s) of T")
        self.delay.setToolTip("Computation delay between sampling and the force output (whole samples)")
        self.delay.setKeyboardTracking(False)
        self.delay.valueChanged.connect(lambda v: self._edit_options("computation delay", delay_samples=int(v)))
        self.impl = QCheckBox("one-sample implementation delay")
        self.impl.setToolTip("Explicit integration: the environment sees the coupling force one sample late")
        self.impl.toggled.connect(lambda on: self._edit_options("implementation delay", implementation_delay=bool(on)))
        loop = QGroupBox("Sampled loop (map, exact limit and simulation)")
        lf = QFormLayout(loop)
        lf.addRow("Computation delay", self.delay)
        lf.addRow(self.impl)
        return loop

    def _scenario_box(self) -> QGroupBox:
        """The scenario preset, environment, grasp and push."""
        self.preset = QComboBox()
        for name in SCENARIOS:
            self.preset.addItem(SCENARIO_TITLES.get(name, name), name)
            self.preset.setItemData(self.preset.count() - 1, SCENARIO_TIPS.get(name, ""), Qt.ItemDataRole.ToolTipRole)
        self.preset.addItem("Custom", "custom")
        self.preset.activated.connect(self._on_preset)
        self.causality = QComboBox()
        self.causality.addItem("penalty (impedance)", "impedance")
        self.causality.addItem("god-object (admittance)", "admittance")
        self.causality.activated.connect(
            lambda _i: self._edit_scenario("environment", causality=self.causality.currentData()))
        self.wall = QCheckBox("wall present")
        self.wall.toggled.connect(lambda on: self._edit_scenario("wall", wall=bool(on)))
        self.grasp = QComboBox()
        for name in GRASPS:
            self.grasp.addItem(name, name)
        self.grasp.activated.connect(
            lambda _i: self._edit_scenario("grasp", grasp=GRASPS[self.grasp.currentData()]))
        sc = QGroupBox("Scenario")
        sf = QFormLayout(sc)
        sf.addRow("Preset", self.preset)
        sf.addRow("Environment", self.causality)
        sf.addRow(self.wall)
        sf.addRow("Wall stiffness k_obj [N/m]", self._scenario_field("wall_stiffness", "Penalty wall stiffness"))
        sf.addRow("Wall position [m]", self._scenario_field("wall_position", "Wall surface position"))
        sf.addRow("Grasp", self.grasp)
        sf.addRow("Push force [N]", self._scenario_field("push_force", "Force of the human on the handle"))
        sf.addRow("Release time [s]", self._scenario_field("release_time", "Grasp and push removed (inf: never)"))
        sf.addRow("Duration [s]", self._scenario_field("duration", "Simulated time (at most 3600 s)"))
        return sc

    def _effects_box(self) -> QGroupBox:
        """Quantization, friction and saturation of the simulator."""
        nl = QGroupBox("Nonlinear effects (simulation only)")
        nf = QFormLayout(nl)
        nf.addRow("Encoder resolution [m]", self._option_field("encoder_resolution", "0 = ideal encoder"))
        nf.addRow("Force resolution [N]", self._option_field("force_resolution", "0 = ideal force gauge"))
        self.friction = _Field("Coulomb friction per mass, handle first, comma separated (empty = none)")
        self.friction.setMaximumWidth(160)
        self.friction.editingFinished.connect(self._on_friction)
        nf.addRow("Friction [N per mass]", self.friction)
        nf.addRow("Peak force [N]", self._option_field("force_peak", "Instantaneous clip (inf = off)"))
        nf.addRow("Continuous force [N]", self._option_field("force_continuous", "RMS limit, I²t model (inf = off)"))
        self.substeps = QSpinBox()
        self.substeps.setRange(1, 4096)
        self.substeps.setKeyboardTracking(False)
        self.substeps.setToolTip("Sub-steps per sample for the friction forces (no effect without friction)")
        self.substeps.valueChanged.connect(lambda v: self._edit_options("sub-steps", substeps=int(v)))
        nf.addRow("Sub-steps", self.substeps)
        self.hbfd_button = QPushButton("HBFD values")
        self.hbfd_button.setToolTip("0.015 mm encoder, 0.05 N gauge, 100 N / 400 N, illustrative friction "
                                    "(keeps the delays)")
        self.hbfd_button.clicked.connect(self._on_hbfd)
        self.ideal_button = QPushButton("Ideal")
        self.ideal_button.setToolTip("No quantization, friction or saturation (keeps the delays)")
        self.ideal_button.clicked.connect(self._on_ideal)
        row = QHBoxLayout()
        row.addWidget(self.hbfd_button)
        row.addWidget(self.ideal_button)
        nf.addRow(row)
        return nl

    def _number_field(self, attr: str, tip: str, scenario: bool) -> _Field:
        f = _Field(tip)
        f.editingFinished.connect(lambda: self._edit_number(f, attr, scenario=scenario))
        self.fields[attr] = f
        return f

    def _scenario_field(self, attr: str, tip: str) -> _Field:
        return self._number_field(attr, tip, True)

    def _option_field(self, attr: str, tip: str) -> _Field:
        return self._number_field(attr, tip, False)

    # -- state ------------------------------------------------------------------------------------
    def section(self) -> SimulationSection:
        return current_section(self.model.profile)

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in ("simulation", "display", "device"):
            self.sync()

    @Slot()
    def sync(self) -> None:
        """Show the model's values (never emits edits)."""
        self._syncing = True
        try:
            s = self.section()
            o, sc = s.options, s.scenario
            self.delay.setValue(o.delay_samples)
            self.impl.setChecked(o.implementation_delay)
            i = self.preset.findData(sc.name if sc.name in SCENARIOS and SCENARIOS[sc.name] == sc else "custom")
            self.preset.setCurrentIndex(i)
            profile = self.model.profile
            for j in range(self.preset.count()):  # the other display's worst case is not offered
                name = self.preset.itemData(j)
                item = self.preset.model().item(j)
                if name in SCENARIOS and item is not None:
                    item.setEnabled(scenario_matches(profile, SCENARIOS[name]))
            self.causality.setCurrentIndex(self.causality.findData(sc.causality))
            self.wall.setChecked(sc.wall)
            g = next((k for k, v in GRASPS.items() if v == sc.grasp), None)
            if g is None:
                if self.grasp.findData("custom") < 0:
                    self.grasp.addItem("custom", "custom")
                g = "custom"
                self.grasp.setToolTip(f"m = {sc.grasp.mass} kg, b = {sc.grasp.damping} N·s/m, "
                                      f"k = {sc.grasp.stiffness} N/m")
            self.grasp.setCurrentIndex(self.grasp.findData(g))
            for attr, f in self.fields.items():
                obj = sc if hasattr(sc, attr) else o
                f.setText(_fmt(getattr(obj, attr)))
            self.friction.setText(", ".join(f"{x:g}" for x in o.friction))
            self.substeps.setValue(o.substeps)
            self.passivity.sync(o)
            for attr in ("wall_stiffness", "wall_position"):
                self.fields[attr].setEnabled(sc.wall)
        finally:
            self._syncing = False

    def _show_error(self, text: str) -> None:
        self.error.setText(text)
        self.error.setVisible(bool(text))

    @Slot(str, str)
    def _on_refused(self, field: str, reason: str) -> None:
        if field == "simulation":
            self._show_error(reason)

    # -- edits --------------------------------------------------------------------------------------
    def _push(self, build: Callable[[SimulationSection], SimulationSection], label: str) -> str | None:
        if self._syncing:
            return None
        try:
            new = build(self.section())
        except (ValidationError, TypeError, ValueError) as err:
            reason = describe_error(err)
            self._show_error(f"{label}: {reason}")
            self.sync()
            return reason
        self._show_error("")
        reason = self.editor.edit_many({"simulation": new}, f"Set {label}")
        if reason:
            self.sync()
        return reason

    def _edit_options(self, label: str, **changes: object) -> str | None:
        return self._push(lambda s: with_options(s, **changes), label)

    def _edit_scenario(self, label: str, **changes: object) -> str | None:
        return self._push(lambda s: with_scenario(s, **changes), label)

    def _edit_number(self, field: _Field, attr: str, scenario: bool) -> None:
        if self._syncing or not field.isModified():
            return
        field.setModified(False)
        label = attr.replace("_", " ")
        try:
            value = _parse_float(field.text())
        except ValueError:
            self._show_error(f"{label}: refused: not a number")
            self.sync()
            return
        if scenario:
            self._edit_scenario(label, **{attr: value})
        else:
            self._edit_options(label, **{attr: value})

    @Slot(int)
    def _on_preset(self, _index: int) -> None:
        name = self.preset.currentData()
        if name == "custom":
            self.sync()
            return
        self._push(lambda s: SimulationSection(options=s.options, scenario=preset(name)), "scenario preset")

    @Slot()
    def _on_friction(self) -> None:
        if self._syncing or not self.friction.isModified():
            return
        self.friction.setModified(False)
        text = self.friction.text().strip()
        try:
            values = tuple(_parse_float(x) for x in text.replace(";", ",").split(",") if x.strip())
        except ValueError:
            self._show_error("friction: refused: a comma-separated list of forces (N)")
            self.sync()
            return
        n = self.model.device.n
        if values and len(values) != n:
            self._show_error(f"friction: refused: must be {n} values (one per mass) or empty")
            self.sync()
            return
        self._edit_options("friction", friction=values)

    @Slot()
    def _on_hbfd(self) -> None:
        self._push(lambda s: hbfd_section(s, self.model.device.n), "HBFD nonlinear effects")

    @Slot()
    def _on_ideal(self) -> None:
        self._push(ideal_section, "ideal sensors and actuator")

