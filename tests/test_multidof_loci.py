"""Multi-DOF (issue 25): the critical stiffnesses from the wall-free loop's loci, certified on the exact loop."""

from __future__ import annotations

import numpy as np
import pytest

from analysis import Device
from analysis.errors import ValidationError
from analysis.multidof import (
    FiveBar,
    RigidCartesianDevice,
    check_directions,
    critical_wall_stiffness,
    first_crossings,
    five_bar_device,
    frequency_first_crossings,
    loop_parts,
    normal_device,
    wall_pencil,
    wall_shape,
    workspace_map,
)
from analysis.multidof.loci import WallFreeLoops, frequency_grid, loop_responses
from analysis.sampled import (
    CROSSING_RTOL,
    Grasp,
    VelocityFilter,
    critical_stiffness,
    is_stable,
    spectral_radius,
    zwidth_region,
)

# Two k's that both are the stable end of a bracket of relative width CROSSING_RTOL around the
# rule's one crossing agree to 2 CROSSING_RTOL.
SAME_K = 2 * CROSSING_RTOL
X6, Y6 = np.linspace(-0.1, 0.1, 6), np.linspace(0.12, 0.28, 6)


def _shapes(directions: int) -> np.ndarray:
    dirs = check_directions(2, directions)
    return np.concatenate([np.eye(2)[None], dirs[:, :, None] * dirs[:, None, :]])


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    both = np.isfinite(a) & np.isfinite(b) & (b > 0)
    assert np.array_equal(np.isfinite(a), np.isfinite(b)) and np.array_equal(a == 0, b == 0)
    return float(np.max(np.abs(a[both] / b[both] - 1.0))) if both.any() else 0.0


def test_a_6x6_map_by_the_loci_equals_the_scan_within_the_bracket() -> None:
    fb = FiveBar()
    loci = workspace_map(fb, x=X6, y=Y6, damping=2.0, delay_samples=1, directions=12)
    scan = workspace_map(fb, x=X6, y=Y6, damping=2.0, delay_samples=1, directions=12, method="scan")
    assert np.array_equal(loci.reachable, scan.reachable) and loci.reachable.sum() >= 30
    r = loci.reachable
    assert _rel(loci.k_max[r], scan.k_max[r]) <= SAME_K
    assert _rel(loci.worst_stiffness[r], scan.worst_stiffness[r]) <= SAME_K
    assert loci.minimum.stiffness == pytest.approx(scan.minimum.stiffness, rel=SAME_K)
    # the symmetric five-bar's mirror points tie within the bracket: either may be the minimum
    assert np.allclose(np.abs(loci.minimum.position), np.abs(scan.minimum.position), rtol=0, atol=1e-15)
    assert 500.0 < np.nanmin(loci.worst_stiffness) < np.nanmax(loci.k_max) < 1e5  # a real, finite map


@pytest.mark.parametrize(("damping", "delay", "vf", "grasp", "tol"), [
    (2.0, 0, None, Grasp(), SAME_K),
    (5.0, 2, VelocityFilter("lowpass1", 600.0), Grasp(), SAME_K),
    (3.0, 1, VelocityFilter("butter2", 900.0), Grasp(0.2, 1.0, 100.0), SAME_K),
    (20.0, 1, None, Grasp(), SAME_K),  # the wall's damping alone destabilizes some walls: k = 0 there
    # b = 0: the crossing pair leaves the circle so slowly (k d rho/dk ~ 1e-4) that the rule's
    # rho <= 1 + 1e-12 is decided by round-off over ~1e-11 of k: both are brackets of it
    (0.0, 1, None, Grasp(), 1e-10),
])
def test_loci_equal_the_scan_for_delays_filters_grasps_and_dampings(damping: float, delay: int, vf, grasp,
                                                                    tol: float) -> None:
    fb = FiveBar()
    devices = [five_bar_device(fb, p) for p in [(0.0, 0.2), (0.06, 0.15), (-0.08, 0.25), (0.03, 0.27)]]
    shapes = _shapes(8)
    k, stats = frequency_first_crossings(devices, shapes, damping, delay, grasp, vf)
    P0, P1 = zip(*(wall_pencil(d, shapes, damping, delay, grasp, vf) for d in devices))
    ref = first_crossings(np.concatenate(P0), np.concatenate(P1)).reshape(k.shape)
    assert _rel(k, ref) <= tol
    assert stats["walls"] == k.size and stats["certified"] + stats["fallback"] <= k.size


def test_a_dense_k_check_finds_no_unstable_k_below_the_reported_one() -> None:
    fb = FiveBar()
    devices = [five_bar_device(fb, p) for p in [(0.0, 0.2), (0.09, 0.13), (-0.05, 0.27)]]
    shapes = _shapes(12)
    k, _ = frequency_first_crossings(devices, shapes, 2.0, 1)
    for dev, row in zip(devices, k):
        P0, P1 = wall_pencil(dev, shapes, 2.0, 1)
        for p0, p1, kc in zip(P0, P1, row):
            ks = np.geomspace(1.0, kc, 600)  # ~230 a decade, up to the reported k itself
            assert np.all(is_stable(spectral_radius(p0 + ks[:, None, None] * p1)))
            assert not is_stable(spectral_radius(p0 + kc * (1 + CROSSING_RTOL) * p1))  # the bracket's top


@pytest.mark.parametrize("device", [
    RigidCartesianDevice(mass=[[0.3, 0.1], [0.1, 0.2]], damping=[[1.0, 0.3], [0.3, 0.5]]),
    RigidCartesianDevice(mass=[[0.3, 0.1], [0.1, 0.2]]),  # no damping: a defective plant, solved whole
    Device(masses=[0.05, 0.2, 0.3], stiffnesses=[2e4, 5e4], dampings=[2.0, 3.0], ground_dampings=[0.0, 0.1, 0.4],
           sample_time=5e-4),
], ids=["rigid", "undamped", "chain"])
def test_modal_responses_equal_the_whole_loop_solved(device) -> None:
    vf = VelocityFilter("lowpass1", 500.0)
    loops = WallFreeLoops.build([device], 2, Grasp(0.1, 2.0, 300.0), vf)
    w = frequency_grid(64)
    Ty, Tv = loops.responses(np.array([0]), w)
    ref = loop_responses(*(a[None] for a in loop_parts(device, 2, Grasp(0.1, 2.0, 300.0), vf)), w)
    for got, want in zip((Ty, Tv), ref):
        assert np.max(np.abs(got - want) / np.abs(want).max(axis=(-1, -2), keepdims=True)) < 1e-9


@pytest.mark.parametrize("normal", [None, (1.0, 0.0), (0.6, -0.8)])
def test_loci_of_a_rigid_and_a_chain_device_equal_the_scan(normal) -> None:
    rigid = RigidCartesianDevice(mass=[[0.3, 0.1], [0.1, 0.2]], damping=[[1.0, 0.3], [0.3, 0.5]])
    S = wall_shape(2, normal)
    k, _ = frequency_first_crossings([rigid], S[None], 5.0, 1)
    assert _rel(k[0], first_crossings(*wall_pencil(rigid, S, 5.0, 1))) <= SAME_K
    chain = Device(masses=[0.05, 0.3], stiffnesses=[3e4], dampings=[2.0], sample_time=1e-3)
    k, _ = frequency_first_crossings([chain], np.ones((1, 1, 1)), 30.0, 1)
    assert _rel(k[0], first_crossings(*wall_pencil(chain, np.ones((1, 1)), 30.0, 1))) <= SAME_K


def test_the_loci_spend_a_few_eigenproblems_a_wall() -> None:
    fb = FiveBar()
    devices = [five_bar_device(fb, (x, y)) for x in (-0.06, 0.0, 0.06) for y in (0.15, 0.22)]
    _, stats = frequency_first_crossings(devices, _shapes(12), 2.0, 1)
    # the scan spends about 134 a wall (24 a decade up to the crossing, then 38 halvings)
    assert stats["certified"] == stats["walls"] == 6 * 13
    assert stats["eigenproblems"] <= 10 * stats["walls"]


def test_an_unknown_method_and_mixed_devices_are_refused_by_name() -> None:
    with pytest.raises(ValidationError, match="method"):
        workspace_map(FiveBar(), x=[0.0], y=[0.2], method="brent")
    a = RigidCartesianDevice(mass=np.eye(2) * 0.2, sample_time=1e-3)
    b = RigidCartesianDevice(mass=np.eye(2) * 0.2, sample_time=5e-4)
    with pytest.raises(ValidationError, match="device 1 differs"):
        frequency_first_crossings([a, b], np.eye(2)[None], 1.0)


def test_a_point_gets_the_same_value_in_any_batch() -> None:
    # the study layer computes the map in bands of rows and joins them: a point's value must not
    # depend on its neighbours (the certificate's points sit on a fixed grid of k)
    fb, x, y = FiveBar(), np.linspace(-0.1, 0.1, 7), np.linspace(0.12, 0.28, 6)
    whole = workspace_map(fb, x=x, y=y, damping=2.0, delay_samples=1, directions=12)
    bands = [workspace_map(fb, x=x, y=y[j:j + 2], damping=2.0, delay_samples=1, directions=12) for j in (0, 2, 4)]
    for name in ("k_max", "worst_stiffness"):
        joined = np.concatenate([getattr(b, name) for b in bands])
        assert _rel(joined.ravel(), getattr(whole, name).ravel()) <= SAME_K
        same = (joined == getattr(whole, name)) | (np.isnan(joined) & np.isnan(getattr(whole, name)))
        assert np.count_nonzero(~same) <= 1  # bit for bit but for a rare straddle of the grid of k


# -- the third layer: the 1-DOF Z-width area along the worst normal ---------------------------
def test_the_device_along_a_principal_normal_is_the_plane_walls_loop() -> None:
    dev = RigidCartesianDevice(mass=np.diag([0.2, 0.5]), damping=np.diag([0.3, 1.5]))
    one = normal_device(dev, [-3.0, 0.0])  # the sign and length of the normal do not matter
    assert one.masses[0] == pytest.approx(0.2, rel=1e-15) and one.ground_dampings[0] == pytest.approx(0.3, rel=1e-15)
    b = np.array([0.5, 2.0, 8.0])
    plane = np.array([critical_wall_stiffness(dev, damping=bi, delay_samples=1, normal=[1.0, 0.0]) for bi in b])
    # the plane wall's loop has the free axis's modes besides: its rule's crossing moves by round-off
    assert _rel(np.array([critical_stiffness(one, bi, 1) for bi in b]), plane) <= 1e-11
    assert _rel(zwidth_region(one, b, 1, passive=False).k_max, plane) <= 1e-9  # the region's own bisection


def test_the_device_along_a_normal_pushes_the_free_handles_mass() -> None:
    M = np.array([[0.3, 0.1], [0.1, 0.2]])
    dev = RigidCartesianDevice(mass=M, damping=2.5 * M)  # proportional damping: b_n = 2.5 m_n
    for th in np.linspace(0.0, np.pi, 7):
        n = np.array([np.cos(th), np.sin(th)])
        one = normal_device(dev, n)
        assert one.masses[0] == pytest.approx(1.0 / (n @ np.linalg.solve(M, n)), rel=1e-13)
        assert one.masses[0] <= n @ M @ n + 1e-15  # the free handle is lighter than the constrained one
        assert one.ground_dampings[0] == pytest.approx(2.5 * one.masses[0], rel=1e-12)
    with pytest.raises(ValidationError, match="normal"):
        normal_device(dev, [0.0, 0.0])


def test_the_maps_zwidth_layer_is_the_area_along_each_worst_normal() -> None:
    fb, x, y = FiveBar(), [-0.06, 0.0, 0.5], [0.2]  # the last point is out of reach
    b = [0.5, 1.0, 2.0, 4.0]
    m = workspace_map(fb, x=x, y=y, damping=2.0, delay_samples=1, directions=8, zwidth_b=b)
    assert workspace_map(fb, x=x, y=y, damping=2.0, delay_samples=1, directions=8).zwidth_area is None
    assert np.array_equal(m.zwidth_b, b) and np.isnan(m.zwidth_area[0, 2])
    for i in (0, 1):
        one = normal_device(five_bar_device(fb, (x[i], y[0])), m.worst_normal[0, i])
        want = zwidth_region(one, b, 1, passive=False).area_linear
        assert m.zwidth_area[0, i] == want and want > 0
