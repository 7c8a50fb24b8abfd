"""Sphinx configuration of the zwidth documentation (``make docs``; ``make test`` builds it with -W)."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # document the working tree, not an installed copy
sys.path.insert(0, str(ROOT / "docs" / "_ext"))  # api_docstrings: the numpydoc check of the API

_pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))

project = "zwidth"
author = "the zwidth developers"
copyright = "zwidth developers"
release = version = _pyproject["project"]["version"]

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "myst_parser",
    "api_docstrings",
    "unresolvable_refs",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}

# The papers zwidth cites, from the one definition (analysis/study/citations.py).  Every page that
# names an equation number cites the paper in full the first time: ``|adams|`` / ``|eom|`` (and
# ``|colgate_brown|``, ``|colgate_schenkel|``, ``|chawda|``, ``|hannaford_ryu|``,
# ``|moreyra_hannaford|``) in the reStructuredText pages (api/); the Markdown pages (guide/) spell
# the citation out so that it also reads on a repository browser.
from analysis.study import citations  # noqa: E402 - after the sys.path insert above

ADAMS = citations.ADAMS.markup().removesuffix(".")
EOM = citations.EOM.markup().removesuffix(".")
_SUBSTITUTIONS = {
    "adams": citations.ADAMS,
    "eom": citations.EOM,
    "colgate_brown": citations.COLGATE_BROWN,
    "colgate_schenkel": citations.COLGATE_SCHENKEL,
    "chawda": citations.CHAWDA,
    "hannaford_ryu": citations.HANNAFORD_RYU,
    "moreyra_hannaford": citations.MOREYRA_HANNAFORD,
}
rst_prolog = "\n".join(f".. |{name}| replace:: {ref.markup().removesuffix('.')}"
                        for name, ref in _SUBSTITUTIONS.items()) + "\n"
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3

exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
root_doc = "index"
language = "en"

# Broken references to third-party objects (numpy arrays in signatures...) are not errors: the
# build runs with -W, so only real mistakes in our own pages and docstrings fail it.
nitpicky = False
# The public names are re-exported by the subpackages (and the root package) on purpose, so a short
# name in an annotation may match more than one documented object; that is not a mistake.
suppress_warnings = ["ref.python"]

autodoc_default_options = {
    "members": True,
    "show-inheritance": True,
}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True
napoleon_google_docstring = True
napoleon_numpy_docstring = True
napoleon_use_rtype = False

html_theme = "pydata_sphinx_theme"
html_title = f"zwidth {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "navbar_align": "left",
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version", "theme-version"],
}
html_static_path: list[str] = []
html_show_sourcelink = False


# Each object is documented once, on the page of the subpackage that defines it: a subpackage that
# re-exports another one's name (analysis.sampled re-exports analysis.chain.VelocityFilter) does not
# document it again (two descriptions of one class are a duplicate-object warning).  A module's
# signature is processed before its members, so it tells which package is being documented.
_documenting: list[str] = [""]


def _note_module(app, what, name, obj, options, signature, return_annotation) -> None:  # noqa: ANN001
    if what == "module":
        _documenting[0] = name


def _skip_reexport(app, what, name, obj, skip, options):  # noqa: ANN001 - Sphinx event
    if what != "module" or skip:
        return None
    home = getattr(obj, "__module__", None) or ""
    current = _documenting[0]
    if home.startswith("analysis.") and current and not (home == current or home.startswith(current + ".")):
        return True
    return None


def setup(app) -> None:  # noqa: ANN001 - Sphinx hook
    app.connect("autodoc-process-signature", _note_module)
    app.connect("autodoc-skip-member", _skip_reexport)
