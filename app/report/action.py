"""File → Export Report… in the main window: file dialog, progress dialog, build, message."""

from __future__ import annotations

import os

from app import qt_compat  # noqa: F401 - before any Qt call

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QFileDialog, QMessageBox, QProgressDialog, QWidget

from analysis.errors import ValidationError
from analysis.profiles.io import Profile, bundled_profiles
from analysis.progress import OperationCancelled
from analysis.study import profile_trials, resolve_trials

from app.report import REPORT_FORMATS, build_report, report_format, report_stages

__all__ = ["export_report", "document_path", "document_folder", "trials_problem"]


def document_path(window: object) -> str | None:
    """The file of the window's document, for the report's File row: the file it was opened from or
    saved to, the bundled file of a preset (``window.preset``), ``None`` for a new document."""
    path = getattr(window, "path", None)
    if isinstance(path, str) and path:
        return path
    preset = getattr(window, "preset", None)
    bundled = bundled_profiles().get(preset) if isinstance(preset, str) else None
    return str(bundled) if bundled is not None else None


def document_folder(window: object) -> str | None:
    """The folder a relative path in the window's profile (its ``trials`` file) is read from: that
    of :func:`document_path`, as the command line reads it from the profile's folder; ``None`` for a
    new document (the working directory)."""
    source = document_path(window)
    return os.path.dirname(os.path.abspath(source)) if source else None


def trials_problem(profile: Profile, source: str | None = None) -> str | None:
    """Why the profile's trials file cannot be used, as the command line says it (the file, the
    line and the column of :mod:`analysis.csvtable`, after ``source: $.controller.trials:``), or
    ``None`` when it can (or the profile names none).  ``profile`` has its path resolved already
    (:func:`analysis.study.resolve_trials`)."""
    try:
        profile_trials(profile)
    except ValidationError as err:
        return f"{source or 'profile'}: $.controller.trials: {err}"
    return None


def export_report(window: QWidget, path: str | None = None, page_size: str = "a4") -> bool:
    """Ask for a file (unless ``path``) and write the report of the window's current profile.

    The format comes from the extension (.pdf or .html); progress is shown while it builds.  A
    relative trials path is read from the document's folder (:func:`document_folder`); a trials
    file that cannot be used refuses the export (a message naming the file, the line and the
    column, :func:`trials_problem`) before anything is asked or written.
    """
    source = document_path(window)
    folder = document_folder(window)
    profile: Profile = window.model.profile
    if folder is not None:
        profile = resolve_trials(profile, folder)
    problem = trials_problem(profile, source)
    if problem is not None:
        QMessageBox.warning(window, "Export Report",
                            f"The report was not written: the profile's trials file cannot be used.\n{problem}")
        return False
    if path is None:
        stem = "".join(ch if ch.isalnum() or ch in "-_" else "-" for ch in profile.name).strip("-") or "report"
        path, _ = QFileDialog.getSaveFileName(window, "Export Report", f"{stem}-report.pdf",
                                              ";;".join(REPORT_FORMATS.values()))
        if not path:
            return False
    if report_format(path) is None:
        path += ".pdf"
    dlg = QProgressDialog("Building the report…", "Cancel", 0, 4, window)
    dlg.setWindowTitle("Export Report")
    dlg.setWindowModality(Qt.WindowModality.WindowModal)
    dlg.setMinimumDuration(0)
    dlg.setValue(0)
    stages = report_stages(str(report_format(path)))

    def progress(done: int, total: int) -> None:
        dlg.setMaximum(total)
        dlg.setLabelText(stages[done] + "…")
        dlg.setValue(done)
        QApplication.processEvents()  # the Cancel click arrives here; cancelled() reads it

    try:
        build_report(profile, path, page_size=page_size, source=source, progress=progress, cancelled=dlg.wasCanceled)
    except OperationCancelled:
        return False
    except Exception as err:  # noqa: BLE001 - shown to the user, never a crash of the app
        dlg.close()
        reason = err.strerror if isinstance(err, OSError) and err.strerror else err  # WriteError: the words
        QMessageBox.warning(window, "Export Report", f"Could not write {os.path.basename(path)}:\n{reason}")
        return False
    finally:
        dlg.close()
    status = getattr(window, "statusBar", None)
    if callable(status):
        status().showMessage(f"Report written to {path}", 5000)
    return True
