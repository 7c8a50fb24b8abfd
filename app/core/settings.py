"""Preferences kept with QSettings: window geometry, last directory, theme, recent files."""

from __future__ import annotations

import os

from PySide6.QtCore import QByteArray, QObject, QSettings, Qt, Signal
from PySide6.QtGui import QGuiApplication

__all__ = ["Settings", "THEMES", "MAX_RECENT"]

THEMES = ("system", "light", "dark")
MAX_RECENT = 10


class Settings(QObject):
    """Typed access to the application's QSettings (the default QSettings unless one is given)."""

    themeChanged = Signal(str)

    def __init__(self, qsettings: QSettings | None = None, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._s = qsettings if qsettings is not None else QSettings()

    @property
    def qsettings(self) -> QSettings:
        return self._s

    def sync(self) -> None:
        self._s.sync()

    # -- geometry ---------------------------------------------------------------------------------
    def geometry(self) -> QByteArray | None:
        value = self._s.value("window/geometry")
        return value if isinstance(value, QByteArray) and not value.isEmpty() else None

    def set_geometry(self, data: QByteArray) -> None:
        self._s.setValue("window/geometry", data)

    def window_state(self) -> QByteArray | None:
        value = self._s.value("window/state")
        return value if isinstance(value, QByteArray) and not value.isEmpty() else None

    def set_window_state(self, data: QByteArray) -> None:
        self._s.setValue("window/state", data)

    # -- files ------------------------------------------------------------------------------------
    def last_directory(self) -> str:
        value = self._s.value("files/last_directory", "")
        return str(value) if value and os.path.isdir(str(value)) else os.path.expanduser("~")

    def set_last_directory(self, path: str) -> None:
        self._s.setValue("files/last_directory", path)

    def recent_files(self) -> list[str]:
        """Recent profiles, newest first, with missing files pruned."""
        value = self._s.value("files/recent", [])
        if isinstance(value, str):
            value = [value]
        files = [str(v) for v in (value or []) if v]
        kept = [f for f in files if os.path.isfile(f)][:MAX_RECENT]
        if kept != files:
            self._s.setValue("files/recent", kept)
        return kept

    def add_recent_file(self, path: str) -> None:
        path = os.path.abspath(path)
        files = [f for f in self.recent_files() if os.path.abspath(f) != path]
        self._s.setValue("files/recent", [path, *files][:MAX_RECENT])

    def clear_recent_files(self) -> None:
        self._s.setValue("files/recent", [])

    # -- appearance -----------------------------------------------------------------------------
    def theme(self) -> str:
        value = str(self._s.value("appearance/theme", "system"))
        return value if value in THEMES else "system"

    def set_theme(self, theme: str) -> None:
        if theme not in THEMES:
            raise ValueError(f"theme must be one of {THEMES}")
        self._s.setValue("appearance/theme", theme)
        self.themeChanged.emit(theme)

    def log_y(self) -> bool:
        return str(self._s.value("plots/stability_log_y", "false")).lower() == "true"

    def set_log_y(self, on: bool) -> None:
        self._s.setValue("plots/stability_log_y", "true" if on else "false")

    def stability_view(self) -> str:
        """The stability plot's view mode ("ratio", "values" or "log"); "ratio" unless chosen."""
        value = str(self._s.value("plots/stability_view", ""))
        return value or ("log" if self.log_y() else "ratio")

    def set_stability_view(self, mode: str) -> None:
        self._s.setValue("plots/stability_view", mode)


def resolve_dark(theme: str) -> bool:
    """Whether ``theme`` means dark colours now (``system`` follows QStyleHints.colorScheme())."""
    if theme == "dark":
        return True
    if theme == "light":
        return False
    app = QGuiApplication.instance()
    if app is None:
        return False
    return QGuiApplication.styleHints().colorScheme() == Qt.ColorScheme.Dark
