"""What a fresh interpreter imports: one interpreter for every "imports no X" check (issue 21).

An interpreter that imports numpy and scipy costs seconds on a loaded 2-core machine, so the checks
of ``test_no_qt`` and ``test_profiles`` share one (:func:`import_probe`, once per test process). It
runs in stages and records ``sys.modules`` (or what the stage checks) after each:

1. ``profile record``: ``analysis.profiles.model``, then ``analysis.profiles.io`` and
   ``analysis.profiles`` load none of :data:`HEAVY`; the lazy names of ``analysis.transparency`` and
   ``analysis.sampled`` resolve;
2. ``analysis``: every module of ``analysis`` imports, and none of them loads Qt or ``app``;
3. ``import app``: the control, the same check flags ``app`` once it is imported;
4. ``report content``: ``app.report.content`` and ``app.report.model`` load no Qt nor ``app.views``;
5. ``import app.cli``: the control again;
6. ``cli``: ``zwidth analyze`` (a bad profile, then the HBFD's JSON summary) loads no Qt.

A stage's record holds what the earlier stages loaded too, and they are checked clean, so each
check says what it said in an interpreter of its own; each test asserts its stage's record.
"""

from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
FORBIDDEN = ("PySide6", "shiboken6", "pyqtgraph", "app")
QT = ("PySide6", "shiboken6", "pyqtgraph")
#: the design stack the Profile record must not load
HEAVY = ("analysis.transparency.design", "analysis.transparency.index", "analysis.sampled.simulator")

SCRIPT = textwrap.dedent(
    """
    import importlib, importlib.util, json, os, pkgutil, sys, tempfile

    def loaded(roots, prefixes=()):
        return sorted(n for n in sys.modules if n.split(".")[0] in roots or n.startswith(prefixes))

    stages = {{}}
    import analysis.profiles.model
    record = {{"after model": loaded((), {heavy!r})}}
    import analysis.profiles.io, analysis.profiles
    record["after io"] = loaded((), {heavy!r})
    from analysis.transparency import WallDesign
    from analysis.sampled import simulate
    import analysis.transparency as t, analysis.sampled as s
    record["all listed"] = set(t.__all__) <= set(dir(t)) and set(s.__all__) <= set(dir(s))
    record["all resolve"] = all(getattr(t, n) is not None for n in t.__all__) and all(
        getattr(s, n) is not None for n in s.__all__)
    record["names"] = [WallDesign.__name__, simulate.__name__]
    stages["profile record"] = record

    import analysis
    imported, failed = [], []
    for info in pkgutil.walk_packages(analysis.__path__, "analysis."):
        try:
            importlib.import_module(info.name)
            imported.append(info.name)
        except Exception as exc:
            failed.append(f"{{info.name}}: {{type(exc).__name__}}: {{exc}}")
    stages["analysis"] = {{"imported": imported, "failed": failed, "bad": loaded({forbidden!r})}}

    import app  # the control: the same check flags a forbidden module once one is imported
    stages["import app"] = {{"bad": loaded({forbidden!r})}}

    import app.report.content, app.report.model
    stages["report content"] = {{"bad": loaded({qt!r}, ("app.views",))}}

    import app.cli
    stages["import app.cli"] = {{"bad": loaded({forbidden!r})}}

    from app.cli import main
    bad = os.path.join(tempfile.mkdtemp(), "bad.json")
    with open(bad, "w") as f:
        f.write("{{}}")
    codes = [main(["analyze", bad]), main([bad])]
    os.remove(bad)
    os.rmdir(os.path.dirname(bad))
    if importlib.util.find_spec("analysis.study.summary") is not None:
        codes.append(main(["analyze", {hbfd!r}, "--json"]))
    stages["cli"] = {{"codes": codes, "bad": loaded({qt!r})}}
    print(json.dumps(stages))
    """
)


def run(code: str) -> dict[str, Any]:
    """The last line of ``python -c code``'s output, as JSON (the process must exit 0)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("QT_API", None)
    proc = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


@functools.lru_cache(maxsize=None)
def _probe_json() -> str:
    hbfd = ROOT / "resources" / "profiles" / "hbfd.json"
    return json.dumps(run(SCRIPT.format(heavy=HEAVY, forbidden=FORBIDDEN, qt=QT, hbfd=str(hbfd))))


def import_probe() -> dict[str, Any]:
    """{stage: its record} (see the module doc); a fresh copy for each caller, from one interpreter."""
    return json.loads(_probe_json())
