"""``zwidth identify`` with real measurement sets (issue 23): each file its own kind
(``FILE[:QUANTITY[:BOUNDARY]]``), time series sampled at their own step, ``--masses`` checked
before anything is read, progress above 4 masses and Ctrl-C as a clean cancel.

The fits are in process (:func:`cli_runner.run_cli`); only the Ctrl-C test starts a real process,
since a signal needs one."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pytest

from analysis.chain.device import Device
from analysis.identify import device_response
from analysis.profiles import load_profile
from analysis.study.identify import MAX_MASSES
from analysis.study.measurement_files import MeasurementSpec, parse_measurement_spec
from cli_runner import ROOT, environment, run_cli

T = 1e-3
#: the issue's 3-mass device: handle 0.12 kg, 0.45, 0.30; k 6e4 and 1.5e5 N/m; 3 N s/m to ground
DEVICE = Device(masses=np.array([0.12, 0.45, 0.30]), stiffnesses=np.array([6e4, 1.5e5]),
                dampings=np.array([2.0, 4.0]), ground_dampings=np.array([0.0, 0.0, 3.0]), sample_time=T)


def write_frf(path: Path, quantity: str = "actuator", boundary: str = "free", device: Device = DEVICE,
              points: int = 300, noise: float = 0.0, seed: int = 0) -> Path:
    """An exact (or noisy) FRF CSV of ``device``, ZOH-sampled at 1 kHz, 1 rad/s .. 0.95 Nyquist."""
    w = np.logspace(0, np.log10(0.95 * np.pi / T), points)
    h = device_response(device, w, quantity, boundary, T, 0)
    if noise:
        rng = np.random.default_rng(seed)
        h = h * (1 + noise * (rng.standard_normal(w.size) + 1j * rng.standard_normal(w.size)) / np.sqrt(2))
    rows = [f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(w, h)]
    path.write_text("frequency_rad_s,real,imag\n" + "\n".join(rows) + "\n")
    return path


def write_timeseries(path: Path, samples: int = 2 ** 14, seed: int = 1) -> Path:
    """A periodic random-phase multisine force through the ZOH and the sampled actuator position
    (exact periodic steady state: each bin's force times the device's ZOH response)."""
    rng = np.random.default_rng(seed)
    f_hat = np.exp(2j * np.pi * rng.random(samples // 2 + 1))
    f_hat[0] = f_hat[-1] = 0.0  # no mean force (the chain drifts), no Nyquist bin
    w = 2 * np.pi * np.fft.rfftfreq(samples, T)
    x_hat = np.zeros_like(f_hat)
    x_hat[1:-1] = device_response(DEVICE, w[1:-1], "actuator", "free", T, 0) * f_hat[1:-1]
    force, position = np.fft.irfft(f_hat, samples), np.fft.irfft(x_hat, samples)
    t = np.arange(samples) * T
    path.write_text("time_s,force_n,position_m\n" + "\n".join(
        f"{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), force.tolist(), position.tolist())) + "\n")
    return path


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    d = tmp_path_factory.mktemp("mixed")
    return {"a": write_frf(d / "a.csv"), "g": write_frf(d / "g.csv", "gauge"),
            "c": write_frf(d / "c.csv", "actuator", "clamped"), "ts": write_timeseries(d / "ts.csv", 2 ** 12)}


def identify_json(capsys, *argv) -> tuple[dict, str]:
    r = run_cli(capsys, "identify", *map(str, argv), "--json")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout), r.stderr


@pytest.mark.numerics  # fits: run under the second OpenBLAS kernel too
def test_mixed_actuator_gauge_clamped_set_recovers_the_device(files, tmp_path, capsys):
    out = tmp_path / "mixed.json"
    data, _ = identify_json(capsys, files["a"], f"{files['g']}:gauge", f"{files['c']}:actuator:clamped",
                            "--masses", "3", "--sample-time", "0.001", "-o", out)
    kinds = [(m["quantity"], m["boundary"]) for m in data["measurements"]]
    assert kinds == [("actuator", "free"), ("gauge", "free"), ("actuator", "clamped")]
    dev = load_profile(out).device
    np.testing.assert_allclose(dev.masses, DEVICE.masses, rtol=1e-5)
    np.testing.assert_allclose(dev.stiffnesses, DEVICE.stiffnesses, rtol=1e-5)
    np.testing.assert_allclose(dev.dampings, DEVICE.dampings, rtol=1e-4)
    assert data["residual"] < 1e-6
    assert [m.boundary for m in load_profile(out).identification.measurements] == ["free", "free", "clamped"]
    # the suggestions come from the set given: a clamped test is never asked for when one was given
    assert not any("clamped-handle" in s for s in [*data["suggestions"].values(), *data["warnings"]])


@pytest.mark.numerics  # fits: run under the second OpenBLAS kernel too
def test_gauge_file_is_fitted_as_gauge_only_when_it_says_so(files, tmp_path, capsys):
    right, _ = identify_json(capsys, files["a"], f"{files['g']}:gauge", "--masses", "3", "--sample-time", "0.001",
                             "-o", tmp_path / "right.json")
    # the gauge file read as an actuator FRF: no stiffnesses and dampings fit it, even with the masses
    # held at the device's (holding them spares the intervals of a fit that cannot converge: ~15x cheaper)
    held = [arg for i, m in enumerate(DEVICE.masses) for arg in ("--fix", f"masses[{i}]={float(m)!r}")]
    wrong, _ = identify_json(capsys, files["a"], files["g"], "--masses", "3", "--sample-time", "0.001", *held,
                             "-o", tmp_path / "wrong.json")
    assert [m["quantity"] for m in right["measurements"]] == ["actuator", "gauge"]
    assert [m["quantity"] for m in wrong["measurements"]] == ["actuator", "actuator"]
    assert right["residual"] < 1e-6 < 1e-2 < wrong["residual"]
    np.testing.assert_allclose(load_profile(tmp_path / "right.json").device.masses, DEVICE.masses, rtol=1e-5)


@pytest.mark.numerics  # fits: run under the second OpenBLAS kernel too
def test_time_series_uses_its_own_step_without_sample_time(files, tmp_path, capsys):
    out = tmp_path / "ts.json"
    sampled, err = identify_json(capsys, files["ts"], "--masses", "3", "-o", out)
    (m,) = sampled["measurements"]
    assert m["time_series"] is True and m["sample_time_from"] == "time step"
    assert m["sample_time"] == pytest.approx(T, rel=1e-9) and sampled["sample_time"] == pytest.approx(T, rel=1e-9)
    assert "own time step T = 0.001 s" in err
    p = load_profile(out)
    assert p.identification.measurements[0].sample_time == pytest.approx(T, rel=1e-9)
    assert p.device.sample_time == pytest.approx(T, rel=1e-9)
    continuous, err = identify_json(capsys, files["ts"], "--masses", "3", "--continuous", "-o", tmp_path / "c.json")
    (m,) = continuous["measurements"]
    assert m["sample_time"] is None and m["sample_time_from"] == "continuous" and "continuous-time" in err
    # the ZOH's half-sample lag near Nyquist is not in a continuous-time model
    assert continuous["residual"] > 2 * sampled["residual"]


def test_frf_without_sample_time_stays_continuous(files, tmp_path, capsys):
    data, err = identify_json(capsys, files["a"], "--masses", "3", "-o", tmp_path / "f.json")
    assert data["measurements"][0]["sample_time"] is None and data["measurements"][0]["time_series"] is False
    assert "time step" not in err


def test_too_many_masses_refused_before_reading_or_allocating(tmp_path, capsys):
    tracemalloc.start()
    try:
        r = run_cli(capsys, "identify", tmp_path / "missing.csv", "--masses", "600", "-o", tmp_path / "x.json")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert r.returncode == 2  # a missing file would be status 1: nothing was read
    assert "--masses" in r.stderr and f"<= {MAX_MASSES}" in r.stderr and "600" in r.stderr
    assert peak < 20 * 2 ** 20
    assert not (tmp_path / "x.json").exists()


@pytest.mark.parametrize(("spec", "words"), [
    ("g.csv:gauges", ["'gauges'", "actuator, handle, gauge"]),
    ("c.csv:clamped", ["'clamped'", "c.csv:actuator:clamped"]),
    ("c.csv:actuator:clampd", ["'clampd'", "free, clamped"]),
])
def test_unknown_kind_is_a_usage_error_naming_the_allowed_ones(tmp_path, capsys, spec, words):
    r = run_cli(capsys, "identify", spec, "--masses", "2", "-o", tmp_path / "x.json")
    assert r.returncode == 2
    assert all(w in r.stderr for w in words), r.stderr


def test_spec_prefers_an_existing_file_and_keeps_drive_letters(tmp_path):
    odd = tmp_path / "run:gauge"
    odd.write_text("")
    assert parse_measurement_spec(str(odd)) == MeasurementSpec(str(odd))
    assert parse_measurement_spec(f"{odd}:actuator") == MeasurementSpec(str(odd), "actuator")
    missing = lambda _path: False  # noqa: E731
    assert parse_measurement_spec("C:\\data\\g.csv", is_file=missing) == MeasurementSpec("C:\\data\\g.csv")
    assert parse_measurement_spec("C:\\data\\g.csv:Gauge:free", is_file=missing) == MeasurementSpec(
        "C:\\data\\g.csv", "gauge", "free")
    assert parse_measurement_spec("d:v2/c.csv::clamped", is_file=missing) == MeasurementSpec(
        "d:v2/c.csv", None, "clamped")


def test_continuous_with_sample_time_is_a_usage_error(files, tmp_path, capsys):
    r = run_cli(capsys, "identify", files["ts"], "--masses", "3", "--continuous", "--sample-time", "0.001",
                "-o", tmp_path / "x.json")
    assert r.returncode == 2 and "--continuous" in r.stderr


def five_masses() -> Device:
    return Device(masses=np.array([0.1, 0.3, 0.25, 0.4, 0.2]), stiffnesses=np.array([4e4, 9e4, 1.2e5, 7e4]),
                  dampings=np.array([1.0, 2.0, 1.5, 2.5]), ground_dampings=np.array([0, 0, 0, 0, 3.0]),
                  sample_time=T)


@pytest.mark.numerics  # fits: run under the second OpenBLAS kernel too
def test_more_than_four_masses_prints_estimate_and_progress(tmp_path, capsys):
    dev = five_masses()
    a = write_frf(tmp_path / "a5.csv", device=dev, points=200)
    g = write_frf(tmp_path / "g5.csv", "gauge", device=dev, points=200)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = run_cli(capsys, "identify", a, f"{g}:gauge", "--masses", "5", "--sample-time", "0.001",
                    "-o", tmp_path / "five.json")
    assert r.returncode == 0, r.stderr
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)]  # none to reach stderr
    assert "fitting 5 masses to 400 points takes about" in r.stderr and "Ctrl-C cancels" in r.stderr
    assert "model evaluations (100 %)" in r.stderr
    np.testing.assert_allclose(load_profile(tmp_path / "five.json").device.masses, dev.masses, rtol=1e-4)


def test_four_masses_print_no_progress(files, tmp_path, capsys):
    r = run_cli(capsys, "identify", files["a"], f"{files['g']}:gauge", "--masses", "3", "--sample-time", "0.001",
                "-o", tmp_path / "three.json")
    assert r.returncode == 0 and "model evaluations" not in r.stderr


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process is POSIX")
def test_ctrl_c_cancels_cleanly(tmp_path):
    rng = np.random.default_rng(0)
    dev = Device(masses=rng.uniform(0.1, 0.5, 6), stiffnesses=rng.uniform(2e4, 2e5, 5),
                 dampings=rng.uniform(0.5, 3.0, 5), ground_dampings=np.array([0, 0, 0, 0, 0, 3.0]), sample_time=T)
    a = write_frf(tmp_path / "a6.csv", device=dev, points=400, noise=0.005, seed=1)
    g = write_frf(tmp_path / "g6.csv", "gauge", device=dev, points=400, noise=0.005, seed=2)
    out = tmp_path / "never.json"
    proc = subprocess.Popen([sys.executable, "-m", "app.cli", "identify", str(a), f"{g}:gauge", "--masses", "6",
                             "--sample-time", "0.001", "-o", str(out)], cwd=ROOT, env=environment(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = proc.stderr.readline()  # the estimate: the fit starts now
        assert "fitting 6 masses" in first, first
        time.sleep(0.5)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    assert proc.returncode == 130, err
    assert "Traceback" not in err and "cancelled; nothing written" in err
    assert not out.exists() and not any(p.name.startswith("never") for p in tmp_path.iterdir())
