"""Every CSV that ``zwidth export-plot`` writes, in one notation (issue 22, "One notation everywhere").

The form (:func:`csv_form.check_csv`): ``curve: quantity [unit]`` headers in the plots' own
spelling, numbers or empty fields, never ``nan`` (empty is "not defined here": no filter has no
cut-off, no passive K at that B).  For every ``--plot`` choice that applies to the hbfd, eom and
rigid profiles, and the identification plots of a profile that has data.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from analysis.identify import device_response
from analysis.profiles import load_profile, save_profile
from analysis.profiles.identification import IdentificationSection, MeasurementData
from app.cli import PLOT_SECTIONS, PLOTS
from app.views.export import HEADER_PATTERN
from cli_runner import Capture, run_cli
from csv_form import check_csv, column, read_csv

ROOT = Path(__file__).resolve().parents[1]
PROFILES = ROOT / "resources" / "profiles"
PRESETS = ("hbfd", "eom", "rigid")


def applicable(preset: str) -> list[str]:
    """The ``--plot`` choices the bundled profile ``preset`` has the sections for."""
    p = load_profile(PROFILES / f"{preset}.json")
    return [plot for plot in PLOTS if getattr(p, PLOT_SECTIONS.get(plot, "device")) is not None]


CASES = [(preset, plot) for preset in PRESETS for plot in applicable(preset)]


def read_export(capture: Capture, tmp_path: Path, profile: Path, plot: str
                ) -> tuple[list[str], list[str], list[list[str]]]:
    """Run ``zwidth export-plot PROFILE --plot PLOT -o f.csv`` in process: (notes, header, rows)."""
    out = tmp_path / f"{plot}.csv"
    proc = run_cli(capture, "export-plot", profile, "--plot", plot, "-o", out)
    assert proc.returncode == 0, proc.stderr
    return read_csv(out)


def filter_optimum_checks(preset: str, header: list[str], rows: list[list[str]]) -> None:
    """No filter has no cut-off (an empty field) and an area; the curve is named by its legend."""
    name = "backward difference (no filter)"
    x = column(header, rows, f"{name}: cut-off f_c [Hz]")
    y = column(header, rows, f"{name}: area ∫K dB [N²·s/m²]")
    assert x[0] == "" and float(y[0]) > 0  # one point: the area without a cut-off
    assert not any(x[1:]) and not any(y[1:])
    assert header[0].startswith(("area, ", "noise-limited area, ")) and "low-pass" in header[0], header[0]


def zwidth_region_checks(preset: str, header: list[str], rows: list[list[str]]) -> None:
    """Every B is written; a K that is not defined there (no passive K) is an empty field beside it."""
    name = "passive K (Colgate-Schenkel)"
    b, k = column(header, rows, f"{name}: B [N·s/m]"), column(header, rows, f"{name}: K [N/m]")
    assert b == column(header, rows, header[0]) and all(b)  # the exact curve's B grid, none dropped
    assert all(float(v) > 0 for v in k if v)
    if preset == "rigid":  # the rigid handle's passive region is empty at some B, not at all
        assert 0 < sum(1 for v in k if not v) < len(k)


EXTRA_CHECKS = {"filter-optimum": filter_optimum_checks, "zwidth-region": zwidth_region_checks}


@pytest.mark.parametrize(("preset", "plot"), CASES, ids=[f"{a}-{b}" for a, b in CASES])
def test_every_export_is_in_the_documented_form(capfd, tmp_path, preset, plot):
    notes, header, rows = read_export(capfd, tmp_path, PROFILES / f"{preset}.json", plot)
    check_csv(header, rows, notes)
    if plot in EXTRA_CHECKS:
        EXTRA_CHECKS[plot](preset, header, rows)


def test_the_cases_cover_every_plot_but_identification():
    covered = {plot for _, plot in CASES}
    assert covered == set(PLOTS) - {"identify", "identify-phase"}  # those: the test below
    assert {plot for preset, plot in CASES if preset == "rigid"} >= set(EXTRA_CHECKS)


@pytest.fixture(scope="module")
def admittance_profile(tmp_path_factory) -> Path:
    """The HBFD as an admittance display: the charts over (m_c, b_c)."""
    path = tmp_path_factory.mktemp("admittance") / "admittance.json"
    save_profile(load_profile(PROFILES / "hbfd.json").replace(display="admittance"), path)
    return path


@pytest.mark.parametrize("plot", ["bound", "range", "chart"])
def test_admittance_exports_are_in_the_documented_form(capfd, tmp_path, admittance_profile, plot):
    notes, header, rows = read_export(capfd, tmp_path, admittance_profile, plot)
    check_csv(header, rows, notes)
    if plot == "chart":  # the feasible b_c interval over m_c, and the current gains, in the gains' units
        assert {"b_c low: m_c [kg]", "b_c high: b_c [N·s/m]", "current gains: m_c [kg]",
                "current gains: b_c [N·s/m]"} <= set(header), header


@pytest.fixture(scope="module")
def identified_profile(tmp_path_factory) -> Path:
    """The HBFD with one embedded actuator measurement (its own model's response) and an interval."""
    p = load_profile(PROFILES / "hbfd.json")
    d = p.device
    w = np.logspace(0, np.log10(0.95 * np.pi / d.sample_time), 60)
    m = MeasurementData(w, device_response(d, w, "actuator", "free", d.sample_time), "actuator", "free",
                        d.sample_time, 0, None, "actuator.csv")
    p = p.replace(identification=IdentificationSection({"ground_dampings[3]": (1.2, 5.0)}, (m,)))
    path = tmp_path_factory.mktemp("identified") / "identified.json"
    save_profile(p, path)
    return path


@pytest.mark.parametrize("plot", ["identify", "identify-phase"])
def test_identification_exports_are_in_the_documented_form(capfd, tmp_path, identified_profile, plot):
    notes, header, rows = read_export(capfd, tmp_path, identified_profile, plot)
    check_csv(header, rows, notes)
    assert all(HEADER_PATTERN.match(h)["unit"] == "rad/s" for h in header[::2])  # x: ω [rad/s]
    assert all(HEADER_PATTERN.match(h)["quantity"] == "ω" for h in header[::2])
