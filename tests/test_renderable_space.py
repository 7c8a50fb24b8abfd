"""The renderable (M, B, K) space and its qualities (issue 24), against independent routes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import optimize

from analysis import Device
from analysis.errors import ValidationError
from analysis.progress import OperationCancelled
from analysis.sampled import (
    AccelerationEstimate,
    Grasp,
    QualitySettings,
    RenderedEnvironment,
    RenderingController,
    VelocityFilter,
    effective_environment,
    passivity_limits,
    rendered_force_response,
    renderable_space,
    renders_passively,
    renders_quietly,
    renders_stably,
    space_volume,
    zwidth_region,
)
from analysis.chain import handle_impedance
from analysis.sampled.loop import is_stable
from analysis.sampled.qualities import accuracy_k, accuracy_mass_limits, stable_radius
from analysis.sampled.rendered import handle_force_response, handle_transmission
from analysis.sampled.terminations import god_object_wall
from test_m_width import hand_radii, hand_radius, loop_radius

T = 1e-3
PROPS = settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def rigid(m: float = 0.5, b: float = 2.0) -> Device:
    return Device(masses=[m], stiffnesses=[], dampings=[], ground_dampings=[b], sensor_element=0, sample_time=T)


@pytest.mark.parametrize("vf", [None, VelocityFilter("lowpass1", cutoff=2 * math.pi * 40)])
@pytest.mark.parametrize("which", ["rigid", "hbfd"])
def test_zero_mass_is_the_zwidth_region_bit_for_bit(which, vf, hbfd):
    dev = rigid() if which == "rigid" else hbfd
    b = np.geomspace(0.1, 100.0, 9)
    s = renderable_space(dev, mass=[-0.05, 0.0, 0.05], damping=b, delay_samples=1, velocity_filter=vf)
    region = zwidth_region(dev, b=b, delay_samples=1, velocity_filter=vf, passive=False)
    assert np.array_equal(s.by_quality["stable"][1], region.k_max)
    assert np.array_equal(s.k_max, s.by_quality["stable"])


def hand_k_max(m: float, b: float, M: float, B: float, d: int) -> float:
    """The first K in [1, 1e9] N/m where the hand-built polynomial's largest root leaves the unit
    circle (brute force: every root on 2000 points, then Brent), 0 if it is outside at 1 N/m, 1e9
    if it never is."""

    def g(K: float) -> float:
        return hand_radius(m, b, M, B, K, d) - 1.0

    grid = np.geomspace(1.0, 1e9, 2000)
    vals = hand_radii(m, b, M, B, grid, d) - 1.0  # g on the whole grid, in one batched call
    if vals[0] > 0:
        return 0.0
    if not np.any(vals > 0):
        return 1e9
    j = int(np.argmax(vals > 0))
    return float(optimize.brentq(g, grid[j - 1], grid[j], xtol=1e-12, rtol=1e-14))


@pytest.mark.parametrize(("M", "B", "d"), [(0.2, 3.0, 1), (-0.2, 1.0, 1), (0.4, 10.0, 0), (-0.1, -1.0, 2)])
def test_k_max_is_the_first_root_crossing_of_the_hand_polynomial(M, B, d):
    m, b = 0.5, 2.0
    s = renderable_space(rigid(m, b), mass=[M], damping=[B], delay_samples=d)
    ref = hand_k_max(m, b, M, B, d)
    assert 1.0 < ref < 1e9  # a crossing, not a bound of the range
    assert float(s.k_max[0, 0]) == pytest.approx(ref, rel=1e-8)


# -- the held object's free step, singular (issue 24's crash) --------------------------------
#: The device of the report: a rigid handle (kg, N s/m).
CRASH_M, CRASH_B = 0.41476820043770657, 1.1611319651463206
#: The god-object's mass (kg), the object the wall holds.
OBJECT_MASS = god_object_wall().mass


def free_step_denominator(M: float, B: float, K: float) -> float:
    """The free object's implicit step, as the controller forms it: the object's inertia m_e/T^2
    (no object damping at the god-object wall) plus the rendered environment's direct feedthrough
    (K + B/T, then + M/T^2 of the second difference, the weight of x[k] in F[k])."""
    return OBJECT_MASS / (T * T) + ((K + B / T) + M * (1.0 / (T * T))) + 0.0 / T


def test_a_feedthrough_that_cancels_the_held_object_is_exact():
    """The report: M = -2BT (B = 30 N s/m, T = 1 ms) and K = 1e4 N/m, a point of the trace's scan,
    make the free object's step singular (0 in floating point too).  The wall holds the object
    there (x_e = x_w), so the loop is the hand-built polynomial's, and the space is its crossing."""
    M, B, K = -2 * 30.0 * T, 30.0, 1e4
    assert free_step_denominator(M, B, K) == 0.0
    rho = loop_radius(rigid(CRASH_M, CRASH_B), M, B, K, 1)
    assert rho == pytest.approx(hand_radius(CRASH_M, CRASH_B, M, B, K, 1), rel=1e-9)
    s = renderable_space(rigid(CRASH_M, CRASH_B), [M], [B])
    assert float(s.k_max[0, 0]) == pytest.approx(hand_k_max(CRASH_M, CRASH_B, M, B, 1), rel=1e-8)
    assert 1.0 < s.k_max[0, 0] < 1e9


@st.composite
def singular_points(draw) -> tuple[float, float, float]:
    """(M, B, K) with the free object's step singular in floating point: M = -(m_e + B T + K T^2)."""
    B = draw(st.floats(-5.0, 60.0))
    K = draw(st.floats(1.0, 1e5))
    M = -(OBJECT_MASS + B * T + K * T * T)
    return M, B, K


@PROPS
@given(point=st.one_of(st.tuples(st.floats(-0.3, 0.6), st.floats(-1.0, 60.0), st.none()),
                       singular_points().filter(lambda p: free_step_denominator(*p) == 0.0)))
def test_the_space_never_raises_and_is_the_brute_force_crossing(point):
    """Random (M, B), and points where the held object's free step is singular: the loop at that K
    is the hand polynomial's, and k_max is the brute-force first crossing."""
    M, B, K = point
    dev = rigid(CRASH_M, CRASH_B)
    if K is not None:
        assert loop_radius(dev, M, B, K, 1) == pytest.approx(hand_radius(CRASH_M, CRASH_B, M, B, K, 1), rel=1e-9)
    k = float(renderable_space(dev, [M], [B]).k_max[0, 0])
    ref = hand_k_max(CRASH_M, CRASH_B, M, B, 1)
    if ref in (0.0, 1e9):
        assert k == ref
    else:
        assert k == pytest.approx(ref, rel=1e-8)


def test_the_space_agrees_with_the_stability_predicate_on_either_side(hbfd):
    ctrl = RenderingController(delay_samples=1)
    s = renderable_space(hbfd, mass=[-0.3, 0.1, 0.4], damping=[0.5, 20.0], delay_samples=1)
    checked = 0
    for i, M in enumerate(s.mass):
        for j, B in enumerate(s.damping):
            k = float(s.k_max[i, j])
            if not 1.0 < k < 1e9:
                continue
            checked += 1
            for frac in (0.1, 0.5, 0.999):
                assert renders_stably(hbfd, ctrl, M, B, frac * k)
            assert not renders_stably(hbfd, ctrl, M, B, 1.001 * k)
    assert checked >= 4


def test_grasps_intersect_the_stable_space(hbfd):
    grasp = Grasp(mass=0.3, damping=5.0, stiffness=200.0)
    M, B = [-0.2, 0.2], [1.0, 30.0]
    alone = renderable_space(hbfd, M, B, 1, settings=QualitySettings(grasps=(grasp,))).k_max
    off = renderable_space(hbfd, M, B, 1).k_max
    both = renderable_space(hbfd, M, B, 1, settings=QualitySettings(grasps=(Grasp(), grasp))).k_max
    assert np.array_equal(both, np.minimum(alone, off))


def test_the_plant_is_discretized_once_per_grasp(hbfd):
    """The trace never recomputes the matrix exponential per point (discrete_plants' cache)."""
    from unittest import mock

    from scipy import linalg

    real, calls = linalg.expm, []

    def counting(a, *args, **kwargs):
        calls.append(np.shape(a))
        return real(a, *args, **kwargs)

    # a handle mass no other test uses, so the plant cache starts cold for this device
    cold = hbfd.replace(masses=hbfd.masses * (1.0 + 3.7e-7))
    with mock.patch.object(linalg, "expm", counting):
        renderable_space(cold, np.linspace(-0.2, 0.2, 5), np.linspace(-1.0, 20.0, 6), 1)
    assert len(calls) == 1


def test_zero_mass_passivity_is_colgate_schenkel():
    b = np.array([0.0, 0.5, 1.0, 1.5])
    s = renderable_space(rigid(), mass=[0.0], damping=b, delay_samples=1, qualities=("passive",))
    ref = passivity_limits(0.5, 2.0, T, b, 1)
    # the space's grid is 2001 points refined on 65 (the Z-width region's 4001 on 4001): the minimum
    # over theta agrees to the grids' quadratic error
    assert s.k_max[0] == pytest.approx(np.where(np.isnan(ref), 0.0, ref), rel=1e-7)
    ctrl = RenderingController(1)
    k = float(s.k_max[0, 1])
    assert renders_passively(rigid(), ctrl, 0.0, 0.5, 0.999 * k)
    assert not renders_passively(rigid(), ctrl, 0.0, 0.5, 1.001 * k)


def test_a_virtual_mass_costs_passivity():
    """b >= M c_M(theta): a positive mass needs damping at Nyquist (c_M(pi) = 2M/T for d = 0)."""
    s = renderable_space(rigid(), mass=[0.0, 2e-4, 5e-4], damping=[0.0], delay_samples=0, qualities=("passive",))
    k = s.k_max[:, 0]
    # d = 0, B = 0: K a(pi) + c_M(pi) <= b with a(pi) = T/2 binds at Nyquist: K = (b - 2M/T)/(T/2)
    assert k[1] == pytest.approx((2.0 - 2 * 2e-4 / T) / (T / 2), rel=1e-9)
    assert k[2] == pytest.approx((2.0 - 2 * 5e-4 / T) / (T / 2), rel=1e-9)


@pytest.mark.parametrize("d", [0, 2])
def test_effective_stiffness_and_damping_of_a_sampled_spring(d):
    """Colonnese et al. 2015: a ZOH spring feels like K_eff = K cos((d+1/2) wT) sinc and a negative
    damping B_eff = -K sin((d+1/2) wT) sin(wT/2)/(w wT/2), -> -K T (d + 1/2) at low frequency."""
    K = 3000.0
    s = QualitySettings(band=(1.0, 600.0), band_points=40)
    eff = effective_environment(rigid(), RenderedEnvironment(stiffness=K), RenderingController(d), s)
    w, h = eff.w, 0.5 * eff.w * T
    assert eff.stiffness == pytest.approx(K * np.cos((d + 0.5) * w * T) * np.sin(h) / h, rel=1e-12)
    assert eff.damping == pytest.approx(-K * np.sin((d + 0.5) * w * T) * np.sin(h) / (w * h), rel=1e-10)
    assert eff.damping[0] == pytest.approx(-K * T * (d + 0.5), rel=1e-5)
    if d == 0:
        assert eff.stiffness == pytest.approx(K * np.sin(w * T) / (w * T), rel=1e-12)
        assert eff.damping == pytest.approx(-K * (1 - np.cos(w * T)) / (w * w * T), rel=1e-9)


def test_the_fitted_environment_recovers_what_is_rendered_at_low_frequency():
    env = RenderedEnvironment(mass=0.2, damping=4.0, stiffness=800.0)
    eff = effective_environment(rigid(), env, RenderingController(0), QualitySettings(band=(1.0, 20.0)))
    # the hold and the differences lag: the damper's j w B e^{-j w T} adds B T w^2 to Re G, so the
    # user feels M - B T; the spring's e^{-j w T/2} takes K T/2 off the damping
    assert eff.fitted_mass == pytest.approx(0.2 - 4.0 * T, rel=1e-3)
    assert eff.fitted_stiffness == pytest.approx(800.0, rel=1e-3)
    assert eff.fitted_damping == pytest.approx(4.0 - 800.0 * T / 2, rel=2e-2)
    assert np.all(eff.error < 0.05)


def test_quiet_is_the_velocity_noise_criterion_at_zero_mass():
    q, F = 1e-5, 0.1
    s = QualitySettings(encoder_resolution=q, force_noise=F)
    b_noise = F / (q * math.sqrt(2.0) / T / math.sqrt(12.0))  # sigma_v of the backward difference
    ctrl = RenderingController(1)
    assert renders_quietly(rigid(), ctrl, 0.0, 0.999 * b_noise, 1e6, s)
    assert not renders_quietly(rigid(), ctrl, 0.0, 1.001 * b_noise, settings=s)
    assert not renders_quietly(rigid(), ctrl, 0.0, -1.001 * b_noise, settings=s)
    # B V + M A: for the second difference sum h_V h_A = (1*1 + (-1)(-2))/T^3 = 3/T^3
    M, B = 1e-3, 2.0
    sigma = q / math.sqrt(12) * math.sqrt(B * B * 2 / T ** 2 + 2 * B * M * 3 / T ** 3 + M * M * 6 / T ** 4)
    assert renders_quietly(rigid(), ctrl, M, B, settings=QualitySettings(encoder_resolution=q, force_noise=sigma * 1.001))
    assert not renders_quietly(rigid(), ctrl, M, B,
                               settings=QualitySettings(encoder_resolution=q, force_noise=sigma * 0.999))
    with pytest.raises(ValidationError) as err:
        renders_quietly(rigid(), ctrl, M, B)
    assert err.value.field == "encoder_resolution"


def test_the_space_of_every_quality_is_the_smallest_and_progress_reaches_the_end(hbfd):
    calls: list[tuple[int, int]] = []
    s = renderable_space(hbfd, np.linspace(-0.05, 0.05, 5), np.linspace(-2.0, 10.0, 4), 1,
                         qualities=("stable", "passive", "accurate", "quiet"),
                         settings=QualitySettings(encoder_resolution=1e-6, force_noise=1.0),
                         progress=lambda d, t: calls.append((d, t)))
    stacked = np.stack([s.by_quality[q] for q in s.qualities])
    assert np.array_equal(s.k_max, stacked.min(axis=0))
    assert np.all(s.by_quality["accurate"] <= s.by_quality["stable"])
    assert calls[-1][0] == calls[-1][1] and [d for d, _ in calls] == sorted(d for d, _ in calls)
    assert s.k_max.shape == (5, 4) and not s.k_max.flags.writeable


def test_cancel_stops_the_space(hbfd):
    with pytest.raises(OperationCancelled):
        renderable_space(hbfd, [0.0, 0.1], [1.0, 2.0], 1, cancelled=lambda: True)


def test_volume_is_the_trapezoid_on_signed_log_damping():
    s = renderable_space(rigid(), mass=[-0.1, 0.1], damping=[-0.5, 9.0], delay_samples=1)
    h = np.log10(np.maximum(s.k_max, 1.0))
    u = np.array([-math.log10(1.5), 1.0])  # sign(B) log10(1 + |B|/1 N s/m)
    assert s.volume == pytest.approx(0.2 * (u[1] - u[0]) * h.mean(), rel=1e-12)
    assert renderable_space(rigid(), mass=[0.1], damping=[1.0, 9.0], delay_samples=1).volume == 0.0
    assert space_volume(s.mass, s.damping, s.k_max, s.settings) == s.volume


def test_space_volume_is_public_and_names_a_bad_k_max():
    m, b = [-1.0, 1.0], [0.0, 9.0]  # u = 0, 1: the volume is 2 kg x 1 decade x the mean height
    assert space_volume(m, b, [[1.0, 1e3], [1e9, 1e12]]) == pytest.approx(2.0 * (0 + 3 + 9 + 9) / 4, rel=1e-15)
    assert space_volume(m, b, np.zeros((2, 2))) == 0.0
    with pytest.raises(ValidationError) as err:
        space_volume(m, b, np.zeros((2, 3)))
    assert err.value.field == "k_max"
    with pytest.raises(ValidationError) as err:
        space_volume(m, b, [[0.0, math.nan], [1.0, 1.0]])
    assert err.value.field == "k_max"


@PROPS
@given(eps=st.floats(0.02, 0.5), factor=st.floats(1.1, 5.0), M=st.floats(-0.3, 0.3), B=st.floats(-1.0, 20.0))
def test_accurate_nests_in_stable_and_grows_with_the_tolerance(eps, factor, M, B):
    band = QualitySettings(band=(2.0, 30.0), tolerance=eps)
    wide = QualitySettings(band=(2.0, 30.0), tolerance=min(10.0, eps * factor))
    a = renderable_space(rigid(), [M], [B], 1, qualities=("stable", "accurate"), settings=band)
    b = renderable_space(rigid(), [M], [B], 1, qualities=("accurate",), settings=wide)
    assert a.by_quality["accurate"][0, 0] <= a.by_quality["stable"][0, 0]
    assert a.by_quality["accurate"][0, 0] <= b.k_max[0, 0]


@PROPS
@given(q1=st.floats(1e-7, 1e-4), factor=st.floats(1.0, 10.0), M=st.floats(-0.01, 0.01), B=st.floats(-5.0, 5.0))
def test_quiet_shrinks_with_a_coarser_encoder(q1, factor, M, B):
    fine = renderable_space(rigid(), [M], [B], 1, qualities=("quiet",), settings=QualitySettings(encoder_resolution=q1))
    coarse = renderable_space(rigid(), [M], [B], 1, qualities=("quiet",),
                              settings=QualitySettings(encoder_resolution=min(q1 * factor, 1e-2)))
    assert coarse.k_max[0, 0] <= fine.k_max[0, 0]


@PROPS
@given(b1=st.floats(0.1, 10.0), extra=st.floats(0.0, 10.0), M=st.floats(-2e-3, 2e-3), B=st.floats(-1.0, 1.0))
def test_passive_grows_with_the_device_damping(b1, extra, M, B):
    """Colgate-Schenkel: b >= K a + c, so more physical damping b never shrinks the passive K."""
    lo = renderable_space(rigid(b=b1), [M], [B], 1, qualities=("passive",)).k_max[0, 0]
    hi = renderable_space(rigid(b=b1 + extra), [M], [B], 1, qualities=("passive",)).k_max[0, 0]
    assert hi >= lo * (1 - 1e-9)


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"mass": [0.0, float("nan")]}, "mass"),
    ({"mass": []}, "mass"),
    ({"damping": np.array([])}, "damping"),
    ({"mass": [0.2, 0.1]}, "mass"),
    ({"mass": [2e3]}, "mass"),
    ({"damping": [1.0, float("inf")]}, "damping"),
    ({"qualities": ("stable", "pleasant")}, "qualities"),
    ({"qualities": ("accurate",), "settings": QualitySettings(band=(1.0, 1e4))}, "band"),
    ({"qualities": ("quiet",)}, "encoder_resolution"),
    ({"settings": {"tolerance": 0.1}}, "settings"),
    ({"velocity_filter": VelocityFilter("butter2", cutoff=5e3)}, "cutoff"),
    ({"acceleration": "second"}, "acceleration"),
])
def test_bad_input_names_the_field(kwargs, field):
    args = {"mass": [0.0], "damping": [1.0], **kwargs}
    with pytest.raises(ValidationError) as err:
        renderable_space(rigid(), args.pop("mass"), args.pop("damping"), 1, **args)
    assert err.value.field == field


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"band": (10.0, 1.0)}, "band"),
    ({"band": (float("nan"), 1.0)}, "band"),
    ({"tolerance": 0.0}, "tolerance"),
    ({"grasps": ()}, "grasps"),
    ({"k_range": (0.0, 10.0)}, "k_range"),
    ({"encoder_resolution": 1.0}, "encoder_resolution"),
])
def test_bad_settings_name_the_field(kwargs, field):
    with pytest.raises(ValidationError) as err:
        QualitySettings(**kwargs)
    assert err.value.field == field


def test_acceleration_estimate_records():
    acc = AccelerationEstimate("filtered_velocity", "butter2", 2 * math.pi * 30)
    assert AccelerationEstimate.from_dict(acc.to_dict()) == acc
    with pytest.raises(ValidationError) as err:
        AccelerationEstimate(lowpass="lowpass1")
    assert err.value.field == "cutoff"
    with pytest.raises(ValidationError) as err:
        AccelerationEstimate(kind="third_difference")
    assert err.value.field == "kind"


@pytest.mark.parametrize(("frac", "stable"), [(0.5, True), (1.5, False)])
def test_the_simulator_renders_the_mass_term(frac, stable):
    """The nonlinear simulator runs the same controller model: inside the space the run settles,
    beyond its edge it does not (a steady push holds the device in the god-object wall)."""
    from analysis.sampled import Scenario, Simulator
    from analysis.sampled.loop import LoopSpec
    from analysis.sampled.terminations import HANDS_OFF

    M, B = 0.3, 2.0
    k = float(renderable_space(rigid(), [M], [B], 1).k_max[0, 0])
    assert 1.0 < k < 1e9
    spec = LoopSpec("impedance", (frac * k, B), delay_samples=1, mass=M)
    sc = Scenario(name="mass", causality="admittance", wall=True, wall_position=0.0, grasp=HANDS_OFF,
                  push_force=5.0, push_start=0.0, initial_position=0.0, duration=1.5)
    assert (Simulator(rigid(), spec, sc).run().verdict.kind == "stable") is stable


def test_the_accurate_edge_agrees_with_the_predicate():
    """A 0.3 kg mass on a light spring: the resonance sqrt(K/M) enters the band, where the
    relative error of K - w^2 M blows up; the space's edge is the predicate's."""
    from analysis.sampled import renders_accurately

    s = QualitySettings(band=(1.0, 10.0), tolerance=0.05)
    sp = renderable_space(rigid(), [0.3], [0.5], 1, qualities=("stable", "accurate"), settings=s)
    k = float(sp.by_quality["accurate"][0, 0])
    assert 1.0 < k < 0.1 * sp.by_quality["stable"][0, 0]
    ctrl = RenderingController(1)
    assert renders_accurately(rigid(), ctrl, 0.3, 0.5, 0.5 * k, s)
    assert renders_accurately(rigid(), ctrl, 0.3, 0.5, 0.999 * k, s)
    assert not renders_accurately(rigid(), ctrl, 0.3, 0.5, 1.001 * k, s)


def test_results_pickle_for_process_pools_and_clusters():
    """The batch layer ships spaces between processes: every result and record pickles by value."""
    import pickle

    from analysis.sampled import m_width

    s = renderable_space(rigid(), [-0.1, 0.1], [1.0, 2.0], 1, qualities=("stable", "passive"))
    back = pickle.loads(pickle.dumps(s))
    assert np.array_equal(back.k_max, s.k_max) and back.qualities == s.qualities
    assert all(np.array_equal(back.by_quality[q], s.by_quality[q]) for q in s.qualities)
    assert back.controller == s.controller and back.settings == s.settings
    w = m_width(rigid(), 1)
    assert pickle.loads(pickle.dumps(w)).m_max == w.m_max


# -- accurate at the handle (issue 24: the rendered impedance at the handle) ---------------------
def _dynamic_stiffness_ratio(device: Device, w: float) -> complex:
    """``(x_actuator/x_handle)^2`` of the free chain driven at the handle, by solving the
    dynamic stiffness matrix ``-w^2 M + j w C + K`` directly (not by the continued fraction)."""
    m, n = device.masses, device.masses.size
    D = np.diag(-w * w * m + 1j * w * device.ground_dampings).astype(complex)
    for i in range(n - 1):
        z = device.stiffnesses[i] + 1j * w * device.dampings[i]
        D[i, i] += z
        D[i + 1, i + 1] += z
        D[i, i + 1] -= z
        D[i + 1, i] -= z
    x = np.linalg.solve(D, np.eye(n)[0])
    return complex((x[-1] / x[0]) ** 2)


def test_a_rigid_device_renders_at_the_handle_what_the_controller_renders():
    """Handle = actuator: the handle response is the controller's, and the quality and the
    effective environment are the old ones (at the encoder)."""
    w = QualitySettings().frequencies()
    env, ctrl = RenderedEnvironment(0.2, 3.0, 800.0), RenderingController(1)
    G = rendered_force_response(w, T, ctrl, env)
    assert np.array_equal(handle_force_response(rigid(), w, ctrl, env), G)
    eff = effective_environment(rigid(), env, ctrl)
    assert np.array_equal(eff.stiffness, G.real) and np.array_equal(eff.damping, G.imag / w)
    alpha, beta = handle_transmission(rigid(), w)
    assert np.all(alpha == 1.0) and np.all(beta == 0.0)


def test_the_handle_transmission_is_the_chain_seen_from_the_handle(hbfd):
    """alpha = (x_handle/x_actuator)^2 of the free chain (an independent linear solve), and
    R_0(Z) - R_0(0) = Z/(alpha + beta Z) at a third, complex termination."""
    w = np.array([0.5, 3.0, 31.4, 300.0])
    alpha, beta = handle_transmission(hbfd, w)
    for i, wi in enumerate(w):
        assert alpha[i] == pytest.approx(1.0 / _dynamic_stiffness_ratio(hbfd, float(wi)), rel=1e-9)
    Z = np.array([40.0 - 300j, 2e3 + 5j, 1e4 - 1e4j, 0.3 + 50j])
    delta = handle_impedance(hbfd, 1j * w, termination=Z) - handle_impedance(hbfd, 1j * w)
    assert delta == pytest.approx(Z / (alpha + beta * Z), rel=1e-9)


def test_at_low_frequency_the_handle_feels_the_device_mass_and_the_rendered_through_the_chain(hbfd):
    """Below the chain's modes the chain is its series spring k_s (1/k_s = sum 1/k_i) and its
    masses move together: R_0(Z_c) -> Z_c/(1 + j w Z_c/k_s) + j w sum m_i + sum g_i, and the
    rendered part G_h -> G/(1 + G/k_s) (the next order, m w^2/k_s, is ~1e-4 at 1 rad/s)."""
    w = np.geomspace(0.1, 1.0, 16)
    ks = 1.0 / np.sum(1.0 / hbfd.stiffnesses)
    ctrl = RenderingController(1)
    for K in (200.0, 2000.0, 20000.0):
        env = RenderedEnvironment(0.1, 5.0, K)
        G = rendered_force_response(w, T, ctrl, env)
        Zc = G / (1j * w)
        total = handle_impedance(hbfd, 1j * w, termination=Zc)
        limit = Zc / (1 + 1j * w * Zc / ks) + 1j * w * hbfd.total_mass + hbfd.total_ground_damping
        assert np.max(np.abs(total / limit - 1)) < 1e-3
        Gh = handle_force_response(hbfd, w, ctrl, env)
        assert np.max(np.abs(Gh / (G / (1 + G / ks)) - 1)) < 1e-3
        # the chain's compliance is what the handle adds: K/k_s of the rendered spring
        assert abs(Gh[0] / G[0] - 1) == pytest.approx(K / (ks + K), rel=2e-3)


def test_the_accurate_spring_at_the_handle_is_the_series_spring_limit(hbfd):
    """A pure spring at a low band: K/(1 + K/k_s) within eps of K iff K <= eps k_s/(1 - eps)
    (the hold's phase at 1 rad/s moves it by ~1e-5); a rigid device has no such limit."""
    ks = 1.0 / np.sum(1.0 / hbfd.stiffnesses)
    for eps in (0.05, 0.1, 0.3):
        s = QualitySettings(band=(0.1, 1.0), tolerance=eps)
        k = accuracy_k(hbfd, RenderingController(1), np.zeros(1), np.zeros(1), s)[0]
        assert k == pytest.approx(eps * ks / (1 - eps), rel=1e-4)
    assert accuracy_k(rigid(), RenderingController(1), np.zeros(1), np.zeros(1),
                      QualitySettings(band=(0.1, 1.0)))[0] == math.inf


@pytest.mark.parametrize(("M", "B"), [(0.0, 0.0), (0.1, 5.0), (-0.2, 20.0), (0.3, -1.0)])
def test_the_accurate_k_is_conservative_and_tight_on_a_dense_check(hbfd, M, B):
    """Every K of a dense grid up to accuracy_k is within eps at the handle on the band; just
    above it one frequency is not."""
    s = QualitySettings(band=(0.5, 10.0), tolerance=0.2, band_points=48)
    ctrl = RenderingController(1)
    k = accuracy_k(hbfd, ctrl, np.array([M]), np.array([B]), s)[0]
    assert 0 < k < 1e9
    w = s.frequencies()

    def worst(K: float) -> float:
        env = RenderedEnvironment(M, B, K)
        return float(np.max(np.abs(handle_force_response(hbfd, w, ctrl, env) - env.target(w)) /
                            np.abs(env.target(w))))

    assert max(worst(K) for K in np.geomspace(1e-3 * k, k, 300)) <= s.tolerance * (1 + 1e-9)
    assert worst(1.001 * k) > s.tolerance
    eff = effective_environment(hbfd, RenderedEnvironment(M, B, 0.999 * k), ctrl, s)
    assert np.all(eff.error <= s.tolerance)


def test_the_accurate_masses_at_the_handle_are_the_first_violations(hbfd):
    """A pure mass at the actuator is felt through the chain's spring: accurate up to a finite
    |M| either way (about eps k_s/w2^2), checked by the handle response on either side."""
    s = QualitySettings(band=(0.5, 5.0), tolerance=0.1)
    ctrl = RenderingController(1)
    lo, hi = accuracy_mass_limits(hbfd, ctrl, s)
    ks = 1.0 / np.sum(1.0 / hbfd.stiffnesses)
    w = s.frequencies()
    for limit in (lo, hi):
        assert 0.5 * 0.1 * ks / 25.0 < abs(limit) < 2.0 * 0.1 * ks / 25.0

        def worst(M: float) -> float:
            env = RenderedEnvironment(mass=M)
            return float(np.max(np.abs(handle_force_response(hbfd, w, ctrl, env) / env.target(w) - 1)))

        assert worst(0.999 * limit) <= 0.1 < worst(1.001 * limit)
    assert accuracy_mass_limits(rigid(), ctrl, s) == (-math.inf, math.inf)


def test_a_denser_k_check_finds_no_unstable_k_below_k_max(hbfd):
    """Conservative: 60 points per decade (7x the trace's coarse scan) from 1 N/m up to each k_max,
    and k_max itself, are all stable; 1e-6 above k_max (where it is a crossing) is not."""
    M, B = np.array([-0.6, -0.1, 0.15]), np.array([-3.0, 10.0, 80.0])
    s = renderable_space(hbfd, M, B, 1)
    ctrl = RenderingController(1)
    crossings = 0
    for i, m in enumerate(M):
        for j, b in enumerate(B):
            k = float(s.k_max[i, j])
            if k == 0.0:
                continue
            ks = np.r_[np.geomspace(1.0, k, max(int(60 * math.log10(k)), 2)), k]
            rho = stable_radius(hbfd, ctrl, np.full(ks.size, m), np.full(ks.size, b), ks, (Grasp(),))
            assert np.all(is_stable(rho)), (m, b, k)
            if k < 1e9:
                crossings += 1
                up = stable_radius(hbfd, ctrl, np.array([m]), np.array([b]), np.array([k * (1 + 1e-6)]),
                                   (Grasp(),))
                assert not is_stable(up[0])
    assert crossings >= 5
