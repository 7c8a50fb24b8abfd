"""The J quadrature's panels near a singularity on the real axis: finite, and few.

An undamped plant mode is a singularity with sigma = 0.  The panels used to approach it in ever
smaller steps until a step fell below the spacing of doubles, and then never passed it: the loop
ran until memory ran out (found while looking for a CI run that never ended).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from analysis.transparency.hinf import MIN_PANEL, panel_breakpoints


@pytest.mark.parametrize("sigma", [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3])
def test_a_singularity_on_or_near_the_axis_costs_few_panels(sigma):
    b = panel_breakpoints(1.0, 1000.0, np.array([10.0 + 1j * sigma, 200.0 + 1j * sigma]))
    assert b[0] == 1.0 and b[-1] == 1000.0 and np.all(np.diff(b) > 0)
    assert b.size < 400  # about 60 panels per singularity on the axis, 25 a decade besides
    assert np.all(np.diff(b)[:-1] >= MIN_PANEL * b[:-2] * (1 - 1e-6))  # (a + h rounds: 2e-7 of h)
    # the panels still close in on the singularity: a breakpoint within max(sigma, 1e-8 w0) of it
    assert np.min(np.abs(b - 10.0)) < max(2 * sigma, 1e-8 * 10.0)


def test_far_from_the_axis_nothing_changes():
    """With sigma well above MIN_PANEL * w0 the floor never applies: the rule of the docstring."""
    c = np.array([10.0 + 0.5j])
    b = panel_breakpoints(1.0, 1000.0, c)
    h = np.diff(b)
    a = b[:-1]
    expected = np.minimum(a * (10 ** (1 / 8) - 1), 0.5 * np.abs(a - c[0]))
    inner = b[1:] < 1000.0 * (1 - 1e-9)
    np.testing.assert_allclose(h[inner], expected[inner], rtol=1e-12)


@settings(max_examples=60, deadline=None)
@given(w0=st.floats(1.5, 900.0), sigma=st.one_of(st.just(0.0), st.floats(0.0, 1e-3)))
def test_any_real_axis_singularity_terminates_in_bounded_panels(w0, sigma):
    b = panel_breakpoints(1.0, 1000.0, np.array([w0 + 1j * sigma]))
    assert b[-1] == 1000.0 and np.all(np.diff(b) > 0) and b.size < 300
