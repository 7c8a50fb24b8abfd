"""The nonlinear time-domain simulator (issue 5)."""

from __future__ import annotations

import numpy as np
import pytest
from hbfd_fixtures import make_hbfd

from analysis.sampled import (
    HANDS_OFF,
    RIGID_GRASP,
    SCENARIOS,
    Grasp,
    LoopSpec,
    Scenario,
    SimulationOptions,
    Termination,
    closed_loop_matrices,
    detect,
    free_motion,
    hbfd_options,
    simulate,
)


@pytest.fixture(scope="module")
def dev():
    return make_hbfd()


@pytest.mark.parametrize("display,coupling,grasp", [
    ("impedance", (50e3, 100.0), Grasp(1.0, 10.0, 500.0)),
    ("admittance", (31.0, 1550.0), RIGID_GRASP),
    ("admittance", (8.0, 400.0), HANDS_OFF),
])
def test_linear_simulation_matches_closed_loop_matrix(dev, display, coupling, grasp):
    """No nonlinear option and no wall: the simulator is the linear loop, step for step."""
    sc = Scenario(wall=False, grasp=grasp, initial_velocity=0.01, duration=0.3)
    r = simulate(dev, sc, display=display, coupling=coupling)
    spec = LoopSpec(display, coupling)
    Phi = closed_loop_matrices(dev, spec, [Termination(grasp, free_motion())])[0]
    n = dev.n
    s = np.zeros(Phi.shape[0])
    s[n:2 * n] = 0.01
    traj = []
    for _ in range(r.t.size):
        traj.append(s[:n].copy())
        s = Phi @ s
    traj = np.array(traj)
    scale = np.max(np.abs(traj))
    np.testing.assert_allclose(r.positions, traj, atol=1e-10 * scale)


def test_halving_the_substep_changes_less_than_1e6(dev):
    """Friction and saturation on (quantization off: it is discontinuous by nature)."""
    base = hbfd_options(encoder_resolution=0.0, force_resolution=0.0, force_continuous=20.0, force_peak=60.0)
    for name, display, c in (("wall_push", "impedance", (50e3, 100.0)),
                             ("admittance_worst_case", "admittance", (31.0, 1550.0))):
        a = simulate(dev, name, 1.0, display=display, coupling=c, options=base.__class__(**{**base.to_dict(),
                                                                                           "substeps": 4}))
        b = simulate(dev, name, 1.0, display=display, coupling=c, options=base.__class__(**{**base.to_dict(),
                                                                                           "substeps": 8}))
        assert a.events > 0
        rel = np.max(np.abs(a.positions - b.positions)) / np.max(np.abs(b.positions))
        assert rel < 1e-6
        relf = np.max(np.abs(a.f_d - b.f_d)) / np.max(np.abs(b.f_d))
        assert relf < 1e-6


def test_energy_observer_and_outputs(dev):
    r = simulate(dev, "wall_push", 1.0)
    assert r.t.shape == (1001,) and r.positions.shape == (1001, 4)
    np.testing.assert_allclose(r.energy_observed, r.energy, rtol=1e-12, atol=1e-15)  # exact encoder
    assert r.contact.any()
    # at rest against the wall: the human force is the push minus the grasp spring, and the
    # actuator holds it (the device is at rest, its dampers carry nothing)
    g = SCENARIOS["wall_push"].grasp
    acc = (r.velocities[-1, 0] - r.velocities[-2, 0]) / 1e-3
    expect = 10.0 - g.stiffness * r.positions[-1, 0] - g.damping * r.velocities[-1, 0] - g.mass * acc
    assert r.f_h[-1] == pytest.approx(expect, rel=1e-3)
    assert r.f_d[-1] == pytest.approx(r.f_h[-1], rel=1e-2)
    q = simulate(dev, "wall_push", 1.0, options=hbfd_options())
    assert np.all(np.abs(np.diff(q.encoder[q.encoder != 0]) / 15e-6 - np.round(np.diff(q.encoder[q.encoder != 0]) / 15e-6))
                  < 1e-6)


def test_saturation(dev):
    opt = SimulationOptions(force_peak=30.0, force_continuous=5.0, thermal_time_constant=0.05)
    r = simulate(dev, "wall_push", 1.0, options=opt)
    assert np.max(np.abs(r.f_d)) <= 30.0 + 1e-12
    assert abs(r.f_d[-1]) <= 5.0 + 1e-12  # folded back to the continuous rating


def test_verdicts(dev):
    ok = simulate(dev, "admittance_worst_case", display="admittance", coupling=(31.0, 1550.0))
    assert ok.verdict.kind == "stable"
    bad = simulate(dev, "admittance_worst_case", display="admittance", coupling=(8.0, 400.0))
    assert bad.verdict.kind == "divergent"
    # saturation turns the divergence into a sustained oscillation
    sat = simulate(dev, "admittance_worst_case", display="admittance", coupling=(8.0, 400.0),
                   options=SimulationOptions(force_peak=400.0, force_continuous=100.0))
    assert sat.verdict.kind in ("sustained oscillation", "divergent")
    t = np.arange(1000) * 1e-3
    assert detect(t, 1e-3 * np.sin(300 * t)).kind == "sustained oscillation"
    assert detect(t, 1e-3 * np.exp(-5 * t) * np.sin(300 * t)).kind == "stable"
    assert detect(t, 1e-6 * np.exp(5 * t) * np.sin(300 * t)).kind == "divergent"


def test_presets_run(dev):
    for name in SCENARIOS:
        r = simulate(dev, name, 0.3, options=hbfd_options(delay_samples=1, implementation_delay=True))
        assert np.all(np.isfinite(r.f_d))


def test_a_frictionless_run_stops_where_it_diverges(dev):
    """Without friction as with it, a run stops once |x_1| passes 1e6 m: the signals after it are NaN
    (drawn as gaps and said), never the overflow of a minute-long exponential growth."""
    import warnings

    sc = Scenario(wall=False, grasp=RIGID_GRASP, initial_velocity=0.01, duration=60.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or invalid-value warning on the way
        r = simulate(dev, sc, display="admittance", coupling=(8.0, 400.0))
    assert r.verdict.kind == "divergent"
    x = r.handle_position
    finite = np.isfinite(x)
    stop = int(np.argmin(finite))
    assert 0 < stop < x.size // 2 and finite[:stop].all() and not finite[stop:].any()
    assert np.abs(x[:stop]).max() <= 1e6 < np.abs(x[:stop]).max() * 1e3  # stopped near the threshold
    for signal in (r.f_d, r.energy, r.encoder):
        assert np.isfinite(signal[:stop]).all() and np.isnan(signal[stop:]).all()
