"""Qt starts headless with the requested platform (the suite fails, never skips, without Qt)."""

from __future__ import annotations

import os

from PySide6.QtWidgets import QApplication


def test_application_runs_on_requested_platform(qapp):
    app = QApplication.instance()
    assert app is not None
    assert os.environ["QT_QPA_PLATFORM"]  # conftest sets it when unset
    assert app.platformName() == os.environ["QT_QPA_PLATFORM"].split(":")[0]


def test_settings_are_isolated(settings, tmp_path):
    assert str(tmp_path) in settings.qsettings.fileName()
