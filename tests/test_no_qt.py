"""The analysis package (and the `zwidth analyze` path) never imports Qt or the app package."""

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

SCRIPT = textwrap.dedent(
    """
    import importlib, json, pkgutil, sys
    {extra}
    import analysis
    imported, failed = [], []
    for info in pkgutil.walk_packages(analysis.__path__, "analysis."):
        try:
            importlib.import_module(info.name)
            imported.append(info.name)
        except Exception as exc:
            failed.append(f"{{info.name}}: {{type(exc).__name__}}: {{exc}}")
    forbidden = {forbidden!r}
    bad = sorted(n for n in sys.modules if n.split(".")[0] in forbidden)
    print(json.dumps({{"imported": imported, "failed": failed, "bad": bad}}))
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


def test_analysis_imports_no_qt():
    result = run(SCRIPT.format(extra="", forbidden=FORBIDDEN))
    assert result["failed"] == []
    # a real walk: the modules this check is about were imported
    assert {"analysis.chain.device", "analysis.errors", "analysis.profiles", "analysis.resources"} <= set(
        result["imported"]
    )
    assert result["bad"] == []


@pytest.mark.parametrize("extra", ["import app.cli", "import app"])
def test_check_catches_forbidden_import(extra):
    """Control: the same script flags a forbidden module when one is imported."""
    result = run(SCRIPT.format(extra=extra, forbidden=FORBIDDEN))
    assert "app" in result["bad"]


def test_cli_analyze_path_imports_no_qt(tmp_path):
    """`zwidth analyze` on a profile (bad here, good too once analysis.summary exists) loads no Qt."""
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    code = textwrap.dedent(
        f"""
        import importlib.util, json, sys
        from app.cli import main
        codes = [main(["analyze", {str(bad)!r}]), main([{str(bad)!r}])]
        if importlib.util.find_spec("analysis.study.summary") is not None:
            codes.append(main(["analyze", {str(ROOT / "resources/profiles/hbfd.json")!r}, "--json"]))
        bad = sorted(n for n in sys.modules if n.split(".")[0] in ("PySide6", "shiboken6", "pyqtgraph"))
        print(json.dumps({{"codes": codes, "bad": bad}}))
        """
    )
    result = run(code)
    assert result["codes"][:2] == [1, 1]
    assert all(c == 0 for c in result["codes"][2:])
    assert result["bad"] == []
