"""Analysis tabs.  Every module here named ``*_tab.py`` that defines ``TAB`` (an AnalysisTab
subclass) is a tab: adding an analysis is adding one module."""

from __future__ import annotations

import importlib
import pkgutil

from app.tabs.base import AnalysisTab, AppContext

__all__ = ["AnalysisTab", "AppContext", "tab_classes"]


def tab_classes() -> list[type[AnalysisTab]]:
    """The registered tab classes, in their ``order``."""
    found: list[type[AnalysisTab]] = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.endswith("_tab"):
            module = importlib.import_module(f"{__name__}.{info.name}")
            tab = getattr(module, "TAB", None)
            if isinstance(tab, type) and issubclass(tab, AnalysisTab):
                found.append(tab)
    return sorted(found, key=lambda t: (t.order, t.title))
