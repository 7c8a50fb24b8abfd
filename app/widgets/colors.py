"""Text colours that stay readable in both themes (WCAG AA: contrast >= 4.5:1 on the window colour).

Views and tabs write status colours into rich text (green "stable", red "unstable", orange
warnings) in their light-theme shades; :func:`for_theme` swaps them for the dark theme's.
"""

from __future__ import annotations

import re

__all__ = ["DARK_TEXT", "WARNING_COLORS", "CURSOR_COLORS", "ERROR_STYLE", "for_theme"]

#: Status colours written into rich text (light theme) and their dark-theme variants: each has a
#: contrast of at least 4.5:1 on its theme's window colour.
DARK_TEXT = {"#2b8a3e": "#69db7c", "#c92a2a": "#ff8787", "#d0312d": "#ff8787", "#e67700": "#ffa94d",
             "#c77c02": "#ffc078", "#495057": "#ced4da", "gray": "#adb5bd"}
#: The warning line's colour by theme (light, dark).
WARNING_COLORS = ("#9c5700", "#ffc078")
#: An error message's style: dark red on its own pale box, readable (7:1) in either theme.
ERROR_STYLE = "color: #8b1a1a; background: #ffe3e3; border-radius: 3px; padding: 1px 4px;"
#: The crosshair readout's (muted) colour by theme (light, dark).
CURSOR_COLORS = ("#50565c", "#b4bbc2")


def for_theme(text: str, dark: bool) -> str:
    """Rich text with its status colours (``color:#2b8a3e`` ...) readable on the theme's background."""
    if not dark:
        return text
    return re.sub(r"color:\s*(#[0-9a-fA-F]{6}|gray)",
                  lambda m: f"color:{DARK_TEXT.get(m.group(1).lower(), m.group(1))}", text)
