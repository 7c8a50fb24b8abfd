"""Can the GUI start here?  Checked before Qt creates its ``QApplication``.

Qt aborts the process (SIGABRT, exit code 134) when its platform plugin cannot load.  With no
display it falls back to X11 (``xcb``) and the message names whatever library the xcb plugin
missed first ("xcb-cursor0 ... is needed"), not the real problem.  :func:`gui_problem` finds the
two usual causes first -- no display at all, or missing X11 client libraries of Qt's ``xcb``
plugin -- so that ``zwidth`` can exit 1 with a message that says what is missing, and which
commands work without a display.  Never imports Qt.
"""

from __future__ import annotations

import ctypes
import os
import sys
from collections.abc import Callable, Mapping, Sequence

__all__ = ["WINDOWLESS_PLATFORMS", "XCB_LIBRARIES", "HEADLESS_COMMANDS", "missing_libraries", "gui_problem"]

#: Qt platform plugins that need no window system (no DISPLAY / WAYLAND_DISPLAY).
WINDOWLESS_PLATFORMS = frozenset({"offscreen", "minimal", "minimalegl", "vnc", "linuxfb", "eglfs",
                                  "vkkhrdisplay"})

#: The X11 client libraries Qt 6's ``xcb`` platform plugin links (soname, Debian/Ubuntu package);
#: packaging/system-deps.sh checks the same list.
XCB_LIBRARIES: tuple[tuple[str, str], ...] = (
    ("libxcb.so.1", "libxcb1"),
    ("libX11-xcb.so.1", "libx11-xcb1"),
    ("libxcb-cursor.so.0", "libxcb-cursor0"),
    ("libxcb-icccm.so.4", "libxcb-icccm4"),
    ("libxcb-image.so.0", "libxcb-image0"),
    ("libxcb-keysyms.so.1", "libxcb-keysyms1"),
    ("libxcb-randr.so.0", "libxcb-randr0"),
    ("libxcb-render.so.0", "libxcb-render0"),
    ("libxcb-render-util.so.0", "libxcb-render-util0"),
    ("libxcb-shape.so.0", "libxcb-shape0"),
    ("libxcb-shm.so.0", "libxcb-shm0"),
    ("libxcb-sync.so.1", "libxcb-sync1"),
    ("libxcb-util.so.1", "libxcb-util1"),
    ("libxcb-xfixes.so.0", "libxcb-xfixes0"),
    ("libxcb-xkb.so.1", "libxcb-xkb1"),
    ("libxkbcommon-x11.so.0", "libxkbcommon-x11-0"),
)

HEADLESS_COMMANDS = ("Without a display, use the commands that need none:\n"
                     "  zwidth analyze PROFILE.json                      the analysis summary\n"
                     "  zwidth report PROFILE.json -o report.pdf         the full report (PDF or HTML)\n"
                     "  zwidth export-plot PROFILE.json --plot chart -o chart.png   one plot (PNG, SVG or CSV)")


def _loads(soname: str) -> bool:
    """Whether the dynamic loader finds ``soname`` (the same search Qt's plugin loader does)."""
    try:
        ctypes.CDLL(soname)
    except OSError:
        return False
    return True


def missing_libraries(libraries: Sequence[tuple[str, str]] = XCB_LIBRARIES,
                      loads: Callable[[str], bool] = _loads) -> list[tuple[str, str]]:
    """The ``(soname, package)`` pairs of ``libraries`` that the dynamic loader cannot find."""
    return [(soname, package) for soname, package in libraries if not loads(soname)]


def _platforms(value: str) -> list[str]:
    """Plugin names of a ``QT_QPA_PLATFORM`` value (``"wayland;xcb"``, ``"offscreen:fontengine=..."``)."""
    return [p.split(":", 1)[0].strip().lower() for p in value.split(";") if p.strip()]


def _no_display(environ: Mapping[str, str]) -> str:
    chosen = environ.get("QT_QPA_PLATFORM", "")
    if environ.get("DISPLAY") or environ.get("WAYLAND_DISPLAY"):
        what = f"QT_QPA_PLATFORM={chosen} needs a display of its kind, and that one is not set"
    else:
        what = "neither DISPLAY nor WAYLAND_DISPLAY is set"
    return (f"cannot start the GUI: there is no display ({what}).\n"
            "Run zwidth in a desktop session, with ssh -X, or under xvfb-run.\n" + HEADLESS_COMMANDS)


def _xcb_problem(missing: list[tuple[str, str]]) -> str:
    names = ", ".join(soname for soname, _ in missing)
    packages = " ".join(dict.fromkeys(package for _, package in missing))
    return (f"cannot start the GUI: Qt's X11 platform plugin (xcb) needs {names}, which "
            f"{'is' if len(missing) == 1 else 'are'} not installed.\n"
            f"Install with: sudo apt-get install -y {packages}   (or run packaging/system-deps.sh)\n"
            + HEADLESS_COMMANDS)


def gui_problem(environ: Mapping[str, str] | None = None, platform: str | None = None,
                missing: Callable[[], list[tuple[str, str]]] = missing_libraries) -> str | None:
    """Why Qt's GUI cannot start in this environment, or ``None`` when it should.

    Linux only (other systems always have their one platform plugin).  ``QT_QPA_PLATFORM`` set to a
    plugin without a window system (:data:`WINDOWLESS_PLATFORMS`) is always fine.  Otherwise a
    display is needed: ``WAYLAND_DISPLAY`` for Wayland, ``DISPLAY`` for X11, and for X11 the
    client libraries of :data:`XCB_LIBRARIES` (``missing()`` lists those not found).  Another
    plugin named in ``QT_QPA_PLATFORM`` (eglfs, ...) is left to Qt.
    """
    env = os.environ if environ is None else environ
    if not (sys.platform if platform is None else platform).startswith("linux"):
        return None
    chosen = _platforms(env.get("QT_QPA_PLATFORM", ""))
    if any(p in WINDOWLESS_PLATFORMS for p in chosen):
        return None
    if chosen and not any(p == "xcb" or p.startswith("wayland") for p in chosen):
        return None  # a plugin this check does not know: Qt reports its own problems
    if env.get("WAYLAND_DISPLAY") and (not chosen or any(p.startswith("wayland") for p in chosen)):
        return None
    if env.get("DISPLAY") and (not chosen or "xcb" in chosen):
        lacking = missing()
        return _xcb_problem(lacking) if lacking else None
    return _no_display(env)
