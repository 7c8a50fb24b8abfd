"""`zwidth export-plot` CSVs: every number in the unit its header names, nothing dropped, empty charts explained.

Issue 13: the design chart's "current gains" were written as log10 values (b_c = 2.0, k_c = 4.69897
for b_c = 100, k_c = 50000); the range plot's view leaves the rise to 10¹¹ N·s/m below Nyquist
off-scale, but the CSV keeps it; the Eom chart, where no k_c is feasible, has a note saying so.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

from analysis.profiles.io import load_profile
from analysis.study import display_kind
from cli_runner import Capture, run_cli

ROOT = Path(__file__).resolve().parents[1]
PROFILES = ROOT / "resources" / "profiles"


def export_csv(capture: Capture, tmp_path: Path, profile: Path, plot: str
               ) -> tuple[list[str], list[str], list[list[str]]]:
    """Run ``zwidth export-plot`` (in process); (note lines, header, rows)."""
    out = tmp_path / f"{plot}.csv"
    proc = run_cli(capture, "export-plot", profile, "--plot", plot, "-o", out)
    assert proc.returncode == 0, proc.stderr
    lines = out.read_text(encoding="utf-8").splitlines()
    notes = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(line for line in lines if not line.startswith("#")))))
    return notes, rows[0], rows[1:]


def column(header: list[str], rows: list[list[str]], name: str) -> np.ndarray:
    j = header.index(name)
    return np.array([float(r[j]) for r in rows if j < len(r) and r[j]])


@pytest.mark.parametrize("preset", ["hbfd", "rigid"])
def test_design_chart_current_gains_are_the_profiles_gains(capfd, tmp_path, preset):
    path = PROFILES / f"{preset}.json"
    notes, header, rows = export_csv(capfd, tmp_path, path, "chart")
    p = load_profile(path)
    x, y = display_kind(p).chart_point(p)
    bc = column(header, rows, "current gains: b_c [N·s/m]")
    kc = column(header, rows, "current gains: k_c [N/m]")
    assert bc.tolist() == [x] and kc.tolist() == [y]  # exactly, not log10
    if preset == "hbfd":
        assert (bc[0], kc[0]) == (100.0, 50000.0)
        assert not notes


def test_range_csv_keeps_the_off_scale_points(capfd, tmp_path):
    notes, header, rows = export_csv(capfd, tmp_path, PROFILES / "hbfd.json", "range")
    p = load_profile(PROFILES / "hbfd.json")
    res = display_kind(p).evaluate(p)
    zmin = column(header, rows, "|Z_min|: |Z_min| [N·s/m]")
    w = column(header, rows, "|Z_min|: ω [rad/s]")
    np.testing.assert_allclose(w, res.w, rtol=1e-15)
    np.testing.assert_allclose(zmin, np.abs(res.zmin), rtol=1e-15)
    assert zmin.max() > 1e11  # the rise just below Nyquist that the default view leaves off-scale


def test_empty_design_chart_export_carries_a_note(capfd, tmp_path):
    notes, header, rows = export_csv(capfd, tmp_path, PROFILES / "eom.json", "chart")
    assert len(notes) == 1 and notes[0].startswith("# note: Nothing is feasible")
    assert "eq. 9" in notes[0] and "b_c from 1 to" in notes[0]
    assert column(header, rows, "largest k_c: k_c [N/m]").size == 0
    p = load_profile(PROFILES / "eom.json")
    assert column(header, rows, "current gains: k_c [N/m]").tolist() == [p.kc]
