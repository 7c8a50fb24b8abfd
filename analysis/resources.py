"""Locate the bundled data files (``resources/`` at the repository root).

With the editable install the Makefile makes (and when running from a checkout),
``resources/`` sits next to the ``analysis`` package directory.  A regular (wheel) install
copies the presets to ``<prefix>/share/zwidth/resources`` (pyproject ``data-files``), which is
looked at second.
"""

from __future__ import annotations

import sys
import sysconfig
from pathlib import Path

__all__ = ["resource_path", "resources_dir"]


def _candidates() -> list[Path]:
    here = Path(__file__).resolve().parent
    found = [here.parent / "resources"]
    for prefix in (sysconfig.get_path("data"), sys.prefix):
        if prefix:
            found.append(Path(prefix) / "share" / "zwidth" / "resources")
    return found


def resources_dir() -> Path:
    """The ``resources/`` directory; raises FileNotFoundError if there is none.

    Looked for beside the ``analysis`` package first, then under
    ``<prefix>/share/zwidth/resources``.

    Returns
    -------
    pathlib.Path
        The first candidate directory that exists.

    Raises
    ------
    FileNotFoundError
        When no candidate directory exists (the message lists where it looked).
    """
    candidates = _candidates()
    for path in candidates:
        if path.is_dir():
            return path
    raise FileNotFoundError(
        "zwidth resources directory not found; looked in " + ", ".join(map(str, candidates))
    )


def resource_path(*parts: str) -> Path:
    """Path of a bundled resource, e.g. ``resource_path("profiles", "hbfd.json")``.

    Parameters
    ----------
    *parts : str
        Path components below ``resources/``.

    Returns
    -------
    pathlib.Path
        The joined path (not checked for existence).

    Raises
    ------
    FileNotFoundError
        When there is no ``resources/`` directory (:func:`resources_dir`).
    """
    return resources_dir().joinpath(*parts)
