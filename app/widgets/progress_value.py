"""A progress bar's new value without Qt's synchronous repaint (the one setter of both progress widgets).

``QProgressBar.setValue`` repaints the bar at once (``repaint()``, not ``update()``) whenever its text
or its chunk changes: the window's backing store is flushed there and then, outside the event loop's
coalesced paint, for every report of a running job.  :func:`set_progress` sets the range and the value
with the bar's updates held, then asks for one ordinary repaint, painted with the window's next paint.
"""

from __future__ import annotations

from PySide6.QtWidgets import QProgressBar

__all__ = ["set_progress"]


def set_progress(bar: QProgressBar, done: int, maximum: int) -> None:
    """Show ``done`` of ``maximum`` (``maximum`` 0: the busy indicator) on ``bar``, painted with the
    next paint of its window rather than at once."""
    held = bar.updatesEnabled()  # off already when a parent holds them: nothing is painted now either
    if held:
        bar.setUpdatesEnabled(False)  # QWidget.repaint() does nothing while updates are off
    try:
        bar.setRange(0, maximum)
        bar.setValue(done)
    finally:
        if held:
            bar.setUpdatesEnabled(True)  # back on: one update() of the whole bar, coalesced
