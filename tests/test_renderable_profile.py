"""The profile's ``renderable`` section (schema 6, issue 24): round trip, errors at their JSON paths,
migration of older files."""

from __future__ import annotations

import copy
import json
import math

import pytest

from analysis.errors import ValidationError
from analysis.profiles import (
    SCHEMA_VERSION,
    ProfileError,
    RenderableSection,
    bundled_profiles,
    load_profile,
    migrate,
    path_of,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from analysis.profiles.schema import RENDERABLE, walk


def _hbfd() -> dict:
    return json.loads(bundled_profiles()["hbfd"].read_text())


FULL = {
    "environment": {"mass": -0.05, "damping": 2.5, "stiffness": 750.0},
    "acceleration": {"kind": "filtered_velocity", "lowpass": "lowpass1", "cutoff": 400.0},
    "qualities": {"names": ["stable", "quiet"], "grasps": "all", "band": {"min": 2.0, "max": 40.0},
                  "tolerance": 0.25, "encoder_resolution": 2e-6, "force_noise": 0.3},
    "grid": {"mass": {"min": -0.4, "max": 0.6, "points": 11}, "damping": {"min": -3.0, "max": 70.0, "points": 13}},
}


def _with(section: object) -> dict:
    d = _hbfd()
    d["renderable"] = section
    return d


def test_schema_6_round_trip_keeps_every_value(tmp_path):
    assert SCHEMA_VERSION == 7
    p = profile_from_dict(_with(copy.deepcopy(FULL)))
    r = p.renderable
    assert (r.virtual_mass, r.virtual_damping, r.virtual_stiffness) == (-0.05, 2.5, 750.0)
    assert r.acceleration.kind == "filtered_velocity" and r.acceleration.cutoff == 400.0
    assert r.qualities == ("stable", "quiet") and r.grasps == "all"
    assert (r.band_low, r.band_high, r.tolerance, r.quiet_resolution, r.quiet_force_noise) == (2.0, 40.0, 0.25, 2e-6, 0.3)
    assert (r.mass_min, r.mass_max, r.mass_points, r.damping_min, r.damping_max, r.damping_points) == \
        (-0.4, 0.6, 11, -3.0, 70.0, 13)
    save_profile(p, tmp_path / "p.json")
    raw = json.loads((tmp_path / "p.json").read_text())
    assert raw["schema_version"] == 7 and raw["renderable"] == FULL
    assert load_profile(tmp_path / "p.json") == p


def test_missing_keys_take_the_defaults_and_inf_cutoff_saves_as_a_string():
    p = profile_from_dict(_with({}))
    assert p.renderable == RenderableSection()
    saved = profile_to_dict(p)["renderable"]
    assert saved["acceleration"] == {"kind": "second_difference", "lowpass": "none", "cutoff": "inf"}
    assert saved["qualities"]["encoder_resolution"] is None
    assert profile_from_dict(_with(saved)).renderable == RenderableSection()


def _bad_values(node) -> list[object]:
    """Values the declaration refuses: of the wrong type, and beyond its range where it has one."""
    if node.kind == "choice":
        return ["nope", 3]
    if node.kind == "choices":
        return [["nope"], [], ["stable", "stable"]]
    if node.kind == "integer":
        return [1, 10_000, 2.5, True]
    bad: list[object] = ["x", True]
    rule = node.rule
    if rule.hi is not None:
        bad.append(rule.hi * 10 if rule.hi > 0 else 1.0)
    if rule.lo is not None:
        bad.append(rule.lo - 1.0 if rule.lo <= 0 else rule.lo / 10)
    return bad


_LEAVES = [(path, node) for path, node in walk(RENDERABLE, "$.renderable") if node.kind != "object"]


@pytest.mark.parametrize("path,node", _LEAVES, ids=[p for p, _ in _LEAVES])
def test_every_field_out_of_range_names_its_json_path(path, node):
    assert path_of(node.name) == path  # the API name maps back to the same path
    for bad in _bad_values(node):
        section = copy.deepcopy(FULL)
        where = section
        keys = path.split(".")[2:]
        for key in keys[:-1]:
            where = where[key]
        where[keys[-1]] = bad
        with pytest.raises(ProfileError) as info:
            profile_from_dict(_with(section))
        assert info.value.json_path == path, (bad, str(info.value))
        if node.rule is not None and node.kind == "number" and not isinstance(bad, (str, bool)):
            assert node.rule.unit in str(info.value)


@pytest.mark.parametrize("section,path", [
    ("nope", "$.renderable"),
    ({"grid": {"mass": {"min": 0.5, "max": 0.1}}}, "$.renderable.grid.mass.max"),
    ({"grid": {"damping": {"min": 10.0, "max": -1.0}}}, "$.renderable.grid.damping.max"),
    ({"qualities": {"band": {"min": 10.0, "max": 5.0}}}, "$.renderable.qualities.band.max"),
    ({"acceleration": {"lowpass": "butter2"}}, "$.renderable.acceleration.cutoff"),
    ({"qualities": {"names": ["quiet"]}}, "$.renderable.qualities.encoder_resolution"),
    ({"qualities": {"names": ["accurate"], "band": {"min": 1.0, "max": 4000.0}}}, "$.renderable.qualities.band.max"),
    ({"acceleration": {"lowpass": "lowpass1", "cutoff": 5000.0}}, "$.renderable.acceleration.cutoff"),
    ({"environment": {"mass": 1.0, "spring": 3.0}}, "$.renderable.environment.spring"),
    ({"extra": 1}, "$.renderable.extra"),
])
def test_cross_field_and_nyquist_errors_name_the_json_path(section, path):
    with pytest.raises(ProfileError) as info:
        profile_from_dict(_with(section))
    assert info.value.json_path == path, str(info.value)


def test_the_record_refuses_with_the_api_name_that_maps_to_the_path():
    with pytest.raises(ValidationError) as info:
        RenderableSection(virtual_mass=math.nan)
    assert path_of(info.value.field) == "$.renderable.environment.mass"
    with pytest.raises(ValidationError) as info:
        RenderableSection(damping_points=500)
    assert path_of(info.value.field) == "$.renderable.grid.damping.points"


@pytest.mark.parametrize("version", [1, 2, 3, 4, 5])
def test_older_versions_migrate_unchanged_without_the_section(version):
    d = _hbfd()
    d["schema_version"] = version
    m = migrate(d)
    assert m["schema_version"] == 7 and "renderable" not in m
    assert {k: v for k, v in m.items() if k != "schema_version"} == {k: v for k, v in d.items() if k != "schema_version"}
    p = profile_from_dict(d)
    assert p.renderable is None
    assert "renderable" not in profile_to_dict(p)


def test_a_version_5_file_with_the_key_is_read_after_migration():
    d = _with({"environment": {"mass": 0.2}})
    d["schema_version"] = 5
    assert profile_from_dict(d).renderable.virtual_mass == 0.2
