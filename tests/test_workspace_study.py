"""The study layer of the workspace (issue 25): requests from the profile, the map in bands, the handle's limits."""

from __future__ import annotations

import math

import numpy as np
import pytest

from analysis.errors import ValidationError
from analysis.multidof import critical_wall_stiffness, five_bar_device, workspace_map
from analysis.profiles import MultiDofSection, bundled_profiles, load_profile
from analysis.progress import OperationCancelled
from analysis.study import (
    HandleRequest,
    WorkspaceRequest,
    handle_edits,
    inertia_ellipse,
    polar_curve,
    workspace_point,
    workspace_study,
)
from analysis.study.workspace import K_RANGE, join_bands

SMALL = MultiDofSection(x_points=7, y_points=5)


def _profile(section: MultiDofSection = SMALL):
    return load_profile(bundled_profiles()["hbfd"]).replace(multidof=section)


def test_the_map_request_ignores_the_handle_and_the_handle_request_ignores_the_grid():
    p = _profile()
    moved = p.replace(multidof=p.multidof.replace(**handle_edits(0.02, 0.25)))
    assert WorkspaceRequest.of(p) == WorkspaceRequest.of(moved)
    assert HandleRequest.of(p) != HandleRequest.of(moved)
    finer = p.replace(multidof=p.multidof.replace(x_points=9))
    assert HandleRequest.of(p) == HandleRequest.of(finer) and WorkspaceRequest.of(p) != WorkspaceRequest.of(finer)
    req = WorkspaceRequest.of(p)
    assert req.x[0] == SMALL.x_min and req.x[-1] == SMALL.x_max and len(req.y) == SMALL.y_points


def test_the_map_in_bands_is_the_map_of_the_whole_grid():
    p = _profile()
    req = WorkspaceRequest.of(p)
    steps: list[tuple[int, int]] = []
    m = workspace_study(req, progress=lambda d, t: steps.append((d, t)))
    full = workspace_map(req.linkage, req.x, req.y, req.damping, req.delay_samples, sample_time=req.sample_time, k_range=K_RANGE)
    assert steps == [(i, SMALL.y_points) for i in range(1, SMALL.y_points + 1)]
    for name in ("reachable", "k_max", "worst_stiffness", "worst_normal"):
        np.testing.assert_array_equal(getattr(m, name), getattr(full, name))
    np.testing.assert_array_equal(m.minimum.position, full.minimum.position)
    assert m.minimum.stiffness == full.minimum.stiffness
    assert m.minimum.stiffness <= np.nanmin(m.worst_stiffness)


def test_joining_bands_takes_the_first_band_with_the_smallest_value_and_fills_unreachable_bands():
    p = _profile()
    req = WorkspaceRequest.of(p)
    x = np.asarray(req.x)
    rows = [np.array([0.2]), np.array([5.0]), np.array([0.25])]  # the middle band is out of reach
    a = workspace_map(req.linkage, x, rows[0], 0.0, 0, sample_time=req.sample_time, k_range=K_RANGE)
    b = workspace_map(req.linkage, x, rows[2], 0.0, 0, sample_time=req.sample_time, k_range=K_RANGE)
    joined = join_bands([a, None, b], x, rows)
    assert joined.k_max.shape == (3, x.size) and not joined.reachable[1].any()
    assert np.isnan(joined.k_max[1]).all() and np.isnan(joined.worst_normal[1]).all()
    better = a if np.nanmin(a.worst_stiffness) <= np.nanmin(b.worst_stiffness) else b
    assert joined.minimum is better.minimum
    with pytest.raises(ValidationError):
        join_bands([None], x, rows[:1])


def test_a_cancelled_map_stops_between_bands():
    calls = []

    def cancelled() -> bool:
        calls.append(1)
        return len(calls) > 1

    assert workspace_study(_profile(), cancelled=cancelled) is None
    assert len(calls) == 2
    with pytest.raises(OperationCancelled):
        workspace_study.__wrapped__(_profile(), cancelled=lambda: True)


def test_the_handle_limits_match_the_analysis_and_the_ellipse_and_polar_curve_come_from_them():
    sec = MultiDofSection(handle_x=0.03, handle_y=0.22, wall_kind="normal", wall_normal=(3.0, 4.0))
    p = _profile(sec)
    pt = workspace_point(p)
    dev = five_bar_device(sec.linkage, sec.handle, p.device.sample_time)
    req = HandleRequest.of(p)
    assert pt.wall == pytest.approx(critical_wall_stiffness(dev, 0.0, req.delay_samples, [0.6, 0.8], k_range=K_RANGE), rel=1e-9)
    assert pt.isotropic == pytest.approx(critical_wall_stiffness(dev, 0.0, req.delay_samples, None, k_range=K_RANGE), rel=1e-9)
    # the worst normal is no worse than the smallest of its own dense check, which the polar curve draws
    assert pt.worst.stiffness <= np.min(pt.stiffness) * (1 + 1e-12)
    np.testing.assert_allclose(pt.mass, dev.mass, rtol=1e-15)
    np.testing.assert_allclose(pt.principal_axes @ np.diag(pt.principal_masses) @ pt.principal_axes.T, dev.mass,
                               rtol=1e-10)
    np.testing.assert_allclose(pt.joints[2], sec.handle)
    link = np.linalg.norm(np.diff(pt.joints, axis=0), axis=1)
    np.testing.assert_allclose(link, [sec.l1, sec.l2, sec.l2, sec.l1], rtol=1e-12)
    x, y = inertia_ellipse(pt, scale=2.0)
    r = np.hypot(x - sec.handle_x, y - sec.handle_y)
    assert r.max() == pytest.approx(2.0 * pt.principal_masses[1], rel=1e-3)
    assert r.min() == pytest.approx(2.0 * pt.principal_masses[0], rel=1e-3)
    px, py = polar_curve(pt)
    finite = np.isfinite(pt.stiffness)
    np.testing.assert_allclose(np.hypot(px, py)[:-1][finite], pt.stiffness[finite], rtol=1e-12)
    assert px[-1] == pytest.approx(px[0]) and len(pt.angles) == 2 * len(pt.worst.directions)
    assert math.isclose(float(np.ptp(np.diff(pt.angles[: len(pt.angles) // 2]))), 0.0, abs_tol=1e-12)


def test_a_handle_out_of_reach_is_refused_by_name():
    sec = MultiDofSection()
    with pytest.raises(ValidationError) as info:
        workspace_point(HandleRequest(sec.linkage, (0.0, 0.4375), None, 0.0, 1e-3, 1, None))
    assert "0.4375" in str(info.value)


def test_light_joint_damping_gives_small_positive_walls_not_zero():
    """The bundled profile's five-bar (joint damping 1e-3 N m s/rad, no wall damping, no delay) renders
    only walls of a few mN/m near its workspace's edge.  With the analysis's default range (from 1
    N/m) 24 of its grid points and the design bound read 0 N/m; the study scans from
    ``K_RANGE[0]``.  Colgate & Brown's passivity condition b > K T / 2 is sufficient, so the bound is
    at least 2 b_min / T of the weakest damping direction at its point, and for so light a damper
    hardly more."""
    profile = load_profile(bundled_profiles()["hbfd"])
    m = workspace_study(profile)
    req = WorkspaceRequest.of(profile)
    assert K_RANGE[0] <= 1e-6 and np.all(m.worst_stiffness[m.reachable] > 0)
    dev = five_bar_device(req.linkage, m.minimum.position, req.sample_time)
    b_min = float(np.linalg.eigvalsh(dev.damping)[0])
    colgate = 2.0 * b_min / req.sample_time
    assert colgate * (1 - 1e-6) <= m.minimum.stiffness <= 1.1 * colgate
    assert m.minimum.stiffness < 0.01  # N/m: the edge of this workspace, a few mN/m
