"""Multi-DOF devices (issue 25): the structural model, the exact MIMO loop and the worst normal."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from analysis import Device
from analysis.errors import ValidationError
from analysis.multidof import (
    FiveBar,
    RigidCartesianDevice,
    StructuralModel,
    chain_model,
    check_directions,
    closed_loop_matrices,
    critical_wall_stiffness,
    discrete_plant,
    first_crossings,
    five_bar_device,
    moving_radius,
    wall_pencil,
    wall_radii,
    wall_shape,
    workspace_map,
    worst_normal,
)
from analysis.sampled import (
    CROSSING_RTOL,
    Grasp,
    VelocityFilter,
    critical_stiffness,
    discrete_plants,
    is_stable,
    spectral_radius,
)

T = 1e-3
# Two k's that both are the stable end of a Brent bracket of relative width CROSSING_RTOL around one
# crossing agree to 2 CROSSING_RTOL.
SAME_K = 2 * CROSSING_RTOL
CHAINS = [
    Device(masses=[0.2], ground_dampings=[0.5], sample_time=T),
    Device(masses=[0.05, 0.3], stiffnesses=[3e4], dampings=[2.0], sample_time=T),
    Device(masses=[0.05, 0.2, 0.3], stiffnesses=[2e4, 5e4], dampings=[2.0, 3.0], ground_dampings=[0.0, 0.1, 0.4],
           sensor_element=1, sample_time=5e-4),
]


def rotation(axes: int, a: float, b: float = 0.0, c: float = 0.0) -> np.ndarray:
    """A rotation of the plane by ``a``, or of space by the angles ``a, b, c`` (z, y, z)."""
    def rz(t: float) -> np.ndarray:
        return np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0], [0.0, 0.0, 1.0]])

    if axes == 2:
        return rz(a)[:2, :2]
    ry = np.array([[math.cos(b), 0.0, math.sin(b)], [0.0, 1.0, 0.0], [-math.sin(b), 0.0, math.cos(b)]])
    return rz(a) @ ry @ rz(c)


# -- the chain through the general model -----------------------------------------------------
@pytest.mark.parametrize("device", CHAINS, ids=["n1", "n2", "n3"])
def test_chain_plant_through_the_general_model_is_the_chains_bit_for_bit(device: Device) -> None:
    Ad, Bd = discrete_plants(device, (Grasp(), Grasp(0.1, 2.0, 300.0)))
    A2, B2 = discrete_plant(chain_model(device), (Grasp(), Grasp(0.1, 2.0, 300.0)))
    assert np.array_equal(Ad, A2)
    assert np.array_equal(Bd[..., 0], -B2[..., 0])  # the chain's F_d enters as -F_d: u = -F_d
    assert np.array_equal(Bd[..., 1], B2[..., 1])


@pytest.mark.parametrize("device", CHAINS, ids=["n1", "n2", "n3"])
@pytest.mark.parametrize(("bc", "delay", "vf", "grasp"), [
    (5.0, 0, None, Grasp()),
    (30.0, 1, None, Grasp()),
    (10.0, 2, VelocityFilter("lowpass1", 600.0), Grasp()),
    (20.0, 1, VelocityFilter("butter2", 900.0), Grasp(0.2, 1.0, 100.0)),
])
def test_chain_critical_stiffness_through_the_general_model(device: Device, bc: float, delay: int,
                                                            vf: VelocityFilter | None, grasp: Grasp) -> None:
    k_chain = critical_stiffness(device, bc, delay, grasp=grasp, velocity_filter=vf)
    k_general = critical_wall_stiffness(chain_model(device), damping=bc, delay_samples=delay, grasp=grasp,
                                        velocity_filter=vf)
    assert 0.0 < k_chain < 1e9
    assert k_general == pytest.approx(k_chain, rel=SAME_K, abs=0.0)
    assert critical_wall_stiffness(device, damping=bc, delay_samples=delay, grasp=grasp,
                                   velocity_filter=vf) == k_general  # a Device is taken as its chain model


# -- reductions ----------------------------------------------------------------------------------
def one_dof(mass: float, damping: float) -> Device:
    return Device(masses=[mass], ground_dampings=[damping], sample_time=T)


@pytest.mark.parametrize(("delay", "vf"), [(0, None), (1, None), (1, VelocityFilter("lowpass1", 500.0))])
def test_diagonal_device_gives_the_smaller_of_its_one_dof_limits(delay: int, vf: VelocityFilter | None) -> None:
    masses, dampings, b = [0.2, 0.5, 0.35], [0.5, 1.0, 3.0], 5.0
    k1 = [critical_stiffness(one_dof(m, c), b, delay, velocity_filter=vf) for m, c in zip(masses, dampings)]
    dev = RigidCartesianDevice(mass=np.diag(masses), damping=np.diag(dampings), sample_time=T)
    assert len(set(k1)) == 3  # distinct limits, so "the smaller" is a real choice
    assert critical_wall_stiffness(dev, b, delay, velocity_filter=vf) == pytest.approx(min(k1), rel=SAME_K, abs=0)
    for axis in range(3):
        normal = np.eye(3)[axis]
        k_axis = critical_wall_stiffness(dev, b, delay, normal=normal, velocity_filter=vf)
        assert k_axis == pytest.approx(k1[axis], rel=SAME_K, abs=0)


def test_worst_normal_is_the_conservative_minimum_of_a_denser_check() -> None:
    M = np.array([[0.3, 0.1], [0.1, 0.2]])
    C = np.array([[1.0, 0.3], [0.3, 0.5]])
    dev = RigidCartesianDevice(mass=M, damping=C, sample_time=T)
    w = worst_normal(dev, damping=5.0, delay_samples=1, directions=24)
    assert np.linalg.norm(w.normal) == pytest.approx(1.0, abs=1e-12)
    assert w.stiffness == pytest.approx(critical_wall_stiffness(dev, 5.0, 1, normal=w.normal), rel=SAME_K, abs=0)
    assert w.stiffness <= w.stiffnesses.min()
    assert w.evaluations > len(w.directions)
    th = np.linspace(0.0, np.pi, 181)
    denser = [critical_wall_stiffness(dev, 5.0, 1, normal=[math.cos(t), math.sin(t)]) for t in th]
    assert w.stiffness <= min(denser) * (1 + 1e-9)
    assert w.stiffness < critical_wall_stiffness(dev, 5.0, 1, normal=[1.0, 0.0])


@pytest.mark.parametrize(("delay", "vf"), [(0, None), (2, VelocityFilter("butter2", 700.0))])
def test_batched_crossings_equal_the_scalar_ones(delay: int, vf: VelocityFilter | None) -> None:
    dev = RigidCartesianDevice(mass=[[0.3, 0.1], [0.1, 0.2]], damping=[[1.0, 0.3], [0.3, 0.5]], sample_time=T)
    dirs = check_directions(2, 6)
    shapes = np.concatenate([dirs[:, :, None] * dirs[:, None, :], np.eye(2)[None], 1e-9 * np.eye(2)[None]])
    ks = first_crossings(*wall_pencil(dev, shapes, 5.0, delay, velocity_filter=vf))
    scalar = [critical_wall_stiffness(dev, 5.0, delay, normal=S, velocity_filter=vf) for S in shapes]
    assert np.isinf(ks[-1]) and np.isinf(scalar[-1])  # a wall too soft to cross below 1e9 N/m
    assert ks[:-1] == pytest.approx(scalar[:-1], rel=SAME_K, abs=0)
    assert np.all(np.isfinite(ks[:-1]) & (ks[:-1] > 0))
    walls = shapes[:-1]
    assert np.all(is_stable(wall_radii(dev, ks[:-1, None, None] * walls, 5.0 * walls, delay, velocity_filter=vf)))
    assert not np.any(is_stable(wall_radii(dev, ks[:-1, None, None] * (1 + 1e-9) * walls, 5.0 * walls, delay,
                                           velocity_filter=vf)))


def test_the_moving_radius_is_stable_where_the_spectral_radius_is_and_not_flat() -> None:
    """Brent's crossing follows moving_radius: the same stability as the spectral radius at every
    k of a plane wall's scan (rigid-body modes of the free directions left out), and not the flat
    1 of the spectral radius on the stable side, so Brent needs few evaluations."""
    dev = RigidCartesianDevice(mass=np.diag([0.2, 0.5, 0.35]), damping=np.diag([0.5, 1.0, 3.0]), sample_time=T)
    u = np.array([0.3, 0.5, 0.81]) / np.linalg.norm([0.3, 0.5, 0.81])
    P0, P1 = wall_pencil(dev, np.outer(u, u)[None], 5.0, 1)
    k = critical_wall_stiffness(dev, 5.0, 1, normal=u)
    ks = np.r_[np.geomspace(1.0, 1e9, 400), k, k * (1 + CROSSING_RTOL), np.geomspace(0.999, 1.001, 41) * k]
    Phi = P0 + ks[:, None, None] * P1
    rho, moving = spectral_radius(Phi), moving_radius(Phi)
    assert np.array_equal(is_stable(rho), is_stable(moving))
    assert is_stable(moving[400]) and not is_stable(moving[401])  # k is the stable end of the bracket
    below = ks < k
    assert np.all(np.abs(rho[below] - 1.0) <= 1e-13)  # flat: the free directions' rigid-body modes
    assert np.all(moving[below] < 1.0) and np.ptp(moving[below]) > 1e-3


def test_worst_normal_of_a_diagonal_device_is_its_weakest_axis_limit() -> None:
    dev = RigidCartesianDevice(mass=np.diag([0.2, 0.5, 0.35]), damping=np.diag([0.5, 1.0, 3.0]), sample_time=T)
    k_axes = [critical_wall_stiffness(dev, 5.0, 1, normal=e) for e in np.eye(3)]
    w = worst_normal(dev, 5.0, 1, directions=64)
    assert w.stiffness <= min(k_axes) * (1 + SAME_K)
    assert np.all(w.stiffnesses >= w.stiffness)


# -- invariance ----------------------------------------------------------------------------------
angles = st.floats(-math.pi, math.pi)


@settings(max_examples=25, deadline=None)
@given(axes=st.sampled_from([2, 3]), masses=st.lists(st.floats(0.1, 2.0), min_size=3, max_size=3),
       dampings=st.lists(st.floats(0.0, 5.0), min_size=3, max_size=3), frame=st.tuples(angles, angles, angles),
       turn=st.tuples(angles, angles, angles), normal=st.tuples(angles, angles, angles),
       isotropic=st.booleans(), b=st.floats(0.5, 5.0), delay=st.integers(0, 2))
def test_rotating_device_and_normal_together_leaves_the_critical_stiffness(
        axes: int, masses: list[float], dampings: list[float], frame: tuple, turn: tuple, normal: tuple,
        isotropic: bool, b: float, delay: int) -> None:
    Q = rotation(axes, *frame)
    M = Q @ np.diag(masses[:axes]) @ Q.T  # random SPD M and C with different principal axes
    C = rotation(axes, *normal) @ np.diag(dampings[:axes]) @ rotation(axes, *normal).T
    n = None if isotropic else rotation(axes, *normal)[:, 0]
    R = rotation(axes, *turn)
    k = critical_wall_stiffness(RigidCartesianDevice(M, C, T), b, delay, normal=n)
    k_rot = critical_wall_stiffness(RigidCartesianDevice(R @ M @ R.T, R @ C @ R.T, T), b, delay,
                                    normal=None if n is None else R @ n)
    assume(0.0 < k < 1e9)  # a crossing inside the range (the damping alone is stable; rarely not so)
    assert k_rot == pytest.approx(k, rel=1e-9)


# -- a brute-force simulation --------------------------------------------------------------------
def simulate_growth(M: np.ndarray, C: np.ndarray, Kw: np.ndarray, Bw: np.ndarray, a: float, delay: int,
                    steps: int) -> float:
    """Growth per sample of the loop simulated by an ODE solver and a float controller.

    The plant ``M x'' + C x' = u`` is integrated over each sample with the held command
    (``solve_ivp``, no matrix exponential); the controller reads ``x``, filters the backward
    difference by ``v[k] = a v[k-1] + (1 - a) d[k]`` and commands ``-(K_w x + B_w v)`` ``delay``
    samples later.
    """
    m = M.shape[0]
    Minv = np.linalg.inv(M)
    rng = np.random.default_rng(7)
    z = rng.standard_normal(2 * m) * 1e-3
    x_prev, v = z[:m].copy(), np.zeros(m)
    queue = [np.zeros(m) for _ in range(delay)]
    norms = []
    for _ in range(steps):
        x = z[:m]
        d = (x - x_prev) / T
        v = a * v + (1 - a) * d
        u = -(Kw @ x + Bw @ v)
        queue.append(u)
        held = queue.pop(0)
        x_prev = x.copy()
        sol = solve_ivp(lambda t, s, f=held: np.r_[s[m:], Minv @ (f - C @ s[m:])], (0.0, T), z,
                        method="DOP853", rtol=1e-11, atol=1e-14 * max(1.0, float(np.abs(z).max())))
        z = sol.y[:, -1]
        norms.append(float(np.linalg.norm(np.r_[z, x_prev, v, *queue])))
    w = steps // 4  # envelope: the largest norm of a window, early and late
    early, late = max(norms[w:2 * w]), max(norms[3 * w:])
    return (late / early) ** (1.0 / (2 * w))


@pytest.mark.parametrize("normal", [None, (0.6, 0.8)], ids=["isotropic", "plane"])
def test_simulated_growth_rate_equals_the_spectral_radius(normal: tuple | None) -> None:
    M = np.array([[0.3, 0.1], [0.1, 0.2]])
    C = np.array([[1.0, 0.3], [0.3, 0.5]])
    dev = RigidCartesianDevice(mass=M, damping=C, sample_time=T)
    vf = VelocityFilter("lowpass1", 800.0)
    S = wall_shape(2, normal)
    kc = critical_wall_stiffness(dev, 8.0, 1, normal=normal, velocity_filter=vf)
    Kw, Bw = 2.0 * kc * S, 8.0 * S  # twice the critical stiffness: a loop that grows
    Phi = closed_loop_matrices(dev, Kw, Bw, 1, velocity_filter=vf)
    rho = float(spectral_radius(Phi)[0])
    mags = np.sort(np.abs(np.linalg.eigvals(Phi[0])))[::-1]
    assert rho > 1.01 and not is_stable(rho)
    assert mags[0] - mags[2] > 0.01  # one dominant pair, so the envelope converges
    growth = simulate_growth(M, C, Kw, Bw, math.exp(-800.0 * T), 1, 800)
    assert growth == pytest.approx(rho, abs=1e-3)


# -- bad input -----------------------------------------------------------------------------------
def test_bad_mass_matrices_are_refused_by_name() -> None:
    with pytest.raises(ValidationError, match=r"mass.*symmetric.*mass\[0, 1\] = 0\.1.*mass\[1, 0\] = 0\.2"):
        RigidCartesianDevice(mass=[[1.0, 0.1], [0.2, 1.0]], sample_time=T)
    with pytest.raises(ValidationError, match=r"mass.*positive definite.*smallest eigenvalue is -1 kg"):
        RigidCartesianDevice(mass=[[1.0, 0.0], [0.0, -1.0]], sample_time=T)
    with pytest.raises(ValidationError, match=r"damping.*shape 2 x 2"):
        RigidCartesianDevice(mass=np.eye(2), damping=np.eye(3), sample_time=T)
    with pytest.raises(ValidationError, match=r"damping.*positive semidefinite"):
        RigidCartesianDevice(mass=np.eye(2), damping=[[1.0, 0.0], [0.0, -2.0]], sample_time=T)
    with pytest.raises(ValidationError, match=r"mass.*finite"):
        RigidCartesianDevice(mass=[[1.0, 0.0], [0.0, math.nan]], sample_time=T)
    with pytest.raises(ValidationError, match=r"sample_time"):
        RigidCartesianDevice(mass=np.eye(2), sample_time=0.0)
    with pytest.raises(ValidationError, match=r"sensing.*shape 1 x 2"):
        StructuralModel(np.eye(2), np.zeros((2, 2)), np.zeros((2, 2)), np.ones((2, 1)), np.ones((1, 2)),
                        np.ones((2, 2)))


def test_bad_walls_are_refused_by_name() -> None:
    dev = RigidCartesianDevice(mass=np.eye(2) * 0.3, sample_time=T)
    with pytest.raises(ValidationError, match="normal.*nonzero"):
        critical_wall_stiffness(dev, 1.0, normal=[0.0, 0.0])
    with pytest.raises(ValidationError, match="normal.*2 components"):
        critical_wall_stiffness(dev, 1.0, normal=[1.0, 0.0, 0.0])
    with pytest.raises(ValidationError, match="damping"):
        critical_wall_stiffness(dev, -1.0)
    with pytest.raises(ValidationError, match="4 axes"):
        worst_normal(RigidCartesianDevice(mass=np.eye(4), sample_time=T), 1.0)
    with pytest.raises(ValidationError, match="device"):
        critical_wall_stiffness("phantom", 1.0)


def test_equal_models_share_one_cached_plant() -> None:
    M = np.array([[0.3, 0.05], [0.05, 0.2]])
    a = discrete_plant(RigidCartesianDevice(mass=M, sample_time=T))
    b = discrete_plant(RigidCartesianDevice(mass=M.copy(), sample_time=T))
    assert a[0] is b[0]
    assert not a[0].flags.writeable


# -- the five-bar's workspace ----------------------------------------------------------------------
def test_five_bar_jacobian_against_finite_differences() -> None:
    fb = FiveBar(distal_masses=(0.012, 0.024))
    h = 1e-7
    for p in ([0.0, 0.2], [0.06, 0.25], [-0.08, 0.15]):
        p = np.array(p)
        dq = np.column_stack([(fb.inverse_kinematics(p + h * e) - fb.inverse_kinematics(p - h * e)) / (2 * h)
                              for e in np.eye(2)])  # dq/dp = J^{-1}
        assert np.linalg.inv(fb.jacobian(p)) == pytest.approx(dq, rel=1e-6, abs=1e-6)


def test_symmetric_five_bar_has_no_cross_axis_coupling_at_its_centre() -> None:
    fb = FiveBar()  # equal link masses: mirror symmetric
    dev = five_bar_device(fb, fb.centre(), T)
    assert abs(dev.mass[0, 1]) <= 1e-14 * dev.mass.max()
    assert abs(dev.damping[0, 1]) <= 1e-14 * dev.damping.max()
    kx, ky = (critical_wall_stiffness(dev, 2.0, 1, normal=e) for e in np.eye(2))
    assert kx != pytest.approx(ky, rel=1e-3)  # the two axes differ ...
    assert critical_wall_stiffness(dev, 2.0, 1) == pytest.approx(min(kx, ky), rel=SAME_K, abs=0)  # ... uncoupled


def test_unreachable_and_singular_positions_are_refused_by_name() -> None:
    fb = FiveBar()
    with pytest.raises(ValidationError, match=r"position = \[0\.3, 0\.5\].*reachable"):
        five_bar_device(fb, (0.3, 0.5))
    y = 0.2 * math.sqrt(1 - 0.75**2)  # both distal links horizontal and collinear
    with pytest.raises(ValidationError, match=r"position.*non-singular.*\(x, y\) = \(0, 0\.1322"):
        five_bar_device(fb, (0.0, y))


def test_workspace_map_is_mirror_symmetric_and_bounded_by_its_minimum() -> None:
    fb = FiveBar()
    xs, ys = np.linspace(-0.12, 0.12, 5), np.array([0.1, 0.2, 0.3, 0.45])
    m = workspace_map(fb, x=xs, y=ys, damping=2.0, delay_samples=1, directions=8)
    assert m.k_max.shape == m.worst_stiffness.shape == (4, 5) and m.worst_normal.shape == (4, 5, 2)
    assert not m.reachable[-1].any() and np.all(np.isnan(m.k_max[-1]))  # y = 0.45 m is beyond l1 + l2
    assert m.reachable[:-1].all()
    ok = m.reachable
    assert m.k_max[ok] == pytest.approx(m.k_max[:, ::-1][ok], rel=1e-9)
    assert m.worst_stiffness[ok] == pytest.approx(m.worst_stiffness[:, ::-1][ok], rel=1e-9)
    assert m.minimum.stiffness <= np.nanmin(m.worst_stiffness)
    j = list(ys).index(m.minimum.position[1])
    i = list(xs).index(m.minimum.position[0])
    assert m.worst_stiffness[j, i] == np.nanmin(m.worst_stiffness)
    dev = five_bar_device(fb, m.minimum.position, T)
    k_at = critical_wall_stiffness(dev, 2.0, 1, normal=m.minimum.normal)
    assert m.minimum.stiffness == pytest.approx(k_at, rel=SAME_K, abs=0)
    assert k_at <= min(critical_wall_stiffness(dev, 2.0, 1, normal=u) for u in check_directions(2, 90)) * (1 + 1e-9)


def test_workspace_map_reports_progress_and_stops_when_cancelled() -> None:
    """The one progress and cancel protocol (analysis.progress): progress after each row, the
    crossings, the refinement and each Z-width point, monotone up to its total; a cancel during the
    Z-width layer stops it at the next point and the map is ``None``; the hooks change no result."""
    fb = FiveBar()
    xs, ys = np.array([-0.05, 0.05]), np.array([0.15, 0.2, 0.45])
    calls: list[tuple[int, int]] = []
    m = workspace_map(fb, x=xs, y=ys, damping=2.0, delay_samples=1, directions=4, zwidth_b=[1.0, 5.0],
                      progress=lambda done, total: calls.append((done, total)))
    plain = workspace_map(fb, x=xs, y=ys, damping=2.0, delay_samples=1, directions=4, zwidth_b=[1.0, 5.0])
    assert np.array_equal(m.worst_stiffness, plain.worst_stiffness, equal_nan=True)
    assert np.array_equal(m.zwidth_area, plain.zwidth_area, equal_nan=True)
    total = ys.size + 2 + xs.size * ys.size
    assert {t for _, t in calls} == {total} and calls[-1] == (total, total)
    done = [d for d, _ in calls]
    assert done == sorted(done) and done[:ys.size] == [1, 2, 3] and len(calls) == ys.size + 2 + 4 + 1
    def cancelled() -> bool:  # true once the first Z-width point is done
        return sum(1 for d, _ in calls if d > ys.size + 2) >= 1

    calls.clear()
    assert workspace_map(fb, x=xs, y=ys, damping=2.0, delay_samples=1, directions=4, zwidth_b=[1.0, 5.0],
                         progress=lambda done, total: calls.append((done, total)), cancelled=cancelled) is None
    assert calls[-1] == (ys.size + 3, total)  # stopped after the first point's area


@pytest.mark.parametrize("position", [(0.0, 0.2), (0.1, 0.15)])
def test_simulated_growth_at_points_of_the_map_equals_the_spectral_radius(position: tuple) -> None:
    fb = FiveBar(distal_masses=(0.012, 0.024))
    m = workspace_map(fb, x=[position[0]], y=[position[1]], damping=2.0, delay_samples=1, directions=6)
    dev = five_bar_device(fb, position, T)
    n = m.worst_normal[0, 0]
    Kw, Bw = 1.5 * m.worst_stiffness[0, 0] * np.outer(n, n), 2.0 * np.outer(n, n)
    Phi = closed_loop_matrices(dev, Kw, Bw, 1)
    rho = float(spectral_radius(Phi)[0])
    mags = np.sort(np.abs(np.linalg.eigvals(Phi[0])))[::-1]
    assert rho > 1.005 and mags[0] - mags[2] > 0.005
    growth = simulate_growth(dev.mass, dev.damping, Kw, Bw, 0.0, 1, 800)  # a = 0: the backward difference
    assert growth == pytest.approx(rho, abs=1e-3)
