"""The analysis package (and the `zwidth analyze` path, and the report's content) never imports Qt or
the app package.

Every check runs in one fresh interpreter (:func:`probe`, computed once per module: an interpreter
that imports numpy and scipy costs seconds on a loaded 2-core machine, issue 21), in stages whose
``sys.modules`` is recorded after each: the walk of every ``analysis`` module first, then ``import
app`` and the report's content, then ``import app.cli`` and the CLI's ``analyze``. A stage's record
holds what every earlier stage loaded, and the earlier stages are themselves checked clean, so each
test asserts what it asserted in an interpreter of its own; each test reports its own failure.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FORBIDDEN = ("PySide6", "shiboken6", "pyqtgraph", "app")
QT = ("PySide6", "shiboken6", "pyqtgraph")

SCRIPT = textwrap.dedent(
    """
    import importlib, importlib.util, json, pkgutil, sys

    def loaded(roots, prefixes=()):
        return sorted(n for n in sys.modules if n.split(".")[0] in roots or n.startswith(prefixes))

    stages = {{}}
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
    codes = [main(["analyze", {bad!r}]), main([{bad!r}])]
    if importlib.util.find_spec("analysis.study.summary") is not None:
        codes.append(main(["analyze", {hbfd!r}, "--json"]))
    stages["cli"] = {{"codes": codes, "bad": loaded({qt!r})}}
    print(json.dumps(stages))
    """
)


def run(code: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("QT_API", None)
    proc = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def probe(tmp_path_factory) -> dict:
    """{stage: its record} of one interpreter (JSON values: nothing a test can change for another)."""
    bad = tmp_path_factory.mktemp("no_qt") / "bad.json"
    bad.write_text("{}")
    hbfd = ROOT / "resources" / "profiles" / "hbfd.json"
    return run(SCRIPT.format(forbidden=FORBIDDEN, qt=QT, bad=str(bad), hbfd=str(hbfd)))


def test_analysis_imports_no_qt(probe):
    result = probe["analysis"]
    assert result["failed"] == []
    # a real walk: the modules this check is about were imported
    assert {"analysis.chain.device", "analysis.errors", "analysis.profiles", "analysis.resources"} <= set(
        result["imported"]
    )
    assert result["bad"] == []


@pytest.mark.parametrize("extra", ["import app.cli", "import app"])
def test_check_catches_forbidden_import(probe, extra):
    """Control: the same check flags a forbidden module when one is imported."""
    assert "app" in probe[extra]["bad"]
    if extra == "import app.cli":
        assert "app.cli" in probe[extra]["bad"]


def test_cli_analyze_path_imports_no_qt(probe):
    """`zwidth analyze` on a profile (bad here, good too once analysis.summary exists) loads no Qt."""
    result = probe["cli"]
    assert result["codes"][:2] == [1, 1]
    assert all(c == 0 for c in result["codes"][2:])
    assert result["bad"] == []


def test_report_content_imports_without_qt(probe):
    """The report's content comes from analysis.study alone: importing it loads no Qt (nor app.views)."""
    assert probe["report content"]["bad"] == []
