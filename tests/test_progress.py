"""The one progress and cancel protocol (issue 21): analysis.progress and every former protocol.

Each former protocol now goes through it: the charts and sweeps that returned ``None`` on
cancel (twoport, sampled, study) stop by the one exception and turn it into ``None`` at their
public boundary; the fit's ``FitCancelled`` is that exception; the filter optimum's refinement
(which had its own private exception) stops by it too.  A cancel hook may therefore also raise
:class:`~analysis.progress.OperationCancelled` itself: every public computation answers ``None``.
"""

from __future__ import annotations

import numpy as np
import pytest

from analysis.identify import FitCancelled, fit_chain, make_measurement
from analysis.profiles.io import bundled_profiles, load_profile
from analysis.progress import (
    Cancelled,
    OperationCancelled,
    Progress,
    check_cancelled,
    none_if_cancelled,
    report_progress,
)
from analysis.sampled import critical_stiffness_chart, optimal_filter
from analysis.study import design_chart, display_kind, identify_chain, simulation, stability_map_result
from analysis.study import map_params
from analysis.twoport import ImpedanceDisplay


def _rigid():
    return load_profile(bundled_profiles()["rigid"])


class _Hook:
    """A cancel hook that turns true after ``after`` polls (or raises, with ``raising``)."""

    def __init__(self, after: int, raising: bool = False) -> None:
        self.after, self.raising, self.polls = after, raising, 0

    def __call__(self) -> bool:
        self.polls += 1
        if self.polls > self.after:
            if self.raising:
                raise OperationCancelled("stopped by the hook")
            return True
        return False


def test_the_helpers():
    check_cancelled(None)
    check_cancelled(lambda: False)
    with pytest.raises(OperationCancelled, match="the fit was cancelled"):
        check_cancelled(lambda: True, "the fit was cancelled")
    seen: list[tuple[int, int]] = []
    report_progress(lambda d, t: seen.append((d, t)), 2, 5)
    report_progress(None, 3, 5)
    assert seen == [(2, 5)]

    @none_if_cancelled
    def work(n: int, *, cancelled: Cancelled | None = None) -> int:
        """Doc kept."""
        check_cancelled(cancelled)
        return 2 * n

    assert work(3) == 6 and work(3, cancelled=lambda: True) is None
    assert work.__doc__ == "Doc kept." and work.__name__ == "work"
    # a cancel is not a bad-input error: code that turns ValueError into an error row never eats it
    assert not issubclass(OperationCancelled, ValueError)


def test_the_aliases_are_the_one_protocol():
    import analysis.twoport as twoport
    from analysis.identify import errors

    assert FitCancelled is OperationCancelled and errors.FitCancelled is OperationCancelled
    assert twoport.Progress is Progress and twoport.Cancelled is Cancelled


@pytest.mark.parametrize("raising", [False, True])
def test_twoport_chart_stops_at_the_next_point(raising):
    """Former protocol ``None`` on cancel (twoport): stops before the third point, answers None."""
    disp = ImpedanceDisplay(_rigid().device)
    done: list[int] = []
    hook = _Hook(2, raising)
    assert disp.stiffness_chart(np.geomspace(1.0, 1e3, 6), progress=lambda d, t: done.append(d),
                                cancelled=hook) is None
    assert done == [1, 2] and hook.polls == 3


@pytest.mark.parametrize("raising", [False, True])
def test_sampled_sweep_stops_at_the_next_point(raising):
    """Former protocol ``None`` on cancel (sampled sweeps)."""
    device = _rigid().device
    done: list[tuple[int, int]] = []
    hook = _Hook(1, raising)
    assert critical_stiffness_chart(device, [1.0, 10.0, 100.0], progress=lambda d, t: done.append((d, t)),
                                    cancelled=hook) is None
    assert done == [(1, 3)] and hook.polls == 2


def test_filter_optimum_stops_inside_its_refinement():
    """Former private exception of the filter optimum's refinement: the cancel comes after the grid,
    during Brent's search, and the public function answers None; with a hook that raises too."""
    device = _rigid().device
    cutoffs = np.geomspace(2 * np.pi * 20, 2 * np.pi * 150, 4)
    b = np.geomspace(1.0, 100.0, 4)
    for raising in (False, True):
        done: list[int] = []
        hook = _Hook(cutoffs.size + 1, raising)  # the grid's polls, then one of the refinement
        assert optimal_filter(device, "lowpass1", cutoffs, b=b, refine_iterations=4,
                              progress=lambda d, t: done.append(d), cancelled=hook) is None
        assert hook.polls == cutoffs.size + 2
        assert done[: cutoffs.size] == list(range(1, cutoffs.size + 1)) and len(done) == cutoffs.size + 1


def _actuator_measurement():
    from analysis.identify import device_response

    device = _rigid().device
    w = np.geomspace(1.0, 0.5 * np.pi / device.sample_time, 40)
    return make_measurement(w, device_response(device, w, "actuator", "free"), "actuator", "free")


def test_fit_raises_the_one_exception_and_the_study_answers_none():
    """Former ``FitCancelled``: the fit raises OperationCancelled at its first model evaluation;
    identify_chain (the study layer) turns it into None."""
    m = _actuator_measurement()
    hook = _Hook(0)
    with pytest.raises(OperationCancelled, match="the fit was cancelled"):
        fit_chain([m], 1, cancelled=hook)
    assert hook.polls == 1
    late = _Hook(0, raising=True)
    assert identify_chain([m], 1, cancelled=late) is None and late.polls == 1


@pytest.mark.parametrize("raising", [False, True])
def test_study_computations_answer_none(raising):
    """The study layer (what the GUI's nodes and the report call): None at the public boundary."""
    profile = _rigid()
    kind = display_kind(profile)
    assert design_chart(profile, kind, points=4, cancelled=_Hook(1, raising)) is None
    params = {**map_params(profile), "points": 4}
    hook = _Hook(1, raising)
    assert stability_map_result(profile, params, cancelled=hook) is None and hook.polls == 2
    # the simulation is one piece: a cancel during the run drops its result
    hook = _Hook(1, raising)
    steps: list[int] = []
    assert simulation(profile, progress=lambda d, t: steps.append(d), cancelled=hook) is None
    assert steps == [0, 1] and hook.polls == 2
