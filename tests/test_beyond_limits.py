"""Designs beyond the tool's own physical limits (issue 22).

The Eom profile's admittance display has its smallest m_c (0.68 kg) at b_c ≈ 1.3·10¹² N·s/m, where
the loader allows at most 10⁸; a one-mass device sampled at 1 µs has its largest k_c at 9.3·10⁹ N/m,
against 10⁹.  Such a design is reported as "beyond the physical range" (and which limit) by the
study's headline, ``zwidth analyze``/``design`` (text, and JSON with the number kept and a
``beyond_limit`` flag) and the report, with the loader's own limits.  A design inside the limits
is still a number.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
from types import SimpleNamespace

import pytest
from cli_runner import ROOT, run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

from analysis import Device, load_profile
from analysis.errors import ValidationError
from analysis.profiles import per_mass_changes
from analysis.profiles.schema import FIELDS_BY_NAME
from analysis.study import (
    BEYOND,
    DESIGN_FIELDS,
    QUANTITIES,
    RobustDesigns,
    beyond_limit,
    edits_beyond_limits,
    field_limit,
    headline,
    quantity,
)

PROFILES = ROOT / "resources" / "profiles"
EOM = PROFILES / "eom.json"
HBFD = PROFILES / "hbfd.json"


@pytest.fixture(scope="module")
def eom_admittance():
    return headline(load_profile(EOM), "admittance")


def one_mass(sample_time: float):
    """A valid one-mass device (1 kg, 10³ N·s/m to ground) at b_c = 10³ N·s/m, impedance display."""
    device = Device(masses=[1.0], stiffnesses=[], dampings=[], ground_dampings=[1e3], sample_time=sample_time,
                    band_min=1.0)
    base = load_profile(HBFD)  # its 4-value friction resized to the one mass (a profile refuses another length)
    return base.replace(device=device, bc=1e3, display="impedance", **per_mass_changes(base, device.n))


def test_limits_are_the_loaders_own():
    for design_key, field in DESIGN_FIELDS.items():
        assert field_limit(field) is FIELDS_BY_NAME[field][1].rule, design_key
    assert field_limit("bc_adm").hi == 1e8 and field_limit("kc").hi == 1e9


def test_eom_admittance_smallest_mass_damping_is_beyond(eom_admittance):
    h = eom_admittance
    bc = h.designs["min_mc_bc"]
    assert bc > 1e11  # the number is kept (≈ 1.3e12 N·s/m)
    assert set(h.beyond_limits) >= {"min_mc_bc", "min_mc_bc_low"}
    assert "min_mc" not in h.beyond_limits  # 0.68 kg lies inside [1e-6, 1e3] kg
    assert "min_mc_bc_high" not in h.beyond_limits  # an unbounded edge (∞) is not a value to set
    b = h.beyond_limits["min_mc_bc"]
    assert b.field == "bc_adm" and b.above and b.value == bc
    assert h.text("min_mc_bc") == "beyond the physical range (b_c ≤ 1e+08 N·s/m)"
    assert h.text("min_mc_bc", rich=True) == "beyond the physical range (b<sub>c</sub> ≤ 1×10<sup>8</sup> N·s/m)"
    assert h.text("min_mc") == quantity("min_mc").format(h.designs["min_mc"])  # still a number
    # the loader refuses the value, which is why it is not offered
    with pytest.raises(ValidationError):
        load_profile(EOM).replace(mc=h.designs["min_mc"], bc_adm=bc)
    assert edits_beyond_limits({"mc": h.designs["min_mc"], "bc_adm": bc}) == b


def test_extreme_device_stiffness_beyond_and_inside():
    inside, beyond = headline(one_mass(1e-5)), headline(one_mass(1e-6))
    # the bound scales with 1/T: ten times the sample rate, ten times the largest k_c
    assert beyond.designs["kc_max"] == pytest.approx(10.0 * inside.designs["kc_max"], rel=1e-6)
    assert 1e8 < inside.designs["kc_max"] < 1e9 < beyond.designs["kc_max"]
    assert inside.beyond_limits == {}
    assert inside.text("kc_max") == quantity("kc_max").format(inside.designs["kc_max"])
    assert beyond.text("kc_max") == "beyond the physical range (k_c ≤ 1e+09 N/m)"


@functools.cache
def _a_headline():
    return headline(one_mass(1e-5))


INSIDE = {field: field_limit(field) for field in set(DESIGN_FIELDS.values())}


@settings(max_examples=200, deadline=None)
@given(key=st.sampled_from(sorted(DESIGN_FIELDS)), u=st.floats(0.0, 1.0))
def test_design_inside_limits_is_a_number(key, u):
    """Any design value inside its field's range is reported as its number (log-uniform draw)."""
    limit = field_limit(DESIGN_FIELDS[key])
    lo = max(limit.lo, 1e-12)
    value = min(limit.hi, max(limit.lo, lo * (limit.hi / lo) ** u))
    assert beyond_limit(DESIGN_FIELDS[key], value) is None
    h = dataclasses.replace(_a_headline(), designs={key: value})  # the flags follow the designs
    assert h.beyond_limits == {}
    if key in QUANTITIES:  # the keys a front end prints (the interval edges at m_c,min are JSON only)
        assert h.text(key) == quantity(key).format(value) and BEYOND not in h.text(key)
    outside = limit.hi * 1.5
    assert set(dataclasses.replace(h, designs={key: outside}).beyond_limits) == {key}


@settings(max_examples=300, deadline=None)
@given(field=st.sampled_from(sorted(INSIDE)),
       value=st.floats(allow_nan=False, allow_infinity=False, min_value=-1e13, max_value=1e13)
       | st.sampled_from([0.0, 1e-6, 1e3, 1e8, 1e9, 1e8 * (1 + 1e-15), 1e9 * (1 + 1e-15), 1e-6 * (1 - 1e-15)]))
def test_apply_check_agrees_with_the_loader(field, value):
    """An "Apply" is refused exactly when the profile record (the loader's validation) refuses it."""
    try:
        load_profile(HBFD).replace(**{field: value})
        accepted = True
    except ValidationError:
        accepted = False
    assert (edits_beyond_limits({field: value}) is None) == accepted


def test_reported_values_not_flagged():
    """None (infeasible), ∞ (unbounded) and NaN are never beyond; a finite value past either edge is."""
    for v in (None, math.inf, math.nan):
        assert beyond_limit("bc_adm", v) is None
    assert beyond_limit("bc_adm", 0.0) is None  # the open lower edge of b_c > 0 itself
    below = beyond_limit("mc", 1e-7)
    assert below is not None and not below.above and below.text() == "beyond the physical range (m_c ≥ 1e-06 kg)"
    assert beyond_limit("kc", 1e9) is None and beyond_limit("kc", 1.0000001e9) is not None


def test_analyze_text_and_json(capsys, eom_admittance):
    text = run_cli(capsys, "analyze", EOM)
    assert text.returncode == 0, text.stderr
    line = next(x for x in text.stdout.splitlines() if "smallest m_c" in x)
    assert "with b_c = beyond the physical range (b_c ≤ 1e+08 N s/m)" in line
    assert "0.681818 kg" in line and "e+12" not in line
    data = json.loads(run_cli(capsys, "analyze", EOM, "--json").stdout)
    mm = data["admittance"]["design"]["min_mass"]
    assert mm["beyond_limit"] is True
    assert mm["bc"] == pytest.approx(eom_admittance.designs["min_mc_bc"], rel=1e-12)  # the number is kept
    assert set(mm["beyond"]) == {"bc", "low"} and mm["beyond"]["bc"].startswith(BEYOND)
    assert data["admittance"]["design"]["feasible_damping"]["beyond_limit"] is False
    assert data["impedance"]["design"]["beyond_limit"] is False and data["impedance"]["design"]["beyond"] == {}


def test_design_command_text_and_json(capsys):
    text = run_cli(capsys, "design", EOM, "--display", "admittance")
    assert text.returncode == 0, text.stderr
    assert "smallest m_c: 0.681818 kg with b_c = beyond the physical range (b_c ≤ 1e+08 N s/m)" in text.stdout
    data = json.loads(run_cli(capsys, "design", EOM, "--display", "admittance", "--json").stdout)
    assert data["min_mass"]["beyond_limit"] is True and data["min_mass"]["bc"] > 1e8
    hbfd = json.loads(run_cli(capsys, "design", HBFD, "--json").stdout)  # inside: numbers, no flag
    assert hbfd["design"]["beyond_limit"] is False and hbfd["design"]["kc_max"] == pytest.approx(117118.18, rel=1e-6)


def test_report_design_table_says_beyond():
    from app.report.content import gather  # Qt-free

    profile = load_profile(EOM).replace(display="admittance", wall=None, observer=None)
    content = gather(profile, sampled=False, date="2026-01-01")
    value, text = content.numbers["design.min_mc_bc"]
    assert value is not None and value > 1e8 and text.startswith(BEYOND)
    rows = {r.label: r for s in content.sections if s.title == "Design results" for r in s.rows}
    row = rows["with damping"]
    assert row.value.startswith(BEYOND) and "b<sub>c</sub> ≤ 1×10<sup>8</sup>" in row.value and row.unit == ""
    assert not rows["smallest stable coupling mass"].value.startswith(BEYOND)


def test_robust_design_beyond_is_reported():
    stiff = SimpleNamespace(kc=5e9, nominal_kc=6e9, bc=1.0, binding={})
    rd = RobustDesigns(impedance=True, intervals={"masses[0]": (0.9, 1.1)}, stiffness=stiff, damping=None,
                       coupling=1e3, holds=True)
    assert set(rd.beyond_limits) == {"kc_max"}
    assert "robust k_c beyond the physical range (k_c ≤ 1e+09 N/m)" in rd.verdict()
    inside = RobustDesigns(impedance=True, intervals={"masses[0]": (0.9, 1.1)},
                           stiffness=SimpleNamespace(kc=5e5, nominal_kc=6e5, bc=1.0, binding={}), damping=None,
                           coupling=1e3, holds=True)
    assert inside.beyond_limits == {} and "robust k_c ≤ 500000 N/m" in inside.verdict()
