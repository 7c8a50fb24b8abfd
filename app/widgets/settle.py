"""Geometry fix-ups that settle before the next paint: the one deferral of the tabs' and views' refits.

A refit that reads a laid-out size (a plot's floor from its laid-out axes, a tab body's size from its
labels' wrapped heights, a legend's columns from the plot's width) must wait until the layouts took
the change that asked for it.  Each used to wait for a 0-ms timer of its own: the timer fired in a
later event-loop turn, after Qt had processed the window's UpdateRequest, so every intermediate
geometry was painted (a plot's height went 216 -> 202 -> 44 -> 216 -> 140 -> 210 -> 216 px over
7-15 paints when its tab was shown).

:func:`settle_later` queues a refit instead.  The first request of a turn posts one event, of a
higher priority than the UpdateRequest (which Qt posts with the lowest), to the application's one
:class:`Settler`; it then runs the queued refits and the layouts they invalidated
(``sendPostedEvents(LayoutRequest)``) in rounds until no refit asks for another, all before the
paint.  A layout that Qt takes in the same event-loop pass as the paint (a result's new text shown)
asks for its refits after the paint was posted: the settler also runs before each UpdateRequest of
a window it has refits for, so that the paint shows the settled geometry.  A cascade that has not settled after :data:`MAX_ROUNDS` rounds goes on in the next turn (it
is painted meanwhile), so nothing can loop without end inside one event.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QCoreApplication, QEvent, QObject, Qt
from PySide6.QtWidgets import QWidget
from shiboken6 import Shiboken

__all__ = ["MAX_ROUNDS", "Settler", "settle_later", "settler"]

#: Rounds of refits and layouts run in one event; a cascade still asking after them goes on next turn.
MAX_ROUNDS = 12

_SETTLE = QEvent.Type(QEvent.registerEventType())
_WATCHED = "settlerWatched"
_NAME = "zwidthSettler"  # the settler's object name under the application  # a window's property: the settler filters its UpdateRequests


class Settler(QObject):
    """Runs queued refits (each once per round, however often it was asked for) before the next paint.

    ``events`` and ``rounds`` count the settle events handled and the rounds run (tests, probes).
    """

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._pending: dict[tuple[int, str], tuple[QObject, Callable[[], object]]] = {}
        self._posted = False
        self._running = False
        self.events = 0
        self.rounds = 0

    def request(self, owner: QObject, refit: Callable[[], object]) -> None:
        """Run ``refit`` (a method of ``owner``) once the layouts took the pending changes, before the
        next paint; skipped if ``owner`` is deleted meanwhile."""
        self._pending[(id(owner), getattr(refit, "__name__", repr(refit)))] = (owner, refit)
        self._watch(owner)
        if not (self._running or self._posted):
            self._posted = True
            QCoreApplication.postEvent(self, QEvent(_SETTLE), Qt.EventPriority.HighEventPriority.value)

    def _watch(self, owner: QObject) -> None:
        """Settle before every paint of ``owner``'s window (its UpdateRequest), once per window."""
        widget = owner if isinstance(owner, QWidget) else owner.parent()
        if not isinstance(widget, QWidget):
            return
        window = widget.window()
        if not window.property(_WATCHED):
            window.setProperty(_WATCHED, True)
            window.installEventFilter(self)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        # a layout taken in the same event-loop pass as the paint (a result's new text, a label shown)
        # asks for refits after the paint was already posted: they run first, and it paints once
        if event.type() == QEvent.Type.UpdateRequest and self._pending:
            self.run()
        return False

    def pending(self) -> int:
        """How many refits are queued."""
        return len(self._pending)

    def event(self, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() != _SETTLE:
            return super().event(event)
        self._posted = False
        self.run()
        return True

    def run(self) -> None:
        """The queued refits and the layouts they invalidate, in rounds, until none asks for another."""
        if self._running:
            return
        self._running = True
        self.events += 1
        try:
            for _ in range(MAX_ROUNDS):
                QCoreApplication.sendPostedEvents(None, QEvent.Type.LayoutRequest.value)
                if not self._pending:
                    break
                self.rounds += 1
                queued, self._pending = self._pending, {}
                for owner, refit in queued.values():
                    if Shiboken.isValid(owner):
                        refit()
        finally:
            self._running = False
        if self._pending and not self._posted:  # not settled: the rest in the next turn
            self._posted = True
            QCoreApplication.postEvent(self, QEvent(_SETTLE), Qt.EventPriority.HighEventPriority.value)


def settler() -> Settler:
    """The application's settler: a child of the application object, made on first use (no module
    state: a new application gets its own)."""
    app = QCoreApplication.instance()
    found = app.findChild(Settler, _NAME, Qt.FindChildOption.FindDirectChildrenOnly)
    if found is None:
        found = Settler(app)
        found.setObjectName(_NAME)
    return found


def settle_later(owner: QObject, refit: Callable[[], object]) -> None:
    """Queue ``refit`` (a method of ``owner``) to run before the next paint: :meth:`Settler.request`."""
    settler().request(owner, refit)
