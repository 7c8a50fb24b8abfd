"""ProfileModel on its own (no window): validated sets, signals with the field name, refusals."""

from __future__ import annotations

import numpy as np
import pytest

from analysis import ValidationError
from analysis.profiles.io import bundled_profiles, load_profile
from app.core.model import ALL_FIELDS, DEVICE_FIELDS, ProfileModel


@pytest.fixture
def model(qapp):
    return ProfileModel(load_profile(bundled_profiles()["hbfd"]))


def record(signal) -> list:
    seen: list = []
    signal.connect(lambda *args: seen.append(args))
    return seen


def test_set_changes_the_profile_and_names_the_field(model):
    seen = record(model.fieldChanged)
    model.set("kc", 61234.5)
    assert model.profile.kc == 61234.5
    assert model.get("kc") == 61234.5
    assert seen == [("kc",)]


def test_device_fields_go_through_the_device(model):
    seen = record(model.fieldChanged)
    masses = np.array(model.device.masses, float)
    masses[0] = 0.3
    model.set("masses", masses)
    assert model.device.masses[0] == 0.3
    np.testing.assert_array_equal(model.get("masses"), masses)
    model.set("sample_time", 5e-4)
    assert model.device.sample_time == 5e-4
    assert seen == [("masses",), ("sample_time",)]


def test_same_value_emits_nothing(model):
    seen = record(model.fieldChanged)
    before = model.profile
    model.set("kc", model.profile.kc)
    model.set("masses", np.array(model.device.masses))
    assert seen == [] and model.profile is before


@pytest.mark.parametrize("field, value", [("kc", -1.0), ("kc", float("nan")), ("display", "foo"),
                                          ("sample_time", 0.0)])
def test_bad_value_is_refused_and_nothing_changes(model, field, value):
    seen = record(model.fieldChanged)
    before = model.profile
    with pytest.raises(ValidationError):
        model.set(field, value)
    assert model.profile is before and seen == []


def test_set_many_is_all_or_nothing(model):
    seen = record(model.fieldChanged)
    before = model.profile
    with pytest.raises(ValidationError):
        model.set_many({"kc": 70000.0, "bc": -5.0})
    assert model.profile is before and seen == []
    model.set_many({"kc": 70000.0, "bc": 150.0})
    assert (model.profile.kc, model.profile.bc) == (70000.0, 150.0)
    assert sorted(seen) == [("bc",), ("kc",)]


def test_unknown_field_is_an_error(model):
    with pytest.raises(KeyError):
        model.get("nonsense")
    with pytest.raises(KeyError):
        model.validated({"nonsense": 1.0})


def test_replace_profile_emits_replaced_not_field_changes(model):
    fields, replaced = record(model.fieldChanged), record(model.profileReplaced)
    other = load_profile(bundled_profiles()["rigid"])
    model.replace_profile(other)
    assert model.profile is other
    assert replaced == [()] and fields == []
    with pytest.raises(TypeError):
        model.replace_profile({"name": "not a profile"})


def test_field_lists_cover_the_device_and_the_profile():
    assert set(DEVICE_FIELDS) <= set(ALL_FIELDS)
    assert {"kc", "bc", "mc", "bc_adm", "kp", "kd", "display", "wall", "observer", "simulation"} <= set(ALL_FIELDS)
