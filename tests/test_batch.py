"""A batch of devices (issue 24): the per-device map, the robust space (the elementwise minimum and
its binding device), devices from an identified parameter box, the local pool and a Dask cluster.

The device functions live in tests/batch_devices.py, a light module that a pool's or a
cluster's worker imports by name.  The Dask tests need the ``distributed`` extra, which the test extra installs:
without it they fail (they are not skipped).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from functools import partial

import numpy as np
import pytest

from batch_devices import fails_at, nan_at_three, ramp, region_k, rigid, sized

from analysis import Device
from analysis.errors import ValidationError
from analysis.identify import parameter_box
from analysis.profiles import RenderableSection
from analysis.profiles.identification import IdentificationSection
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.progress import OperationCancelled
from analysis.sampled import (
    DeviceFailed,
    QualitySettings,
    RobustSpace,
    box_corners,
    box_samples,
    intersect_devices,
    map_devices,
    renderable_space,
    robust_renderable_space,
    space_volume,
)
from analysis.study.renderable import RenderableRequest, robust_box_reason, robust_study

M_GRID = np.array([-0.05, 0.0, 0.05])
D_GRID = np.array([0.0, 2.0, 8.0])


def box():
    """A box like one identification gives: the handle's mass and its ground damping."""
    return parameter_box(rigid(), {"masses[0]": (0.3, 0.8), "ground_dampings[0]": (0.5, 4.0)})


@pytest.fixture(scope="module")
def devices() -> list[Device]:
    return box_samples(box(), 12, seed=3)


# -- devices from the box -------------------------------------------------------------------------
def test_box_samples_are_seeded_and_inside_the_box() -> None:
    bx = box()
    a, b, c = box_samples(bx, 20, seed=5), box_samples(bx, 20, seed=5), box_samples(bx, 20, seed=6)
    masses = np.array([d.masses[0] for d in a])
    grounds = np.array([d.ground_dampings[0] for d in a])
    assert [d.masses[0] for d in a] == [d.masses[0] for d in b]
    assert [d.ground_dampings[0] for d in a] == [d.ground_dampings[0] for d in b]
    assert [d.masses[0] for d in a] != [d.masses[0] for d in c]
    assert np.all((masses >= 0.3) & (masses <= 0.8)) and np.all((grounds >= 0.5) & (grounds <= 4.0))
    assert masses.max() - masses.min() > 0.2  # spread over the box, not one point


def test_box_corners_are_every_end() -> None:
    corners = box_corners(box())
    pairs = sorted((d.masses[0], d.ground_dampings[0]) for d in corners)
    assert np.allclose(pairs, [(0.3, 0.5), (0.3, 4.0), (0.8, 0.5), (0.8, 4.0)], rtol=1e-12)


@pytest.mark.parametrize(("n", "seed", "field"), [(0, 1, "n"), (2.5, 1, "n"), (3, -1, "seed")])
def test_box_samples_refuse_bad_counts(n, seed, field: str) -> None:
    with pytest.raises(ValidationError) as err:
        box_samples(box(), n, seed=seed)
    assert err.value.field == field


# -- the map and the intersection ----------------------------------------------------------------
@pytest.fixture(scope="module")
def each(devices: list[Device]) -> np.ndarray:
    """Every device's region_k, one by one in this process (the independent route), read-only."""
    out = np.stack([region_k(d) for d in devices])
    out.flags.writeable = False
    return out


@pytest.fixture(scope="module")
def local(devices: list[Device]) -> RobustSpace:
    """The batch's intersection in this process (workers=1), which the pool and cluster results
    must equal; a frozen result of read-only arrays, shared by the tests that compare with it."""
    r = intersect_devices(region_k, devices, workers=1)
    r.k_max.flags.writeable = r.binding.flags.writeable = False
    return r


def test_intersection_is_the_elementwise_minimum_and_its_device(devices: list[Device], each: np.ndarray,
                                                                local: RobustSpace) -> None:
    r = local
    assert r.devices == len(devices)
    assert np.array_equal(r.k_max, each.min(axis=0))
    assert np.array_equal(r.binding, each.argmin(axis=0))  # argmin: the first of equal values
    assert np.all(r.k_max > 0) and np.all(np.isfinite(r.k_max))
    # the lightest, least damped device renders the least: it binds somewhere
    masses = np.array([d.masses[0] for d in devices])
    assert len(set(r.binding.tolist())) >= 1 and masses[r.binding].min() <= np.median(masses)


def test_pool_of_one_and_two_workers_agree_bit_for_bit(devices: list[Device], each: np.ndarray,
                                                      local: RobustSpace) -> None:
    one = local
    two = intersect_devices(region_k, devices, workers=2)
    odd = intersect_devices(region_k, devices, workers=2, chunk_size=5)
    for r in (two, odd):
        assert np.array_equal(r.k_max, one.k_max) and np.array_equal(r.binding, one.binding)
    mapped = map_devices(region_k, devices, workers=2, chunk_size=5)
    assert len(mapped) == len(devices)
    assert all(np.array_equal(m, e) for m, e in zip(mapped, each))


@pytest.mark.parametrize(("workers", "chunk"), [(1, None), (2, 1), (2, 4), (2, None)])
def test_ties_bind_the_lowest_index_whatever_the_chunks(workers: int, chunk: int | None) -> None:
    values = list(range(10))
    r = intersect_devices(ramp, values, workers=workers, chunk_size=chunk)
    assert r.k_max.tolist() == [0.0, 4.0, 1.0]
    assert r.binding.tolist() == [0, 1, 0]


@pytest.mark.parametrize("workers", [1, 2])
def test_a_failing_device_is_named(workers: int) -> None:
    with pytest.raises(DeviceFailed) as err:
        intersect_devices(fails_at, list(range(12)), workers=workers, chunk_size=2)
    assert err.value.index == 7
    assert "device 7" in str(err.value) and "ValueError: no model for unit 7" in str(err.value)


def test_the_lowest_failing_device_is_reported() -> None:
    fn = partial(fails_at, bad=(9, 4, 11))
    for workers in (1, 2):
        with pytest.raises(DeviceFailed) as err:
            map_devices(fn, list(range(12)), workers=workers, chunk_size=3)
        assert err.value.index == 4


def test_nan_and_shape_changes_are_failures() -> None:
    with pytest.raises(DeviceFailed, match="device 3 .*NaN"):
        intersect_devices(nan_at_three, list(range(5)), workers=1)
    with pytest.raises(DeviceFailed, match="device 2 .*shape"):
        intersect_devices(sized, list(range(4)), workers=1)


def test_bad_arguments_name_their_field(devices: list[Device]) -> None:
    cases = [({"workers": 0}, "workers"), ({"chunk_size": 0}, "chunk_size"),
             ({"workers": 2, "client": object()}, "workers")]
    for kwargs, field in cases:
        with pytest.raises(ValidationError) as err:
            intersect_devices(region_k, devices, **kwargs)
        assert err.value.field == field
    with pytest.raises(ValidationError) as err:
        intersect_devices(region_k, [], workers=1)
    assert err.value.field == "devices"
    with pytest.raises(ValidationError) as err:  # a pool pickles the function by name
        intersect_devices(lambda d: region_k(d), devices, workers=2)
    assert err.value.field == "fn"


# -- progress and cancel -------------------------------------------------------------------------
@pytest.mark.parametrize("workers", [1, 2])
def test_progress_counts_devices_to_the_end(devices: list[Device], workers: int) -> None:
    seen: list[tuple[int, int]] = []
    intersect_devices(region_k, devices, workers=workers, chunk_size=3,
                      progress=lambda done, total: seen.append((done, total)))
    assert seen[0] == (0, 12) and seen[-1] == (12, 12)
    assert all(t == 12 for _, t in seen) and [d for d, _ in seen] == sorted(d for d, _ in seen)


def test_cancel_stops_in_this_process(devices: list[Device]) -> None:
    polls: list[int] = []

    def cancel() -> bool:
        polls.append(1)
        return len(polls) > 3

    seen: list[int] = []
    with pytest.raises(OperationCancelled):
        intersect_devices(region_k, devices, workers=1, progress=lambda d, t: seen.append(d), cancelled=cancel)
    assert max(seen) == 3  # three devices computed, then it stopped


def test_cancel_stops_the_pool(devices: list[Device]) -> None:
    seen: list[int] = []
    with pytest.raises(OperationCancelled):
        intersect_devices(region_k, devices * 20, workers=2, chunk_size=1,
                          progress=lambda d, t: seen.append(d), cancelled=lambda: True)
    assert max(seen) < len(devices) * 20


# -- the robust renderable space ---------------------------------------------------------------------
def test_robust_renderable_space_is_the_minimum_of_the_devices_spaces() -> None:
    batch = box_corners(box())
    qualities = ("stable", "passive")
    spaces = [renderable_space(d, M_GRID, D_GRID, qualities=qualities) for d in batch]
    r = robust_renderable_space(batch, M_GRID, D_GRID, qualities=qualities, workers=2, chunk_size=1)
    assert r.devices == 4 and r.qualities == qualities
    assert np.array_equal(r.mass, M_GRID) and np.array_equal(r.damping, D_GRID)
    assert np.array_equal(r.k_max, np.min([s.k_max for s in spaces], axis=0))
    for q in qualities:
        assert np.array_equal(r.by_quality[q], np.min([s.by_quality[q] for s in spaces], axis=0))
    assert np.array_equal(r.binding, np.argmin([s.k_max for s in spaces], axis=0))
    assert np.any(r.k_max > 0)
    assert np.all(r.k_max <= np.minimum(r.by_quality["stable"], r.by_quality["passive"]))
    # the volume by the one rule of a device's space, so no device's space is smaller than the robust one
    assert r.volume == space_volume(r.mass, r.damping, r.k_max)
    assert 0.0 < r.volume <= min(s.volume for s in spaces)
    assert r.volume < max(s.volume for s in spaces)  # the corners differ: the intersection costs volume


def test_one_device_robust_volume_is_its_own_and_follows_the_settings() -> None:
    coarse = QualitySettings(k_range=(10.0, 1e6), b_ref=0.1)
    own = renderable_space(rigid(), M_GRID, D_GRID, settings=coarse)
    r = robust_renderable_space([rigid()], M_GRID, D_GRID, settings=coarse, workers=1)
    assert np.array_equal(r.k_max, own.k_max)
    assert r.volume == own.volume == space_volume(M_GRID, D_GRID, own.k_max, coarse)
    assert r.volume != space_volume(M_GRID, D_GRID, own.k_max)  # the default floor and b_ref differ


def test_robust_renderable_space_names_a_bad_field() -> None:
    with pytest.raises(ValidationError) as err:
        robust_renderable_space([rigid()], M_GRID, D_GRID, qualities=("stable", "silky"), workers=1)
    assert err.value.field == "qualities"
    with pytest.raises(DeviceFailed, match="device 0 .*mass"):
        robust_renderable_space([rigid()], [0.0, math.nan], D_GRID, workers=1)


# -- a Dask cluster ----------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def client() -> Iterator[object]:
    """A LocalCluster of two worker processes, one thread each.  ``distributed`` is in the test
    extra: without it this fails, on purpose (a suite that skips on a failed import hides it)."""
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_cluster_result_equals_the_local_result_bit_for_bit(client: object, devices: list[Device],
                                                            local: RobustSpace) -> None:
    remote = intersect_devices(region_k, devices, client=client, chunk_size=5)
    assert np.array_equal(remote.k_max, local.k_max) and np.array_equal(remote.binding, local.binding)
    batch = box_corners(box())
    here = robust_renderable_space(batch, M_GRID, D_GRID, qualities=("stable", "passive"), workers=1)
    there = robust_renderable_space(batch, M_GRID, D_GRID, qualities=("stable", "passive"), client=client)
    assert np.array_equal(there.k_max, here.k_max) and np.array_equal(there.binding, here.binding)
    assert all(np.array_equal(there.by_quality[q], here.by_quality[q]) for q in here.qualities)


def test_cluster_failure_names_the_device(client: object) -> None:
    with pytest.raises(DeviceFailed) as err:
        intersect_devices(fails_at, list(range(12)), client=client, chunk_size=2)
    assert err.value.index == 7 and "no model for unit 7" in str(err.value)


def test_cluster_cancel_stops(client: object) -> None:
    seen: list[int] = []
    with pytest.raises(OperationCancelled):
        intersect_devices(region_k, [rigid()] * 40, client=client, chunk_size=1,
                          progress=lambda d, t: seen.append(d), cancelled=lambda: True)
    assert max(seen) < 40


# -- the study layer's robust route (the Renderable space tab's overlay) --------------------------------
def test_the_study_request_takes_the_profiles_identified_box() -> None:
    intervals = {"masses[0]": (0.4, 0.6), "ground_dampings[0]": (1.0, 3.0)}
    plain = load_profile(bundled_profiles()["rigid"]).replace(
        renderable=RenderableSection(mass_points=3, damping_points=3))
    assert "no identified intervals" in robust_box_reason(plain)
    assert RenderableRequest.of(plain, robust="corners").robust is None
    boxed = plain.replace(identification=IdentificationSection(intervals))
    assert robust_box_reason(boxed) is None
    assert RenderableRequest.of(boxed).robust is None  # off by default: the request is the device's own
    corners = RenderableRequest.of(boxed, robust="corners")
    assert corners == RenderableRequest.of(boxed, robust="corners", samples=99)  # the corners have no count
    assert corners != RenderableRequest.of(boxed, robust="samples", samples=5)
    r = robust_study(corners)
    ref = robust_renderable_space(box_corners(parameter_box(boxed.device, intervals)), corners.mass, corners.damping,
                                  corners.delay_samples, corners.velocity_filter, corners.acceleration,
                                  corners.qualities, settings=corners.settings, workers=1)
    assert r.devices == 4 and np.array_equal(r.k_max, ref.k_max) and r.volume == ref.volume
    assert corners.robust.label(boxed.device) == "4 corners of the identified box"
    open_box = plain.replace(identification=IdentificationSection({"masses[0]": (0.4, math.inf)}))
    assert "masses[0] open" in robust_box_reason(open_box)
    with pytest.raises(ValidationError) as err:
        RenderableRequest.of(boxed, robust="everywhere")
    assert err.value.field == "robust"
    with pytest.raises(ValidationError) as err:
        robust_study(RenderableRequest.of(boxed))
    assert err.value.field == "robust"
