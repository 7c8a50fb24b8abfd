"""Cross-references that cannot resolve skip the Python domain's fuzzy search (docs build speed).

A type in a docstring's field list (``x : float``, ``numpy.ndarray``) becomes a "refspecific"
pending reference, and the Python domain resolves each of those by scanning every documented object
for one whose name ends in ``.float``: about 19 000 scans of the whole index in this build, a
quarter of its time, for names that are not documented here at all (there is no intersphinx).

Before the references are resolved, this transform drops the flag from the references whose last
name component is no documented object's last component (nor the whole target a documented name):
neither the fuzzy nor the exact search can find them, so the result (the plain text) is the same;
only the scan is skipped.  References that may resolve are left untouched.
"""

from __future__ import annotations

from typing import Any

from sphinx.addnodes import pending_xref
from sphinx.transforms.post_transforms import SphinxPostTransform


class SkipHopelessFuzzySearch(SphinxPostTransform):
    """Drop ``refspecific`` from Python references that no documented object can match."""

    default_priority = 5  # before sphinx.transforms.post_transforms.ReferencesResolver (10)

    def run(self, **kwargs: Any) -> None:
        objects = self.env.domains["py"].objects
        last = {name.rpartition(".")[2] for name in objects}
        for node in self.document.findall(pending_xref):
            if node.get("refdomain") != "py" or not node.hasattr("refspecific"):
                continue
            target = str(node.get("reftarget", ""))
            if target and target not in objects and target.rpartition(".")[2] not in last:
                del node["refspecific"]


def setup(app: Any) -> dict[str, Any]:
    app.add_post_transform(SkipHopelessFuzzySearch)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}

