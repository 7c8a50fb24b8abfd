"""What a tab does when one of its background nodes is cancelled or fails, and how it runs it again.

The tab keeps the graph key of a cancelled or failed node (its result is *held*: the last good one
stays on the plot and nothing restarts it until the user says so) and the failure message.
Used by the Sampled-data, Z-width, Renderable-space and Workspace tabs.
"""

from __future__ import annotations

from typing import Any

__all__ = ["AsyncJobs"]


class AsyncJobs:
    """Mixin for an :class:`~app.tabs.base.AnalysisTab` with ``job_titles`` (node -> title),
    ``progress`` (node -> NodeProgress), ``_held`` and ``_errors`` dicts."""

    job_titles: dict[str, str]

    def on_job_cancelled(self, name: str) -> None:
        if name in self.job_titles:
            self._held[name] = self.ctx.graph.key_of(name)
            if self.isVisible():
                self.refresh()

    def on_job_failed(self, name: str, message: str) -> None:
        if name in self.job_titles:
            self._held[name] = self.ctx.graph.key_of(name)
            self._errors[name] = f"{self.job_titles[name]} failed: {message}"
            if self.isVisible():
                self.refresh()

    def run_again(self, name: str) -> None:
        """Restart a cancelled (or failed) computation."""
        self._held.pop(name, None)
        self._errors.pop(name, None)
        self.progress[name].hide()
        if self.isVisible():
            self.refresh()
        else:
            self.stale = True

    def pull(self, name: str) -> Any:
        """Request ``name`` unless the user cancelled it (or it failed) for the same inputs: then its
        held result; new inputs release the hold."""
        g = self.ctx.graph
        held = self._held.get(name)
        if held is not None:
            if held == g.key_of(name):
                return g.result(name)
            del self._held[name]
            self._errors.pop(name, None)
        return g.request(name)

    def busy(self, name: str) -> bool:
        """Whether ``name`` is computing for the current inputs (not fresh, and not held)."""
        return not self.ctx.graph.is_fresh(name) and name not in self._held
