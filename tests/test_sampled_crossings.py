"""The exact sweeps' stability crossings and the cached plant (issue 21).

The critical couplings are found by Brent's method on the scan's bracket with one discretized
plant per device and grasp.  They are checked here against an independent route written in this
file: the plant discretized afresh (``discretize_zoh`` of ``plant_matrices``, no cache), the same
scan, then plain bisection (60 halvings to 1e-12 relative, the previous implementation), and
against a dense grid below the reported limit (nothing there unstable: conservative).
"""

from __future__ import annotations

import math
from unittest import mock

import numpy as np
import pytest
from hbfd_fixtures import make_hbfd

from analysis import Device
from analysis.sampled import (
    CROSSING_RTOL,
    HANDS_OFF,
    RIGID_GRASP,
    STABILITY_TOLERANCE,
    LoopSpec,
    Termination,
    closed_loop_matrices,
    critical_mass,
    critical_stiffness,
    critical_stiffness_chart,
    discrete_plants,
    discretize_zoh,
    free_motion,
    god_object_wall,
    is_stable,
    plant_matrices,
    spectral_radius,
    stability_map,
    stable_end,
    zwidth_region,
)

TOP = 1.0 + STABILITY_TOLERANCE


def fresh_radius(device: Device, spec: LoopSpec, term: Termination, gain: str):
    """Spectral radius against one gain, the plant discretized here (not the cache)."""
    plants = discretize_zoh(*plant_matrices(device, [term.grasp]), device.sample_time)

    def f(values: np.ndarray) -> np.ndarray:
        values = np.asarray(values, float).reshape(-1)
        Phi = closed_loop_matrices(device, spec, [term] * values.size, plants, np.zeros(values.size, dtype=int),
                                   {gain: values})
        return spectral_radius(Phi)

    return f


def bisection_crossing(f, lo: float, hi: float, increasing: bool) -> float:
    """The previous implementation: 24 points per decade, then 60 halvings (stable end)."""
    n = max(int(math.ceil(24 * math.log10(hi / lo))), 2) + 1
    grid = np.geomspace(lo, hi, n)
    if not increasing:
        grid = grid[::-1]
    bad = f(grid) > TOP
    if not bad.any():
        return math.inf if increasing else 0.0
    j = int(np.argmax(bad))
    if j == 0:
        return 0.0 if increasing else math.inf
    safe, unsafe = float(grid[j - 1]), float(grid[j])
    for _ in range(60):
        mid = math.sqrt(safe * unsafe)
        if f(np.array([mid]))[0] > TOP:
            unsafe = mid
        else:
            safe = mid
        if abs(unsafe - safe) <= 1e-12 * safe:
            break
    return safe


def impedance_spec(bc: float, d: int) -> LoopSpec:
    return LoopSpec("impedance", (1.0, bc), delay_samples=d)


WALL = Termination(HANDS_OFF, god_object_wall())


@pytest.mark.parametrize("bc, d", [(1.0, 0), (5.0, 2), (20.0, 1), (100.0, 0), (100.0, 1), (150.0, 2), (200.0, 0)])
def test_critical_stiffness_agrees_with_bisection_and_is_conservative(bc, d):
    dev = make_hbfd()
    k = critical_stiffness(dev, bc, d)
    f = fresh_radius(dev, impedance_spec(bc, d), WALL, "kc")
    ref = bisection_crossing(f, 1.0, 1e9, True)
    assert math.isfinite(k) and k > 1.0
    # both are the stable end of a bracket of relative width <= 2e-12 around the same crossing
    assert k == pytest.approx(ref, rel=1e-10)
    # conservative: stable at the reported value and on a dense grid below it; unstable just above
    assert is_stable(f(np.array([k]))[0])
    assert np.all(is_stable(f(np.geomspace(1.0, k, 3000))))
    assert not is_stable(f(np.array([k * (1.0 + 1e-9)]))[0])


@pytest.mark.parametrize("bc, d", [(1000.0, 0), (1550.0, 1), (3000.0, 1)])
def test_critical_mass_agrees_with_bisection_and_is_conservative(bc, d):
    dev = make_hbfd()
    m = critical_mass(dev, bc, (50e3, 100.0), d)
    spec = LoopSpec("admittance", (1.0, bc), (50e3, 100.0), d)
    f = fresh_radius(dev, spec, Termination(RIGID_GRASP, free_motion("impedance")), "mc")
    ref = bisection_crossing(f, 1e-3, 1e4, False)
    assert 1e-3 < m < 1e4
    assert m == pytest.approx(ref, rel=1e-10)
    assert is_stable(f(np.array([m]))[0])
    assert np.all(is_stable(f(np.geomspace(m, 1e4, 2000))))
    assert not is_stable(f(np.array([m * (1.0 - 1e-9)]))[0])


def test_stable_end_returns_the_stable_end_below_every_unstable_point_found():
    """Several sign changes in the bracket: the result is stable, next to a point found
    unstable, and below all of them (a decreasing bracket too)."""
    def g(x: float) -> float:
        return math.sin(x)  # stable (<= 0) on [pi, 2 pi], crossings at 2 pi, 3 pi, 4 pi, ...

    seen: list[tuple[float, float]] = []

    def rec(x: float) -> float:
        v = g(x)
        seen.append((x, v))
        return v

    x = stable_end(rec, 4.0, 14.0)  # three crossings inside: 2 pi and 4 pi up, 3 pi down
    bad = [p for p, v in seen if v > 0]
    assert g(x) <= 0 and x < min(bad)
    assert min(bad) - x <= 2 * CROSSING_RTOL * min(bad)
    assert any(abs(x - c) < 1e-9 for c in (2 * math.pi, 4 * math.pi))  # an upward crossing, not 3 pi
    y = stable_end(math.sin, 6.0, 2.0)  # decreasing: stable on [pi, 2 pi], unstable below pi
    assert math.sin(y) <= 0 and y == pytest.approx(math.pi, rel=1e-11)


def test_stable_end_stops_at_an_exact_zero_and_keeps_it():
    """A function exactly 0 at its crossing (a spectral radius equal to the tolerance to the
    last bit): the zero is stable and is returned."""
    def g(t: float) -> float:
        return -1.0 if t < 1.5 else (0.0 if t <= 2.0 else 1.0)

    x = stable_end(g, 1.0, 3.0)
    assert g(x) <= 0 and 1.0 <= x <= 2.0


def count_expm(run) -> int:
    """Number of ``scipy.linalg.expm`` calls during ``run()``."""
    from scipy import linalg

    real = linalg.expm
    calls = []

    def counting(a, *args, **kwargs):
        calls.append(np.shape(a))
        return real(a, *args, **kwargs)

    with mock.patch.object(linalg, "expm", counting):
        run()
    return len(calls)


def unique_device(tag: float) -> Device:
    """An HBFD with a handle mass no other test uses, so the plant cache starts cold for it."""
    dev = make_hbfd()
    return dev.replace(masses=dev.masses * (1.0 + tag))


def test_a_chart_of_24_points_discretizes_the_plant_once():
    dev = unique_device(1.234e-7)
    assert count_expm(lambda: critical_stiffness_chart(dev, np.geomspace(1.0, 1e4, 24), 1)) == 1
    assert count_expm(lambda: critical_stiffness(dev, 100.0, 2)) == 0  # same device and grasp: cached


@pytest.mark.parametrize("sweep", ["critical_stiffness", "stability_map", "zwidth_region"])
def test_each_sweep_discretizes_the_plant_once(sweep):
    dev = unique_device({"critical_stiffness": 2.345e-7, "stability_map": 3.456e-7, "zwidth_region": 4.567e-7}[sweep])
    run = {
        "critical_stiffness": lambda: critical_stiffness(dev, 100.0, 1),
        "stability_map": lambda: stability_map(dev, ("kc", np.geomspace(1e3, 1e6, 12)),
                                               ("kobj", np.geomspace(1e3, 1e7, 12))),
        "zwidth_region": lambda: zwidth_region(dev, np.geomspace(1.0, 100.0, 8), 1, passive=False),
    }[sweep]
    assert count_expm(run) == 1


def test_plant_cache_is_keyed_by_value_and_follows_every_change():
    dev = make_hbfd()
    Ad, Bd = discrete_plants(dev, (HANDS_OFF, RIGID_GRASP))
    ref = discretize_zoh(*plant_matrices(dev, [HANDS_OFF, RIGID_GRASP]), dev.sample_time)
    assert np.array_equal(Ad, ref[0]) and np.array_equal(Bd, ref[1])
    assert not Ad.flags.writeable and not Bd.flags.writeable
    with pytest.raises(ValueError):
        Ad[0, 0, 0] = 1.0
    # an equal device built again is the same key; another sample time or grasp is not
    assert discrete_plants(make_hbfd(), (HANDS_OFF, RIGID_GRASP))[0] is Ad
    slow = dev.replace(sample_time=2 * dev.sample_time)
    Ad2, _ = discrete_plants(slow, (HANDS_OFF, RIGID_GRASP))
    ref2 = discretize_zoh(*plant_matrices(slow, [HANDS_OFF, RIGID_GRASP]), slow.sample_time)
    assert np.array_equal(Ad2, ref2[0]) and not np.allclose(Ad2, Ad)
    assert not np.allclose(discrete_plants(dev, (RIGID_GRASP,))[0][0], Ad[0])


def test_a_changed_device_gives_its_own_critical_stiffness():
    """The cache never hands one device's plant to another: each result equals the uncached
    route for its own device, and they differ."""
    dev = make_hbfd()
    other = [dev.replace(masses=dev.masses * np.r_[2.0, np.ones(dev.n - 1)]), dev.replace(sample_time=5e-4)]
    k0 = critical_stiffness(dev, 100.0, 1)
    for o in other:
        k = critical_stiffness(o, 100.0, 1)
        ref = bisection_crossing(fresh_radius(o, impedance_spec(100.0, 1), WALL, "kc"), 1.0, 1e9, True)
        assert k == pytest.approx(ref, rel=1e-10)
        assert abs(k - k0) > 1e-3 * k0
    assert critical_stiffness(dev, 100.0, 1) == k0


def test_is_stable_is_the_one_rule():
    assert is_stable(1.0) is True and is_stable(TOP) is True
    assert is_stable(np.nextafter(TOP, 2.0)) is False and is_stable(float("nan")) is False
    assert is_stable(np.array([0.5, TOP, 1.1])).tolist() == [True, True, False]
    sm = stability_map(make_hbfd(), ("kc", np.geomspace(1e3, 1e6, 6)), ("kobj", np.geomspace(1e3, 1e7, 5)))
    assert np.array_equal(sm.stable, sm.spectral_radius <= TOP) and sm.stable.any() and not sm.stable.all()
