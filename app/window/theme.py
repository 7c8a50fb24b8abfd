"""The window's theme: light, dark or the system's, with the View → Theme menu.

The palette is set on the application; plot views restyle themselves (``apply_theme(dark)``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from PySide6.QtCore import QObject
from PySide6.QtGui import QAction, QActionGroup, QColor, QPalette
from PySide6.QtWidgets import QApplication, QMenu

from app.core.settings import THEMES, Settings, resolve_dark

__all__ = ["Theme", "dark_palette", "DARK_COLORS"]

#: The dark palette's colours by role.
DARK_COLORS: dict[QPalette.ColorRole, str] = {
    QPalette.ColorRole.Window: "#2b2d30",
    QPalette.ColorRole.WindowText: "#dfe1e5",
    QPalette.ColorRole.Base: "#1e1f22",
    QPalette.ColorRole.AlternateBase: "#2b2d30",
    QPalette.ColorRole.ToolTipBase: "#3c3f41",
    QPalette.ColorRole.ToolTipText: "#dfe1e5",
    QPalette.ColorRole.Text: "#dfe1e5",
    QPalette.ColorRole.Button: "#3c3f41",
    QPalette.ColorRole.ButtonText: "#dfe1e5",
    QPalette.ColorRole.BrightText: "#ff6b6b",
    QPalette.ColorRole.Highlight: "#3574f0",
    QPalette.ColorRole.HighlightedText: "#ffffff",
    QPalette.ColorRole.Mid: "#8c8f94",
    QPalette.ColorRole.PlaceholderText: "#8c8f94",
}
_DISABLED = "#6f737a"


def dark_palette(dark: bool) -> QPalette:
    """The style's standard palette, or its dark variant."""
    app = QApplication.instance()
    base = app.style().standardPalette() if isinstance(app, QApplication) else QPalette()
    if not dark:
        return base
    p = QPalette(base)
    for role, color in DARK_COLORS.items():
        p.setColor(role, QColor(color))
    for role in (QPalette.ColorRole.Text, QPalette.ColorRole.ButtonText, QPalette.ColorRole.WindowText):
        p.setColor(QPalette.ColorGroup.Disabled, role, QColor(_DISABLED))
    return p


class Theme(QObject):
    """Applies the stored theme to the application and to ``targets`` (objects with ``apply_theme(dark)``)."""

    def __init__(self, settings: Settings, targets: Callable[[], Iterable[object]],
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.settings = settings
        self._targets = targets
        self.dark = False
        self.actions: dict[str, QAction] = {}

    def fill_menu(self, menu: QMenu) -> None:
        """One checkable action per theme (light, dark, system)."""
        group = QActionGroup(menu)
        for name in THEMES:
            act = menu.addAction(name.capitalize())
            act.setCheckable(True)
            act.setChecked(name == self.settings.theme())
            group.addAction(act)
            act.triggered.connect(lambda _=False, n=name: self.set_theme(n))
            self.actions[name] = act

    def set_theme(self, theme: str) -> None:
        """Store ``theme`` and apply it."""
        self.settings.set_theme(theme)
        if theme in self.actions:
            self.actions[theme].setChecked(True)
        self.apply()

    def apply(self) -> bool:
        """Apply the stored theme; returns whether it is dark."""
        dark = resolve_dark(self.settings.theme())
        app = QApplication.instance()
        if isinstance(app, QApplication):
            app.setPalette(dark_palette(dark))
        for target in self._targets():
            target.apply_theme(dark)
        self.dark = dark
        return dark
