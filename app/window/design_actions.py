"""Design → Maximize k_c (eq. 9) and Minimize m_c (eq. 21): the analysis core's designs as one undo step."""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QObject, Slot
from PySide6.QtGui import QAction

from analysis.study import display_kind

from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel

__all__ = ["DesignActions"]


class DesignActions(QObject):
    """Owns the two design actions; each is enabled only for its display type.

    ``maximize`` and ``minimize`` are the window's QActions; ``say(message)`` shows a status message.
    """

    def __init__(self, model: ProfileModel, graph: ComputeGraph, editor: Editor, maximize: QAction,
                 minimize: QAction, say: Callable[[str, int], None], parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.model, self.graph, self.editor, self._say = model, graph, editor, say
        self.maximize, self.minimize = maximize, minimize
        self.pending_min_mass = False
        maximize.triggered.connect(lambda _=False: self.maximize_kc())
        minimize.triggered.connect(lambda _=False: self.minimize_mc())
        graph.ready.connect(self._on_ready)
        graph.failed.connect(self._on_failed)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.update_enabled)
        self.update_enabled()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "display":
            self.update_enabled()

    def _impedance(self) -> bool:
        return display_kind(self.model.profile).is_impedance

    @Slot()
    def update_enabled(self) -> None:
        imp = self._impedance()
        self.maximize.setEnabled(imp)
        self.minimize.setEnabled(not imp)

    @Slot()
    def maximize_kc(self) -> None:
        """k_c := the analysis core's conservative largest k_c for the current b_c."""
        if not self._impedance():
            return
        d = self.graph.get("max_stiffness", hold=False)  # the current design, even during a drag
        if d.kc is None:
            self._say(f"No k_c ≥ 0 satisfies eq. (9) with b_c = {d.bc:g} N·s/m", 8000)
            return
        if d.kc == float("inf"):
            self._say("Every k_c satisfies eq. (9) for this device: k_c is unlimited", 8000)
            return
        self.editor.edit_many({"kc": d.kc}, "Maximize k_c")
        self._say(f"k_c = {d.kc:.6g} N/m (binding at {d.frequency:.4g} rad/s)", 8000)

    @Slot()
    def minimize_mc(self) -> None:
        """(m_c, b_c) := the analysis core's smallest feasible coupling mass (runs on the worker)."""
        if self._impedance():
            return
        self.pending_min_mass = True
        if self.graph.request("min_mass") is not None and self.graph.is_fresh("min_mass"):
            self._apply_min_mass()

    def _apply_min_mass(self) -> None:
        self.pending_min_mass = False
        d = self.graph.result("min_mass")
        self.editor.edit_many({"mc": d.mc, "bc_adm": d.bc}, "Minimize m_c")
        self._say(f"m_c = {d.mc:.6g} kg, b_c = {d.bc:.6g} N·s/m", 8000)

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == "min_mass" and self.pending_min_mass and self.graph.is_fresh("min_mass"):
            self._apply_min_mass()

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name == "min_mass":
            self.pending_min_mass = False
