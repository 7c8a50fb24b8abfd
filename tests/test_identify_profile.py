"""The profile's optional ``identification`` section (schema 4): round trip, migration, strict
validation with JSON paths, and the robust designs computed from it (issue 14)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from analysis.identify import device_response, make_measurement
from analysis.profiles import ProfileError, load_profile, profile_from_dict, profile_to_dict, save_profile
from analysis.profiles.identification import IdentificationSection, MeasurementData
from analysis.resources import resource_path
from analysis.study.identify import fit_curves, profile_with_fit, robust_designs, section_measurements
from analysis.identify import fit_chain

HBFD = resource_path("profiles", "hbfd.json")


def hbfd():
    return load_profile(HBFD)


def measurement_data(coherence: bool = True) -> MeasurementData:
    d = hbfd().device
    w = np.logspace(0, 3, 40)
    h = device_response(d, w, "actuator", "free", d.sample_time, 1)
    coh = np.linspace(0.5, 0.99, 40) if coherence else None
    return MeasurementData(w, h, "actuator", "free", d.sample_time, 1, coh, "frf.csv")


def with_section(**changes) -> dict:
    d = profile_to_dict(hbfd().replace(identification=IdentificationSection(
        {"ground_dampings[3]": (1.2, 5.0), "masses[0]": (0.19, 0.21)}, (measurement_data(),))))
    d["identification"].update(changes)
    return d


def test_round_trip_keeps_every_number(tmp_path):
    p = profile_from_dict(with_section())
    assert profile_to_dict(p)["schema_version"] == 7
    save_profile(p, tmp_path / "p.json")
    q = load_profile(tmp_path / "p.json")
    assert q == p
    sec = q.identification
    assert sec.intervals == {"ground_dampings[3]": (1.2, 5.0), "masses[0]": (0.19, 0.21)}
    m, ref = sec.measurements[0], measurement_data()
    np.testing.assert_array_equal(m.frequency, ref.frequency)
    np.testing.assert_array_equal(m.response, ref.response)  # JSON floats round-trip exactly
    np.testing.assert_array_equal(m.coherence, ref.coherence)
    assert (m.quantity, m.boundary, m.sample_time, m.delay_samples, m.source) == ("actuator", "free", 0.001, 1,
                                                                                  "frf.csv")


def test_the_fit_notes_round_trip_and_are_left_out_when_empty(tmp_path):
    assert "notes" not in with_section()["identification"]
    p = profile_from_dict(with_section(notes=["the handle mode is not detected", "masses[0] is loose"]))
    assert p.identification.notes == ("the handle mode is not detected", "masses[0] is loose")
    save_profile(p, tmp_path / "n.json")
    assert load_profile(tmp_path / "n.json") == p
    assert profile_to_dict(p)["identification"]["notes"] == ["the handle mode is not detected", "masses[0] is loose"]


def test_old_schemas_load_without_the_section():
    for version in (1, 2, 3):
        d = profile_to_dict(hbfd())
        d["schema_version"] = version
        p = profile_from_dict(d)
        assert p.identification is None and p == hbfd()
    assert json.loads(HBFD.read_text())["schema_version"] == 3  # the bundled presets are schema 3 files


@pytest.mark.parametrize(("change", "json_path", "text"), [
    ({"intervals": {"masses[9]": [1, 2]}}, '$.identification.intervals["masses[9]"]', "index 9 is outside"),
    ({"intervals": {"mass[0]": [1, 2]}}, "$.identification.intervals.mass[0]", "unknown parameter key"),
    ({"intervals": {"masses[0]": [2, 1]}}, '$.identification.intervals["masses[0]"][1]', "got 1"),
    ({"intervals": {"masses[0]": [-1, 1]}}, '$.identification.intervals["masses[0]"][0]', "got -1"),
    ({"intervals": {"masses[0]": ["inf", 1]}}, '$.identification.intervals["masses[0]"][0]', ">= 0 and finite"),
    ({"intervals": {"masses[0]": [1, "big"]}}, '$.identification.intervals["masses[0]"][1]', 'or "inf"'),
    ({"intervals": {"masses[0]": [1]}}, '$.identification.intervals["masses[0]"]', "[low, high]"),
    ({"extra": 1}, "$.identification.extra", "unknown key"),
    ({"notes": "one line"}, "$.identification.notes", "a list of strings"),
    ({"notes": ["ok", 3]}, "$.identification.notes[1]", "a string"),
])
def test_bad_intervals_name_the_json_path(change, json_path, text):
    with pytest.raises(ProfileError) as info:
        profile_from_dict(with_section(**change))
    assert info.value.json_path == json_path
    assert text in str(info.value)


def _bad_measurement(key: str, value) -> dict:
    d = with_section()
    d["identification"]["measurements"][0][key] = value
    return d


@pytest.mark.parametrize(("key", "value", "json_path"), [
    ("frequency", lambda f: f[:3] + [f[1]] + f[4:], "$.identification.measurements[0].frequency[3]"),
    ("real", lambda r: r[:5] + ["x"] + r[6:], "$.identification.measurements[0].real[5]"),
    ("imag", lambda r: r[:-1], "$.identification.measurements[0].imag"),
    ("coherence", lambda c: c[:2] + [1.5] + c[3:], "$.identification.measurements[0].coherence[2]"),
    ("quantity", lambda q: "velocity", "$.identification.measurements[0].quantity"),
    ("boundary", lambda q: "held", "$.identification.measurements[0].boundary"),
    ("sample_time", lambda t: 0.1, "$.identification.measurements[0].frequency[39]"),  # above Nyquist
    ("delay_samples", lambda d: -1, "$.identification.measurements[0].delay_samples"),
    ("units", lambda d: "Hz", "$.identification.measurements[0].units"),
])
def test_bad_measurement_names_the_json_path(key, value, json_path):
    d = with_section()
    m = d["identification"]["measurements"][0]
    m[key] = value(m.get(key))
    with pytest.raises(ProfileError) as info:
        profile_from_dict(d)
    assert info.value.json_path == json_path


def test_fit_to_profile_and_the_embedded_measurements_reproduce_the_fit():
    p = hbfd()
    d = p.device
    w = np.logspace(0, np.log10(0.95 * np.pi / d.sample_time), 400)
    m = make_measurement(w, device_response(d, w, "actuator", "free", d.sample_time), "actuator", "free",
                         d.sample_time, source="/somewhere/frf.csv")
    fit = fit_chain([m], 4, ground_dampings=(3,))
    q = profile_from_dict(profile_to_dict(profile_with_fit(p, fit, [m])))
    np.testing.assert_allclose(q.device.masses, d.masses, rtol=1e-6)
    np.testing.assert_allclose(q.device.ground_dampings, d.ground_dampings, rtol=1e-6, atol=1e-9)
    assert set(q.identification.intervals) == set(fit.keys)
    assert q.identification.measurements[0].source == "frf.csv"
    assert q.identification.notes == fit.warnings
    (back,) = section_measurements(q.identification)
    np.testing.assert_array_equal(back.response, m.response)
    (mm, model), = fit_curves(q)
    assert np.max(np.abs(model / mm.response - 1)) < 1e-6


def test_robust_designs_of_the_seed_case():
    """HBFD, b4 = ground_dampings[3] in [1.2, 5], b_c = 100: robust k_c 49.15 kN/m (the b4 = 1.2
    value), nominal 117.1 kN/m; the profile's k_c = 50 kN/m does not hold for the whole box."""
    p = hbfd().replace(identification=IdentificationSection({"ground_dampings[3]": (1.2, 5.0)}))
    assert p.bc == 100.0
    r = robust_designs(p)
    assert r.stiffness.kc == pytest.approx(49.15e3, rel=1e-3)
    assert r.stiffness.nominal_kc == pytest.approx(117.1e3, rel=1e-3)
    assert r.stiffness.binding == {"ground_dampings[3]": pytest.approx(1.2)}
    assert r.holds is False
    assert "does NOT hold" in r.verdict() and "49149 N/m" in r.verdict()
    ok = robust_designs(p.replace(kc=40e3))
    assert ok.holds is True and "k_c = 40000 N/m holds" in ok.verdict()


def test_robust_designs_admittance_interval_contains_current_damping_or_not():
    p = hbfd().replace(display="admittance", identification=IdentificationSection({"ground_dampings[3]": (1.2, 5.0)}))
    r = robust_designs(p)
    assert r.damping is not None and not r.impedance
    assert r.holds == (r.damping.low is not None and r.damping.low <= p.bc_adm <= r.damping.high)
    assert robust_designs(hbfd()) is None  # no section, no robust designs


def test_unbounded_intervals_are_saved_as_zero_and_inf_and_refused_by_the_robust_designs(tmp_path):
    # a fit of the actuator FRF alone reports the handle side as (0, inf); the profile keeps that
    # (strict JSON has no Infinity: "inf", as elsewhere in the profile; saving used to fail), and the
    # robust designs name the open intervals instead of designing over a box that is not one
    section = IdentificationSection({"masses[0]": (0.0, math.inf), "stiffnesses[1]": (83.4e3, math.inf),
                                     "ground_dampings[3]": (4.9, 5.1)}, (measurement_data(),))
    p = hbfd().replace(identification=section)
    assert profile_to_dict(p)["identification"]["intervals"]["masses[0]"] == [0.0, "inf"]
    path = tmp_path / "unbounded.json"
    save_profile(p, path)
    assert "Infinity" not in path.read_text()
    q = load_profile(path)
    assert q.identification == section and q.identification.intervals["masses[0]"] == (0.0, math.inf)
    rd = robust_designs(q)
    assert rd.unbounded == ("masses[0]", "stiffnesses[1]") and not rd.holds
    assert rd.stiffness is None and rd.damping is None
    assert "do not bound masses[0], stiffnesses[1]" in rd.verdict()
    # a damping may be bounded below by 0 (no damper): a box edge, searched (with b4 = 0 eq. 9 then
    # admits no k_c at all), not an open interval
    ok = robust_designs(q.replace(identification=IdentificationSection({"ground_dampings[3]": (0.0, 5.0)}, ())))
    assert ok.unbounded == () and ok.stiffness is not None and ok.stiffness.kc is None

