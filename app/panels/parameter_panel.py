"""The parameter panel: display type, coupling and PD gains, sampling and band, device chain."""

from __future__ import annotations

from PySide6.QtCore import Qt, Slot
from PySide6.QtGui import QAction, QFont
from PySide6.QtWidgets import QGroupBox, QLabel, QScrollArea, QToolButton, QVBoxLayout, QWidget

from analysis.study import display_kind

from app.core.commands import Editor
from app.core.model import ProfileModel
from app.panels.chain_editor import ChainEditor
from app.panels.filter_panel import FilterPanel
from app.widgets.display_selector import DisplaySelector
from app.widgets.log_slider_field import LogSliderField, with_range

__all__ = ["ParameterPanel"]


class ParameterPanel(QScrollArea):
    """Display type, coupling and PD gains, sampling and band, and the device chain; ``fields`` by name."""

    def __init__(self, model: ProfileModel, editor: Editor, maximize_kc: QAction, minimize_mc: QAction,
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self._model = model
        self.setWidgetResizable(True)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        body = QWidget()
        lay = QVBoxLayout(body)
        lay.setContentsMargins(8, 8, 8, 8)
        lay.setSpacing(8)
        self._editor = editor
        self.fields: dict[str, LogSliderField] = {}
        field = self._field
        self.title = QLabel()
        self.title.setWordWrap(True)
        font = self.title.font()  # a font, not a style sheet: a style sheet keeps the palette's old text colour
        font.setPixelSize(14)
        font.setWeight(QFont.Weight.DemiBold)
        self.title.setFont(font)
        lay.addWidget(self.title)
        lay.addWidget(self._coupling_box(maximize_kc, minimize_mc))

        self.pd_box = QGroupBox("PD position loop (admittance display, eq. 30)")
        gp = QVBoxLayout(self.pd_box)
        gp.addWidget(field("kp", "k<sub>p</sub>", "N/m", 10.0, 1e7, True, "Proportional gain of the position loop"))
        gp.addWidget(field("kd", "k<sub>d</sub>", "N·s/m", 1e-2, 1e5, True, "Derivative gain of the position loop"))
        lay.addWidget(self.pd_box)
        self.filter_panel = FilterPanel(model, editor)  # the controller's velocity estimate (issue 15)
        lay.addWidget(self.filter_panel)

        box = QGroupBox("Sampling and analysis band")
        gs = QVBoxLayout(box)
        gs.addWidget(field("sample_time", "T", "s", 1e-5, 1e-1, False, "Sample period"))
        gs.addWidget(field("band_min", "ω<sub>min</sub>", "rad/s", 1e-3, 1e3, False,
                           "Lower edge of the analysis band [ω_min, π/T)"))
        lay.addWidget(box)

        box = QGroupBox("Device chain (eq. 25–28)")
        gc = QVBoxLayout(box)
        self.chain = ChainEditor(model, editor)
        gc.addWidget(self.chain)
        lay.addWidget(box)
        lay.addStretch(1)
        self.setWidget(body)
        self.setMinimumWidth(360)

        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.refresh)
        self.refresh()

    def _field(self, name: str, label: str, unit: str, lo: float, hi: float, zero: bool, tip: str) -> LogSliderField:
        """A slider field bound to the model field ``name`` (edits through the editor, one undo step)."""
        ed = self._editor
        f = LogSliderField(self._model, (name,), lambda m: float(m.get(name)), lambda v, d: ed.edit(name, v, d),
                           ed, label, unit, lo, hi, allow_zero=zero, tooltip=with_range(tip, name))
        f.setObjectName(name)
        self.fields[name] = f
        return f

    def _coupling_box(self, maximize_kc: QAction, minimize_mc: QAction) -> QGroupBox:
        """The display type and the coupling gains of each display (with its design action)."""
        field, model, editor = self._field, self._model, self._editor
        box = QGroupBox("Display and virtual coupling")
        g = QVBoxLayout(box)
        g.addWidget(DisplaySelector(model, editor))
        self.impedance_box = QWidget()
        gi = QVBoxLayout(self.impedance_box)
        gi.setContentsMargins(0, 0, 0, 0)
        gi.addWidget(field("kc", "k<sub>c</sub>", "N/m", 10.0, 1e7, True, "Coupling stiffness (eq. 4)"))
        gi.addWidget(field("bc", "b<sub>c</sub>", "N·s/m", 1e-2, 1e5, True, "Coupling damping (eq. 4)"))
        self.maximize_button = QToolButton()
        self.maximize_button.setDefaultAction(maximize_kc)
        gi.addWidget(self.maximize_button, 0, Qt.AlignmentFlag.AlignRight)
        self.admittance_box = QWidget()
        ga = QVBoxLayout(self.admittance_box)
        ga.setContentsMargins(0, 0, 0, 0)
        ga.addWidget(field("mc", "m<sub>c</sub>", "kg", 1e-3, 1e3, False, "Coupling mass (eq. 16)"))
        ga.addWidget(field("bc_adm", "b<sub>c</sub>", "N·s/m", 1e-1, 1e5, False, "Coupling damping (eq. 16)"))
        self.minimize_button = QToolButton()
        self.minimize_button.setDefaultAction(minimize_mc)
        ga.addWidget(self.minimize_button, 0, Qt.AlignmentFlag.AlignRight)
        g.addWidget(self.impedance_box)
        g.addWidget(self.admittance_box)
        return box

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field in ("display", "name"):
            self.refresh()

    @Slot()
    def refresh(self) -> None:
        p = self._model.profile
        self.title.setText(p.name or "Untitled profile")
        self.title.setToolTip(p.notes)
        imp = display_kind(p).is_impedance
        self.impedance_box.setVisible(imp)
        self.admittance_box.setVisible(not imp)
        self.pd_box.setVisible(not imp)
