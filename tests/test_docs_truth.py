"""The user guide says what the program does (issue 22).

* Every JSON key that ``docs/guide/results.md`` names in its tables exists in the real output of
  ``zwidth analyze --json`` (inside the display's object), for the HBFD profile's impedance
  display and the Eom profile's admittance display, and ``zwidth design --json`` prints the same
  design objects at its top level, as the page says.
* The bad-profile message quoted in ``docs/guide/quickstart.md`` is the one the command prints.
* ``results.md`` and the report's Methods define the stability reserve alike, and truly: the
  smallest ``1 - bound/coupling term`` over the band.

The commands run in process (:func:`cli_runner.run_cli`).
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from cli_runner import ROOT, run_cli

from analysis import load_profile
from analysis.study.displays import DISPLAY_KINDS
from analysis.study.headline import HEADLINE_KEYS, Headline

GUIDE = ROOT / "docs" / "guide"
PROFILES = ROOT / "resources" / "profiles"
#: backticked names in a table cell that are JSON key paths (``design.min_mass.mc``), not values
KEY_PATH = re.compile(r"`([a-z_][a-z0-9_]*(?:\.[a-z_][a-z0-9_]*)*)`")
JSON_LITERALS = {"null", "true", "false"}


def table_rows(text: str) -> list[dict[str, str]]:
    """The body rows of every Markdown table in ``text``, as {header: cell}."""
    rows: list[dict[str, str]] = []
    header: list[str] | None = None
    for line in text.splitlines():
        if not line.startswith("|"):
            header = None
            continue
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
        if header is None:
            header = cells
        elif not all(set(c) <= {"-", ":"} for c in cells):
            rows.append(dict(zip(header, cells)))
    return rows


def documented_keys(text: str) -> dict[str, set[str]]:
    """Key paths named in the tables of a guide page, by the display they belong to
    (``"both"`` for a table without a display column)."""
    keys: dict[str, set[str]] = {}
    for row in table_rows(text):
        if "key" not in row:
            continue
        display = row.get("display", "both")
        names = {m for cell in row.values() for m in KEY_PATH.findall(cell)} - JSON_LITERALS
        keys.setdefault(display, set()).update(names)
    return keys


def resolve(obj: dict[str, Any], path: str) -> Any:
    """The value at the dotted ``path`` of ``obj``; ``KeyError`` naming the missing part."""
    for part in path.split("."):
        if not isinstance(obj, dict) or part not in obj:
            raise KeyError(f"{path}: no {part!r}")
        obj = obj[part]
    return obj


def same(a: Any, b: Any) -> bool:
    """JSON values equal, floats to 1e-9 relative."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, float) and isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=0.0)
    return a == b


RESULTS = documented_keys((GUIDE / "results.md").read_text(encoding="utf-8"))


def test_results_page_names_keys_per_display():
    assert set(RESULTS) == {"both", "impedance", "admittance"}
    assert set(HEADLINE_KEYS) <= RESULTS["both"]  # every verdict key is documented
    assert {"design.kc_max", "design.frequency"} <= RESULTS["impedance"]
    assert {"design.feasible_damping.low", "design.feasible_damping.high", "design.min_mass.mc",
            "design.min_mass.bc"} <= RESULTS["admittance"]


@pytest.mark.parametrize(("profile", "display", "design_objects"), [
    ("hbfd.json", "impedance", ("design",)),
    ("eom.json", "admittance", ("feasible_damping", "min_mass")),
])
def test_results_page_keys_exist(capsys, profile, display, design_objects):
    analyzed = run_cli(capsys, "analyze", PROFILES / profile, "--json")
    assert analyzed.returncode == 0, analyzed.stderr
    obj = json.loads(analyzed.stdout)[display]
    missing = []
    for path in sorted(RESULTS["both"] | RESULTS[display]):
        try:
            resolve(obj, path)
        except KeyError as exc:
            missing.append(str(exc))
    assert not missing, f"results.md names keys that {profile}'s {display} output lacks: {missing}"

    designed = run_cli(capsys, "design", PROFILES / profile, "--display", display, "--json")
    assert designed.returncode == 0, designed.stderr
    top = json.loads(designed.stdout)
    assert top["display"] == display
    # the page: `zwidth design --json` prints the same design objects at its top level
    inner = obj["design"] if display == "admittance" else obj
    for name in design_objects:
        assert same(top[name], inner[name]), name


def quoted_error(text: str) -> tuple[list[str], str]:
    """The command and the stderr line that quickstart.md quotes for a bad profile."""
    m = re.search(r"`zwidth ([^`]+)` on a copy of\s+the bundled HBFD profile[^`]*?```text\n(.+?)\n```", text,
                  re.DOTALL)
    assert m, "quickstart.md no longer quotes a bad profile's message in a text block"
    return m.group(1).split(), m.group(2)


def test_quickstart_error_message_is_real(capsys, monkeypatch, tmp_path: Path):
    argv, message = quoted_error((GUIDE / "quickstart.md").read_text(encoding="utf-8"))
    data = json.loads((PROFILES / "hbfd.json").read_text(encoding="utf-8"))
    data["device"]["masses"][2] = -1.0  # "whose third mass is set to -1"
    (tmp_path / argv[-1]).write_text(json.dumps(data), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    r = run_cli(capsys, *argv)
    assert r.returncode == 1
    assert r.stdout == ""
    assert r.stderr.strip() == message


#: the reserve's definition as results.md and the report's Methods (HTML) write it
RESERVE = "1 − bound/coupling term"


def test_reserve_defined_alike_in_guide_and_report():
    from app.report.content import METHODS

    methods = " ".join(METHODS).replace("&minus;", "−")
    results = (GUIDE / "results.md").read_text(encoding="utf-8")
    assert f"the smallest {RESERVE}" in results
    assert f"smallest margin relative to the coupling term, {RESERVE}, over the band" in methods
    assert "relative to the bound" not in methods + results


@pytest.mark.parametrize("display", sorted(DISPLAY_KINDS))
@pytest.mark.parametrize("profile", ["hbfd.json", "eom.json"])
def test_reserve_is_smallest_one_minus_bound_over_coupling(profile, display):
    kind = DISPLAY_KINDS[display]
    p = load_profile(PROFILES / profile)
    result = kind.evaluate(p, kind.build(p))
    reserve = Headline.from_result(result).stability_reserve
    assert np.all(result.coupling_term > 0)
    on_grid = float(np.min(1.0 - result.bound / result.coupling_term))
    # refined between grid points, so at most the grid's minimum and close to it
    assert reserve <= on_grid + 1e-12 * max(1.0, abs(on_grid))
    assert reserve >= on_grid - 1e-2 * max(1.0, abs(on_grid))
