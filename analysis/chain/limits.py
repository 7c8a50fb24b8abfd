"""The physical range of every input, and the largest work an input may ask for: ONE definition.

The loader (:mod:`analysis.profiles`), the API (:class:`~analysis.chain.Device`, the displays,
the profile record, the settings records) and the GUI (every typed field goes through those
records) all validate with the rules below, so a value is refused the same way, with the same
message naming the range, wherever it comes from.  A slider's range in the GUI is only a soft
display range: a value typed beyond it is accepted when it lies inside the physical range here.

Where the bounds come from
    The numerics are tested over an envelope: ``tests/test_stress.py`` draws devices with masses
    1e-4..1e3 kg (plus a 1e-6 kg handle on a 1e9 N/m element), element stiffnesses 1..1e9 N/m,
    damping ratios 1e-5..10 (eq. 28, so element dampings up to 2·10·sqrt(1e9·500) ≈ 1.4e7 N·s/m: bound 1e8,
    and lossless elements), ground dampings 0 and 1e-3..1e3 N·s/m, chains of 1..50 masses (and
    one of 500), frequencies from 1e-5 rad/s to just below Nyquist, T 1e-5..0.1 s;
    ``tests/strategies.py`` (the property tests) stays inside that envelope.  The bounds below
    are that envelope, rounded outwards to the decade where the envelope was open, except the
    sample period, whose range 1 µs .. 1 s is the physical one a haptic loop can have (issue 13)
    and a decade wider than the stress envelope on each side (``tests/test_limits.py`` runs the
    stress test's checks at both ends: no NaN, overflow or division by zero);
    the coupling and PD gains share the bounds of the device elements they act like (a virtual
    spring is no stiffer than the stiffest tested element, a virtual damper no more viscous than
    the most viscous one, a virtual mass within the tested masses).
Work limits
    Sizes that follow from the input are checked before anything is allocated:
    :data:`MAX_SIMULATION_STEPS` (``duration / T × substeps``), :data:`MAX_SIMULATION_VALUES`
    (the stored trace), :data:`MAX_MAP_POINTS` (the stability map's grid) and
    :data:`MAX_CHART_POINTS` (points of a design or limit chart).  Frequency grids are bounded by
    construction (a fixed base grid plus at most 40 resonances, :mod:`analysis.chain.grids`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

from analysis.checks import Real
from analysis.errors import ValidationError

__all__ = [
    "Limit",
    "LIMITS",
    "MASS",
    "STIFFNESS",
    "DAMPING",
    "GROUND_DAMPING",
    "DAMPING_RATIO",
    "SAMPLE_TIME",
    "BAND_MIN",
    "GAIN_STIFFNESS",
    "POSITIVE_DAMPING",
    "MAX_MASSES",
    "MAX_SIMULATION_STEPS",
    "MAX_SIMULATION_VALUES",
    "MAX_MAP_POINTS",
    "MAX_CHART_POINTS",
    "check_count",
    "check_simulation_size",
]


@dataclass(frozen=True)
class Limit:
    """The physical range ``[lo, hi]`` of one kind of input, in ``unit``.

    ``positive``: the value must be > 0 (a mass, a period) even where ``lo`` is 0.
    :attr:`text` is the allowed range shown in every refusal, e.g.
    ``"> 0 and finite, within the physical range [1e-06, 1000] (kg)"``.

    Calling a limit, ``LIMIT(name, value, index=None)``, validates one value and returns it as
    a float (a :class:`~analysis.errors.ValidationError` when it is outside).

    Parameters
    ----------
    lo : float
        Lower edge of the range, in ``unit``.
    hi : float
        Upper edge of the range, in ``unit`` (may be ``inf``).
    unit : str
        The unit shown in messages, e.g. ``"kg"``; ``""`` for a dimensionless value.
    positive : bool, optional
        Whether the value must be > 0 even where ``lo`` is 0 (default True).
    """

    lo: float
    hi: float
    unit: str
    positive: bool = True

    @cached_property
    def text(self) -> str:
        basic = "> 0 and finite" if self.positive else ">= 0 and finite"
        unit = f" ({self.unit})" if self.unit else ""
        return f"{basic}, within the physical range [{self.lo:g}, {self.hi:g}]{unit}"

    @cached_property
    def rule(self) -> Real:
        """The :class:`~analysis.checks.Real` rule (errors carry the float value)."""
        return Real(lo=self.lo, hi=self.hi, lo_open=self.positive and self.lo == 0.0, allowed=self.text,
                    not_real="a real number " + self.text, report_float=True)

    def __call__(self, name: str, value: object, index: int | None = None) -> float:
        return self.rule(name, value, index)

    def contains(self, value: float) -> bool:
        """True if ``value`` passes the rule.

        Parameters
        ----------
        value : float
            The value, in the limit's ``unit``.

        Returns
        -------
        bool
            Whether ``value`` lies in the physical range.
        """
        return self.rule.accepts(float(value))


#: Masses of the chain and virtual masses (kg).
MASS = Limit(1e-6, 1e3, "kg")
#: Element stiffnesses, coupling and PD stiffnesses (N/m).
STIFFNESS = Limit(1.0, 1e9, "N/m")
#: Element dampings, coupling and PD dampings (N·s/m); 0 = lossless.
DAMPING = Limit(0.0, 1e8, "N s/m", positive=False)
#: Dampings from a mass to ground (N·s/m).
GROUND_DAMPING = Limit(0.0, 1e3, "N s/m", positive=False)
#: Element damping ratios (eq. 28).
DAMPING_RATIO = Limit(0.0, 10.0, "", positive=False)
#: The sample period T (s).
SAMPLE_TIME = Limit(1e-6, 1.0, "s")
#: The lower edge of the analysis band (rad/s); the upper edge is Nyquist.
BAND_MIN = Limit(1e-5, math.inf, "rad/s")
#: Virtual-coupling and PD stiffness (N/m): 0 (off) up to the stiffest tested element.
GAIN_STIFFNESS = Limit(0.0, 1e9, "N/m", positive=False)
#: Virtual-coupling damping of the admittance display (N·s/m, > 0).
POSITIVE_DAMPING = Limit(0.0, 1e8, "N s/m")

#: Every limit by the name used in messages and profiles' fields.
LIMITS: dict[str, Limit] = {
    "masses": MASS,
    "stiffnesses": STIFFNESS,
    "dampings": DAMPING,
    "damping_ratios": DAMPING_RATIO,
    "ground_dampings": GROUND_DAMPING,
    "sample_time": SAMPLE_TIME,
    "kc": GAIN_STIFFNESS,
    "bc": DAMPING,
    "mc": MASS,
    "bc_adm": POSITIVE_DAMPING,
    "kp": GAIN_STIFFNESS,
    "kd": DAMPING,
}

#: The longest tested chain (tests/test_stress.py, "500-masses").
MAX_MASSES = 500
#: ``duration / T × substeps`` of one simulation (2 s at T = 1 µs with 2 substeps fits).
MAX_SIMULATION_STEPS = 5_000_000
#: Numbers stored by one simulation (samples × (2 n + 10)): about 512 MB of float64.
MAX_SIMULATION_VALUES = 64_000_000
#: Grid points of one stability map (400 × 400, the map panel's largest).
MAX_MAP_POINTS = 160_000
#: Points of one design or limit chart.
MAX_CHART_POINTS = 10_000


def check_count(name: str, count: int, limit: int, what: str = "") -> int:
    """``count`` if it is at most ``limit``, else a :class:`~analysis.errors.ValidationError`
    saying ``"at most <limit> <name> (what)"`` -- call before allocating ``count`` of anything.

    Parameters
    ----------
    name : str
        What is counted, as named in the message (e.g. ``"simulation steps"``).
    count : int
        The size asked for.
    limit : int
        The largest size allowed.
    what : str, optional
        How ``count`` follows from the input, added to the message in parentheses.

    Returns
    -------
    int
        ``count``, unchanged.

    Raises
    ------
    ValidationError
        When ``count > limit``.
    """
    if count > limit:
        raise ValidationError(name, f"at most {limit:g} {name}" + (f" ({what})" if what else ""), count)
    return count


def check_simulation_size(duration: float, sample_time: float, substeps: int = 1, masses: int = 1) -> int:
    """The number of samples of a simulation, after checking its steps and stored values.

    Steps are ``duration / T × substeps`` (at most :data:`MAX_SIMULATION_STEPS`); the trace holds
    ``(2 n + 10)`` numbers per sample (at most :data:`MAX_SIMULATION_VALUES`).

    Parameters
    ----------
    duration : float
        Simulated time [s].
    sample_time : float
        Sample period ``T`` [s].
    substeps : int, optional
        Integration steps per sample.
    masses : int, optional
        Number of masses ``n`` of the chain.

    Returns
    -------
    int
        The number of samples, ``round(duration / T) + 1``.

    Raises
    ------
    ValidationError
        When the steps or the stored values exceed their limits.
    """
    samples = int(round(duration / sample_time)) + 1
    check_count("simulation steps", samples * substeps, MAX_SIMULATION_STEPS,
                f"duration / T × substeps = {duration:g} s / {sample_time:g} s × {substeps}; "
                "shorten the duration or lengthen T")
    check_count("simulation values", samples * (2 * masses + 10), MAX_SIMULATION_VALUES,
                f"samples × (2 n + 10) for {masses} masses; shorten the duration")
    return samples
