"""Every CSV that ``zwidth export-plot`` writes, in one notation (issue 22, "One notation everywhere").

The form (:func:`csv_form.check_csv`): ``curve: quantity [unit]`` headers in the plots' own
spelling, numbers or empty fields, never ``nan`` (empty is "not defined here": no filter has no
cut-off, no passive K at that B).  For every ``--plot`` choice that applies to the hbfd, eom and
rigid profiles, and the identification plots of a profile that has data; and the tables of
``zwidth space`` and ``zwidth workspace`` (:func:`csv_form.check_table`: ``quantity [unit]``
headers, issues 24 and 25), written by the one table writer.

The plots and commands that compute a grid run on a coarse one (:func:`coarse`): the form does not
depend on the grid's size, and a full workspace map or Z-width region costs seconds per case.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from analysis.identify import device_response
from analysis.profiles import load_profile, save_profile
from analysis.profiles.identification import IdentificationSection, MeasurementData
from app.cli import DEFAULT_SECTION_PLOTS, MULTIDOF_PLOTS, PLOT_SECTIONS, PLOTS, RENDERABLE_PLOTS
from app.views.base import Axis
from app.views.export import HEADER_PATTERN, TABLE_HEADER_PATTERN, table_csv_text
from cli_runner import Capture, run_cli
from coarse_grids import coarse
from csv_form import check_csv, check_table, column, read_csv

ROOT = Path(__file__).resolve().parents[1]
PROFILES = ROOT / "resources" / "profiles"
PRESETS = ("hbfd", "eom", "rigid")


def applicable(preset: str) -> list[str]:
    """The ``--plot`` choices the bundled profile ``preset`` has the sections for."""
    p = load_profile(PROFILES / f"{preset}.json")
    return [plot for plot in PLOTS if getattr(p, PLOT_SECTIONS.get(plot, "device")) is not None]


CASES = [(preset, plot) for preset in PRESETS for plot in applicable(preset)]
def export_profile(preset: str, plot: str, tmp_path: Path) -> Path:
    """The bundled profile ``preset``, on a coarse grid where ``plot`` computes one."""
    path = PROFILES / f"{preset}.json"
    for plots, section in ((MULTIDOF_PLOTS, "multidof"), (RENDERABLE_PLOTS, "renderable"),
                           (DEFAULT_SECTION_PLOTS, "controller")):
        if plot in plots:
            return coarse(path, section, tmp_path)
    return path


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
    notes, header, rows = read_export(capfd, tmp_path, export_profile(preset, plot, tmp_path), plot)
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


def test_the_table_writer_writes_nan_empty_inf_kept_and_flags_as_digits():
    text = table_csv_text([(Axis("x", "m"), np.array([0.1, -0.0, 3e-17])),
                           (Axis("k_worst", "N/m"), np.array([math.nan, math.inf, -math.inf])),
                           (Axis("reachable", ""), np.array([False, True, True])),
                           (Axis("binding device", "–"), np.array([0, 7, 12]))], ["why\n  two lines"])
    lines = text.splitlines()
    assert lines[0] == "# note: why two lines"
    assert lines[1:] == ["x [m],k_worst [N/m],reachable [-],binding device [-]",
                         "0.1,,0,0", "-0.0,inf,1,7", "3e-17,-inf,1,12"]
    notes, header, rows = lines[:1], lines[1].split(","), [r.split(",") for r in lines[2:]]
    check_table(header, rows, notes)
    assert all(TABLE_HEADER_PATTERN.match(h) and not HEADER_PATTERN.match(h) for h in header)
    with pytest.raises(ValueError, match="length"):
        table_csv_text([(Axis("x", "m"), [1.0, 2.0]), (Axis("y", "m"), [1.0])])


def test_zwidth_space_writes_the_documented_table(capfd, tmp_path):
    """``zwidth space``: one row per (M, B), every quality's K_max and a batch's binding device."""
    boxed = coarse(PROFILES / "rigid.json", "renderable", tmp_path, qualities=("stable", "passive"))
    p = load_profile(boxed)
    save_profile(p.replace(identification=IdentificationSection({"masses[0]": (0.4, 0.6)})), boxed)
    out = tmp_path / "space.csv"
    proc = run_cli(capfd, "space", boxed, "-o", out, "--corners", "--workers", "1")
    assert proc.returncode == 0, proc.stderr
    notes, header, rows = read_csv(out)
    check_table(header, rows, notes)
    assert header == ["M [kg]", "B [N·s/m]", "K_max (all qualities) [N/m]", "K_max (stable) [N/m]",
                      "K_max (passive) [N/m]", "binding device [-]"]
    assert len(rows) == 4 * 5 and {r[-1] for r in rows} <= {"0", "1"}  # two corners: index 0 or 1
    k, stable, passive = (np.array(column(header, rows, h), float) for h in header[2:5])
    assert np.all(k <= np.minimum(stable, passive)) and np.any(stable > 0)


def test_zwidth_workspace_writes_the_documented_table(capfd, tmp_path):
    """``zwidth workspace``: one row per handle position; a point the linkage does not reach has
    empty stiffnesses and normal (not defined there), never NaN."""
    profile = coarse(PROFILES / "hbfd.json", "multidof", tmp_path, x_min=-0.45, x_max=0.45, y_min=0.02, y_max=0.5)
    out = tmp_path / "map.csv"
    proc = run_cli(capfd, "workspace", profile, "-o", out)
    assert proc.returncode == 0, proc.stderr
    notes, header, rows = read_csv(out)
    check_table(header, rows, notes)
    assert header == ["x [m]", "y [m]", "reachable [-]", "k_isotropic [N/m]", "k_worst [N/m]", "n_x [-]", "n_y [-]"]
    assert len(rows) == 5 * 4
    reach = column(header, rows, "reachable [-]")
    assert set(reach) == {"0", "1"}  # the coarse grid has both
    for r in rows:
        assert all((f == "") == (r[2] == "0") for f in r[3:]), r
    n = np.array([[float(r[5]), float(r[6])] for r in rows if r[2] == "1"])
    np.testing.assert_allclose(np.hypot(n[:, 0], n[:, 1]), 1.0, rtol=1e-12)  # a unit normal
    assert any(note.startswith("# note: design bound") for note in notes)
