"""No modal dialog may wait for a click that never comes: a test that opens one fails, with its text.

Offscreen there is nobody to press a button, so an unexpected ``QMessageBox.critical`` (a refused
save, say) or a file dialog would block its test for ever, and CI would end on its time limit with
no word of why.  :class:`ModalGuard` replaces Qt's modal entry points by functions that raise
:class:`ModalDialogOpened` naming the dialog and its text.  A test that means to answer a dialog
patches the same function itself (``monkeypatch.setattr``), which takes precedence.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtWidgets import QDialog, QFileDialog, QInputDialog, QMessageBox

#: (class, static or bound method name): every way the application opens a modal dialog
ENTRY_POINTS: tuple[tuple[type, str], ...] = (
    *((QMessageBox, n) for n in ("critical", "warning", "question", "information", "about")),
    *((QFileDialog, n) for n in ("getOpenFileName", "getOpenFileNames", "getSaveFileName", "getExistingDirectory")),
    *((QInputDialog, n) for n in ("getInt", "getDouble", "getText", "getItem")),
    (QDialog, "exec"),
)


_INHERITED = object()  # the class had no attribute of its own: restoring deletes ours


class ModalDialogOpened(AssertionError):
    """A modal dialog opened where no one can answer it."""


def _text(args: tuple[Any, ...]) -> str:
    return " | ".join(str(a) for a in args[1:4] if isinstance(a, str)) or repr(args[:1])


class ModalGuard:
    """Installs the failing replacements; :meth:`restore` puts Qt's own back."""

    def __init__(self) -> None:
        self.opened: list[str] = []
        self._saved: list[tuple[type, str, Any]] = []

    def install(self) -> ModalGuard:
        for cls, name in ENTRY_POINTS:
            self._saved.append((cls, name, cls.__dict__.get(name, _INHERITED)))
            setattr(cls, name, self._refuse(cls, name))
        return self

    def restore(self) -> None:
        for cls, name, original in reversed(self._saved):
            if original is _INHERITED:
                delattr(cls, name)
            else:
                setattr(cls, name, original)
        self._saved.clear()

    def _refuse(self, cls: type, name: str) -> Any:
        def refuse(*args: Any, **_kwargs: Any) -> Any:
            message = f"modal {cls.__name__}.{name} opened in a test: {_text(args)}"
            self.opened.append(message)
            raise ModalDialogOpened(message)

        return staticmethod(refuse) if name != "exec" else refuse
