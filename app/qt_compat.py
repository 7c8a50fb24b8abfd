"""Work around a reference-count bug of PySide6 6.12.0 on CPython 3.11.

Every wrapped C++ method that returns ``void`` hands ``None`` back to Python without taking a
reference, so each call (``widget.update()``, ``QApplication.processEvents()``, ...) drops one
reference to ``None``.  On CPython >= 3.12 ``None`` is immortal (PEP 683) and nothing happens; on
3.11 the process aborts with "none_dealloc: deallocating None" after a few thousand calls.

:func:`protect_none` gives ``None`` (and ``True``/``False``, which some wrappers drop too) 2**40
extra references, the same effect immortality has on
3.12 (a leak of that size would take years of calls).  It is applied when this module is imported
and does nothing on Python >= 3.12.  The proper fix is to run on Python >= 3.12 or a PySide6 build
without the bug.
"""

from __future__ import annotations

import ctypes
import sys

__all__ = ["protect_none", "NEEDED"]

NEEDED = sys.version_info < (3, 12)
_EXTRA = 1 << 40


def protect_none() -> None:
    """Make ``None``, ``True`` and ``False`` effectively immortal (some bool wrappers leak too)."""
    if not NEEDED:
        return
    for obj in (None, True, False):
        refcount = ctypes.c_ssize_t.from_address(id(obj))
        if refcount.value < _EXTRA:
            refcount.value += _EXTRA


protect_none()
