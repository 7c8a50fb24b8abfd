"""The study requests (analysis.study.requests and friends): what each computation depends on.

Two profiles that differ only in a field a computation does not read give equal requests (a
cache hit in the GUI's compute graph); a change of a field it reads gives a different one (a
recompute).  And a computation given the request computes what it computes from the profile.
"""

from __future__ import annotations

import dataclasses

import math

import numpy as np
import pytest

from analysis.chain.velocity_filter import VelocityFilter
from analysis.profiles.controller import ControllerSection
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.profiles.model import Profile
from analysis.profiles.sections import SimulationSection
from analysis.sampled import SimulationOptions, scenario
from analysis.study import (
    ChartRequest,
    DeviceRequest,
    ExactChartRequest,
    ExactLimitRequest,
    MapRequest,
    OptimumRequest,
    RobustRequest,
    SimulationRequest,
    StabilityRequest,
    TwoAxisRequest,
    TwoAxisStepRequest,
    WallRequest,
    ZWidthRequest,
    design_radius,
    exact_limit,
    map_params,
    observer_settings,
    stability,
    wall_settings,
)
from analysis.transparency.settings import ObserverSettings


@pytest.fixture(scope="module")
def hbfd() -> Profile:
    return load_profile(bundled_profiles()["hbfd"])


def _delayed(p: Profile, samples: int) -> Profile:
    return p.replace(simulation=SimulationSection(options=SimulationOptions(delay_samples=samples),
                                                  scenario=scenario("impedance_worst_case")))


def _filtered(p: Profile, cutoff: float) -> Profile:
    return p.replace(controller=ControllerSection(velocity_filter=VelocityFilter("lowpass1", cutoff)))


GAINS = {"kc": 12345.0, "bc": 77.0, "mc": 3.0, "bc_adm": 250.0, "kp": 1234.0, "kd": 55.0}


def _unused_equal(build, p: Profile, unused: dict) -> None:
    for field, value in unused.items():
        assert build(p.replace(**{field: value})) == build(p), field
        assert hash(build(p.replace(**{field: value}))) == hash(build(p)), field


def _used_differ(build, p: Profile, used: dict) -> None:
    for field, value in used.items():
        assert build(p.replace(**{field: value})) != build(p), field


def test_the_impedance_device_model_holds_no_coupling_gain(hbfd):
    build = DeviceRequest.of
    _unused_equal(build, hbfd, {"name": "other", "notes": "x", **GAINS})
    _used_differ(build, hbfd, {"device": hbfd.device.replace(sample_time=5e-4)})
    assert build(_filtered(hbfd, 300.0)) != build(hbfd)


def test_the_admittance_device_model_holds_the_pd_gains_only(hbfd):
    p = hbfd.replace(display="admittance")
    build = DeviceRequest.of
    _unused_equal(build, p, {k: GAINS[k] for k in ("kc", "bc", "mc", "bc_adm")})
    _used_differ(build, p, {"kp": GAINS["kp"], "kd": GAINS["kd"]})


def test_stability_holds_the_coupling_of_its_display_only(hbfd):
    build = StabilityRequest.of
    _unused_equal(build, hbfd, {k: GAINS[k] for k in ("mc", "bc_adm", "kp", "kd")})
    _used_differ(build, hbfd, {"kc": GAINS["kc"], "bc": GAINS["bc"], "display": "admittance"})
    # the cached display object is the same one for both gains: equal device requests
    assert StabilityRequest.of(hbfd.replace(kc=1e3)).model == StabilityRequest.of(hbfd).model


def test_the_design_chart_holds_its_own_grid_only(hbfd):
    def build(p: Profile) -> ChartRequest:
        return ChartRequest.of(p, bc_range=(1.0, 1e4), mc_range=(1e-3, 1e3), points=8)

    _unused_equal(build, hbfd, GAINS)
    other_mc = ChartRequest.of(hbfd, bc_range=(1.0, 1e4), mc_range=(1.0, 2.0), points=8)
    assert other_mc == build(hbfd)  # the impedance chart reads no m_c grid
    assert ChartRequest.of(hbfd, bc_range=(1.0, 1e3), mc_range=(1e-3, 1e3), points=8) != build(hbfd)


def test_the_exact_limit_holds_b_c_and_the_delays_not_k_c(hbfd):
    build = ExactLimitRequest.of
    _unused_equal(build, hbfd, {k: GAINS[k] for k in ("kc", "mc", "bc_adm", "kp", "kd")})
    _used_differ(build, hbfd, {"bc": GAINS["bc"]})
    assert build(_delayed(hbfd, 2)) != build(hbfd)
    # a request that differs in b_c computes a different limit; one that does not, the same
    assert exact_limit(build(hbfd.replace(kc=1e3))) == exact_limit(hbfd)
    assert exact_limit(build(hbfd.replace(bc=400.0))) != exact_limit(hbfd)


def test_the_exact_chart_holds_no_coupling(hbfd):
    def build(p: Profile) -> ExactChartRequest:
        return ExactChartRequest.of(p, (1.0, 1e4), 6)

    _unused_equal(build, hbfd, GAINS)
    assert build(_delayed(hbfd, 1)) != build(hbfd)
    _used_differ(build, hbfd, {"display": "admittance"})


def test_the_map_and_the_simulation_hold_the_coupling_and_the_section(hbfd):
    def build(p: Profile) -> MapRequest:
        return MapRequest.of(p, map_params(hbfd))

    _unused_equal(build, hbfd, {"name": "other", "notes": "x", "mc": 3.0, "bc_adm": 250.0})
    _used_differ(build, hbfd, {"kc": GAINS["kc"], "bc": GAINS["bc"]})
    assert build(_delayed(hbfd, 1)) != build(hbfd)
    sim = SimulationRequest.of
    _unused_equal(sim, hbfd, {"name": "other", "mc": 3.0})
    _used_differ(sim, hbfd, {"kc": GAINS["kc"]})
    assert sim(_delayed(hbfd, 1)) != sim(hbfd)


def test_the_design_point_is_the_one_of_the_map(hbfd):
    """The map point computed from a profile and from its request agree, and a gain the map does
    not read (m_c on the impedance display) leaves it unchanged."""
    r = design_radius(hbfd, "kc", "kobj")
    assert r is not None and math.isfinite(r) and r > 0
    assert design_radius(hbfd.replace(mc=3.0), "kc", "kobj") == r
    assert design_radius(hbfd.replace(kc=2 * hbfd.kc), "kc", "kobj") != r


def test_the_z_width_region_holds_no_wall_gain_and_the_optimum_no_cutoff(hbfd):
    _unused_equal(ZWidthRequest.of, hbfd, GAINS)
    assert ZWidthRequest.of(_filtered(hbfd, 300.0)) != ZWidthRequest.of(_filtered(hbfd, 600.0))
    assert ZWidthRequest.of(_delayed(hbfd, 1)) != ZWidthRequest.of(hbfd)
    # the optimum sweeps the cut-off: two cut-offs of the same kind share one sweep (the request without
    # the profile's own filter), which is compared with the current filter (part of the request)
    def sweep(p):
        return dataclasses.replace(OptimumRequest.of(p), current=None)

    assert sweep(_filtered(hbfd, 300.0)) == sweep(_filtered(hbfd, 600.0))
    assert sweep(_filtered(hbfd, 300.0)) == sweep(hbfd)  # the backward difference: lowpass1
    assert OptimumRequest.of(_filtered(hbfd, 300.0)) != OptimumRequest.of(_filtered(hbfd, 600.0))
    lp2 = hbfd.replace(controller=ControllerSection(velocity_filter=VelocityFilter("butter2", 300.0)))
    assert OptimumRequest.of(lp2) != OptimumRequest.of(hbfd)
    np.testing.assert_array_equal(ZWidthRequest.of(hbfd).b, np.geomspace(0.1, 100.0, ZWidthRequest.of(hbfd).b_points))


def test_a_rigid_body_wall_does_not_hold_the_device(hbfd):
    st = wall_settings(hbfd)
    assert st.plant != "chain"
    p = hbfd.replace(wall=st)
    _unused_equal(WallRequest.of, p, {"device": hbfd.device.replace(sample_time=5e-4), **GAINS})
    chain = hbfd.replace(wall=st.replace(plant="chain"))
    _used_differ(WallRequest.of, chain, {"device": hbfd.device.replace(sample_time=5e-4)})


def test_the_two_axis_observer_holds_its_preset_and_filter_only(hbfd):
    st = observer_settings(hbfd)
    p = hbfd.replace(observer=st)
    _unused_equal(TwoAxisRequest.of, p, {"observer": st.replace(nominal_mass=2 * st.nominal_mass,
                                                                step_force=2 * st.step_force)})
    _used_differ(TwoAxisRequest.of, p, {"observer": st.replace(cutoff=2 * st.cutoff)})
    _used_differ(TwoAxisStepRequest.of, p, {"observer": st.replace(step_force=2 * st.step_force)})
    assert isinstance(st, ObserverSettings)


def test_robust_designs_hold_the_design_point_of_their_display(hbfd):
    _unused_equal(RobustRequest.of, hbfd, {k: GAINS[k] for k in ("mc", "bc_adm", "kp", "kd")})
    _used_differ(RobustRequest.of, hbfd, {"kc": GAINS["kc"], "bc": GAINS["bc"]})
    adm = hbfd.replace(display="admittance")
    _unused_equal(RobustRequest.of, adm, {"kc": GAINS["kc"], "bc": GAINS["bc"]})
    _used_differ(RobustRequest.of, adm, {"mc": GAINS["mc"], "bc_adm": GAINS["bc_adm"], "kd": GAINS["kd"]})


def test_stability_from_the_request_reuses_a_built_display(hbfd):
    """The graph evaluates the request on its cached display object: the same numbers as a fresh one."""
    req = StabilityRequest.of(hbfd)
    disp = req.model.build()
    a, b = stability(req, display=disp), stability(hbfd)
    assert a.relative_margin == b.relative_margin and a.worst_margin == b.worst_margin
