"""The profile schema (issue 21): one declaration per field, JSON paths derived from where it sits;
saving unchanged byte for byte; lists indexed by mass checked against the device (issue 23)."""

from __future__ import annotations

import copy
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.profiles import (
    SCALAR_FIELDS,
    Profile,
    ProfileError,
    bundled_profiles,
    error_at,
    load_profile,
    path_of,
    per_mass_changes,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from analysis.profiles.schema import PER_MASS, PER_MASS_LISTS, SCHEMA, walk
from analysis.sampled import SimulationOptions, simulate

SAVED = Path(__file__).resolve().parent / "data" / "saved_profiles"


def hbfd_dict() -> dict:
    return json.loads(bundled_profiles()["hbfd"].read_text())


def three_masses(friction: list[float]) -> dict:
    """The HBFD's file with its last mass (and element) removed and the given friction list."""
    d = hbfd_dict()
    dev = d["device"]
    dev["masses"], dev["stiffnesses"] = dev["masses"][:3], dev["stiffnesses"][:2]
    dev["damping_ratios"], dev["ground_dampings"] = dev["damping_ratios"][:2], [0.0, 0.0, 5.0]
    d["simulation"]["options"]["friction"] = friction
    return d


# -- saving is unchanged, byte for byte -----------------------------------------------------------


@pytest.mark.parametrize("key", ["hbfd", "rigid", "eom"])
def test_saving_a_bundled_profile_writes_the_same_bytes_as_before(tmp_path, key):
    """The bundled files are hand-written schema-3 files (4-space indent, damping ratios), so a save
    cannot reproduce them; it reproduces what saving wrote before the schema rework."""
    save_profile(load_profile(bundled_profiles()[key]), tmp_path / "p.json")
    assert (tmp_path / "p.json").read_bytes() == (SAVED / f"{key}.json").read_bytes()


def test_a_file_with_every_section_loads_and_saves_to_the_same_bytes(tmp_path):
    p = load_profile(SAVED / "all_sections.json")
    assert None not in (p.wall, p.observer, p.simulation, p.identification, p.controller)
    save_profile(p, tmp_path / "again.json")
    assert (tmp_path / "again.json").read_bytes() == (SAVED / "all_sections.json").read_bytes()


# -- one declaration per field ----------------------------------------------------------------------


def test_every_key_saved_is_declared_and_every_declared_value_key_is_saved():
    saved = profile_to_dict(load_profile(SAVED / "all_sections.json"))
    top = {k for k in saved}
    assert top == set(SCHEMA.keys)  # every top-level key of a full file, no more
    assert set(saved["device"]) == set(SCHEMA.child("device").keys) - {"damping_ratios"}
    for path, node in walk():
        if node.kind in ("number", "numbers", "integer", "string", "choice") and node.key != "damping_ratios":
            value = saved
            for key in path.split(".")[1:]:
                value = value[key]  # KeyError: a declared path that the saved file does not have


def test_every_name_device_and_profile_can_refuse_has_a_json_path():
    device_names = [f.name for f in dataclasses.fields(Device)]
    profile_names = [f.name for f in dataclasses.fields(Profile)]
    for name in (*device_names, *profile_names, "cutoff", "simulation steps", "simulation values", "friction"):
        assert path_of(name) is not None and path_of(name).startswith("$"), name
    assert path_of("band_min") == "$.band.min" and path_of("kc") == "$.impedance_coupling.stiffness"
    assert path_of("friction") == "$.simulation.options.friction"
    assert {name: spec.json_path for name, spec in SCALAR_FIELDS.items()} == {
        "kc": "$.impedance_coupling.stiffness", "bc": "$.impedance_coupling.damping",
        "mc": "$.admittance_coupling.mass", "bc_adm": "$.admittance_coupling.damping",
        "kp": "$.pd_gains.stiffness", "kd": "$.pd_gains.damping"}


def test_an_api_error_is_reported_at_the_declared_path_with_range_and_unit():
    with pytest.raises(ValidationError) as info:
        Device(masses=[0.2, 2.0], stiffnesses=[1e5], dampings=[10.0], ground_dampings=[0.0, np.float64(-0.45)])
    err = error_at(info.value)
    assert err.json_path == "$.device.ground_dampings[1]"
    assert str(err) == ("$.device.ground_dampings[1] (ground damping of mass 2): expected a number >= 0 and "
                        "finite, within the physical range [0, 1000] (N s/m), got -0.45")
    assert error_at(ValidationError("kd", "x", -1.0)).json_path == "$.pd_gains.damping"
    # a name the schema does not declare: the profile as a whole, the name kept in the message
    odd = error_at(ValidationError("mystery", "> 0", -1.0))
    assert odd.json_path == "$" and "mystery > 0" in str(odd)


def test_an_element_damping_from_ratios_is_reported_at_damping_ratios():
    err = error_at(ValidationError("dampings", "x", 2e8, 0), {"dampings": "damping_ratios"})
    assert err.json_path == "$.device.damping_ratios[0]"
    assert error_at(ValidationError("dampings", "x", 2e8, 0)).json_path == "$.device.dampings[0]"


# -- lists indexed by mass (issue 23) -----------------------------------------------------------------


def test_the_per_mass_lists_of_the_sections_are_declared():
    assert [path for path, _ in PER_MASS_LISTS] == ["$.simulation.options.friction"]
    assert all(node.length == PER_MASS for _, node in PER_MASS_LISTS)


def test_a_friction_list_longer_than_the_device_is_refused_with_its_json_path():
    with pytest.raises(ProfileError) as info:
        profile_from_dict(three_masses([0.0, 1.0, 0.0, 0.5]), path="three.json")
    assert info.value.json_path == "$.simulation.options.friction"
    assert str(info.value) == (
        "three.json: $.simulation.options.friction: expected a list of exactly 3 values (one per mass, "
        "3 masses), each >= 0 and finite (N), or an empty list, got a list of 4 items")
    with pytest.raises(ProfileError, match=r"\$\.simulation\.options\.friction: expected a list of exactly 3"):
        profile_from_dict(three_masses([1.0]))


def test_what_loads_also_simulates():
    """The loader and the simulator agree: a friction list the loader accepts is one the simulation takes."""
    for friction in ([], [0.0, 1.0, 0.5]):
        p = profile_from_dict(three_masses(friction))
        assert p.simulation.options.friction == tuple(friction)
        result = simulate(p, p.simulation.scenario, 0.01, options=p.simulation.options)
        assert result.t.size == 11 and np.all(np.isfinite(result.positions))


def test_per_mass_changes_keep_friction_one_value_per_mass(tmp_path):
    p = load_profile(bundled_profiles()["hbfd"])
    assert p.simulation.options.friction == (0.0, 1.0, 0.0, 0.5)
    assert per_mass_changes(p, 4) == {}
    removed = per_mass_changes(p, 3, removed=1)["simulation"]
    assert removed.options.friction == (0.0, 0.0, 0.5) and removed.scenario == p.simulation.scenario
    added = per_mass_changes(p, 5)["simulation"]
    assert added.options.friction == (0.0, 1.0, 0.0, 0.5, 0.0)
    no_friction = p.replace(simulation=dataclasses.replace(
        p.simulation, options=SimulationOptions(**{**p.simulation.options.to_dict(), "friction": []})))
    assert per_mass_changes(no_friction, 3) == {}
    # a chain edited that way saves and loads back
    dev = p.device
    smaller = Device(masses=np.delete(dev.masses, 1), stiffnesses=dev.stiffnesses[1:], dampings=dev.dampings[1:],
                     ground_dampings=np.delete(dev.ground_dampings, 1), sample_time=dev.sample_time)
    q = p.replace(device=smaller, **per_mass_changes(p, smaller.n, removed=1))
    save_profile(q, tmp_path / "q.json")
    assert load_profile(tmp_path / "q.json") == q


# -- a failed load applies nothing ---------------------------------------------------------------------


@pytest.mark.parametrize("mutate", [
    lambda d: d["controller"].update(b_range={"points": 1}),  # the last section read
    lambda d: d["simulation"]["options"].update(friction=[1.0]),  # checked after every section
    lambda d: d["device"]["masses"].__setitem__(3, -1.0),
])
def test_a_failed_load_changes_nothing(tmp_path, mutate):
    d = hbfd_dict()
    d["controller"] = {"b_range": {"min": 0.5, "max": 50.0, "points": 20}}
    mutate(d)
    before = copy.deepcopy(d)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(d))
    text = path.read_bytes()
    with pytest.raises(ProfileError):
        load_profile(path)
    assert d == before and path.read_bytes() == text
    # and the next load is not affected by the failed one
    assert profile_to_dict(load_profile(bundled_profiles()["hbfd"])) == json.loads((SAVED / "hbfd.json").read_text())
