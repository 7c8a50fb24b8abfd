"""The colours of both themes, readable at WCAG AA: text 4.5:1 on the window colour, plot text 4.5:1
and curves 3:1 on the plot background (tests/app/test_contrast.py measures them on screen).

Views and tabs write status colours into rich text (green "stable", red "unstable", orange
warnings) in their light-theme shades; :func:`for_theme` swaps them for shades readable on the
theme's window colour.  :data:`PALETTE` holds the plots' colours by theme.
"""

from __future__ import annotations

import re

import numpy as np
from PySide6.QtGui import QPalette

__all__ = ["DARK_TEXT", "WARNING_COLORS", "CURSOR_COLORS", "ERROR_STYLE", "INDICATOR_OUTLINE", "LIGHT_TEXT", "PALETTE", "for_theme", "is_dark",
           "AA_TEXT", "AA_LARGE", "AA_GRAPHICS", "relative_luminance", "contrast_ratio"]

#: WCAG 2.x level AA: normal text, large text (18 pt, or 14 pt bold) and graphics (curves, markers,
#: legend lines, check-box and radio-button indicators) against the colour beside them.
AA_TEXT, AA_LARGE, AA_GRAPHICS = 4.5, 3.0, 3.0

#: Status colours written into rich text (light theme) and their dark-theme variants: each has a
#: contrast of at least 4.5:1 on its theme's window colour.
DARK_TEXT = {"#2b8a3e": "#69db7c", "#c92a2a": "#ff8787", "#d0312d": "#ff8787", "#e67700": "#ffa94d",
             "#c77c02": "#ffc078", "#495057": "#ced4da", "gray": "#adb5bd"}
#: The same status colours on the light theme's window colour (#efefef, Fusion's): the shades that
#: are below 4.5:1 there (the green was 3.8:1, the orange 2.6:1) are written darker.
LIGHT_TEXT = {"#2b8a3e": "#237032", "#e67700": "#a35200", "#c77c02": "#9c5700", "#d0312d": "#c92a2a",
              "gray": "#5c636a"}
#: The plots' colours by theme: text ("fg", "muted": axis text, labels in the plot) 4.5:1 and lines,
#: markers and the measured data ("*_pale", drawn under the fitted model) 3:1 on "bg"; the
#: translucent shadings ("bad", "fill") are bounded by curves and exempt.
PALETTE = {
    "light": {"bg": "#ffffff", "fg": "#222222", "grid": 0.25, "a": "#1f5fbf", "b": "#d9480f", "c": "#2b8a3e",
              "bad": (220, 40, 40, 45), "fill": (31, 95, 191, 45), "mark": "#c92a2a", "muted": "#6c757d",
              "a_pale": (31, 95, 191, 200), "b_pale": (217, 72, 15, 200), "c_pale": (43, 138, 62, 200)},
    "dark": {"bg": "#1e1f22", "fg": "#dddddd", "grid": 0.3, "a": "#74a7ff", "b": "#ff922b", "c": "#69db7c",
             "bad": (255, 80, 80, 60), "fill": (116, 167, 255, 55), "mark": "#ff6b6b", "muted": "#adb5bd",
             "a_pale": (116, 167, 255, 150), "b_pale": (255, 146, 43, 150), "c_pale": (105, 219, 124, 150)},
}
#: The warning line's colour by theme (light, dark).
WARNING_COLORS = ("#9c5700", "#ffc078")
#: An error message's style: dark red on its own pale box, readable (7:1) in either theme.
ERROR_STYLE = "color: #8b1a1a; background: #ffe3e3; border-radius: 3px; padding: 1px 4px;"
#: The crosshair readout's (muted) colour by theme (light, dark).
CURSOR_COLORS = ("#50565c", "#b4bbc2")
#: The outline of check-box and radio-button indicators by theme (light, dark): at least 3:1 on the
#: window and the base (field, table cell) colours, as the indicator is the control (Fusion's own
#: outline is a shade darker than the window: 1.1:1 in the dark theme, 2:1 in the light one).
INDICATOR_OUTLINE = ("#767676", "#8c8f94")


def for_theme(text: str, dark: bool) -> str:
    """Rich text with its status colours (``color:#2b8a3e`` ...) readable on the theme's background."""
    table = DARK_TEXT if dark else LIGHT_TEXT
    return re.sub(r"color:\s*(#[0-9a-fA-F]{6}|gray)",
                  lambda m: f"color:{table.get(m.group(1).lower(), m.group(1))}", text)


def is_dark(palette: QPalette) -> bool:
    """Whether ``palette`` is a dark one (its window colour is dark): for the system theme too."""
    return palette.color(QPalette.ColorRole.Window).lightness() < 128


def relative_luminance(rgb: object) -> np.ndarray:
    """WCAG 2.x relative luminance of sRGB colours (an array ``(..., 3)`` of 0..255)."""
    c = np.asarray(rgb, float) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return lin @ np.array([0.2126, 0.7152, 0.0722])


def contrast_ratio(a: object, b: object) -> np.ndarray:
    """WCAG contrast ratio (1 to 21) of sRGB colours ``a`` and ``b`` (arrays ``(..., 3)`` of 0..255)."""
    la, lb = relative_luminance(a), relative_luminance(b)
    return (np.maximum(la, lb) + 0.05) / (np.minimum(la, lb) + 0.05)
