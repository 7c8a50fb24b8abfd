"""Design → Maximize k_c (eq. 9) and Minimize m_c (eq. 21): the analysis core's designs as one undo step.

A design outside the physical range of the field it would set (the loader's own limits,
:func:`analysis.study.edits_beyond_limits`) is never applied: its action is disabled, its tooltip
and the status bar say "beyond the physical range" and which limit (issue 22).  The designs are
known once computed (Maximize on the GUI thread, Minimize on the worker); an edit of their inputs
makes them stale, and the action is offered again.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QObject, Slot
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QMenu

from analysis.study import BeyondLimit, display_kind, edits_beyond_limits, format_number

from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel

__all__ = ["DesignActions", "design_edits", "refusal_tip", "status_number"]


def status_number(value: float, digits: int) -> str:
    """A number in a status message: the GUI's text form (true minus, ×10 exponents)."""
    return format_number(value, digits, style="text")


def design_edits(name: str, design: Any) -> dict[str, float] | None:
    """The profile edits of the ``max_stiffness`` or ``min_mass`` node's design; ``None`` when it
    sets nothing (no k_c, or every k_c: unlimited)."""
    if name == "max_stiffness":
        kc = design.kc
        return None if kc is None or not math.isfinite(kc) else {"kc": float(kc)}
    return {"mc": float(design.mc), "bc_adm": float(design.bc)}


def refusal_tip(beyond: BeyondLimit) -> str:
    """The tooltip of a design action that is disabled because its design is beyond a limit."""
    return (f"Disabled: this design is {beyond.text()}, outside the range a profile accepts for it; "
            "change the device or the gains to get a design inside it")


def show_tips(action: QAction) -> None:
    """Let the menus holding ``action`` show its tooltip (Qt's menus hide tooltips by default)."""
    for obj in action.associatedObjects():
        if isinstance(obj, QMenu):
            obj.setToolTipsVisible(True)


class DesignActions(QObject):
    """Owns the two design actions; each is enabled only for its display type, and only while its
    design (once computed) lies inside the physical range.

    ``maximize`` and ``minimize`` are the window's QActions; ``say(message)`` shows a status message.
    """

    def __init__(self, model: ProfileModel, graph: ComputeGraph, editor: Editor, maximize: QAction,
                 minimize: QAction, say: Callable[[str, int], None], parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.model, self.graph, self.editor, self._say = model, graph, editor, say
        self.maximize, self.minimize = maximize, minimize
        self._tips = {"max_stiffness": maximize.toolTip(), "min_mass": minimize.toolTip()}
        self.pending_min_mass = False
        self.refused: set[str] = set()  # the nodes whose design is beyond a limit (action disabled)
        maximize.triggered.connect(lambda _=False: self.maximize_kc())
        minimize.triggered.connect(lambda _=False: self.minimize_mc())
        graph.ready.connect(self._on_ready)
        graph.failed.connect(self._on_failed)
        graph.invalidated.connect(self._on_invalidated)
        model.fieldChanged.connect(self._on_field)
        model.profileReplaced.connect(self.update_enabled)
        self.update_enabled()

    @Slot(str)
    def _on_field(self, field: str) -> None:
        if field == "display":
            self.update_enabled()

    @Slot(object)
    def _on_invalidated(self, names: object) -> None:
        # only an action refused for its design can change (a drag step costs nothing otherwise)
        if any(name in names for name in self.refused):  # type: ignore[operator]
            self.update_enabled()

    def _impedance(self) -> bool:
        return display_kind(self.model.profile).is_impedance

    def beyond(self, name: str) -> BeyondLimit | None:
        """Why the design of node ``name`` (``max_stiffness``, ``min_mass``) cannot be applied;
        ``None`` when it can, or is not computed for the current profile yet."""
        if not self.graph.is_fresh(name):
            return None
        edits = design_edits(name, self.graph.result(name))
        return None if edits is None else edits_beyond_limits(edits)

    @Slot()
    def update_enabled(self) -> None:
        imp = self._impedance()
        for action, name, offered in ((self.maximize, "max_stiffness", imp), (self.minimize, "min_mass", not imp)):
            beyond = self.beyond(name) if offered else None
            (self.refused.discard if beyond is None else self.refused.add)(name)
            action.setEnabled(offered and beyond is None)
            action.setToolTip(self._tips[name] if beyond is None else refusal_tip(beyond))
            if beyond is not None:
                show_tips(action)

    def _refuse(self, name: str, what: str) -> bool:
        """Refuse a design beyond the physical range (status message, action disabled); ``True`` if refused."""
        beyond = self.beyond(name)
        if beyond is None:
            return False
        self._say(f"{what} not applied: the design is {beyond.text()}", 8000)
        self.update_enabled()
        return True

    @Slot()
    def maximize_kc(self) -> None:
        """k_c := the analysis core's conservative largest k_c for the current b_c."""
        if not self._impedance():
            return
        d = self.graph.get("max_stiffness", hold=False)  # the current design, even during a drag
        if d.kc is None:
            self._say(f"No k_c ≥ 0 satisfies eq. (9) with b_c = {status_number(d.bc, 6)} N·s/m", 8000)
            return
        if d.kc == float("inf"):
            self._say("Every k_c satisfies eq. (9) for this device: k_c is unlimited", 8000)
            return
        if self._refuse("max_stiffness", "Maximize k_c"):
            return
        self.editor.edit_many({"kc": d.kc}, "Maximize k_c")
        self._say(f"k_c = {status_number(d.kc, 6)} N/m (binding at {status_number(d.frequency, 4)} rad/s)", 8000)

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
        if self._refuse("min_mass", "Minimize m_c"):
            return
        d = self.graph.result("min_mass")
        self.editor.edit_many({"mc": d.mc, "bc_adm": d.bc}, "Minimize m_c")
        self._say(f"m_c = {status_number(d.mc, 6)} kg, b_c = {status_number(d.bc, 6)} N·s/m", 8000)

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name == "min_mass" and self.graph.is_fresh("min_mass"):
            if self.pending_min_mass:
                self._apply_min_mass()
            else:
                self.update_enabled()

    @Slot(str, str)
    def _on_failed(self, name: str, message: str) -> None:
        if name == "min_mass":
            self.pending_min_mass = False
