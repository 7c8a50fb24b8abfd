"""Starting the GUI without a display: exit 1 with a message, never Qt's abort (exit 134).

The subprocess test runs ``python -m app.cli PROFILE`` with DISPLAY, WAYLAND_DISPLAY and
QT_QPA_PLATFORM removed; the others check :func:`app.display_check.gui_problem` on given
environments (the library loader replaced by a list of what is installed).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from app.display_check import XCB_LIBRARIES, gui_problem, missing_libraries

ROOT = Path(__file__).resolve().parents[1]
HBFD = ROOT / "resources" / "profiles" / "hbfd.json"
HEADLESS = ("zwidth analyze", "zwidth report", "zwidth export-plot")


def _without_display() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    return env


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the display variables are Linux's")
@pytest.mark.parametrize("argv", [[str(HBFD)], ["gui", str(HBFD)], []])
def test_no_display_exits_1_with_a_message(argv):
    proc = subprocess.run([sys.executable, "-m", "app.cli", *argv], env=_without_display(), cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1, (proc.returncode, proc.stderr)
    assert proc.stdout == ""
    assert proc.stderr.startswith("zwidth: error: cannot start the GUI: there is no display "
                                  "(neither DISPLAY nor WAYLAND_DISPLAY is set).")
    for command in HEADLESS:
        assert command in proc.stderr
    assert "xcb" not in proc.stderr  # not Qt's misleading plugin message


def test_bad_profile_is_reported_before_the_display(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{")
    proc = subprocess.run([sys.executable, "-m", "app.cli", str(bad)], env=_without_display(), cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 1
    assert "no display" not in proc.stderr
    assert str(bad) in proc.stderr


def _installed(*missing: str):
    """A loader that finds every library except ``missing``."""
    return lambda: missing_libraries(loads=lambda soname: soname not in missing)


def test_no_display_variables():
    msg = gui_problem({}, "linux", _installed())
    assert msg is not None and "neither DISPLAY nor WAYLAND_DISPLAY is set" in msg
    for command in HEADLESS:
        assert command in msg


@pytest.mark.parametrize("platform", ["offscreen", "minimal", "vnc", "offscreen:fontengine=freetype",
                                      "wayland;offscreen"])
def test_a_windowless_platform_needs_no_display(platform):
    assert gui_problem({"QT_QPA_PLATFORM": platform}, "linux", _installed("libxcb-cursor.so.0")) is None


def test_x11_with_every_xcb_library_starts():
    assert gui_problem({"DISPLAY": ":0"}, "linux", _installed()) is None
    assert gui_problem({"WAYLAND_DISPLAY": "wayland-0"}, "linux", _installed("libxcb-cursor.so.0")) is None


def test_missing_xcb_cursor_is_named_with_its_package():
    msg = gui_problem({"DISPLAY": ":0"}, "linux", _installed("libxcb-cursor.so.0"))
    assert msg is not None
    assert "needs libxcb-cursor.so.0, which is not installed" in msg
    assert "sudo apt-get install -y libxcb-cursor0 " in msg
    msg = gui_problem({"DISPLAY": ":0"}, "linux", _installed("libxcb-cursor.so.0", "libxcb-icccm.so.4"))
    assert msg is not None
    assert "needs libxcb-cursor.so.0, libxcb-icccm.so.4, which are not installed" in msg
    assert "apt-get install -y libxcb-cursor0 libxcb-icccm4 " in msg


def test_platform_and_display_must_match():
    msg = gui_problem({"QT_QPA_PLATFORM": "xcb", "WAYLAND_DISPLAY": "wayland-0"}, "linux", _installed())
    assert msg is not None and "QT_QPA_PLATFORM=xcb needs a display of its kind" in msg
    assert gui_problem({"QT_QPA_PLATFORM": "xcb", "DISPLAY": ":1"}, "linux", _installed()) is None
    assert gui_problem({"QT_QPA_PLATFORM": "eglfs"}, "linux", _installed()) is None
    assert gui_problem({}, "darwin", _installed()) is None
    assert gui_problem({}, "win32", _installed()) is None


def test_the_xcb_list_names_the_libraries_of_the_issue():
    packages = {package for _, package in XCB_LIBRARIES}
    assert {"libxcb-cursor0", "libxkbcommon-x11-0", "libxcb-icccm4", "libxcb-image0", "libxcb-keysyms1",
            "libxcb-render-util0", "libxcb-shape0", "libxcb-randr0"} <= packages
    script = (ROOT / "packaging" / "system-deps.sh").read_text()
    for soname, package in XCB_LIBRARIES:  # the script checks the same list
        assert f'"{soname} {package}"' in script
