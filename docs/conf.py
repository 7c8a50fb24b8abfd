"""Sphinx configuration of the zwidth documentation (``make docs``; ``make test`` builds it with -W)."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))  # document the working tree, not an installed copy

_pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))

project = "zwidth"
author = "the zwidth developers"
copyright = "zwidth developers"
release = version = _pyproject["project"]["version"]

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "myst_parser",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}

# The two papers zwidth implements.  Every page that names an equation number cites the paper in
# full the first time: ``|adams|`` / ``|eom|`` in the reStructuredText pages (api/); the Markdown
# pages (guide/) spell the citation out so that it also reads on a repository browser.
ADAMS = (
    "Adams, R. J., Moreyra, M. R., & Hannaford, B. (1998). *Stability and Performance of Haptic "
    "Displays: Theory and Experiments*. Proceedings of the ASME International Mechanical "
    "Engineering Congress and Exposition, Haptic Interfaces for Virtual Environment and "
    "Teleoperator Systems, DSC-Vol. 64, Anaheim, CA, pp. 227–234"
)
EOM = (
    "Eom, K. S., Suh, I. H., & Yi, B.-J. (2000). *A Design Method of Haptic Interface Controller "
    "Considering Transparency and Robust Stability*. Proceedings of the IEEE/RSJ International "
    "Conference on Intelligent Robots and Systems (IROS 2000), Takamatsu, Japan"
)
rst_prolog = f"""
.. |adams| replace:: {ADAMS}
.. |eom| replace:: {EOM}
"""
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
