"""File → Export: a plot view as PNG (asks the width), SVG or CSV, through a file dialog."""

from __future__ import annotations

import os

from PySide6.QtWidgets import QFileDialog, QInputDialog, QMainWindow, QMessageBox

from app.core.settings import Settings
from app.views import export
from app.views.base import PlotView

__all__ = ["export_view", "default_export_name"]

_WRITERS = {"png": None, "svg": export.export_svg, "csv": export.export_csv}


def default_export_name(view: PlotView, fmt: str) -> str:
    """``stability_plot.png`` from the view's title (the part before a colon)."""
    base = view.title.split(":")[0].strip().lower().replace(" ", "_").replace("(", "").replace(")", "")
    return f"{base}.{fmt}"


def export_view(window: QMainWindow, settings: Settings, view: PlotView, fmt: str, path: str | None = None,
                width: int | None = None) -> bool:
    """Export ``view``; asks for the file (and the PNG width) unless given.  False if cancelled or failed."""
    if fmt not in _WRITERS:
        raise ValueError(f"unknown export format {fmt!r}")
    if path is None:
        start = os.path.join(settings.last_directory(), default_export_name(view, fmt))
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
