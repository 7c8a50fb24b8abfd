"""Robust designs of analysis.identify over parameter boxes, checked against dense random samples."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from analysis import ImpedanceDisplay, ValidationError, load_profile
from analysis.identify import (
    box_search,
    device_with,
    parameter_box,
    robust_max_stiffness,
)

from tests.hbfd_fixtures import make_hbfd

pytestmark = pytest.mark.numerics

HBFD = "resources/profiles/hbfd.json"


def test_acceptance_seed_section_vi_uncertain_b4():
    """Adams et al., section VI: b4 in [1.2, 5] N s/m, b_c = 100 -> the b4 = 1.2 design."""
    d = load_profile(HBFD).device
    r = robust_max_stiffness(d, 100.0, intervals={"ground_dampings[3]": (1.2, 5.0)})
    assert r.kc == pytest.approx(49.15e3, rel=1e-3)
    assert r.nominal_kc == pytest.approx(117.1e3, rel=1e-3)
    assert r.binding == {"ground_dampings[3]": 1.2} and r.corner
    np.testing.assert_array_equal(r.device.ground_dampings, [0, 0, 0, 1.2])
    assert r.kc == ImpedanceDisplay(r.device).max_stiffness(100.0).kc
    assert r.frequency == pytest.approx(39.4, rel=0.01)


def _margin_ok(device, kc, bc) -> float:
    disp = ImpedanceDisplay(device)
    w = disp.frequencies()
    return float(np.min(disp.coupling_term(w, kc, bc) - disp.bound(w)))


def _sample(box_intervals, count, seed):
    keys = list(box_intervals)
    lo = np.array([box_intervals[k][0] for k in keys])
    hi = np.array([box_intervals[k][1] for k in keys])
    u = np.random.default_rng(seed).random((count, len(keys)))
    return [dict(zip(keys, row)) for row in lo + u * (hi - lo)]


def test_all_fourteen_hbfd_parameters_against_a_dense_random_check():
    d = make_hbfd()
    iv = {}
    for field in ("masses", "stiffnesses", "dampings", "ground_dampings"):
        for i, v in enumerate(getattr(d, field)):
            iv[f"{field}[{i}]"] = (0.9 * v, 1.1 * v) if v > 0 else (0.0, 0.5)
    assert len(iv) == 14
    r = robust_max_stiffness(d, 100.0, iv)
    assert 0 < r.kc < r.nominal_kc
    assert set(r.binding) == set(iv)
    assert r.kc == pytest.approx(ImpedanceDisplay(r.device).max_stiffness(100.0).kc, rel=1e-12)
    for values in _sample(iv, 2000, seed=7):
        assert _margin_ok(device_with(d, values), r.kc, 100.0) >= 0.0


def test_small_box_all_corners_and_random_devices_hold():
    d = make_hbfd()
    iv = {"masses[1]": (1.5, 3.0), "stiffnesses[1]": (5e4, 1.5e5), "ground_dampings[3]": (1.0, 6.0)}
    r = robust_max_stiffness(d, 100.0, iv)
    corners = [dict(zip(iv, c)) for c in itertools.product(*iv.values())]
    limits = [ImpedanceDisplay(device_with(d, c)).max_stiffness(100.0).kc for c in corners]
    assert r.kc <= min(limits)
    assert r.kc == pytest.approx(min(limits), rel=1e-9)  # here the worst case is a corner
    for values in _sample(iv, 500, seed=3):
        assert _margin_ok(device_with(d, values), r.kc, 100.0) >= 0.0


def test_box_search_finds_an_interior_minimum():
    d = make_hbfd()
    box = parameter_box(d, {"masses[0]": (0.1, 0.4), "masses[1]": (1.0, 4.0)})

    def bowl(u: np.ndarray) -> np.ndarray:  # minimum 1 inside the box, not at a corner
        return 1.0 + (u[:, 0] - 0.37) ** 2 + 2.0 * (u[:, 1] - 0.61) ** 2

    tr = box_search(bowl, box)
    assert tr.values[tr.best] == pytest.approx(1.0, abs=1e-6) and not tr.corner
    np.testing.assert_allclose(tr.points[tr.best], [0.37, 0.61], atol=2e-3)


def test_bad_intervals():
    d = make_hbfd()
    with pytest.raises(ValidationError):
        robust_max_stiffness(d, 100.0, {"masses[0]": (0.3, 0.1)})
    with pytest.raises(ValidationError):
        robust_max_stiffness(d, 100.0, {"masses[0]": (0.0, 0.1)})
    with pytest.raises(ValueError, match="ground_dampings\\[4\\]"):
        robust_max_stiffness(d, 100.0, {"ground_dampings[4]": (0.0, 1.0)})
    # a point interval fixes the parameter
    r = robust_max_stiffness(d, 100.0, {"ground_dampings[3]": (1.2, 1.2)})
    assert r.kc == pytest.approx(49.15e3, rel=1e-3) and r.keys == ()
