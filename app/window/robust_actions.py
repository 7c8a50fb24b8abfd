"""Design → the robust variants (issue 14), offered when the profile has parameter intervals, and
the verdict's line saying whether the current coupling holds for the whole box.

* "Robust largest k_c" (impedance display): k_c := the largest k_c satisfying eq. (9) for every
  device in the profile's box at the current b_c (:func:`analysis.identify.robust_max_stiffness`);
* "Robust b_c" (admittance display): b_c := the geometric middle of the b_c interval satisfying
  eq. (21) for every device in the box at the current m_c (its lower edge × 2 when unbounded).

Both read the ``robust_designs`` node (:mod:`app.core.nodes_identify`, on the worker) and apply
their change as one undo step.  A change outside the physical range of its field (the loader's own
limits, :func:`analysis.study.edits_beyond_limits`) is never applied: the action is disabled with a
tooltip saying "beyond the physical range" and which limit (issue 22).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from PySide6.QtCore import QObject, Slot
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QMainWindow, QMenu

from analysis.study import BeyondLimit, RobustDesigns, display_kind, edits_beyond_limits

from app.core import nodes_identify
from app.core.commands import Editor
from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel
from app.core.nodes_identify import ROBUST_NODE
from app.window.design_actions import refusal_tip, show_tips, status_number

__all__ = ["RobustActions", "robust_changes", "robust_beyond"]



def robust_changes(designs: RobustDesigns) -> tuple[dict[str, float], str] | None:
    """The profile edits of the robust design and a status message; ``None`` when infeasible."""
    if designs.impedance:
        kc = designs.stiffness.kc if designs.stiffness else None
        if kc is None or not math.isfinite(kc):
            return None
        return {"kc": kc}, f"k_c = {status_number(kc, 6)} N/m holds for the whole box (nominal {status_number(designs.stiffness.nominal_kc, 6)})"
    d = designs.damping
    if d is None or d.low is None:
        return None
    bc = math.sqrt(d.low * d.high) if math.isfinite(d.high) else 2.0 * d.low
    return {"bc_adm": bc}, f"b_c = {status_number(bc, 6)} N·s/m, inside the robust interval [{status_number(d.low, 6)}, {status_number(d.high, 6)}]"


def robust_beyond(designs: RobustDesigns | None) -> BeyondLimit | None:
    """Why the robust design's edits cannot be applied (a value beyond its field's physical range);
    ``None`` when they can, or when there is nothing to apply."""
    change = robust_changes(designs) if designs is not None else None
    return None if change is None else edits_beyond_limits(change[0])


class RobustActions(QObject):
    """The two robust design actions in the Design menu, and the verdict's robust line."""

    def __init__(self, window: QMainWindow, model: ProfileModel, graph: ComputeGraph, editor: Editor,
                 say: Callable[[str, int], None], verdict: object | None = None) -> None:
        super().__init__(window)
        self.model, self.graph, self.editor, self._say, self.verdict = model, graph, editor, say, verdict
        nodes_identify.register(graph)
        self.kc_action = QAction("Robust largest k_c over the parameter box", window)
        self.kc_action.setStatusTip("Set k_c to the largest value satisfying eq. (9) for every device in the "
                                    "profile's parameter intervals")
        self.bc_action = QAction("Robust b_c over the parameter box", window)
        self.bc_action.setStatusTip("Set b_c inside the interval satisfying eq. (21) for every device in the "
                                    "profile's parameter intervals")
        menu = next((a.menu() for a in window.menuBar().actions()
                     if isinstance(a.menu(), QMenu) and a.text().replace("&", "") == "Design"), None)
        if menu is not None:
            menu.addSeparator()
            menu.addAction(self.kc_action)
            menu.addAction(self.bc_action)
        self.pending = False
        self.kc_action.triggered.connect(lambda _=False: self.apply())
        self.bc_action.triggered.connect(lambda _=False: self.apply())
        graph.ready.connect(self._on_ready)
        graph.invalidated.connect(self._on_invalidated)
        model.fieldChanged.connect(lambda _f: self.update_enabled())
        model.profileReplaced.connect(self.update_enabled)
        self.update_enabled()

    @Slot()
    def update_enabled(self) -> None:
        has_box = bool(self.model.profile.identification and self.model.profile.identification.intervals)
        imp = display_kind(self.model.profile).is_impedance
        fresh = has_box and self.graph.is_fresh(ROBUST_NODE)
        beyond = robust_beyond(self.graph.result(ROBUST_NODE)[0]) if fresh else None
        for action, offered in ((self.kc_action, has_box and imp), (self.bc_action, has_box and not imp)):
            refused = offered and beyond is not None
            action.setEnabled(offered and not refused)
            action.setToolTip(refusal_tip(beyond) if refused and beyond is not None else action.statusTip())
            if refused:
                show_tips(action)
        if not has_box and self.verdict is not None and hasattr(self.verdict, "update_robust"):
            self.verdict.update_robust(None, True)
        elif has_box:
            self.graph.request(ROBUST_NODE)

    def apply(self) -> None:
        """Apply the robust design once the ``robust_designs`` node is fresh (on the worker)."""
        self.pending = True
        out = self.graph.request(ROBUST_NODE)
        if out is not None and self.graph.is_fresh(ROBUST_NODE):
            self._apply(out[0])

    def _apply(self, designs: RobustDesigns | None) -> None:
        self.pending = False
        change = robust_changes(designs) if designs is not None else None
        if change is None:
            self._say(designs.verdict() if designs is not None and designs.unbounded else
                      "No coupling satisfies the bound for every device in the parameter box", 8000)
            return
        edits, message = change
        beyond = edits_beyond_limits(edits)
        if beyond is not None:
            self._say(f"Robust design not applied: it is {beyond.text()}", 8000)
            self.update_enabled()
            return
        self.editor.edit_many(edits, "Robust design")
        self._say(message, 8000)

    @Slot(object)
    def _on_invalidated(self, names: object) -> None:
        if ROBUST_NODE in names and self.model.profile.identification is not None:
            self.graph.request(ROBUST_NODE)

    @Slot(str)
    def _on_ready(self, name: str) -> None:
        if name != ROBUST_NODE or not self.graph.is_fresh(ROBUST_NODE):
            return
        designs = self.graph.result(ROBUST_NODE)[0]
        self.update_enabled()
        if self.verdict is not None and hasattr(self.verdict, "update_robust"):
            self.verdict.update_robust(None if designs is None else designs.verdict(),
                                       True if designs is None else designs.holds)
        if self.pending:
            self._apply(designs)
