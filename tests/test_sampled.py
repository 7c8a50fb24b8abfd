"""Exact sampled-data analysis (issue 5): the linear loop, rigid-device closed forms, HBFD figures.

Findings recorded here (T = 1 ms, HBFD of Adams et al. with b4 = 5 N s/m, b_c = 100 N s/m,
hands-off against a rigid (god-object) wall, see ``test_hbfd_*``):

* the two-port bound (eq. 9) allows k_c <= 117 kN/m; the exact sampled loop is stable up to
  k_c ~ 430 kN/m without delay -- here the bound is conservative;
* with one sample of computation delay the exact limit drops to ~ 86 kN/m: 50 kN/m is stable
  and 110 kN/m oscillates, as on the hardware.  With two samples it is ~ 43 kN/m.  A
  one-sample delay explains the paper's experiment; the b4 = 1.2 N s/m explanation is not
  needed;
* over every passive grasp and environment (``worst_case``) the design 110 kN/m is not
  unconditionally stable even without delay (an undamped grasp spring with a soft penalty wall
  gives rho = 1.00016): the bound's Tustin/half-sample model is optimistic there;
* a massless penalty object with the one-sample implementation delay is unstable by itself
  whenever k_obj > k_c + b_c/T (the paper's 500 kN/m wall with 50 kN/m, 100 N s/m: rho ~ 2.6).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hbfd_fixtures import make_hbfd
from scipy import signal

from analysis import AdmittanceDisplay, Device, ImpedanceDisplay
from analysis.errors import ValidationError
from analysis.sampled import (
    ADMITTANCE_LOOP,
    CONSTRAINT,
    HANDS_OFF,
    IMPEDANCE_LOOP,
    PENALTY,
    RIGID_GRASP,
    Environment,
    Grasp,
    LoopSpec,
    Scenario,
    SimulationOptions,
    Termination,
    causality_kind,
    closed_loop_matrices,
    critical_mass,
    critical_mass_chart,
    critical_stiffness,
    critical_stiffness_chart,
    default_terminations,
    discretize_zoh,
    display_loop,
    free_motion,
    god_object_wall,
    linear_stability_limit,
    passivity_closed_form,
    passivity_limit,
    penalty_wall,
    plant_matrices,
    radii,
    required_damping,
    rigid_stability_polynomial,
    spectral_radius,
    stability_map,
    virtual_wall,
    worst_case,
)


# -- the plant ----------------------------------------------------------------------------
@pytest.mark.parametrize("grasp", [HANDS_OFF, Grasp(1.0, 20.0, 3e3), RIGID_GRASP])
def test_zoh_plant_matches_cont2discrete(grasp):
    dev = make_hbfd()
    A, B = plant_matrices(dev, [grasp])
    Ad, Bd = discretize_zoh(A, B, dev.sample_time)
    C = np.eye(A.shape[1])
    ref = signal.cont2discrete((A[0], B[0], C, np.zeros((C.shape[0], 2))), dev.sample_time, method="zoh")
    np.testing.assert_allclose(Ad[0], ref[0], rtol=1e-10, atol=1e-13)
    np.testing.assert_allclose(Bd[0], ref[1], rtol=1e-10, atol=1e-16)


def _brute_force_impedance_wall(dev: Device, kc: float, bc: float, d: int, steps: int) -> np.ndarray:
    """Independent loop: cont2discrete plant, encoder on the last mass, PD wall at x = 0, delay d."""
    n = dev.n
    M, Bm, K = dev.matrices()
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ Bm]])
    Bu = np.zeros((2 * n, 1))
    Bu[2 * n - 1, 0] = -1.0 / M[n - 1, n - 1]
    Ad, Bd, *_ = signal.cont2discrete((A, Bu, np.eye(2 * n), np.zeros((2 * n, 1))), dev.sample_time, method="zoh")
    rng = np.random.default_rng(1)
    x = rng.normal(size=2 * n) * 1e-3
    yprev = x[n - 1]
    queue = [0.0] * d
    norms = []
    log_scale = 0.0
    for _ in range(steps):
        y = x[n - 1]
        f = kc * y + bc * (y - yprev) / dev.sample_time
        yprev = y
        queue.append(f)
        f = queue.pop(0)
        x = Ad @ x + Bd[:, 0] * f
        nx = np.linalg.norm(x)
        norms.append(log_scale + math.log(nx))
        if nx > 1e50 or nx < 1e-50:  # the loop is linear: rescale every stored signal
            x, yprev, queue = x / nx, yprev / nx, [q / nx for q in queue]
            log_scale += math.log(nx)
    return np.array(norms)  # log of the state norm


@pytest.mark.parametrize("kc,d", [(50e3, 0), (110e3, 1), (60e3, 2), (500e3, 0)])
def test_spectral_radius_equals_brute_force_growth(kc, d):
    dev = make_hbfd()
    spec = LoopSpec("impedance", (kc, 100.0), delay_samples=d)
    rho = spectral_radius(closed_loop_matrices(dev, spec, [Termination(HANDS_OFF, god_object_wall())]))[0]
    steps = 40000
    norms = _brute_force_impedance_wall(dev, kc, 100.0, d, steps)
    # log-linear growth over the second half (the dominant mode has taken over)
    k = np.arange(steps // 2, steps)
    slope = np.polyfit(k, norms[k], 1)[0]
    assert np.exp(slope) == pytest.approx(rho, rel=2e-5)
    assert (np.exp(slope) > 1) == (rho > 1)


def test_closed_loop_matches_transfer_function_roots_rigid():
    """State-space loop eigenvalues = roots of the transfer-function characteristic polynomial."""
    for m, b, T, K, B, d in [(1.0, 2.0, 1e-3, 3000.0, 1.0, 0), (0.3, 0.5, 5e-4, 900.0, 0.0, 2), (5.0, 20.0, 2e-3, 1e4, 5.0, 1)]:
        dev = Device(masses=[m], ground_dampings=[b], sample_time=T)
        spec = LoopSpec("impedance", (K, B), delay_samples=d)
        ev = np.linalg.eigvals(closed_loop_matrices(dev, spec, [Termination(HANDS_OFF, god_object_wall())])[0])
        roots = np.roots(rigid_stability_polynomial(m, b, T, K, B, d))
        assert np.max(np.abs(ev)) == pytest.approx(np.max(np.abs(roots)), rel=1e-9)


# -- rigid device: exact stability and passivity limits ---------------------------------------
RIGID_CASES = [
    # mass, damping, virtual damping, T, delay
    (1.0, 2.0, 0.0, 1e-3, 0),
    (1.0, 2.0, 1.0, 1e-3, 0),
    (0.5, 1.0, 0.5, 1e-3, 1),
    (2.0, 5.0, 2.0, 5e-4, 2),
    (5.0, 3.0, 0.0, 2e-3, 1),
    (0.2, 0.1, 0.05, 1e-3, 3),
    (10.0, 20.0, 10.0, 1e-4, 0),
]


@pytest.mark.parametrize("m,b,B,T,d", RIGID_CASES)
def test_rigid_stability_limit_matches_literature(m, b, B, T, d):
    dev = Device(masses=[m], ground_dampings=[b], sample_time=T)
    k = critical_stiffness(dev, B, d)
    assert k == pytest.approx(linear_stability_limit(b, T, B, d), rel=5e-3)
    # and exactly the first K where the transfer-function polynomial gets a root outside |z| = 1
    below = np.max(np.abs(np.roots(rigid_stability_polynomial(m, b, T, k * (1 - 1e-7), B, d))))
    above = np.max(np.abs(np.roots(rigid_stability_polynomial(m, b, T, k * (1 + 1e-7), B, d))))
    assert below <= 1.0 + 1e-12 < above


@pytest.mark.parametrize("m,b,B,T,d", RIGID_CASES + [(1.0, 2.0, -1.5, 1e-3, 0), (1.0, 4.0, 0.0, 1e-3, 5)])
def test_passivity_limit_matches_closed_form(m, b, B, T, d):
    k = passivity_limit(m, b, T, B, d)
    if d == 0 or B == 0:
        assert k == pytest.approx(passivity_closed_form(b, T, B, d), rel=5e-3)
    # the general criterion for an arbitrary H(z): K is exactly the largest passive stiffness
    need, _ = required_damping(virtual_wall(k, B, T, d), T)
    assert need == pytest.approx(b, rel=1e-6)
    assert required_damping(virtual_wall(1.01 * k, B, T, d), T)[0] > b


def test_passivity_infeasible_and_validation():
    assert math.isnan(passivity_limit(1.0, 1.0, 1e-3, virtual_damping=2.0))
    with pytest.raises(ValidationError) as e:
        passivity_limit(1.0, -1.0, 1e-3)
    assert e.value.field == "damping"
    with pytest.raises(ValidationError) as e:
        passivity_limit(1.0, 1.0, 1e-3, delay_samples=-1)
    assert e.value.field == "delay_samples"


def test_passivity_is_stricter_than_stability_with_virtual_damping():
    b, T, B = 2.0, 1e-3, 1.0
    assert passivity_limit(1.0, b, T, B) < critical_stiffness(Device(masses=[1.0], ground_dampings=[b], sample_time=T), B)


# -- HBFD: the paper's couplings ----------------------------------------------------------------
@pytest.fixture(scope="module")
def dev():
    return make_hbfd()


def test_hbfd_critical_stiffness_and_delay(dev):
    bound = ImpedanceDisplay(dev).max_stiffness(100.0).kc
    assert bound == pytest.approx(117.1e3, rel=2e-3)
    k0 = critical_stiffness(dev, 100.0, 0)
    k1 = critical_stiffness(dev, 100.0, 1)
    k2 = critical_stiffness(dev, 100.0, 2)
    assert k0 > bound  # the bound is conservative for this termination without delay
    assert 50e3 < k1 < 110e3  # one sample of delay reproduces the experiment
    assert k2 < 50e3
    assert k0 == pytest.approx(430.6e3, rel=1e-2)
    assert k1 == pytest.approx(85.6e3, rel=1e-2)
    assert k2 == pytest.approx(43.2e3, rel=1e-2)
    # bisection result is a true crossing
    r = radii(dev, LoopSpec("impedance", (k1, 100.0), delay_samples=1),
              [Termination(HANDS_OFF, god_object_wall())] * 2, {"kc": [k1 * 0.999, k1 * 1.001]})
    assert r[0] <= 1.0 < r[1]


def test_hbfd_worst_case_paper_couplings(dev):
    imp50 = worst_case(dev, "impedance", (50e3, 100.0))
    assert imp50.stable
    imp110 = worst_case(dev, "impedance", (110e3, 100.0))
    assert not imp110.stable and imp110.spectral_radius < 1.001
    assert imp110.radii.shape == (len(default_terminations()),)
    assert imp110.termination == imp110.terminations[imp110.index]
    assert not worst_case(dev, "impedance", (50e3, 100.0), delay_samples=1).stable
    adm = AdmittanceDisplay(dev, 50e3, 100.0)
    md = adm.min_mass()
    # the paper's bound design is stable for every default termination without delay; the
    # experimental (8 kg, 400 N s/m) is not: a heavy undamped hand destabilizes the PD loop
    assert worst_case(dev, "admittance", (31.0, 1550.0)).stable
    assert worst_case(dev, "admittance", (md.mc, md.bc)).stable
    exp = worst_case(dev, "admittance", (8.0, 400.0))
    assert not exp.stable and exp.termination.grasp.mass > 0


def test_critical_charts(dev):
    chart = critical_stiffness_chart(dev, [20.0, 100.0, 300.0])
    assert chart.kc.shape == (3,) and np.all(chart.kc > 0)
    assert chart.kc[1] == pytest.approx(critical_stiffness(dev, 100.0))
    mc = critical_mass(dev, 1550.0, grasp=Grasp(2.0, 50.0, 2e3))
    assert 0 <= mc < 31.0
    mchart = critical_mass_chart(dev, [800.0, 1550.0], grasp=Grasp(2.0, 50.0, 2e3))
    assert mchart.mc[1] == pytest.approx(mc)


def test_stability_map_is_one_batched_sweep(dev):
    kcs = np.geomspace(1e4, 1e6, 7)
    kobjs = np.geomspace(1e3, 1e6, 5)
    sm = stability_map(dev, ("kc", kcs), ("kobj", kobjs))
    assert sm.spectral_radius.shape == (5, 7)
    j, i = 3, 4
    spec = LoopSpec("impedance", (kcs[i], 100.0))
    r = radii(dev, spec, [Termination(HANDS_OFF, penalty_wall(kobjs[j]))])[0]
    assert sm.spectral_radius[j, i] == pytest.approx(r, rel=1e-12)
    gm = stability_map(dev, ("kc", kcs), ("grasp_mass", [0.0, 1.0, 3.0]),
                       termination=Termination(HANDS_OFF, god_object_wall()))
    assert gm.spectral_radius.shape == (3, 7)
    assert gm.stable.dtype == bool
    with pytest.raises(ValidationError):
        stability_map(dev, ("kc", kcs), ("nonsense", [1.0]))


def test_four_architectures_and_implementation_delay(dev):
    terms_imp = [Termination(HANDS_OFF, penalty_wall()), Termination(HANDS_OFF, free_motion())]
    terms_adm = [Termination(HANDS_OFF, god_object_wall()), Termination(RIGID_GRASP, free_motion("admittance"))]
    for display, c in (("impedance", (50e3, 100.0)), ("admittance", (31.0, 1550.0))):
        for lag in (False, True):
            spec = LoopSpec(display, c, implementation_delay=lag)
            r = radii(dev, spec, terms_imp + terms_adm)
            assert np.all(np.isfinite(r))
    # explicit integration of a massless penalty object: unstable by itself when k_obj > k_c + b_c/T
    r = radii(dev, LoopSpec("impedance", (50e3, 100.0), implementation_delay=True), [terms_imp[0]])[0]
    assert r > 2.0
    r = radii(dev, LoopSpec("impedance", (50e3, 100.0), implementation_delay=True),
              [Termination(HANDS_OFF, penalty_wall(100e3))])[0]
    assert r <= 1.0


def test_loop_spec_validation():
    with pytest.raises(ValidationError) as e:
        LoopSpec("impedance", (-1.0, 100.0))
    assert e.value.field == "kc"
    with pytest.raises(ValidationError) as e:
        LoopSpec("admittance", (0.0, 100.0))
    assert e.value.field == "mc"
    with pytest.raises(ValidationError) as e:
        LoopSpec("sideways")
    assert e.value.field == "display"
    with pytest.raises(ValidationError) as e:
        critical_stiffness(make_hbfd(), -5.0)
    assert e.value.field == "bc"


# -- displays and causalities are objects --------------------------------------------------------
def test_display_and_causality_names_map_to_one_object_each():
    assert display_loop("impedance") is IMPEDANCE_LOOP and display_loop("admittance") is ADMITTANCE_LOOP
    assert display_loop(ADMITTANCE_LOOP) is ADMITTANCE_LOOP
    assert LoopSpec("admittance", (8.0, 400.0)).loop is ADMITTANCE_LOOP
    assert causality_kind("impedance") is PENALTY and causality_kind("admittance") is CONSTRAINT
    assert Environment("admittance", wall=True).kind is CONSTRAINT and penalty_wall().kind is PENALTY
    for bad, lookup, field in (("sideways", display_loop, "display"), ("x", causality_kind, "causality")):
        with pytest.raises(ValidationError) as e:
            lookup(bad)
        assert e.value.field == field and "impedance or admittance" in str(e.value)


def test_loop_objects_name_memory_gains_and_terminations():
    assert IMPEDANCE_LOOP.memory_names(PENALTY, False) == ("delta", "xe")
    assert IMPEDANCE_LOOP.memory_names(CONSTRAINT, True) == ("delta", "xe", "ve", "fe")
    assert ADMITTANCE_LOOP.memory_names(PENALTY, True) == ("yp", "xc", "w", "fe")
    assert ADMITTANCE_LOOP.memory_names(CONSTRAINT, False) == ("yp", "xc", "ve", "w")
    assert IMPEDANCE_LOOP.default_coupling == (50e3, 100.0) and ADMITTANCE_LOOP.default_coupling == (8.0, 400.0)
    assert IMPEDANCE_LOOP.default_termination() == Termination(HANDS_OFF, penalty_wall())
    assert ADMITTANCE_LOOP.default_termination() == Termination(RIGID_GRASP, free_motion("impedance"))
    # the penalty wall pushes only while penetrated; the god-object wall holds the object on it
    assert not PENALTY.contact(1e-3, 1e-3) and PENALTY.contact(2e-3, 1e-3)
    assert CONSTRAINT.contact(1e-3, 1e-3) and not CONSTRAINT.contact(0.0, 1e-3)
    assert not PENALTY.constrains(True) and CONSTRAINT.constrains(True) and not CONSTRAINT.constrains(False)
    with pytest.raises(ValidationError) as e:
        Environment("impedance", wall=True)
    assert e.value.field == "wall"
    with pytest.raises(ValidationError) as e:
        Environment("admittance", mass=0)
    assert e.value.field == "mass" and e.value.value == 0


def test_stability_map_default_termination_is_the_loops():
    dev = make_hbfd()
    x, y = ("mc", [4.0, 8.0, 31.0]), ("bc", [400.0, 1550.0])
    a = stability_map(dev, x, y, display="admittance", coupling=(8.0, 400.0))
    b = stability_map(dev, x, y, display="admittance", coupling=(8.0, 400.0),
                      termination=ADMITTANCE_LOOP.default_termination())
    assert a.spectral_radius.shape == (2, 3)
    np.testing.assert_array_equal(a.spectral_radius, b.spectral_radius)
    # against a rigid grasp, b_c = 400 N s/m is unstable for every m_c and b_c = 1550 N s/m is
    # stable above critical_mass (1.63 kg), the same termination's exact limit
    assert np.all(a.spectral_radius[0] > 1.0)
    assert critical_mass(dev, 1550.0) < 4.0 and np.all(a.spectral_radius[1] <= 1.0)


# -- options and scenarios for the profile -------------------------------------------------------
def test_options_and_scenario_round_trip():
    opt = SimulationOptions(substeps=6, encoder_resolution=15e-6, friction=(0, 1, 0, 0.5), force_continuous=100.0,
                            force_peak=400.0, delay_samples=1)
    assert SimulationOptions.from_dict(opt.to_dict()) == opt
    assert SimulationOptions.from_dict(SimulationOptions().to_dict()) == SimulationOptions()
    sc = Scenario(name="x", grasp=Grasp(1.0, 2.0, 3.0), release_time=0.3)
    assert Scenario.from_dict(sc.to_dict()) == sc
    import json

    assert Scenario.from_dict(json.loads(json.dumps(Scenario().to_dict()))) == Scenario()


@pytest.mark.parametrize("cls,data,field", [
    (SimulationOptions, {"substeps": 0}, "substeps"),
    (SimulationOptions, {"encoder_resolution": -1}, "encoder_resolution"),
    (SimulationOptions, {"friction": [0, -1]}, "friction"),
    (SimulationOptions, {"force_continuous": 500.0, "force_peak": 400.0}, "force_peak"),
    (SimulationOptions, {"bogus": 1}, "bogus"),
    (Scenario, {"causality": "x"}, "causality"),
    (Scenario, {"duration": 0}, "duration"),
    (Scenario, {"grasp": {"mass": -1}}, "mass"),
    (Scenario, {"push_start": 1.0, "push_end": 0.5}, "push_end"),
])
def test_options_validation_names_field(cls, data, field):
    with pytest.raises(ValidationError) as e:
        cls.from_dict(data)
    assert e.value.field == field
