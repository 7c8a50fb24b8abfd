"""Measurement files and Welch FRF estimation of analysis.identify."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

from analysis.chain import chain_state_space, discretize_zoh
from analysis.identify import MeasurementError, device_response, estimate_frf, load_measurement

from tests.hbfd_fixtures import make_hbfd

T = 1e-3
W = np.geomspace(1.0, 0.95 * math.pi / T, 50)


def rf(x) -> str:
    """Round-trip text of a float (numpy scalars included)."""
    return repr(float(x))


def _write(path, header, rows):
    lines = [",".join(header)] + [",".join(str(v) for v in r) for r in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def _h():
    return device_response(make_hbfd(), W, sample_time=T)


def test_three_response_forms_and_both_frequency_units_load_the_same(tmp_path):
    h = _h()
    coh = np.linspace(0.5, 1.0, W.size)
    a = _write(tmp_path / "a.csv", ["frequency_hz", "real", "imag", "coherence"],
               [(rf(w / (2 * math.pi)), rf(x.real), rf(x.imag), rf(c)) for w, x, c in zip(W, h, coh)])
    b = _write(tmp_path / "b.csv", ["frequency_rad_s", "magnitude", "phase_deg"],
               [(rf(w), rf(abs(x)), rf(math.degrees(np.angle(x)))) for w, x in zip(W, h)])
    c = _write(tmp_path / "c.csv", ["frequency_rad_s", "magnitude_db", "phase_deg"],
               [(rf(w), rf(20 * math.log10(abs(x))), rf(math.degrees(np.angle(x)))) for w, x in zip(W, h)])
    for path in (a, b, c):
        m = load_measurement(path, quantity="actuator", boundary="free", sample_time=T, delay_samples=0)
        np.testing.assert_allclose(m.frequency, W, rtol=1e-13)
        np.testing.assert_allclose(m.response, h, rtol=1e-12)
        assert m.sample_time == T and m.quantity == "actuator" and m.source == str(path)
    np.testing.assert_allclose(load_measurement(a).coherence, coh)
    assert load_measurement(b).coherence is None


def _frf_rows(n=12):
    return [[f"{w:.6g}", "1e-3", "-2e-4"] for w in np.geomspace(1, 100, n)]


@pytest.mark.parametrize("edit,line,column,words", [
    (lambda r: r[3].__setitem__(2, "abc"), 5, "imag", "not a number"),
    (lambda r: r[6].__setitem__(1, "nan"), 8, "real", "not finite"),
    (lambda r: r[4].__setitem__(0, "0.5"), 6, "frequency_rad_s", "increase strictly"),
    (lambda r: r[0].__setitem__(0, "-1"), 2, "frequency_rad_s", "> 0"),
])
def test_bad_values_name_file_line_and_column(tmp_path, edit, line, column, words):
    rows = _frf_rows()
    edit(rows)
    path = _write(tmp_path / "bad.csv", ["frequency_rad_s", "real", "imag"], rows)
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    e = exc.value
    assert (e.file, e.line, e.row, e.column) == (str(path), line, line - 1, column)
    msg = str(e)
    assert str(path) in msg and f"line {line} (data row {line - 1})" in msg and repr(column) in msg and words in msg


@pytest.mark.parametrize("header,column,words", [
    (["frequency_hz", "frequency_rad_s", "real", "imag"], "frequency_rad_s", "mixed units"),
    (["frequency_hz", "real", "imag", "magnitude"], "magnitude", "mixed response forms"),
    (["frequency_hz", "real"], "imag", "missing"),
    (["frequency_hz", "real", "imaginary"], "imaginary", "unknown column"),
    (["frequency_hz", "magnitude_db"], "phase_deg", "missing"),
])
def test_bad_headers_are_refused(tmp_path, header, column, words):
    rows = [[f"{w:.6g}"] + ["1e-3"] * (len(header) - 1) for w in np.geomspace(1, 100, 12)]
    path = _write(tmp_path / "h.csv", header, rows)
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert exc.value.column == column and exc.value.line == 1 and words in str(exc.value)
    assert str(path) in str(exc.value)


def test_too_few_points_row_length_and_comments(tmp_path):
    path = _write(tmp_path / "few.csv", ["frequency_rad_s", "real", "imag"], _frf_rows(5))
    with pytest.raises(MeasurementError, match="at least 8"):
        load_measurement(path)
    rows = _frf_rows()
    rows[2] = rows[2][:2]
    path = _write(tmp_path / "short.csv", ["frequency_rad_s", "real", "imag"], rows)
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert exc.value.line == 4 and exc.value.column is None
    # comment and blank lines are skipped but counted
    text = "# measured 2026-12-01\n\n" + (tmp_path / "few.csv").read_text()
    (tmp_path / "c.csv").write_text(text.replace("1e-3,-2e-4", "x,-2e-4", 1))
    with pytest.raises(MeasurementError) as exc:
        load_measurement(tmp_path / "c.csv")
    assert exc.value.line == 4 and exc.value.column == "real"
    with pytest.raises(MeasurementError, match="cannot read"):
        load_measurement(tmp_path / "missing.csv")


def _simulate(device, seconds: float, seed: int = 0):
    """Force held by a ZOH, sampled actuator position: exact discrete model, scipy.signal.dlsim."""
    A, B = chain_state_space(device)
    Phi, Gam = discretize_zoh(A[0], -B[0][:, :1], T)
    C = np.zeros((1, A.shape[-1]))
    C[0, device.n - 1] = 1.0
    n = int(round(seconds / T))
    u = np.random.default_rng(seed).normal(0.0, 10.0, n)
    _, y, _ = signal.dlsim((Phi, Gam, C, np.zeros((1, 1)), T), u)
    return np.arange(n) * T, u, y[:, 0]


def test_estimate_frf_recovers_the_sampled_response_where_coherence_is_high():
    d = make_hbfd()
    t, f, x = _simulate(d, 30.0)
    m = estimate_frf(t, f, x, quantity="actuator", boundary="free", sample_time=T)
    assert m.coherence is not None and m.sample_time == T
    true = device_response(d, m.frequency, sample_time=T)
    good = m.coherence > 0.99
    assert np.count_nonzero(good) > 0.8 * m.size
    err = np.abs(m.response[good] / true[good] - 1)
    assert np.median(err) < 5e-3 and np.max(err) < 0.05
    # user segment length: resolution fs / nperseg
    m2 = estimate_frf(t, f, x, sample_time=T, nperseg=512, noverlap=128)
    assert m2.frequency[0] == pytest.approx(2 * math.pi * 1000.0 / 512)


def test_time_series_file_goes_through_welch_and_bad_time_is_refused(tmp_path):
    d = make_hbfd()
    t, f, x = _simulate(d, 4.0, seed=1)
    rows = [(rf(a), rf(b), rf(c)) for a, b, c in zip(t, f, x)]
    path = _write(tmp_path / "ts.csv", ["time_s", "force_n", "position_m"], rows)
    m = load_measurement(path, sample_time=T, nperseg=256)
    assert m.coherence is not None and m.size == 127
    with pytest.raises(MeasurementError, match="uniform"):
        estimate_frf(np.r_[t[:100], t[100:] + 1e-4], f, x, sample_time=T)
    with pytest.raises(MeasurementError, match="differs from sample_time"):
        estimate_frf(t, f, x, sample_time=2e-3)
    rows[10] = (rows[10][0], "inf", rows[10][2])
    path = _write(tmp_path / "ts2.csv", ["time_s", "force_n", "position_m"], rows)
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert exc.value.line == 12 and exc.value.column == "force_n"
