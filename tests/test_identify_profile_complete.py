"""The profile ``zwidth identify`` writes is complete and consistent (issue 23): a 3-mass fit on the
4-mass HBFD base drops the base's per-mass friction (with a note), carries notes written for the
fit instead of the HBFD's, and runs in ``analyze``, ``report`` and ``export-plot``; a per-mass list
of the wrong length is refused at load, with its JSON path, by every one of them.  A time series'
input power is embedded with its measurement, so a reloaded profile judges the bins as the fit did."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from analysis.chain.device import Device
from analysis.identify import device_response
from analysis.profiles import ProfileError, load_profile, save_profile
from analysis.profiles.identification import parse_identification
from analysis.profiles.schema import PER_MASS_LISTS, drop_per_mass, per_mass_values
from analysis.profiles.sections import SimulationSection
from analysis.resources import resource_path
from analysis.study.identify import fit_curves, fit_notes, identify_chain, load_measurements, profile_with_fit
from cli_runner import run_cli
from tests.identify_files import write_chirp_csv

pytestmark = pytest.mark.numerics

HBFD = resource_path("profiles", "hbfd.json")
FRICTION = "$.simulation.options.friction"
#: the hidden 3-mass device of the issue (handle, link, actuator; 3 N s/m to ground at the actuator)
TRUTH = Device(masses=[0.12, 0.45, 0.30], stiffnesses=[6e4, 1.5e5], dampings=[20.0, 30.0],
               ground_dampings=[0.0, 0.0, 3.0], sample_time=1e-3)


def write_frf(path: Path, device: Device = TRUTH, points: int = 200) -> Path:
    """A noise-free actuator FRF of ``device``, ZOH-sampled, 1 rad/s .. 0.95 Nyquist."""
    T = device.sample_time
    w = np.logspace(0, np.log10(0.95 * np.pi / T), points)
    h = device_response(device, w, "actuator", "free", T, 0)
    rows = [f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(w, h)]
    path.write_text("frequency_rad_s,real,imag\n" + "\n".join(rows) + "\n")
    return path


@pytest.fixture(scope="module")
def fitted(tmp_path_factory) -> tuple[Path, Path]:
    """The measurement file and the profile identified from it on the HBFD base (as the CLI does)."""
    folder = tmp_path_factory.mktemp("identified")
    frf = write_frf(folder / "act3.csv")
    base = load_profile(HBFD)
    measurements = load_measurements([frf], sample_time=TRUTH.sample_time)
    result = identify_chain(measurements, 3, sample_time=TRUTH.sample_time, band_min=base.device.band_min)
    out = folder / "fit3.json"
    save_profile(profile_with_fit(base, result.fit, measurements, name="fit3"), out)
    return frf, out


def test_the_hbfd_base_has_a_four_value_friction_list():
    """The premise: the default base's friction is one value per mass of its 4-mass chain."""
    base = load_profile(HBFD)
    assert base.device.n == 4 and len(base.simulation.options.friction) == 4
    assert "four masses" in base.notes


def test_identified_profile_drops_the_friction_and_keeps_the_base_settings(fitted):
    base, p = load_profile(HBFD), load_profile(fitted[1])
    assert p.device.n == 3
    np.testing.assert_allclose(p.device.masses, TRUTH.masses, rtol=1e-6)
    assert p.simulation.options.friction == ()
    assert per_mass_values(p) == {FRICTION: ()}
    # everything else of the base is kept
    assert p.simulation.scenario == base.simulation.scenario
    assert p.simulation.options.replace(friction=base.simulation.options.friction) == base.simulation.options
    assert (p.kc, p.bc, p.display, p.device.sample_time) == (base.kc, base.bc, base.display, base.device.sample_time)


def test_notes_describe_the_fit_not_the_base_device(fitted):
    notes = load_profile(fitted[1]).notes
    assert "3 masses" in notes and "1 measurement" in notes and "act3.csv" in notes
    assert "four" not in notes.lower() and "Adams" not in notes  # nothing of the HBFD's description
    assert "HBFD (worst case)" in notes  # the base named as what gave the settings
    assert FRICTION in notes and "dropped" in notes  # the drop is said, with the values dropped
    assert "0, 1, 0, 0.5" in notes


def test_same_order_keeps_the_per_mass_lists(fitted):
    p = load_profile(fitted[1])
    base = p.replace(simulation=SimulationSection(
        options=p.simulation.options.replace(friction=(0.1, 0.0, 0.2)), scenario=p.simulation.scenario))
    assert drop_per_mass(base, 3) == ({}, {})
    measurements = load_measurements([fitted[0]], sample_time=TRUTH.sample_time)
    fit = identify_chain(measurements, 3, sample_time=TRUTH.sample_time).fit
    again = profile_with_fit(base, fit, measurements)
    assert again.simulation.options.friction == (0.1, 0.0, 0.2)
    assert "dropped" not in again.notes and "3 masses" in again.notes


def test_drop_per_mass_empties_every_list_that_does_not_fit():
    base = load_profile(HBFD)
    # every declared per-mass list is found on the record by its path
    assert set(per_mass_values(base)) == {path for path, _ in PER_MASS_LISTS}
    assert drop_per_mass(base, 4) == ({}, {})
    changes, dropped = drop_per_mass(base, 2)
    assert dropped == {FRICTION: (0.0, 1.0, 0.0, 0.5)}
    assert changes["simulation"].options.friction == ()
    assert changes["simulation"].scenario == base.simulation.scenario
    assert base.simulation.options.friction == (0.0, 1.0, 0.0, 0.5)  # the base is unchanged
    assert drop_per_mass(base.replace(simulation=None), 2) == ({}, {})


def test_fit_notes_say_when_the_fit_did_not_converge_and_its_warnings(fitted):
    """And which parameters were fixed rather than fitted."""
    measurements = load_measurements([fitted[0]], sample_time=TRUTH.sample_time)
    fit = identify_chain(measurements, 3, sample_time=TRUTH.sample_time).fit
    assert "did NOT converge" not in fit_notes(fit, measurements, "base", 4)
    assert "fixed, not fitted" not in fit_notes(fit, measurements, "base", 4)
    bad = dataclasses.replace(fit, converged=False, warnings=("masses[1] is not identifiable",))
    text = fit_notes(bad, measurements, "base", 4)
    assert "did NOT converge" in text and "Warning: masses[1] is not identifiable" in text


def test_cli_identify_writes_a_profile_every_command_runs(fitted, tmp_path, capsys):
    out = tmp_path / "mine.json"
    r = run_cli(capsys, "identify", fitted[0], "--masses", "3", "--sample-time", "0.001", "-o", out)
    assert r.returncode == 0, r.stderr
    p = load_profile(out)
    assert p.name == "mine" and p.device.n == 3 and p.simulation.options.friction == ()
    assert "3 masses" in p.notes and "four" not in p.notes.lower()
    r = run_cli(capsys, "analyze", out, "--json")
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    np.testing.assert_allclose(data["profile"]["masses"], TRUTH.masses, rtol=1e-6)


def test_report_and_map_export_succeed_on_the_identified_profile(fitted, tmp_path, capsys):
    html = tmp_path / "report.html"
    r = run_cli(capsys, "report", fitted[1], "-o", html)
    assert r.returncode == 0, r.stderr
    text = html.read_text(encoding="utf-8")
    assert "3 masses" in text and "four masses" not in text
    png = tmp_path / "map.png"
    r = run_cli(capsys, "export-plot", fitted[1], "--plot", "map", "-o", png)
    assert r.returncode == 0, r.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 1000


@pytest.mark.parametrize("command", [("analyze", "--json"), ("report", "-o", "r.html"),
                                     ("export-plot", "--plot", "map", "-o", "m.png")],
                         ids=["analyze", "report", "export-plot"])
def test_a_wrong_length_friction_list_is_refused_by_every_command(fitted, tmp_path, capsys, monkeypatch, command):
    data = json.loads(fitted[1].read_text(encoding="utf-8"))
    data["simulation"]["options"]["friction"] = [0.0, 1.0, 0.0, 0.5]
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    r = run_cli(capsys, command[0], bad, *command[1:])
    assert r.returncode == 1
    assert f"{FRICTION}: expected a list of exactly 3 values (one per mass" in r.stderr
    assert "got a list of 4 items" in r.stderr
    assert not (tmp_path / "r.html").exists() and not (tmp_path / "m.png").exists()


def test_fit_notes_name_the_fixed_parameters(fitted):
    measurements = load_measurements([fitted[0]], sample_time=TRUTH.sample_time)
    fit = identify_chain(measurements, 3, {"ground_dampings[2]": 3.0}, sample_time=TRUTH.sample_time).fit
    text = fit_notes(fit, measurements, "base", 4)
    assert "(ground_dampings[2] = 3 fixed, not fitted)" in text
    assert "3 masses" in text


# -- the input power of a time series, embedded (issue 23) ---------------------------------------------


def _section(**measurement: object) -> dict:
    w = np.logspace(1, 3, 10)
    m = {"quantity": "actuator", "boundary": "free", "sample_time": None, "delay_samples": 0,
         "frequency": w.tolist(), "real": (1 / w).tolist(), "imag": [0.0] * 10, **measurement}
    return {"intervals": {}, "measurements": [m]}


def test_input_power_round_trips_and_is_optional():
    power = [0.0] + [float(x) for x in np.logspace(-3, 2, 9)]
    sec = parse_identification(_section(input_power=power, coherence=[0.9] * 10))
    np.testing.assert_array_equal(sec.measurements[0].input_power, power)
    assert sec.to_dict()["measurements"][0]["input_power"] == power
    assert parse_identification(sec.to_dict()) == sec
    old = parse_identification(_section(coherence=[0.9] * 10))  # a file written before the key
    assert old.measurements[0].input_power is None and "input_power" not in old.to_dict()["measurements"][0]
    assert parse_identification(_section(input_power=None)).measurements[0].input_power is None


@pytest.mark.parametrize(("value", "where", "expected"), [
    ([1.0] * 9 + [-1e-9], "input_power[9]", "a number >= 0 and finite (N^2/Hz)"),
    ([1.0] * 4 + [float("inf")] + [1.0] * 5, "input_power[4]", "a finite number (N^2/Hz, >= 0)"),
    ([1.0] * 9, "input_power", "a list of exactly 10 values (one per frequency)"),
    ("high", "input_power", "a list of numbers (N^2/Hz, >= 0)"),
    ([1.0] * 9 + [True], "input_power[9]", "a finite number"),
])
def test_a_bad_input_power_is_refused_at_its_json_path(value, where, expected):
    with pytest.raises(ProfileError) as info:
        parse_identification(_section(input_power=value))
    assert info.value.json_path == f"$.identification.measurements[0].{where}"
    assert expected in str(info.value)


def test_reloaded_chirp_uses_the_fits_bins_and_the_report_says_the_cli_count(tmp_path, capsys):
    """The issue's chirp (tests/identify_files.py) through ``zwidth identify``: the profile's embedded
    measurement, reloaded, has the informative bins of the fit (coherence and input power, not
    coherence alone), and ``zwidth report`` prints the count the CLI's fit wrote into the notes."""
    csv = write_chirp_csv(tmp_path / "chirp.csv")
    out = tmp_path / "chirp.json"
    r = run_cli(capsys, "identify", csv, "--masses", "3", "-o", out)
    assert r.returncode == 0, r.stderr
    fitted = load_measurements([csv])[0]  # the Welch estimate the fit used (the same file, the same bins)
    assert fitted.input_power is not None and not fitted.used.all()
    p = load_profile(out)
    (m, _), = fit_curves(p)
    np.testing.assert_array_equal(m.input_power, fitted.input_power)
    np.testing.assert_array_equal(m.used, fitted.used)
    summary = m.bins.summary
    assert summary.startswith(f"chirp.csv: {m.bins.used} of {m.bins.total} bins used (by coherence and input power)")
    assert f"Bins: {summary}" in p.notes  # the count the CLI's fit wrote
    assert m.bins.used == int(np.count_nonzero(fitted.used)) and m.bins.low_power > 0
    html = tmp_path / "chirp.html"
    r = run_cli(capsys, "report", out, "-o", html)
    assert r.returncode == 0, r.stderr
    assert f"&bull;&nbsp;{summary}" in html.read_text(encoding="utf-8")
    # a profile written before input_power was embedded still loads; its bins are judged by coherence only
    data = json.loads(out.read_text(encoding="utf-8"))
    del data["identification"]["measurements"][0]["input_power"]
    old_file = tmp_path / "old.json"
    old_file.write_text(json.dumps(data), encoding="utf-8")
    (old, _), = fit_curves(load_profile(old_file))
    assert old.input_power is None and old.bins.criteria == ("coherence",)
    assert old.bins.used >= m.bins.used and np.all(old.used[m.used])  # coherence alone keeps more
