"""Plots that stand still during a slider drag: the axes keep their range while the drag moves,
and a plot is redrawn only when the results it shows change (a result held back by the drag is
the same object on every step).  Used by the Sampled-data, Transparency and Observer tabs.
"""

from __future__ import annotations

__all__ = ["HeldPlots"]


class HeldPlots:
    """Mixin for an :class:`~app.tabs.base.AnalysisTab`; call :meth:`init_held_plots` in ``build``."""

    def init_held_plots(self) -> None:
        self._drawn: dict[str, object] = {}  # plot -> the result objects it shows
        self._range_held = False  # the axes stand still during a slider drag
        self.ctx.editor.dragChanged.connect(self._on_drag)

    def _changed(self, view: str, *shown: object) -> bool:
        """Whether ``view`` must be redrawn: it shows other result objects than ``shown`` (a held
        result is the same object during a drag: its plots are not redrawn on every step)."""
        old = self._drawn.get(view)
        if old is not None and len(old) == len(shown) and all(
                a is b or (isinstance(a, (str, bool, float)) and a == b) for a, b in zip(old, shown)):
            return False
        self._drawn[view] = shown
        return True

    def apply_theme(self, dark: bool) -> None:
        if self.is_built():
            self._drawn.clear()  # every plot is drawn again in the theme's colours
        super().apply_theme(dark)

    def _hold_ranges(self, hold: bool) -> None:
        """Keep the axes still while a slider is dragged (auto-range again after it)."""
        if hold != self._range_held:
            self._range_held = hold
            for view in self.held_views():
                view.hold_range(hold)

    def held_views(self) -> list:
        """The plots whose axes stand still during a drag (all by default)."""
        return self.plot_views()

    def _on_drag(self, on: bool) -> None:
        if not on:  # the drag ended: the axes follow the data again
            self._hold_ranges(False)
