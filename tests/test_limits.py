"""Physical ranges and work limits (analysis.chain.limits): one rule, the same refusal from the API,
the loader and the settings records, checked before anything is allocated (issue 13)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from analysis import AdmittanceDisplay, Device, ImpedanceDisplay, ValidationError
from analysis.chain.limits import (
    LIMITS,
    MASS,
    MAX_MASSES,
    MAX_SIMULATION_STEPS,
    SAMPLE_TIME,
    STIFFNESS,
    check_simulation_size,
)
from analysis.profiles.errors import ProfileError, element_label
from analysis.profiles.io import bundled_profiles, load_profile, profile_from_dict
from analysis.sampled import SimulationOptions, scenario, simulate
from analysis.study import (
    derived_wall_settings,
    observer_device_label,
    observer_settings,
    wall_device_label,
    wall_settings,
    wall_tradeoff,
)
from analysis.transparency.settings import ObserverSettings, WallSettings


def hbfd_dict() -> dict:
    return json.loads(bundled_profiles()["hbfd"].read_text())


# -- one rule, one message --------------------------------------------------------------------------

def test_the_envelope_of_the_stress_tests_is_inside_the_limits():
    """tests/test_stress.py's ranges (masses 1e-4..1e3 and a 1e-6 kg handle, k 1..1e9, T 1e-5..0.1,
    eq. 28 dampings up to 2·10·sqrt(1e9·500)) all pass; a decade beyond does not."""
    for x in (1e-6, 1e-4, 1e3):
        assert MASS.contains(x)
    for x in (1.0, 1e9):
        assert STIFFNESS.contains(x)
    assert LIMITS["dampings"].contains(2 * 10 * math.sqrt(1e9 * 500)) and LIMITS["dampings"].contains(0.0)
    for x in (1e-6, 1e-5, 0.1, 1.0):
        assert SAMPLE_TIME.contains(x)
    for x in (1e-7, 2.0, 0.0, -1e-3, math.nan, math.inf):
        assert not SAMPLE_TIME.contains(x)
    assert not MASS.contains(1e4) and not STIFFNESS.contains(1e10)


@pytest.mark.parametrize("T", [1e-6, 1.0])
def test_the_ends_of_the_sample_time_range_keep_the_numerics_clean(T):
    """The stress test's checks (tests/test_stress.py) on random chains at T = 1 µs and T = 1 s."""
    rng = np.random.default_rng(11)
    for _ in range(6):
        n = int(rng.integers(1, 8))
        m, k, z = 10 ** rng.uniform(-4, 3, n), 10 ** rng.uniform(0, 9, n - 1), 10 ** rng.uniform(-5, 1, n - 1)
        g = np.zeros(n)
        g[int(rng.integers(0, n))] = 10 ** rng.uniform(-3, 3)
        dev = Device.from_damping_ratios(m, k, z, ground_dampings=g, sample_time=T,
                                         band_min=min(1.0, 0.1 * np.pi / T))
        w = np.geomspace(1e-5, dev.nyquist * (1 - 1e-7), 60)
        kp = 0.3 * float(dev.stiffnesses.min()) if n > 1 else 1e3
        with np.errstate(over="raise", invalid="raise", divide="raise"):
            imp = ImpedanceDisplay(dev)
            br, res = imp.bound_result(w), imp.evaluate(1e3, 10.0, w)
            adm = AdmittanceDisplay(dev, kp, 0.1 * math.sqrt(kp * dev.masses[-1])).evaluate(1.0, 100.0, w)
        assert not np.any(np.isnan(br.bound)) and np.all(br.re_p11 >= 0.0)
        assert not np.any(np.isnan(res.margin)) and not np.any(np.isnan(adm.margin))


def test_sample_time_is_refused_the_same_way_by_device_loader_and_records():
    text = SAMPLE_TIME.text
    assert text == "> 0 and finite, within the physical range [1e-06, 1] (s)"
    with pytest.raises(ValidationError) as api:
        Device(masses=[1.0], sample_time=1e-12)
    assert str(api.value) == f"sample_time = 1e-12 is invalid: allowed range is {text}"
    d = hbfd_dict()
    d["sample_time"] = 1e-12
    with pytest.raises(ProfileError) as loader:
        profile_from_dict(d, path="hbfd.json")
    assert str(loader.value) == f"hbfd.json: $.sample_time: expected a number {text}, got 1e-12"
    with pytest.raises(ValidationError) as wall:
        WallSettings(sample_time=1e-12)
    assert wall.value.allowed == text
    p = load_profile(bundled_profiles()["hbfd"])
    with pytest.raises(ValidationError) as gui:  # the GUI edits through Device.replace
        p.device.replace(sample_time=1e-7)
    assert gui.value.allowed == text


@pytest.mark.parametrize("field, value, rng", [
    ("kc", 2e9, "[0, 1e+09] (N/m)"), ("bc", 2e8, "[0, 1e+08] (N s/m)"), ("mc", 2e3, "[1e-06, 1000] (kg)"),
    ("kp", 1e10, "[0, 1e+09] (N/m)"), ("kd", -1.0, "[0, 1e+08] (N s/m)"),
])
def test_profile_gains_have_physical_ranges(field, value, rng):
    p = load_profile(bundled_profiles()["hbfd"])
    with pytest.raises(ValidationError) as info:
        p.replace(**{field: value})
    assert info.value.field == field and info.value.allowed.endswith(f"within the physical range {rng}")
    assert p.replace(kc=2e7).kc == 2e7  # beyond the GUI slider (1e7), inside the physical range


def test_element_errors_name_the_gui_element():
    d = hbfd_dict()
    d["device"]["masses"][2] = 5e3
    with pytest.raises(ProfileError) as info:
        profile_from_dict(d)
    assert str(info.value) == ("$.device.masses[2] (mass 3): expected a number > 0 and finite, within the "
                               "physical range [1e-06, 1000] (kg), got 5000.0")
    assert element_label("$.device.stiffnesses[0]") == "element 1"
    assert element_label("$.device.ground_dampings[3]") == "ground damping of mass 4"
    assert element_label("$.sample_time") == ""


def test_chain_length_is_bounded():
    n = MAX_MASSES + 1
    with pytest.raises(ValidationError, match="at most 500 masses"):
        Device(masses=np.full(n, 0.1), stiffnesses=np.full(n - 1, 1e4), dampings=np.zeros(n - 1))


# -- work limits ------------------------------------------------------------------------------------

def test_simulation_size_is_checked_before_allocation():
    assert check_simulation_size(2.0, 1e-3, 2, 4) == 2001
    assert check_simulation_size(2.0, 1e-6, 2, 4) == 2_000_001  # 2 s at 1 µs with 2 substeps fits
    with pytest.raises(ValidationError) as info:
        check_simulation_size(3600.0, 1e-6, 1, 4)
    assert info.value.field == "simulation steps" and info.value.value == 3_600_000_001
    assert f"at most {MAX_SIMULATION_STEPS:g} simulation steps" in info.value.allowed
    dev = Device(masses=[0.5], ground_dampings=[2.0], sample_time=1e-6)
    with pytest.raises(ValidationError, match="simulation steps"):  # 20 s at 1 µs, refused at once
        simulate(dev, scenario("free_sliding"), 20.0)


def test_a_saved_scenario_that_is_too_long_is_refused_by_the_loader():
    d = hbfd_dict()
    d["simulation"]["scenario"]["duration"] = 3000.0
    with pytest.raises(ProfileError) as info:
        profile_from_dict(d)
    assert info.value.json_path == "$.simulation.scenario.duration"
    assert "at most 5e+06 simulation steps" in str(info.value)
    assert "3000 s / 0.001 s" in str(info.value)


def test_options_and_scenarios_use_the_same_ranges():
    with pytest.raises(ValidationError) as info:
        scenario("wall_push", object_mass=1e4)
    assert info.value.allowed == MASS.text
    assert SimulationOptions().substeps == 2


# -- the wall and observer tabs analyse the profile's own device --------------------------------------

@pytest.mark.parametrize("name, mass, bc", [("hbfd", 5.0, 7638.11), ("rigid", 0.5, 763.183)])
def test_a_profile_without_wall_section_gets_its_own_device(name, mass, bc):
    p = load_profile(bundled_profiles()[name])
    assert p.wall is None
    st = wall_settings(p)
    assert st == derived_wall_settings(p) and st.mass == mass and st.sample_time == p.device.sample_time
    assert st.damping == p.device.total_ground_damping
    trade = wall_tradeoff(p)
    assert np.all(np.isfinite(trade.curves.index)) and np.all(np.isfinite(trade.curves.peak))
    o = trade.optimum
    assert o.feasible and math.isfinite(o.bc) and o.bc == pytest.approx(bc, rel=1e-4)
    assert st.bc_min < o.bc < st.bc_max and o.peak <= 1.0  # robust, inside the range
    assert p.name in wall_device_label(p) and "rigid body" in wall_device_label(p)
    ob = observer_settings(p)
    assert (ob.nominal_mass, ob.nominal_damping) == (mass, p.device.total_ground_damping)
    assert p.name in observer_device_label(p)


def test_a_profile_with_wall_section_keeps_it():
    p = load_profile(bundled_profiles()["eom"])
    assert wall_settings(p) is p.wall and observer_settings(p) is p.observer
    assert wall_device_label(p).startswith("Device: a rigid handle of m = 0.01 kg")
    assert ObserverSettings().nominal_mass == 0.01
