"""The docs build's shortcut for references that cannot resolve (docs/_ext/unresolvable_refs.py).

Only a reference that no documented object can match loses its fuzzy search: the rendered page is
the same (measured on the whole build: identical HTML, 42 -> 32 CPU-s), so what must hold is that a
reference which could resolve keeps it.
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

from docutils.frontend import get_default_settings
from docutils.parsers.rst import Parser
from docutils.utils import new_document
from sphinx.addnodes import pending_xref
from test_api_docstrings import docs_extension

ROOT = Path(__file__).resolve().parent.parent


def test_only_references_no_documented_object_can_match_lose_the_fuzzy_search():
    ext = docs_extension("unresolvable_refs")
    objects = {"analysis.Device": None, "analysis.twoport.ImpedanceDisplay.max_stiffness": None}
    settings = get_default_settings(Parser)
    settings.env = SimpleNamespace(domains={"py": SimpleNamespace(objects=objects)})
    document = new_document("test", settings)
    targets = ["float", "numpy.ndarray", "Device", "analysis.Device", "max_stiffness", "other.Device", "optional"]
    for target in targets:
        document += pending_xref("", refdomain="py", reftype="class", reftarget=target, refspecific=True)
    document += pending_xref("", refdomain="std", reftype="ref", reftarget="float", refspecific=True)
    ext.SkipHopelessFuzzySearch(document).run()
    kept = {n["reftarget"]: n.hasattr("refspecific") for n in document.findall(pending_xref) if n["refdomain"] == "py"}
    assert kept == {"float": False, "numpy.ndarray": False, "Device": True, "analysis.Device": True,
                    "max_stiffness": True, "other.Device": True, "optional": False}
    assert next(n for n in document.findall(pending_xref) if n["refdomain"] == "std").hasattr("refspecific")
    assert "unresolvable_refs" in (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
