"""Starting the GUI without a display: exit 1 with a message, never Qt's abort (exit 134).

One real process (:func:`cli_runner.run_process`) with DISPLAY, WAYLAND_DISPLAY and QT_QPA_PLATFORM
removed runs ``zwidth PROFILE``, ``zwidth gui PROFILE`` and ``zwidth`` in turn (Qt's abort would end
that process); the others check :func:`app.display_check.gui_problem` on given environments (the
library loader replaced by a list of what is installed), and a bad profile in process.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from app.display_check import XCB_LIBRARIES, gui_problem, missing_libraries
from cli_runner import DISPLAY_VARIABLES, environment, run_cli

ROOT = Path(__file__).resolve().parents[1]
HBFD = ROOT / "resources" / "profiles" / "hbfd.json"
HEADLESS = ("zwidth analyze", "zwidth report", "zwidth export-plot")
#: the launches checked in the no-display process: with a profile, spelt out, and with no argument
LAUNCHES = ([str(HBFD)], ["gui", str(HBFD)], [])

#: run each launch with its own captured output; print (exit code, stdout, stderr) of each as JSON
_SCRIPT = textwrap.dedent("""
    import contextlib, io, json, sys
    from app.cli import main
    results = []
    for argv in json.loads(sys.argv[1]):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
        results.append((code, out.getvalue(), err.getvalue()))
    print(json.dumps(results))
""")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the display variables are Linux's")
def test_no_display_exits_1_with_a_message():
    proc = subprocess.run([sys.executable, "-c", _SCRIPT, json.dumps(LAUNCHES)], env=environment(display=False),
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, (proc.returncode, proc.stderr)  # 134: Qt aborted the process
    assert "xcb" not in proc.stderr  # not Qt's misleading plugin message
    results = json.loads(proc.stdout.strip().splitlines()[-1])
    assert len(results) == len(LAUNCHES)
    for argv, (code, out, err) in zip(LAUNCHES, results):
        assert code == 1, (argv, err)
        assert out == ""
        assert err.startswith("zwidth: error: cannot start the GUI: there is no display "
                              "(neither DISPLAY nor WAYLAND_DISPLAY is set)."), (argv, err)
        for command in HEADLESS:
            assert command in err
        assert "xcb" not in err


def test_bad_profile_is_reported_before_the_display(capsys, monkeypatch, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{")
    for var in DISPLAY_VARIABLES:  # the display check would fail here: the profile must be read first
        monkeypatch.delenv(var, raising=False)
    r = run_cli(capsys, bad)
    assert r.returncode == 1
    assert "no display" not in r.stderr
    assert str(bad) in r.stderr


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
