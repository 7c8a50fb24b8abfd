"""File → Export: a plot view as PNG (asks the width), SVG or CSV, through a file dialog.

An export computes what it shows first: a plot on a tab that was never opened (or is stale) is
brought up to date -- its tab pulls its graph nodes, the asynchronous ones on the worker behind a
progress dialog -- and an export that still has nothing to show is refused with the reason,
never written as an empty file.
"""

from __future__ import annotations

import os
import re
import unicodedata
from typing import Any

from PySide6.QtCore import QEventLoop, Qt, QTimer
from PySide6.QtWidgets import QFileDialog, QInputDialog, QMainWindow, QMessageBox, QProgressDialog

from app.core.settings import Settings
from app.views import export
from app.views.base import PlotView
from app.window.menus import plain_title, tab_export_entries

__all__ = ["export_view", "default_export_name", "file_stem", "bring_up_to_date", "has_content"]

_WRITERS = {"png": None, "svg": export.export_svg, "csv": export.export_csv}


#: Letters and signs of plot titles that NFKD leaves non-ASCII, spelled for a file name.
_ASCII = {"α": "alpha", "β": "beta", "γ": "gamma", "δ": "delta", "Δ": "Delta", "ζ": "zeta", "η": "eta",
          "θ": "theta", "λ": "lambda", "μ": "mu", "π": "pi", "ρ": "rho", "σ": "sigma", "τ": "tau",
          "φ": "phi", "ω": "omega", "Ω": "Omega", "∞": "inf", "‖": "", "–": "-", "—": "-", "−": "-",
          "×": "x", "·": "_"}
#: Names Windows reserves whatever the extension.
_RESERVED = {"CON", "PRN", "AUX", "NUL", *(f"COM{i}" for i in range(10)), *(f"LPT{i}" for i in range(10))}


def file_stem(title: str, max_length: int = 120) -> str:
    """A title (rich text allowed) as a file stem valid on Linux, Windows and macOS.

    ``J(B<sub>c</sub>), eq. 11 (Fig. 8)`` -> ``j_b_c_eq_11_fig_8``: tags stripped and entities
    decoded (:func:`app.window.menus.plain_title`), Greek letters spelled, sub- and superscripts
    as plain digits (NFKD), lower case (unique also on case-insensitive file systems), only
    ``[a-z0-9._-]`` kept, runs of separators one underscore, never a leading or trailing dot.
    """
    text = "".join(_ASCII.get(ch, ch) for ch in plain_title(title))
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii").lower()
    text = re.sub(r"(?<![0-9])\.|\.(?![0-9])", "_", text)  # a dot only inside a number
    text = re.sub(r"[^a-z0-9._-]+", "_", text)
    text = re.sub(r"_*-_*", "-", re.sub(r"_+", "_", text)).strip("._-")[:max_length].strip("._-")
    if not text:
        return "plot"
    return text + "_" if text.split(".")[0].upper() in _RESERVED else text


def default_export_name(view: PlotView, fmt: str, window: Any = None) -> str:
    """``stability_and_z-width-impedance_range_z-width.png``: the tab's and the plot's titles as
    one safe file stem (:func:`file_stem`), so no two plots of the window share a default name
    (two plots of one tab with one title are told apart as the export menu does)."""
    tab = _tab_of(window, view)
    if tab is not None:
        name = next(n for n, v in tab_export_entries(tab) if v is view)
        return f"{file_stem(tab.title)}-{file_stem(name)}.{fmt}"
    return f"{file_stem(view.title)}.{fmt}"


def has_content(view: PlotView) -> bool:
    """Whether an export of ``view`` has something to say: data, or a note why there is none."""
    return bool(view.export_notes()) or any(len(s.x) for s in view.export_series())


def _pending(window: Any, tab: Any) -> list[str]:
    """The tab's asynchronous nodes without a fresh value that an export computes and waits for.

    Not the nodes that run only when the user asks (a tab's ``on_demand_nodes``: the
    identification fit runs when Fit is pressed, on the measurements loaded): requesting one
    would compute nothing, and waiting for it would never end.
    """
    graph = window.graph
    skip = getattr(tab, "on_demand_nodes", frozenset())
    return [n for n in sorted(tab.nodes) if n in graph and n not in skip and graph.node(n).asynchronous
            and not graph.is_fresh(n)]


def _tab_of(window: Any, view: PlotView) -> Any:
    """The built tab that shows ``view`` (None if none: the tabs not built yet are not searched)."""
    return next((t for t in getattr(window, "analysis_tabs", []) if t.is_built() and view in t.views()), None)


def _wait_for(window: Any, names: list[str], title: str) -> str | None:
    """Run the nodes ``names`` on the worker and wait (progress dialog, Cancel); the reason if not done."""
    graph = window.graph
    failures: dict[str, str] = {}
    dialog = QProgressDialog(f"Computing “{title}” for the export…", "Cancel", 0, 0, window)
    dialog.setWindowTitle("Export")
    dialog.setWindowModality(Qt.WindowModality.WindowModal)
    dialog.setMinimumDuration(300)
    loop = QEventLoop()

    def check(*_args: object) -> None:
        # a node neither fresh nor computing any more (dropped, superseded) would never arrive
        if dialog.wasCanceled() or failures or all(graph.is_fresh(n) or not graph.runner.is_running(n)
                                                   for n in names):
            loop.quit()

    def failed(name: str, message: str) -> None:
        if name in names:
            failures[name] = message
        check()

    for name in names:
        graph.request(name)
    connections = [(graph.ready, check), (graph.failed, failed), (graph.cancelled, check), (dialog.canceled, check)]
    for signal, slot in connections:
        signal.connect(slot)
    poll = QTimer(dialog)  # a job dropped without a signal still ends the wait
    poll.timeout.connect(check)
    poll.start(250)
    QTimer.singleShot(0, check)
    try:
        loop.exec()
    finally:
        poll.stop()
        for signal, slot in connections:
            signal.disconnect(slot)
        cancelled = dialog.wasCanceled()
        dialog.hide()  # not close(): QProgressDialog's close event counts as Cancel
        dialog.deleteLater()
    if failures:
        return "; ".join(f"{n} failed: {m}" for n, m in failures.items())
    if cancelled:
        return "cancelled while computing"
    stopped = [n for n in names if not graph.is_fresh(n)]
    return f"{', '.join(stopped)} stopped before it finished" if stopped else None


def bring_up_to_date(window: Any, view: PlotView) -> str | None:
    """Compute what ``view`` shows (its tab's graph nodes) and refresh its tab; the reason if it cannot."""
    tab = _tab_of(window, view)  # a view exists only once its tab is built
    if tab is None:
        return None
    pending = _pending(window, tab)
    if tab.stale or pending:
        tab.refresh()  # sets the tab's node parameters (e.g. the map's axes) and pulls the nodes
        pending = _pending(window, tab)
        if pending:
            reason = _wait_for(window, pending, plain_title(view.title.split(":")[0]))
            if reason:
                return reason
        tab.refresh()
    return None


def export_view(window: QMainWindow, settings: Settings, view: PlotView, fmt: str, path: str | None = None,
                width: int | None = None) -> bool:
    """Export ``view``; asks for the file (and the PNG width) unless given.  False if cancelled or failed.

    The view is brought up to date first; an export with nothing to show is refused (a message box).
    """
    if fmt not in _WRITERS:
        raise ValueError(f"unknown export format {fmt!r}")
    reason = bring_up_to_date(window, view)
    if reason is None and not has_content(view):  # at once: nothing is computing that would fill it
        tab = _tab_of(window, view)
        hint = getattr(tab, "export_hint", "")
        reason = f"nothing to export yet: {hint}" if hint else "nothing to export yet: the plot has no data"
    if reason is not None:
        name = plain_title(view.title.split(":")[0])
        QMessageBox.warning(window, "Nothing exported", f"{name} was not exported: {reason}.")
        return False
    if path is None:
        start = os.path.join(settings.last_directory(), default_export_name(view, fmt, window))
        path, _ = QFileDialog.getSaveFileName(window, f"Export {fmt.upper()}", start, export.FORMATS[fmt])
        if not path:
            return False
    if fmt == "png" and width is None:
        w0 = view.plot_widget.viewport().width() * 2
        width, ok = QInputDialog.getInt(window, "PNG resolution", "Width in pixels:", w0, 16, 20000, 100)
        if not ok:
            return False
    try:
        if fmt == "png":
            export.export_png(view, path, int(width or 1600))
        else:
            _WRITERS[fmt](view, path)
    except OSError as exc:
        QMessageBox.critical(window, "Export failed", str(exc))
        return False
    settings.set_last_directory(os.path.dirname(os.path.abspath(path)))
    window.statusBar().showMessage(f"Exported {path}", 5000)
    return True
