"""The shared validators, settings-record helpers and JSON spelling of inf (analysis.checks)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from analysis.checks import (
    NONNEGATIVE,
    POSITIVE,
    Real,
    boolean,
    check_elements,
    choice,
    describe_range,
    frequencies,
    from_json_float,
    integer,
    is_real,
    json_float,
    jsonable,
    nonnegative,
    positive,
    real,
    record_from_dict,
    record_to_dict,
    string,
    vector,
)
from analysis.errors import ValidationError
from analysis.sampled.scenarios import SCENARIOS, Scenario, SimulationOptions, hbfd_options
from analysis.sampled.terminations import Environment, Grasp, god_object_wall, penalty_wall
from analysis.transparency.settings import ObserverSettings, WallSettings

finite = st.floats(allow_nan=False, allow_infinity=False, width=64)


def rejected(func, *args, **kwargs) -> ValidationError:
    with pytest.raises(ValidationError) as info:
        func(*args, **kwargs)
    return info.value


# -- numbers -------------------------------------------------------------------------------------


@settings(max_examples=200, deadline=None)
@given(lo=finite, span=st.floats(min_value=0.0, max_value=1e300), frac=st.floats(0.0, 1.0))
def test_any_finite_value_in_range_passes_unchanged(lo, span, frac):
    hi = lo + span
    if not math.isfinite(hi):
        return
    x = min(max(lo + frac * (hi - lo), lo), hi)
    out = real("x", x, lo=lo, hi=hi)
    assert out == x and type(out) is float
    assert real("x", np.float64(x), lo=lo, hi=hi) == x


@settings(max_examples=200, deadline=None)
@given(lo=st.floats(-1e6, 1e6), below=st.floats(min_value=1e-3, max_value=1e6), unit=st.sampled_from(["", "kg"]))
def test_any_value_below_the_range_names_field_and_range(lo, below, unit):
    rule = Real(lo=lo, unit=unit)
    err = rejected(rule, "mass", lo - below)
    assert err.field == "mass" and err.index is None
    assert err.allowed == describe_range(lo, unit=unit)
    assert str(err) == f"mass = {lo - below!r} is invalid: allowed range is {err.allowed}"
    assert err.allowed.startswith(f">= {lo:g} and finite")


@settings(max_examples=100, deadline=None)
@given(x=st.floats(min_value=1.0, max_value=1e300, exclude_min=True))
def test_any_value_above_an_open_unit_interval_is_refused(x):
    err = rejected(real, "alpha", x, lo=0.0, hi=1.0, hi_open=True)
    assert (err.field, err.allowed, err.value) == ("alpha", "in [0, 1)", x)


def test_open_and_closed_ends():
    assert real("a", 0.0, lo=0.0) == 0.0
    assert rejected(real, "a", 0.0, lo=0.0, lo_open=True).allowed == "> 0 and finite"
    assert real("b", 1.0, lo=0.0, hi=1.0) == 1.0
    assert rejected(real, "b", 1.0, lo=0.0, hi=1.0, hi_open=True).allowed == "in [0, 1)"
    assert positive("m", 2) == 2.0 and nonnegative("b", 0) == 0.0
    assert rejected(positive, "m", 0.0, "kg").allowed == "> 0 and finite (kg)"
    assert rejected(nonnegative, "b", -1e-300, "N s/m").allowed == ">= 0 and finite (N s/m)"
    assert POSITIVE("x", 1e-300) == 1e-300 and NONNEGATIVE("x", 0) == 0.0


@pytest.mark.parametrize("bad", [True, False, np.bool_(True), "1.0", None, [1.0], 1j])
def test_non_numbers_are_refused_with_their_own_message(bad):
    rule = Real(lo=0.0, not_real="a real number")
    err = rejected(rule, "k", bad)
    assert err.allowed == "a real number" and err.value is bad
    assert not is_real(bad)
    assert rejected(POSITIVE, "k", bad).allowed == "> 0 and finite"


def test_nan_and_infinity():
    for x in (math.nan, math.inf, -math.inf):
        assert rejected(NONNEGATIVE, "x", x).allowed == ">= 0 and finite"
    rule = Real(lo=0.0, allow_inf=True, allowed=">= 0", not_finite="a number")
    assert rule("t", math.inf) == math.inf
    assert rejected(rule, "t", math.nan).allowed == "a number"
    assert rejected(rule, "t", -math.inf).allowed == ">= 0"
    assert describe_range(0.0, allow_inf=True) == ">= 0"


def test_huge_integers_are_refused_not_overflowed():
    err = rejected(POSITIVE, "k", 10**400)
    assert err.allowed == "> 0 and finite" and err.value == 10**400


def test_report_float_and_index():
    err = rejected(Real(lo=0.0, report_float=True), "masses", np.float64(-2.0), 3)
    assert err.value == -2.0 and type(err.value) is float and err.index == 3
    assert str(err) == "masses[3] = -2.0 is invalid: allowed range is >= 0 and finite"
    err = rejected(Real(lo=0.0), "x", -2)
    assert err.value == -2 and type(err.value) is int


@pytest.mark.parametrize("lo,hi,kw,text", [
    (0.0, None, {"lo_open": True, "unit": "kg"}, "> 0 and finite (kg)"),
    (0.0, 1.0, {"hi_open": True}, "in [0, 1)"),
    (-1.0, 1.0, {}, "in [-1, 1]"),
    (0.0, 100.0, {"lo_open": True}, "in (0, 100]"),
    (None, None, {"unit": "N"}, "finite (N)"),
    (None, 5.0, {"hi_open": True}, "< 5 and finite"),
])
def test_describe_range(lo, hi, kw, text):
    assert describe_range(lo, hi, **kw) == text
    assert Real(lo=lo, hi=hi, **kw).text == text


# -- other scalars and vectors ---------------------------------------------------------------------


@settings(max_examples=100, deadline=None)
@given(lo=st.integers(-100, 100), span=st.integers(0, 100), offset=st.integers(-300, 300))
def test_integer_in_range(lo, span, offset):
    hi = lo + span
    value = lo + offset
    if lo <= value <= hi:
        assert integer("n", value, lo, hi) == value
        assert integer("n", np.int64(value), lo, hi) == value
    else:
        err = rejected(integer, "n", value, lo, hi)
        assert (err.field, err.allowed, err.value) == ("n", f"an integer in [{lo}, {hi}]", value)


def test_integer_refuses_floats_and_booleans():
    for bad in (1.0, True, "1", None):
        assert rejected(integer, "order", bad, 1, 8).allowed == "an integer in [1, 8]"
    assert rejected(integer, "delay_samples", -1, 0).allowed == "an integer >= 0"
    assert integer("delay_samples", 10**6, 0) == 10**6


def test_choice_boolean_string():
    assert choice("hold", "zoh", ("zoh", "pade")) == "zoh"
    assert rejected(choice, "hold", "foh", ("zoh", "pade")).allowed == "one of 'zoh', 'pade'"
    assert rejected(choice, "c", 3, ("a", "b"), allowed="a or b").allowed == "a or b"
    assert boolean("w", np.bool_(True)) is True
    assert rejected(boolean, "w", 1).allowed == "true or false"
    assert string("name", "") == ""
    assert rejected(string, "name", "  ", nonempty=True).allowed == "a non-empty string"
    assert rejected(string, "name", 3).allowed == "a string"


def test_vector_and_elements():
    v = vector("masses", [1, 2.5], 2)
    assert v.tolist() == [1.0, 2.5] and v.dtype == float and not v.flags.writeable
    assert rejected(vector, "stiffnesses", [1.0], 2).allowed == "exactly 2 values"
    assert rejected(vector, "masses", [[1.0], [1.0, 2.0]]).allowed == "a list of real numbers"
    assert check_elements("f", (0, 1.5)) is None
    assert check_elements("f", np.array([0.0, np.inf]), Real(lo=0.0, allow_inf=True)) is None
    for bad in (np.array([1.0, np.nan]), np.array([1.0, -np.inf]), np.array([0.0, 1.0])):
        err = rejected(check_elements, "masses", bad, Real(lo=0.0, lo_open=True, report_float=True))
        assert (err.field, err.allowed, type(err.value)) == ("masses", "> 0 and finite", float)
    err = rejected(check_elements, "friction", [0.0, 1.0, -1.0], Real(lo=0.0, unit="N"))
    assert (err.index, err.allowed, err.value) == (2, ">= 0 and finite (N)", -1.0)


def test_frequencies():
    w = frequencies([[1, 2.5]])
    assert w.shape == (1, 2) and w.dtype == float and w.tolist() == [[1.0, 2.5]]
    assert frequencies([]).size == 0
    for bad in ([1.0, 0.0], [np.nan], [1.0, np.inf], [-1.0]):
        err = rejected(frequencies, bad)
        assert (err.field, err.allowed) == ("frequency", "finite and > 0 (rad/s)")


def test_inside_marks_the_enclosing_record():
    err = ValidationError("mass", ">= 0", -1.0).inside("grasp").inside("scenario")
    assert err.within == ("scenario", "grasp") and err.field == "mass"
    assert str(err) == "mass = -1.0 is invalid: allowed range is >= 0"


# -- JSON ----------------------------------------------------------------------------------------


@given(x=st.floats(allow_nan=False))
def test_json_float_round_trip(x):
    text = json.dumps(json_float(x), allow_nan=False)
    assert from_json_float(json.loads(text)) == x


def test_json_spelling():
    assert [json_float(x) for x in (math.inf, -math.inf, math.nan, 1.5)] == ["inf", "-inf", "nan", 1.5]
    assert from_json_float("inf") == math.inf and from_json_float("-inf") == -math.inf
    assert from_json_float("nan") == "nan" and from_json_float("x") == "x" and from_json_float(2) == 2
    data = {"a": np.array([1.0, np.inf]), "b": (np.int64(3), np.bool_(False)), 4: None, "c": np.float32(0.5)}
    assert jsonable(data) == {"a": [1.0, "inf"], "b": [3, False], "4": None, "c": 0.5}
    assert jsonable(object) == str(object)


# -- settings records ----------------------------------------------------------------------------

RECORDS = [
    WallSettings(),
    WallSettings(hold="zoh", controller_stiffness=900.0, weight_order=2, plant="chain", bc_min=-1.0),
    ObserverSettings(),
    ObserverSettings(order=3, cutoff=150.0, preset="five_bar_offset", delta=-1.0),
    SimulationOptions(),
    hbfd_options(delay_samples=2, implementation_delay=True),
    *SCENARIOS.values(),
    Scenario(name="inf", grasp=Grasp(1.0, 2.0, 3.0), release_time=0.3, wall_position=-1e-3),
    Grasp(),
    Grasp(mass=2.0, damping=50.0, stiffness=2e3),
    Environment(),
    penalty_wall(),
    god_object_wall(),
]


@pytest.mark.parametrize("record", RECORDS, ids=lambda r: type(r).__name__)
def test_every_settings_record_round_trips_through_strict_json(record):
    data = record_to_dict(record)
    assert data == record.to_dict()
    assert list(data) == [f for f in record.__dataclass_fields__]
    text = json.dumps(data, allow_nan=False)
    again = record_from_dict(type(record), json.loads(text), "x")
    assert again == record
    assert type(record).from_dict(json.loads(text)) == record


@settings(max_examples=60, deadline=None)
@given(
    release=st.one_of(st.just(math.inf), st.floats(0.0, 10.0)),
    push_start=st.floats(0.0, 1.0),
    push_len=st.one_of(st.just(math.inf), st.floats(0.0, 1.0)),
    duration=st.floats(1e-3, 3600.0),
    grasp=st.tuples(st.floats(0.0, 10.0), st.floats(0.0, 1e3), st.floats(0.0, 1e6)),
    force_continuous=st.one_of(st.just(math.inf), st.floats(1e-3, 1e3)),
)
def test_scenarios_and_options_round_trip(release, push_start, push_len, duration, grasp, force_continuous):
    sc = Scenario(release_time=release, push_start=push_start, push_end=push_start + push_len, duration=duration,
                  grasp=Grasp(*grasp))
    opt = SimulationOptions(force_continuous=force_continuous, friction=(0.0, 1.0))
    for record in (sc, opt):
        assert type(record).from_dict(json.loads(json.dumps(record.to_dict(), allow_nan=False))) == record


def test_record_from_dict_errors():
    err = rejected(WallSettings.from_dict, {"mass": 0.02, "colour": 1})
    assert (err.field, err.value) == ("colour", 1) and err.allowed.startswith("a known field: alpha, bc_count")
    assert rejected(WallSettings.from_dict, [1, 2]).field == "transparency"
    assert rejected(SimulationOptions.from_dict, "x").field == "simulation options"
    assert rejected(Grasp.from_dict, None).allowed == "an object"
    err = rejected(Scenario.from_dict, {"grasp": {"mass": -1}})
    assert (err.field, err.within, err.allowed) == ("mass", ("grasp",), ">= 0 and finite")
    err = rejected(Scenario.from_dict, {"grasp": {"mass": 1.0, "reach": 2.0}})
    assert (err.field, err.within) == ("reach", ("grasp",))
    # "inf" is a number only in float fields
    assert Scenario.from_dict({"name": "inf", "push_end": "inf"}).name == "inf"
    assert rejected(Scenario.from_dict, {"duration": "inf"}).allowed == "a finite number"
    assert rejected(Scenario.from_dict, {"duration": "2"}).allowed == "a real number"


def test_errors_print_numpy_values_as_plain_numbers():
    """A refused numpy value reads as the number it holds, never as ``np.float64(0.45)``."""
    cases = [
        (lambda: Real(lo=1.0)("x", np.float64(0.45)), "x = 0.45 is invalid: allowed range is >= 1 and finite"),
        (lambda: integer("n", np.int64(7), 0, 4), "n = 7 is invalid: allowed range is an integer in [0, 4]"),
        (lambda: vector("v", np.array([0.45, 1.0]), 3), "v = [0.45, 1.0] is invalid: allowed range is exactly 3 values"),
        (lambda: SimulationOptions(stick_velocity=np.float64(-0.45)), "stick_velocity = -0.45 is invalid"),
    ]
    for call, text in cases:
        with pytest.raises(ValidationError) as info:
            call()
        assert str(info.value).startswith(text) and "np." not in str(info.value)
