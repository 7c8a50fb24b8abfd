"""The report's disturbance-observer part (Eom, Suh & Yi, section 2), when the profile has an
``observer`` section.

:func:`observer_part` (Qt-free, called by :func:`app.report.content.gather`): the observer's
settings and what it does, from :mod:`analysis.study` (the functions the app's Observer tab calls):
the disturbance-to-velocity peak with and without the observer (eq. 3-5), the cross-axis coupling
of the two-axis five-bar device and the y answer to a force step on x.  Its figures (needing Qt)
are in :mod:`app.report.observer_figures`.
"""

from __future__ import annotations

import html
from typing import Any

import numpy as np

from analysis.profiles import Profile
from analysis.study import observer_coupling, observer_response, observer_step
from analysis.study.labels import OBSERVER_PRESET_LABELS
from app.report.model import Numbers, Part, Section, num, row

__all__ = ["observer_part"]

_ADMITTANCE = "m/(N&middot;s)"


def _peak(values: np.ndarray) -> float:
    return float(np.max(np.abs(values)))


def observer_part(profile: Profile) -> Part:
    """The report's section on the profile's disturbance observer (empty without one); results
    ``observer_response``, ``observer_coupling`` and ``observer_step`` for its figures."""
    st = profile.observer
    if st is None:
        return Part()
    resp, coupling, step = observer_response(st), observer_coupling(profile), observer_step(profile)
    numbers: Numbers = {}
    preset = OBSERVER_PRESET_LABELS.get(st.preset, st.preset)
    rows = (
        row(numbers, "observer.nominal_mass", "nominal mass of P<sub>n</sub> (eq. 3)", "<i>M</i>&#772;",
            st.nominal_mass, "kg"),
        row(numbers, "observer.nominal_damping", "nominal damping of P<sub>n</sub> (eq. 3)", "<i>B</i>&#772;",
            st.nominal_damping, "N&middot;s/m"),
        row(numbers, "observer.order", "order of the low-pass Q", "<i>r</i>", st.order, ""),
        row(numbers, "observer.cutoff", "cut-off of the low-pass Q", "&omega;<sub>Q</sub>", st.cutoff, "rad/s"),
        row(numbers, "observer.alpha", "mass uncertainty of the real plant (eq. 13)", "&alpha;", st.alpha, ""),
        row(numbers, "observer.beta", "damping uncertainty of the real plant (eq. 13)", "&beta;", st.beta, ""),
        row(numbers, "observer.delta", "perturbation of the real plant (eq. 13)", "&delta;", st.delta, ""),
        row(numbers, "observer.disturbance_without", "largest |v/d| without the observer", "",
            _peak(resp.disturbance_without), _ADMITTANCE),
        row(numbers, "observer.disturbance_with", "largest |v/d| with the observer", "",
            _peak(resp.disturbance_with), _ADMITTANCE),
        row(numbers, "observer.coupling_without", "largest cross-axis |v<sub>y</sub>/F<sub>x</sub>| without "
            "the observers", "", _peak(coupling.coupling_without), _ADMITTANCE),
        row(numbers, "observer.coupling_with", "largest cross-axis |v<sub>y</sub>/F<sub>x</sub>| with the "
            "observers", "", _peak(coupling.coupling_with), _ADMITTANCE),
        row(numbers, "observer.step_y_without", "largest |y| after the step on x, without the observers", "",
            _peak(step.y_without) * 1e3, "mm"),
        row(numbers, "observer.step_y_with", "largest |y| after the step on x, with the observers", "",
            _peak(step.y_with) * 1e3, "mm"),
    )
    par = ("The disturbance observer of Eom, Suh &amp; Yi (Fig. 1, eq. 2&ndash;5): the low-pass "
           f"<i>Q</i> = (&omega;<sub>Q</sub>/(<i>s</i> + &omega;<sub>Q</sub>))<sup><i>r</i></sup> and the nominal "
           "plant <i>P</i><sub>n</sub> = 1/(<i>M</i>&#772;<i>s</i> + <i>B</i>&#772;); the real plant has the mass "
           "<i>M</i>&#772;(1 + &alpha;&delta;) and the damping <i>B</i>&#772;(1 + &beta;&delta;) (eq. 13). "
           f"The two-axis device is the {html.escape(preset)} preset, its step a "
           f"{num(st.step_force, rich=True)} N force on x for {num(st.step_duration, rich=True)} s.")
    results: dict[str, Any] = {"observer_response": resp, "observer_coupling": coupling, "observer_step": step}
    return Part((Section("Disturbance observer (Eom, Suh &amp; Yi)", (par,), rows),), numbers, results)
