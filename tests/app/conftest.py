"""GUI test setup: headless Qt, isolated QSettings, and a main window on the HBFD profile.

PySide6 is imported at module level on purpose, without a guard: if Qt cannot start, the GUI
suite fails instead of being skipped.
"""

from __future__ import annotations

import os
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
REQUESTED_PLATFORM = os.environ["QT_QPA_PLATFORM"]

import PySide6  # noqa: E402,F401
import pytest  # noqa: E402
from PySide6.QtCore import QSettings  # noqa: E402

import app.qt_compat  # noqa: E402,F401 - PySide6 6.12 on CPython 3.11 (see the module)
from analysis.profiles.io import bundled_profiles, load_profile  # noqa: E402

# Nothing a test does may touch the user's real preferences.
QSettings.setDefaultFormat(QSettings.Format.IniFormat)
QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, tempfile.mkdtemp(prefix="zwidth-qsettings-"))


@pytest.fixture(scope="session", autouse=True)
def _app_names(qapp):
    qapp.setOrganizationName("zwidth-tests")
    qapp.setApplicationName("zwidth-tests")
    qapp.setStyle("Fusion")
    yield qapp


@pytest.fixture
def settings(tmp_path):
    from app.core.settings import Settings

    QSettings.setPath(QSettings.Format.IniFormat, QSettings.Scope.UserScope, str(tmp_path / "user"))
    return Settings(QSettings(str(tmp_path / "zwidth-test.ini"), QSettings.Format.IniFormat))


@pytest.fixture
def hbfd_profile():
    return load_profile(bundled_profiles()["hbfd"])


def _main_window(qtbot, settings, profile):
    from app.window.main_window import MainWindow

    w = MainWindow(settings=settings, profile=profile)
    w.resize(1400, 900)
    w.show()
    qtbot.waitExposed(w)
    qtbot.waitUntil(lambda: not w.tabs.currentWidget().stale, timeout=5000)
    yield w
    # not qtbot.addWidget: pytest-qt would close it before this teardown and the unsaved-changes
    # question would block
    w.undo_stack.setClean()
    w.runner.shutdown()
    w.close()
    w.deleteLater()


@pytest.fixture
def win(qtbot, settings, hbfd_profile):
    """The real main window on the HBFD preset, shown offscreen at 1400x900."""
    yield from _main_window(qtbot, settings, hbfd_profile)


@pytest.fixture
def eom_win(qtbot, settings):
    """The real main window on the Eom, Suh & Yi preset (wall and observer sections)."""
    yield from _main_window(qtbot, settings, load_profile(bundled_profiles()["eom"]))
