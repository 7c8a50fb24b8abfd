"""The study layer of the renderable space (issue 24): the request of a profile and its result."""

from __future__ import annotations

import numpy as np
import pytest

from analysis.profiles import RenderableSection, bundled_profiles, load_profile
from analysis.sampled import FIRM_GRASP, HANDS_OFF, m_width, renderable_space
from analysis.study import (
    RenderableRequest,
    damping_axis,
    damping_from_axis,
    k_max_at,
    renderable_section,
    renderable_study,
)


def _profile(**section):
    p = load_profile(bundled_profiles()["rigid"])
    return p.replace(renderable=RenderableSection(mass_points=5, damping_points=7, **section))


def test_the_damping_axis_is_signed_log_and_inverts():
    b = np.array([-1e3, -9.0, -0.5, 0.0, 0.5, 9.0, 99.0])
    u = damping_axis(b)
    assert u[1] == pytest.approx(-1.0) and u[3] == 0.0 and u[6] == pytest.approx(2.0)
    assert np.all(np.diff(u) > 0)
    assert damping_from_axis(u) == pytest.approx(b)


def test_request_holds_the_grid_and_settings_not_the_environment():
    p = _profile(grasps="firm", mass_min=-0.2, mass_max=0.4, damping_min=-2.0, damping_max=50.0)
    req = RenderableRequest.of(p)
    assert req.mass == pytest.approx(tuple(np.linspace(-0.2, 0.4, 5)))
    assert req.damping[0] == -2.0 and req.damping[-1] == 50.0 and len(req.damping) == 7
    assert np.diff(damping_axis(req.damping)) == pytest.approx(np.full(6, np.diff(damping_axis(req.damping))[0]))
    assert req.settings.grasps == (HANDS_OFF, FIRM_GRASP)
    moved = p.replace(renderable=p.renderable.replace(virtual_mass=0.1, virtual_damping=3.0, virtual_stiffness=9.0))
    assert RenderableRequest.of(moved) == req and hash(RenderableRequest.of(moved)) == hash(req)
    assert RenderableRequest.of(p.replace(renderable=p.renderable.replace(mass_points=6))) != req


def test_without_a_section_the_defaults_are_used():
    p = load_profile(bundled_profiles()["rigid"])
    assert renderable_section(p) == RenderableSection()
    assert RenderableRequest.of(p).qualities == ("stable",)


def test_the_study_is_the_sampled_layers_space_and_m_width():
    p = _profile(qualities=("stable", "passive"))
    req = RenderableRequest.of(p)
    seen: list[tuple[int, int]] = []
    s = renderable_study(p, progress=lambda d, t: seen.append((d, t)))
    direct = renderable_space(p.device, req.mass, req.damping, req.delay_samples, req.velocity_filter,
                              req.acceleration, req.qualities, settings=req.settings)
    np.testing.assert_array_equal(s.space.k_max, direct.k_max)
    np.testing.assert_array_equal(s.space.by_quality["passive"], direct.by_quality["passive"])
    w = m_width(p.device, req.delay_samples, req.velocity_filter, req.acceleration, req.qualities,
                settings=req.settings)
    assert (s.width.m_min, s.width.m_max) == (w.m_min, w.m_max)
    assert s.width.m_min < 0 < s.width.m_max
    assert seen[-1][0] == seen[-1][1] and all(d <= t for d, t in seen)


def test_k_max_at_reads_the_nearest_grid_point():
    s = renderable_study(_profile()).space
    i, j = 3, 4
    assert k_max_at(s, float(s.mass[i]) + 1e-9, float(s.damping[j])) == s.k_max[i, j]
    assert k_max_at(s, float(s.mass[i]), float(s.damping[j]), "stable") == s.by_quality["stable"][i, j]
    assert np.isnan(k_max_at(s, float(s.mass[-1]) + 1.0, 0.0))


def test_cancelled_returns_none():
    assert renderable_study(_profile(), cancelled=lambda: True) is None
