"""The suite's guard against unanswered modal dialogs: one that opens fails its test, with its text."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QDialog, QFileDialog, QMessageBox, QWidget

from modal_guard import ENTRY_POINTS, ModalDialogOpened, ModalGuard


def test_every_gui_test_runs_guarded(qtbot):
    parent = QWidget()
    qtbot.addWidget(parent)
    with pytest.raises(ModalDialogOpened, match="critical.*Cannot save profile.*disk full"):
        QMessageBox.critical(parent, "Cannot save profile", "p.json: disk full")
    with pytest.raises(ModalDialogOpened, match="getSaveFileName"):
        QFileDialog.getSaveFileName(parent, "Save profile", "", "*.json")
    with pytest.raises(ModalDialogOpened, match="QDialog.exec"):
        QDialog(parent).exec()


def test_restore_puts_qt_back_and_nesting_unwinds():
    originals = {(cls, name): cls.__dict__.get(name) for cls, name in ENTRY_POINTS}
    outer = ModalGuard().install()  # inside the suite's own guard: three levels deep
    inner = ModalGuard().install()
    inner.restore()
    with pytest.raises(ModalDialogOpened):
        QMessageBox.warning(None, "t", "x")
    assert outer.opened == ["modal QMessageBox.warning opened in a test: t | x"] and inner.opened == []
    outer.restore()
    assert {(cls, name): cls.__dict__.get(name) for cls, name in ENTRY_POINTS} == originals
