"""Application icon and the About box.

``app_icon()`` is the window icon (every size in ``resources/icons``); ``show_about(parent)`` opens
:class:`AboutDialog`: version, the papers implemented and the licenses of the dependencies.
"""

from __future__ import annotations

import html
import importlib
import sys
from importlib import metadata
from pathlib import Path

from app import qt_compat  # noqa: F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import Qt, qVersion
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import QDialog, QDialogButtonBox, QHBoxLayout, QLabel, QVBoxLayout, QWidget

__all__ = [
    "APP_NAME",
    "AboutDialog",
    "DEPENDENCIES",
    "PAPERS",
    "app_icon",
    "app_version",
    "dependency_versions",
    "icon_path",
    "show_about",
]

APP_NAME = "zwidth"
ICON_SIZES = (16, 32, 48, 64, 128, 256, 512)

PAPERS = (
    ("Adams, Moreyra & Hannaford",
     "Stability and Performance of Haptic Displays: Theory and Experiments"),
    ("Eom, Suh & Yi",
     "A Design Method of Haptic Interface Controller Considering Transparency and Robust Stability"),
)

# (label, distribution name, import name for the fallback __version__, license)
DEPENDENCIES = (
    ("NumPy", "numpy", "numpy", "BSD-3-Clause"),
    ("SciPy", "scipy", "scipy", "BSD-3-Clause"),
    ("PySide6 / Qt", "PySide6-Essentials", "PySide6", "LGPL-3.0-only (Qt for Python and Qt)"),
    ("pyqtgraph", "pyqtgraph", "pyqtgraph", "MIT"),
)


def _resource_candidates(*parts: str) -> list[Path]:
    found = []
    try:
        from analysis.resources import resource_path

        found.append(resource_path(*parts))
    except FileNotFoundError:
        pass
    found.append(Path(__file__).resolve().parent.parent.joinpath("resources", *parts))
    frozen = getattr(sys, "_MEIPASS", None)
    if frozen:
        found.append(Path(frozen).joinpath("resources", *parts))
    return found


def icon_path(size: int | None = None) -> Path | None:
    """The icon file: ``zwidth-<size>.png``, or the SVG source for ``size=None``; None if missing."""
    name = "zwidth.svg" if size is None else f"zwidth-{size}.png"
    for path in _resource_candidates("icons", name):
        if path.is_file():
            return path
    return None


_ICON: QIcon | None = None


def app_icon() -> QIcon:
    """The application icon with every bundled PNG size (null QIcon if none is installed)."""
    global _ICON
    if _ICON is None or _ICON.isNull():
        icon = QIcon()
        for size in ICON_SIZES:
            path = icon_path(size)
            if path is not None:
                icon.addFile(str(path))
        _ICON = icon
    return QIcon(_ICON)


def app_version() -> str:
    try:
        return metadata.version(APP_NAME)
    except metadata.PackageNotFoundError:
        return "unknown (not installed)"


def dependency_versions() -> list[tuple[str, str, str]]:
    """``(label, version, license)`` of each runtime dependency, read at run time."""
    rows = []
    for label, dist, module, license_name in DEPENDENCIES:
        try:
            version = metadata.version(dist)
        except metadata.PackageNotFoundError:
            try:
                version = str(getattr(importlib.import_module(module), "__version__", "unknown"))
            except ImportError:
                version = "not installed"
        if dist.startswith("PySide6"):
            version = f"{version} (Qt {qVersion()})"
        rows.append((label, version, license_name))
    return rows


def _about_html() -> str:
    esc = html.escape
    papers = "".join(
        f"<li>{esc(authors)}, &ldquo;{esc(title)}.&rdquo;</li>"
        for authors, title in PAPERS
    )
    deps = "".join(
        f"<tr><td>{esc(label)}&nbsp;&nbsp;</td><td>{esc(version)}&nbsp;&nbsp;</td><td>{esc(lic)}</td></tr>"
        for label, version, lic in dependency_versions()
    )
    python = ".".join(map(str, sys.version_info[:3]))
    return (
        "<p>Design tool for stable haptic interfaces: two-port virtual coupling design and the "
        "Z-width (the range of impedances a haptic display renders stably).</p>"
        f"<p><b>Methods implemented</b></p><ul>{papers}</ul>"
        "<p><b>Open-source components</b></p>"
        f"<table>{deps}<tr><td>Python</td><td>{esc(python)}</td><td>PSF-2.0</td></tr></table>"
        "<p>Qt and PySide6 are used under the GNU LGPL v3; their source is available from "
        "<a href='https://download.qt.io/'>download.qt.io</a>.</p>"
    )


class AboutDialog(QDialog):
    """Icon, name and version, the papers implemented and the dependencies with their licenses."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"About {APP_NAME}")
        self.setWindowIcon(app_icon())
        self.setObjectName("AboutDialog")

        icon_label = QLabel()
        icon_label.setPixmap(app_icon().pixmap(96, 96))
        icon_label.setAlignment(Qt.AlignmentFlag.AlignTop)
        self.icon_label = icon_label

        title = QLabel(f"<h2 style='margin:0'>{APP_NAME}</h2><p style='margin:0'>Version "
                       f"{html.escape(app_version())}</p>")
        title.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.title_label = title

        body = QLabel(_about_html())
        body.setWordWrap(True)
        body.setOpenExternalLinks(True)
        body.setTextInteractionFlags(Qt.TextInteractionFlag.TextBrowserInteraction)
        body.setMinimumWidth(460)
        self.body_label = body

        text = QVBoxLayout()
        text.addWidget(title)
        text.addWidget(body)
        text.addStretch(1)
        top = QHBoxLayout()
        top.addWidget(icon_label)
        top.addSpacing(12)
        top.addLayout(text, 1)

        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)
        buttons.accepted.connect(self.accept)

        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addWidget(buttons)


def show_about(parent: QWidget | None = None) -> int:
    """Open the About box (modal) and return when it is closed."""
    dialog = AboutDialog(parent)
    return dialog.exec()
