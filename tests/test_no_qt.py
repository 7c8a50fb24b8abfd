"""The analysis package (and the `zwidth analyze` path, and the report's content) never imports Qt or
the app package.

Every check reads one fresh interpreter's records (:func:`import_probe.import_probe`, which says
why one interpreter serves them all); each test reports its own failure.
"""

from __future__ import annotations

import pytest

from import_probe import import_probe


@pytest.fixture(scope="module")
def probe() -> dict:
    """{stage: its record} of the probe's interpreter (JSON values, a copy of this module's own)."""
    return import_probe()


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
