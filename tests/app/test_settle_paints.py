"""A tab's geometry fix-ups settle before the paint (issue 21, s13): :mod:`app.widgets.settle`.

The floors, the tab body's fit, the settings' width and the legend rows used to wait for a 0-ms
timer each, which fired after Qt had painted: every intermediate geometry was painted (a plot of the
Sampled-data tab at 216 -> 202 -> 44 -> 216 px).  These tests count what is painted and when, never
how long anything takes: a cascade of refits is run inside one event, before the window's paint, on
any machine.
"""

from __future__ import annotations

import pytest
from PySide6.QtCore import QEvent, QObject
from PySide6.QtGui import QPaintEvent
from PySide6.QtWidgets import QApplication, QVBoxLayout, QWidget

from app.widgets.settle import MAX_ROUNDS, settle_later, settler


class _Block(QWidget):
    """A widget that records the height it was painted at."""

    def __init__(self) -> None:
        super().__init__()
        self.painted: list[int] = []
        self.setMinimumHeight(50)

    def paintEvent(self, event: QPaintEvent) -> None:  # noqa: N802 - Qt API
        self.painted.append(self.height())


class _Floor(QObject):
    """Refits like the tabs' floors: reads the laid-out height, then sets a minimum from it."""

    def __init__(self, block: _Block, steps: list[int]) -> None:
        super().__init__(block)
        self.block, self.steps, self.calls = block, list(steps), 0
        block.installEventFilter(self)

    def fit(self) -> None:
        self.calls += 1
        if self.steps:
            self.block.setMinimumHeight(self.steps.pop(0))

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() == QEvent.Type.Resize:
            settle_later(self, self.fit)
        return False


@pytest.fixture
def shown(qtbot):
    """A shown window holding one :class:`_Block`, idle."""
    window = QWidget()
    qtbot.addWidget(window)
    block = _Block()
    lay = QVBoxLayout(window)
    lay.addWidget(block)
    lay.addStretch(1)
    window.resize(300, 600)
    window.show()
    qtbot.waitExposed(window)
    qtbot.waitUntil(lambda: bool(block.painted))
    for _ in range(3):
        QApplication.processEvents()
    block.painted.clear()
    return window, block


def test_a_cascade_of_refits_is_painted_once_at_its_end(shown):
    """Each refit's new minimum resizes the block, whose resize asks for the next refit: five
    geometries, of which only the last is painted, and all in one event-loop pass."""
    _window, block = shown
    floor = _Floor(block, [150, 40, 300, 90, 220])
    settle_later(floor, floor.fit)
    QApplication.processEvents()
    assert floor.steps == []  # every step of the cascade ran in that one pass
    assert block.height() >= 220
    assert block.painted, "the window was not painted"
    assert set(block.painted) == {block.height()}, f"intermediate heights painted: {block.painted}"


def test_a_refit_asked_for_with_a_pending_paint_runs_before_it(shown):
    """A paint already posted (the window's UpdateRequest) waits for the refit asked for after it."""
    _window, block = shown
    order: list[str] = []
    owner = QObject(block)

    def refit() -> None:
        order.append("refit")
        block.setMinimumHeight(260)

    original = block.paintEvent
    block.paintEvent = lambda event: (order.append("paint"), original(event))  # type: ignore[method-assign]
    block.update()
    settle_later(owner, refit)
    QApplication.processEvents()
    assert order and order[0] == "refit", order
    assert set(block.painted) == {block.height()} and block.height() >= 260


def test_refits_of_one_owner_are_coalesced_and_a_deleted_owner_is_skipped(shown):
    _window, block = shown
    floor = _Floor(block, [])
    gone = _Floor(block, [500])
    for _ in range(5):
        settle_later(floor, floor.fit)
    settle_later(gone, gone.fit)
    gone.deleteLater()
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete.value)
    QApplication.processEvents()
    assert floor.calls == 1
    assert block.minimumHeight() < 500  # the deleted floor's refit did not run


def test_a_cascade_that_never_settles_goes_on_in_the_next_turn(shown):
    """A refit that always asks again runs :data:`MAX_ROUNDS` times in one event, then the rest is
    left to later turns: the event loop is never held."""
    _window, block = shown
    owner = QObject(block)
    calls = []

    def again() -> None:
        calls.append(1)
        if len(calls) < 3 * MAX_ROUNDS:
            settle_later(owner, again)

    settle_later(owner, again)
    settler().run()  # one settle event's worth
    assert len(calls) == MAX_ROUNDS
    for _ in range(10):
        QApplication.processEvents()
    assert len(calls) == 3 * MAX_ROUNDS
    assert settler().pending() == 0

