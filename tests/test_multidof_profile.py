"""The profile's ``multidof`` section (schema 7, issue 25): round trip, errors at their JSON paths, migrations."""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest

from analysis.errors import ValidationError
from analysis.profiles import (
    SCHEMA_VERSION,
    MultiDofSection,
    ProfileError,
    bundled_profiles,
    load_profile,
    migrate,
    path_of,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)

FULL = {
    "linkage": {"kind": "five_bar", "l1": 0.25, "l2": 0.3, "base": 0.12, "proximal_masses": [0.03, 0.031],
                "distal_masses": [0.012, 0.024], "handle_mass": 0.01, "rotor_inertia": 2e-5, "joint_damping": 0.002},
    "handle": {"x": 0.04, "y": 0.3},
    "wall": {"kind": "normal", "normal": [0.6, -0.8], "damping": 3.5},
    "map": {"x": {"min": -0.2, "max": 0.25, "points": 17}, "y": {"min": 0.12, "max": 0.45, "points": 13}},
}


def _hbfd() -> dict:
    return json.loads(bundled_profiles()["hbfd"].read_text())


def _with(section: object) -> dict:
    d = _hbfd()
    d["schema_version"] = SCHEMA_VERSION
    d["multidof"] = section
    return d


def test_schema_7_round_trip_keeps_every_value(tmp_path):
    assert SCHEMA_VERSION == 7
    p = profile_from_dict(_with(copy.deepcopy(FULL)))
    s = p.multidof
    assert (s.l1, s.l2, s.base, s.proximal_masses, s.distal_masses) == (0.25, 0.3, 0.12, (0.03, 0.031), (0.012, 0.024))
    assert (s.handle_mass, s.rotor_inertia, s.joint_damping) == (0.01, 2e-5, 0.002)
    assert (s.handle_x, s.handle_y, s.wall_kind, s.wall_normal, s.wall_damping) == (0.04, 0.3, "normal", (0.6, -0.8), 3.5)
    assert (s.x_min, s.x_max, s.x_points, s.y_min, s.y_max, s.y_points) == (-0.2, 0.25, 17, 0.12, 0.45, 13)
    np.testing.assert_allclose(s.normal, [0.6, -0.8], rtol=1e-15)
    assert s.linkage.l2 == 0.3 and s.linkage.distal_masses == (0.012, 0.024)
    save_profile(p, tmp_path / "p.json")
    raw = json.loads((tmp_path / "p.json").read_text())
    assert raw["schema_version"] == 7 and raw["multidof"] == FULL
    assert load_profile(tmp_path / "p.json") == p


def test_missing_keys_take_the_defaults_and_the_isotropic_wall_has_no_normal():
    p = profile_from_dict(_with({"handle": {"x": 0.01}}))
    assert p.multidof == MultiDofSection(handle_x=0.01)
    assert p.multidof.normal is None
    assert MultiDofSection().linkage.inverse_kinematics(MultiDofSection().handle).shape == (2,)


@pytest.mark.parametrize("path, value, words", [
    ("linkage.l1", 0.0, "(0, 10] (m)"),
    ("linkage.l2", "long", 'the string "long"'),
    ("linkage.base", -0.1, "[0, 10] (m)"),
    ("linkage.kind", "phantom", '"five_bar"'),
    ("linkage.joint_damping", -1.0, "(N m s/rad)"),
    ("linkage.rotor_inertia", float("nan"), ""),
    ("handle.x", 11.0, "10"),
    ("wall.kind", "plane", '"isotropic" or "normal"'),
    ("wall.damping", -2.0, "(N s/m)"),
    ("map.x.points", 1, "2"),
    ("map.y.points", 2.5, "an integer"),
    ("map.y.min", "low", "[-10, 10] (m)"),
])
def test_a_bad_value_is_reported_at_its_json_path(path, value, words):
    sec = copy.deepcopy(FULL)
    node = sec
    *head, last = path.split(".")
    for key in head:
        node = node[key]
    node[last] = value
    with pytest.raises(ProfileError) as info:
        profile_from_dict(_with(sec))
    assert info.value.json_path == f"$.multidof.{path}"
    assert words in str(info.value)


@pytest.mark.parametrize("path, value, where", [
    ("linkage.proximal_masses", [0.02, -0.01], "$.multidof.linkage.proximal_masses[1]"),
    ("linkage.distal_masses", [0.02], "$.multidof.linkage.distal_masses"),
    ("wall.normal", [0.0, 0.0], "$.multidof.wall.normal"),
    ("wall.normal", [1.0, 0.0, 0.0], "$.multidof.wall.normal"),
    ("map.x.max", -0.3, "$.multidof.map.x.max"),
    ("handle.y", 2.0, "$.multidof.handle"),
])
def test_lists_ranges_and_an_unreachable_handle_are_reported_at_their_paths(path, value, where):
    sec = copy.deepcopy(FULL)
    node = sec
    *head, last = path.split(".")
    for key in head:
        node = node[key]
    node[last] = value
    with pytest.raises(ProfileError) as info:
        profile_from_dict(_with(sec))
    assert info.value.json_path == where


def test_an_unknown_key_is_named():
    with pytest.raises(ProfileError) as info:
        profile_from_dict(_with({"wall": {"stiffness": 1.0}}))
    assert info.value.json_path == "$.multidof.wall.stiffness"
    with pytest.raises(ProfileError) as info:
        profile_from_dict(_with([1, 2]))
    assert info.value.json_path == "$.multidof"


def test_the_record_names_the_field_whose_path_the_schema_declares():
    with pytest.raises(ValidationError) as info:
        MultiDofSection(y_points=500)
    assert path_of(info.value.field) == "$.multidof.map.y.points"
    with pytest.raises(ValidationError) as info:
        MultiDofSection(handle_x=0.5, handle_y=0.5)
    assert path_of(info.value.field) == "$.multidof.handle" and "0.5" in str(info.value)


@pytest.mark.parametrize("version", [1, 2, 3, 4, 5, 6])
def test_older_versions_migrate_unchanged_without_the_section(version):
    d = _hbfd()
    d["schema_version"] = version
    m = migrate(d)
    assert m["schema_version"] == 7 and "multidof" not in m
    assert {k: v for k, v in m.items() if k != "schema_version"} == {k: v for k, v in d.items() if k != "schema_version"}
    p = profile_from_dict(d)
    assert p.multidof is None
    assert "multidof" not in profile_to_dict(p)


def test_a_version_6_file_with_a_renderable_section_keeps_it():
    d = _hbfd()
    d["schema_version"] = 6
    d["renderable"] = {"environment": {"mass": 0.2}}
    p = profile_from_dict(d)
    assert p.renderable.virtual_mass == 0.2 and p.multidof is None
