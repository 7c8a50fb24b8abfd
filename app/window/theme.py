"""The window's theme: light, dark or the system's, with the View → Theme menu.

The palette is set on the application; plot views restyle themselves (``apply_theme(dark)``).
The application's style is wrapped in :class:`ContrastStyle`, which outlines check-box and
radio-button indicators readably (WCAG AA, 3:1) in either theme.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from PySide6.QtCore import QObject, QPointF, QRectF, Qt
from PySide6.QtGui import QAction, QActionGroup, QColor, QPainter, QPalette, QPen
from PySide6.QtWidgets import QApplication, QMenu, QProxyStyle, QStyle, QStyleOption, QWidget

from app.core.settings import THEMES, Settings, resolve_dark
from app.widgets.colors import INDICATOR_OUTLINE, is_dark

__all__ = ["Theme", "dark_palette", "DARK_COLORS", "ContrastStyle", "install_contrast_style"]

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


_PE = QStyle.PrimitiveElement
_CHECKS = (_PE.PE_IndicatorCheckBox, _PE.PE_IndicatorItemViewItemCheck)


class ContrastStyle(QProxyStyle):
    """The application's style, with check-box and radio-button indicators outlined in
    :data:`~app.widgets.colors.INDICATOR_OUTLINE` (3:1 on the window and on a table cell) while
    enabled; a disabled indicator keeps the style's faint outline."""

    def drawPrimitive(self, element: QStyle.PrimitiveElement, option: QStyleOption,  # noqa: N802 - Qt API
                      painter: QPainter, widget: QWidget | None = None) -> None:
        super().drawPrimitive(element, option, painter, widget)
        radio = element == _PE.PE_IndicatorRadioButton
        if not (radio or element in _CHECKS) or not option.state & QStyle.StateFlag.State_Enabled:
            return
        painter.save()
        painter.setRenderHint(QPainter.RenderHint.Antialiasing, True)
        painter.setPen(QPen(QColor(INDICATOR_OUTLINE[1 if is_dark(option.palette) else 0]), 1.0))
        painter.setBrush(Qt.BrushStyle.NoBrush)
        r = QRectF(option.rect)
        if radio:  # Fusion's circle: centred on the rectangle, one pixel inside it
            radius = (r.width() + (int(r.width()) + 1) % 2) / 2.0 - 1
            painter.drawEllipse(r.center() + QPointF(0.5, 0.5), radius, radius)
        else:  # Fusion's square: on the pixel centres of the rectangle's edges
            painter.drawRect(r.adjusted(0.5, 0.5, -0.5, -0.5))
        painter.restore()


def install_contrast_style(app: QApplication) -> None:
    """Wrap the application's style in :class:`ContrastStyle` (once)."""
    if not isinstance(app.style(), ContrastStyle):
        app.setStyle(ContrastStyle(app.style().name()))


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
            install_contrast_style(app)
            app.setPalette(dark_palette(dark))
        for target in self._targets():
            target.apply_theme(dark)
        self.dark = dark
        return dark
