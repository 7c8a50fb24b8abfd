"""A progress report repaints its bar with the window's next paint, not at once (set_progress)."""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject
from PySide6.QtWidgets import QApplication, QProgressBar, QVBoxLayout, QWidget

from app.widgets.progress_value import set_progress


class Paints(QObject):
    def __init__(self) -> None:
        super().__init__()
        self.count = 0

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:  # noqa: N802 - Qt API
        if event.type() == QEvent.Type.Paint:
            self.count += 1
        return False


def _shown_bar(qtbot) -> tuple[QWidget, QProgressBar, Paints]:
    window = QWidget()
    bar = QProgressBar(window)
    bar.setTextVisible(True)
    QVBoxLayout(window).addWidget(bar)
    window.resize(300, 60)
    window.show()
    qtbot.waitExposed(window)
    QApplication.processEvents()
    paints = Paints()
    bar.installEventFilter(paints)
    return window, bar, paints


def test_a_new_value_is_painted_with_the_next_paint_not_at_once(qtbot):
    window, bar, paints = _shown_bar(qtbot)
    try:
        bar.setRange(0, 100)
        bar.setValue(10)  # Qt's own setter paints the bar inside the call (Qt 6.12): the reason for set_progress
        QApplication.processEvents()
        paints.count = 0
        for done in range(11, 60):
            set_progress(bar, done, 100)
        assert paints.count == 0 and bar.value() == 59 and bar.maximum() == 100
        qtbot.waitUntil(lambda: paints.count >= 1, timeout=5000)  # one coalesced repaint
        assert bar.updatesEnabled()
        set_progress(bar, 0, 0)  # the busy indicator
        assert (bar.minimum(), bar.maximum()) == (0, 0)
    finally:
        window.close()


def test_a_bar_held_by_its_parent_stays_held_and_follows_the_parent(qtbot):
    window, bar, _paints = _shown_bar(qtbot)
    try:
        window.setUpdatesEnabled(False)
        set_progress(bar, 5, 10)
        assert bar.value() == 5 and not bar.updatesEnabled()
        window.setUpdatesEnabled(True)
        assert bar.updatesEnabled()  # not left forced off by set_progress
    finally:
        window.close()
