"""Chain fit of analysis.identify: recovery from the automatic start, fixed parameters, order
selection and identifiability (noise-free and 1 % noise, HBFD at 1 kHz)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analysis import Device, ValidationError
from analysis.identify import (
    ChainFit,
    ChainParameters,
    FitProblem,
    Measurement,
    device_response,
    device_value,
    fit_chain,
    load_measurement,
    make_measurement,
    order_selection,
)

from tests.hbfd_fixtures import make_hbfd

pytestmark = pytest.mark.numerics

T = 1e-3
W = np.geomspace(1.0, 0.95 * math.pi / T, 400)  # 400 log-spaced points, 1 rad/s .. 0.95 Nyquist


def _measure(device: Device, quantity="actuator", boundary="free", noise=0.0, seed=0, sample_time=T):
    h = device_response(device, W, quantity, boundary, sample_time=sample_time)
    if noise:
        rng = np.random.default_rng(seed)
        h = h * (1 + noise * (rng.normal(size=W.size) + 1j * rng.normal(size=W.size)) / math.sqrt(2))
    return make_measurement(W, h, quantity, boundary, sample_time=sample_time)


def _rel_errors(fit: ChainFit, device: Device) -> np.ndarray:
    return np.array([fit.value(k) / device_value(device, k) - 1 for k in fit.keys])


def test_noise_free_hbfd_every_parameter_recovered_from_the_automatic_start():
    d = make_hbfd()
    fit = fit_chain([_measure(d)], n_masses=4, ground_dampings=(3,))
    assert fit.keys == ("masses[0]", "masses[1]", "masses[2]", "masses[3]", "stiffnesses[0]", "stiffnesses[1]",
                        "stiffnesses[2]", "dampings[0]", "dampings[1]", "dampings[2]", "ground_dampings[3]")
    assert np.max(np.abs(_rel_errors(fit, d))) < 1e-6
    assert fit.converged and fit.residual < 1e-8
    assert isinstance(fit.device, Device) and fit.device.sample_time == T and fit.device.sensor_element == 0
    np.testing.assert_allclose(fit.device.ground_dampings, [0, 0, 0, 5.0], rtol=1e-6)
    assert set(fit.intervals) == set(fit.keys)
    assert len(fit.responses) == 1 and fit.responses[0].shape == (400,)
    np.testing.assert_allclose(fit.responses[0], fit.measurements[0].response, rtol=1e-7)


def test_fixed_parameter_and_continuous_plus_clamped_measurements():
    d = make_hbfd()
    ms = [_measure(d, sample_time=None), _measure(d, "actuator", "clamped", sample_time=None)]
    fit = fit_chain(ms, 4, ground_dampings=(3,), fixed={"masses[0]": 0.2})
    j = fit.keys.index("masses[0]")
    assert fit.fixed[j] and fit.values[j] == 0.2 and fit.intervals["masses[0]"] == (0.2, 0.2)
    assert "masses[0]" not in fit.free_keys and fit.covariance.shape == (10, 10)
    assert np.max(np.abs(_rel_errors(fit, d))) < 1e-6
    np.testing.assert_allclose(np.diag(fit.correlation), 1.0)


@pytest.mark.parametrize("key", ["masses[0]", "masses[2]", "masses[3]", "stiffnesses[0]", "stiffnesses[2]",
                                 "dampings[1]", "ground_dampings[3]"])
def test_any_parameter_fixed_at_its_true_value_recovers_every_other_from_the_automatic_start(key):
    # The data-derived start knows nothing of the fixed value; pasted into it, a fixed handle mass
    # once moved the hidden handle mode away and the fit landed at stiffnesses[0] = 83 kN/m.
    d = make_hbfd()
    fit = fit_chain([_measure(d)], 4, ground_dampings=(3,), fixed={key: device_value(d, key)})
    assert fit.fixed[fit.keys.index(key)] and fit.value(key) == device_value(d, key)
    assert len(fit.free_keys) == 10 and key not in fit.free_keys
    assert np.max(np.abs(_rel_errors(fit, d))) < 1e-6
    assert fit.converged and fit.residual < 1e-8


def _truth_residual(device: Device, m: Measurement, keys: tuple[str, ...]) -> float:
    """The fit's residual (RMS of the weighted real residuals) of the true device on ``m``: the noise floor."""
    problem = FitProblem((m,), keys, ChainParameters.from_device(device), 0)
    return float(np.sqrt(np.mean(problem.residual(np.log([device_value(device, k) for k in keys])) ** 2)))


def test_a_fixed_handle_mass_at_one_percent_noise_still_fits_to_the_noise_floor():
    # The released fit places the (non-identifiable) handle mode with a tiny mass; putting the
    # known mass back rescales the handle side so that the mode stays where the data put it.
    # The floor is the true device's residual on the same data, not another optimizer run (which
    # optimum a free fit reaches depends on the BLAS kernel, issue 21): least squares over 10 free
    # parameters must fit at least as well as the truth (about 10 s^2 of 790 below it, 0.6 % in
    # the RMS; measured 0.8 % below on every kernel).
    d = make_hbfd()
    m = _measure(d, noise=0.01, seed=5)
    for mass in (0.2, 0.25):
        fit = fit_chain([m], 4, ground_dampings=(3,), fixed={"masses[0]": mass}, intervals="wald")
        assert fit.residual <= _truth_residual(d, m, fit.keys)
        assert fit.value("stiffnesses[2]") == pytest.approx(874e3, rel=0.01)


def test_the_issues_api_example_with_a_fixed_handle_mass(tmp_path):
    d = make_hbfd()
    h = device_response(d, W, "actuator", "free", sample_time=T)
    rows = [f"{float(a)!r},{float(b.real)!r},{float(b.imag)!r}" for a, b in zip(W, h)]
    path = tmp_path / "frf.csv"
    path.write_text("frequency_rad_s,real,imag\n" + "\n".join(rows) + "\n")
    m = load_measurement(path, quantity="actuator", boundary="free", sample_time=1e-3, delay_samples=0)
    fit = fit_chain([m], n_masses=4, ground_dampings=(3,), fixed={"masses[0]": 0.2})
    np.testing.assert_allclose(fit.device.masses, [0.2, 2.3, 2.0, 0.5], rtol=1e-6)
    np.testing.assert_allclose(fit.device.stiffnesses, [130e3, 84e3, 874e3], rtol=1e-6)
    np.testing.assert_allclose(fit.device.dampings, d.dampings, rtol=1e-6)
    np.testing.assert_allclose(fit.device.ground_dampings, [0, 0, 0, 5.0], rtol=1e-6)
    assert fit.intervals["masses[0]"] == (0.2, 0.2)
    lo, hi = fit.intervals["stiffnesses[0]"]
    assert lo <= 130e3 <= hi


def test_order_selection_picks_four_masses():
    d = make_hbfd()
    sel = order_selection([_measure(d, noise=1e-3, seed=3)], max_masses=4, min_masses=2)
    assert list(sel.n) == [2, 3, 4]
    assert sel.best_bic == 4
    assert sel.residual[0] > sel.residual[1] > sel.residual[2]
    assert sel.residual[2] == pytest.approx(1e-3 / math.sqrt(2), rel=0.15)  # the noise level per component
    assert np.all(np.diff(sel.aic) < 0)


def test_handle_side_is_not_identifiable_from_the_actuator_alone_and_the_fit_says_so():
    # The HBFD handle mode nearly cancels at the actuator (pole 842.45, zero 842.72 rad/s); at 1 %
    # noise the actuator FRF cannot place it.  The actuator-side parameters stay well determined.
    d = make_hbfd()
    flagged, covered = 0, np.zeros(11)
    reps = 4
    for seed in range(reps):
        # Wald intervals (fast); the default's profile intervals: test_identify_intervals.py
        fit = fit_chain([_measure(d, noise=0.01, seed=100 + seed)], 4, ground_dampings=(3,), intervals="wald")
        tv = np.array([device_value(d, k) for k in fit.keys])
        covered += (fit.lower <= tv) & (tv <= fit.upper)
        hs = {"masses[0]", "stiffnesses[0]", "dampings[0]"} & set(fit.non_identifiable)
        if hs:
            flagged += 1
            key = sorted(hs)[0]
            assert "clamped" in fit.suggestions[key] or "gauge" in fit.suggestions[key]
            assert any(key in w for w in fit.warnings)
    assert flagged >= reps - 1
    actuator_side = [fit.keys.index(k) for k in ("masses[3]", "stiffnesses[2]", "dampings[2]", "ground_dampings[3]")]
    assert np.all(covered[actuator_side] >= reps - 1)


def test_bad_arguments():
    m = _measure(make_hbfd())
    with pytest.raises(ValidationError):
        fit_chain([], 4)
    with pytest.raises(ValidationError):
        fit_chain([m], 0)
    with pytest.raises(ValueError, match="masses\\[7\\]"):
        fit_chain([m], 4, fixed={"masses[7]": 1.0})
    with pytest.raises(ValidationError):
        fit_chain([m], 4, ground_dampings=(4,))
