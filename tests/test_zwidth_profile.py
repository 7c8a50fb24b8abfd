"""The profile's ``controller`` section (schema 5, issue 15): round trip, migration, errors."""

from __future__ import annotations

import json
import math

import pytest

from analysis.profiles import (
    SCHEMA_VERSION,
    ControllerSection,
    ProfileError,
    bundled_profiles,
    load_profile,
    migrate,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from analysis.sampled import VelocityFilter


def _hbfd_dict() -> dict:
    return profile_to_dict(load_profile(bundled_profiles()["hbfd"]))


def test_schema_5_round_trip_keeps_every_number(tmp_path):
    assert SCHEMA_VERSION == 7
    d = _hbfd_dict()
    d["controller"] = {"velocity_filter": {"kind": "butter2", "cutoff": 2 * math.pi * 42.5},
                       "b_range": {"min": 0.5, "max": 250.0, "points": 37}, "trials": "trials.csv"}
    p = profile_from_dict(d)
    assert p.controller == ControllerSection(VelocityFilter("butter2", 2 * math.pi * 42.5), (0.5, 250.0), 37,
                                             "trials.csv")
    save_profile(p, tmp_path / "p.json")
    raw = json.loads((tmp_path / "p.json").read_text())
    assert raw["schema_version"] == 7
    assert raw["controller"] == {"velocity_filter": {"kind": "butter2", "cutoff": 2 * math.pi * 42.5},
                                 "b_range": {"min": 0.5, "max": 250.0, "points": 37}, "trials": "trials.csv"}
    assert load_profile(tmp_path / "p.json") == p


def test_backward_filter_saves_inf_as_string_and_loads_back(tmp_path):
    p = load_profile(bundled_profiles()["hbfd"]).replace(controller=ControllerSection())
    save_profile(p, tmp_path / "p.json")
    raw = json.loads((tmp_path / "p.json").read_text())
    assert raw["controller"]["velocity_filter"] == {"kind": "backward", "cutoff": "inf"}
    assert "trials" not in raw["controller"]
    q = load_profile(tmp_path / "p.json")
    assert q.controller.velocity_filter.is_backward and q.controller.b_range == (0.1, 100.0)


@pytest.mark.parametrize("version", [1, 2, 3, 4])
def test_older_versions_migrate_without_a_controller_section(version):
    d = _hbfd_dict()
    d["schema_version"] = version
    m = migrate(d)
    assert m["schema_version"] == 7 and "controller" not in m
    p = profile_from_dict(d)
    assert p.controller is None
    assert profile_to_dict(p)["schema_version"] == 7


def test_version_4_file_with_a_controller_key_loads_it():
    d = _hbfd_dict()
    d["schema_version"] = 4
    d["controller"] = {"velocity_filter": {"kind": "lowpass1", "cutoff": 100.0}}
    assert profile_from_dict(d).controller.velocity_filter == VelocityFilter("lowpass1", 100.0)


@pytest.mark.parametrize(("section", "path"), [
    ({"velocity_filter": {"kind": "lowpass2", "cutoff": 100.0}}, "$.controller.velocity_filter.kind"),
    ({"velocity_filter": {"kind": "lowpass1", "cutoff": -1.0}}, "$.controller.velocity_filter.cutoff"),
    ({"velocity_filter": {"kind": "butter2", "cutoff": 4000.0}}, "$.controller.velocity_filter.cutoff"),
    ({"b_range": {"min": 10.0, "max": 1.0}}, "$.controller.b_range.max"),
    ({"b_range": {"points": 1}}, "$.controller.b_range.points"),
    ({"trials": 3}, "$.controller.trials"),
    ({"filter": {}}, "$.controller.filter"),
])
def test_errors_name_the_json_path(section, path):
    d = _hbfd_dict()
    d["controller"] = section
    with pytest.raises(ProfileError) as err:
        profile_from_dict(d)
    assert err.value.json_path == path, str(err.value)


def test_cutoff_above_nyquist_is_refused_for_this_device():
    p = load_profile(bundled_profiles()["hbfd"])  # T = 1 ms: Nyquist pi/T = 3141.59 rad/s
    ok = ControllerSection(VelocityFilter("lowpass1", 3000.0))
    assert p.replace(controller=ok).controller is ok
    with pytest.raises(ValueError, match="Nyquist"):
        p.replace(controller=ControllerSection(VelocityFilter("lowpass1", 3200.0)))
