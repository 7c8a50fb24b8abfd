"""The window's document: the profile file (or preset) it shows, open, save, recent files, drops.

:class:`Documents` owns the file path and the preset name, keeps the window title
(``name[*] — zwidth``) and asks before unsaved changes are lost.  Loading replaces the model's
profile and clears the undo stack; saving writes atomically (:func:`analysis.profiles.save_profile`).
The document's folder (:attr:`Documents.folder`) is where a relative path in the profile (its
trials file) is read from, by the compute graph (:func:`app.core.nodes_zwidth.set_trials_folder`)
and the report (:func:`app.report.action.document_folder`), as the command line reads it.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QObject, Slot
from PySide6.QtGui import QDropEvent, QUndoStack
from PySide6.QtWidgets import QFileDialog, QMainWindow, QMenu, QMessageBox

from analysis.profiles import (
    Profile,
    ProfileError,
    WriteError,
    atomic_write,
    bundled_profiles,
    load_profile,
    save_profile,
)

from app.core.compute_graph import ComputeGraph
from app.core.model import ProfileModel
from app.core.nodes_zwidth import set_trials_folder
from app.core.settings import Settings
from app.core.worker import TaskRunner
from app.report.action import document_folder

__all__ = ["Documents", "default_profile", "is_bundled", "write_atomically", "dropped_files", "APP_NAME",
           "PROFILE_FILTER"]

APP_NAME = "zwidth"
PROFILE_FILTER = "zwidth profiles (*.json);;All files (*)"


def default_profile() -> Profile:
    """The profile a new document starts from (the bundled HBFD preset)."""
    presets = bundled_profiles()
    return load_profile(presets.get("hbfd") or next(iter(presets.values())))


def is_bundled(path: str | os.PathLike) -> bool:
    """Whether ``path`` is one of the bundled preset files."""
    real = os.path.realpath(path)
    return any(os.path.realpath(p) == real for p in bundled_profiles().values())


def write_atomically(path: str, data: bytes) -> str | None:
    """Write ``data`` to ``path`` with :func:`analysis.profiles.atomic_write`; returns the reason on
    failure, in words (``"No such folder: …"``), or ``None``."""
    try:
        atomic_write(path, data)
    except WriteError as err:
        return err.strerror
    return None


def dropped_files(event: QDropEvent) -> list[str]:
    """The local files of a drag or drop event."""
    mime = event.mimeData()
    return [u.toLocalFile() for u in mime.urls() if u.isLocalFile()] if mime.hasUrls() else []


class Documents(QObject):
    """Open, save, presets and recent files of ``window``; ``ask()`` is the unsaved-changes question."""

    def __init__(self, window: QMainWindow, model: ProfileModel, stack: QUndoStack, settings: Settings,
                 runner: TaskRunner, ask: Callable[[], bool], preset: str | None) -> None:
        super().__init__(window)
        self.window, self.model, self.stack, self.settings, self.runner = window, model, stack, settings, runner
        self._ask = ask
        self.path: str | None = None
        self.preset = preset

    @property
    def folder(self) -> str | None:
        """The folder a relative trials path is read from: the document file's (a preset's bundled
        file's), ``None`` for a new document (the working directory)."""
        return document_folder(self)

    def _sync_folder(self) -> None:
        """Tell the window's compute graph where a relative trials path is read from now."""
        graph = getattr(self.window, "graph", None)
        if isinstance(graph, ComputeGraph):
            set_trials_folder(graph, self.folder)

    def _status(self, message: str) -> None:
        self.window.statusBar().showMessage(message, 5000)

    def update_title(self, *_args: object) -> None:
        if self.path:
            name = os.path.basename(self.path)
        elif self.preset:
            name = f"{self.model.profile.name} (preset)"
        else:
            name = "Untitled"
        self.window.setWindowTitle(f"{name}[*] — {APP_NAME}")
        self.window.setWindowModified(not self.stack.isClean())

    def is_modified(self) -> bool:
        return not self.stack.isClean()

    def maybe_save(self) -> bool:
        """Ask before unsaved changes are lost; False means the user cancelled."""
        if not self.is_modified():
            return True
        buttons = QMessageBox.StandardButton
        answer = QMessageBox.question(self.window, "Unsaved changes",
                                      "The profile has unsaved changes.  Save them first?",
                                      buttons.Save | buttons.Discard | buttons.Cancel, buttons.Save)
        if answer == buttons.Save:
            return self.save()
        return answer == buttons.Discard

    def load(self, profile: Profile, path: str | None, preset: str | None) -> None:
        """Show ``profile`` as a fresh, unmodified document."""
        self.runner.cancel_all()
        self.path, self.preset = path, preset
        self._sync_folder()  # before the profile: its views then read the trials from its folder
        self.model.replace_profile(profile)
        self.stack.clear()
        self.stack.setClean()
        self.update_title()

    def new_profile(self) -> bool:
        if not self._ask():
            return False
        self.load(default_profile().replace(name="Untitled"), None, None)
        return True

    def open_path(self, path: str, ask: bool = True) -> bool:
        """Open a profile file; a bad file is refused and the current profile stays."""
        if ask and not self._ask():
            return False
        try:
            profile = load_profile(path)
        except ProfileError as err:
            QMessageBox.critical(self.window, "Cannot open profile", str(err))
            return False
        if is_bundled(path):
            self.load(profile, None, Path(path).stem)
        else:
            self.load(profile, os.path.abspath(path), None)
            self._remember(path)
        self._status(f"Opened {path}")
        return True

    def load_preset(self, name: str) -> bool:
        presets = bundled_profiles()
        if name not in presets:
            raise KeyError(name)
        if not self._ask():
            return False
        try:
            profile = load_profile(presets[name])
        except ProfileError as err:
            QMessageBox.critical(self.window, "Cannot open preset", str(err))
            return False
        self.load(profile, None, name)
        return True

    def open_dialog(self) -> None:
        if not self._ask():
            return
        path, _ = QFileDialog.getOpenFileName(self.window, "Open profile", self.settings.last_directory(),
                                              PROFILE_FILTER)
        if path:
            self.open_path(path, ask=False)

    def fill_recent_menu(self, menu: QMenu) -> None:
        """The recent files (missing ones pruned by the settings), or "(none)"."""
        menu.clear()
        files = self.settings.recent_files()
        for f in files:
            act = menu.addAction(os.path.basename(f).replace("&", "&&"))
            act.setToolTip(f)
            act.setStatusTip(f)
            act.triggered.connect(lambda _=False, p=f: self.open_path(p))
        if not files:
            menu.addAction("(none)").setEnabled(False)
        else:
            menu.addSeparator()
            menu.addAction("Clear list", self.settings.clear_recent_files)

    def _remember(self, path: str) -> None:
        self.settings.add_recent_file(path)
        self.settings.set_last_directory(os.path.dirname(os.path.abspath(path)))

    def save_to(self, path: str) -> bool:
        """Write the profile atomically (:func:`analysis.profiles.save_profile`); on failure say
        why and keep the edits."""
        try:
            save_profile(self.model.profile, path)
        except ProfileError as err:
            QMessageBox.critical(self.window, "Cannot save profile", f"{err}\n\nYour changes are kept.")
            return False
        self.path, self.preset = os.path.abspath(path), None
        self._sync_folder()  # saved elsewhere: a relative trials path is read as the saved file reads it
        self.stack.setClean()
        self._remember(path)
        self.update_title()
        self._status(f"Saved {path}")
        return True

    @Slot()
    def save(self) -> bool:
        if self.path is None:
            return self.save_as()
        return self.save_to(self.path)

    @Slot()
    def save_as(self) -> bool:
        start = os.path.join(self.settings.last_directory(), (self.preset or "profile") + ".json")
        path, _ = QFileDialog.getSaveFileName(self.window, "Save profile", start, PROFILE_FILTER)
        if not path:
            return False
        if not path.lower().endswith(".json"):
            path += ".json"
        return self.save_to(path)
