"""Texts rewritten on every step of a slider drag, shown at a reading pace instead.

During a drag the plots follow every step (60 frames a second), but a number that changes 60
times a second cannot be read, and laying out its rich text (legend labels, summaries) is a good
part of a step's time.  A :class:`TextPacer` shows such texts at once outside a drag; during a
drag it shows them at most every :attr:`TextPacer.interval_ms` (the first step at once, then the
newest text of each key when the interval has passed, and always the last one when the drag pauses
or ends), so the numbers stay live at ten updates a second and end exact.

Why not ``pyqtgraph.SignalProxy(signal, rateLimit=10)``: it delivers every update from a timer,
never in the call, so the first step of a drag and the text at its release arrive a turn of the
event loop to 100 ms late (measured: the release's text 72 ms after it), and outside a drag an
edit's numbers would lag its plots; it also paces one signal's arguments, not texts by key.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from PySide6.QtCore import QObject, QTimer, Slot

__all__ = ["TextPacer"]


class TextPacer(QObject):
    """Applies text updates (callables, by key) at once, or paced while ``active()`` is true."""

    def __init__(self, active: Callable[[], bool], parent: QObject | None = None, interval_ms: int = 100) -> None:
        super().__init__(parent)
        self.active = active
        self.interval_ms = interval_ms
        self.applied = 0  # updates shown (tests)
        self._pending: dict[str, Callable[[], None]] = {}
        self._last = -1e9  # monotonic seconds of the last paced flush
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.timeout.connect(self.flush)

    def show(self, key: str, apply: Callable[[], None]) -> None:
        """Show a text now (no drag), or pace it: ``apply`` replaces a pending update of ``key``."""
        if not self.active():
            self._pending.pop(key, None)
            self._apply(apply)
            return
        self._pending[key] = apply
        wait_ms = self.interval_ms - 1e3 * (time.monotonic() - self._last)
        if wait_ms <= 0:
            self.flush()
        elif not self._timer.isActive():
            self._timer.start(max(1, int(wait_ms)))

    @property
    def pending(self) -> list[str]:
        """The keys whose newest text is not shown yet."""
        return list(self._pending)

    @Slot()
    def flush(self) -> None:
        """Show every pending text now."""
        self._timer.stop()
        self._last = time.monotonic()
        pending, self._pending = self._pending, {}
        for apply in pending.values():
            self._apply(apply)

    def _apply(self, apply: Callable[[], None]) -> None:
        apply()
        self.applied += 1
