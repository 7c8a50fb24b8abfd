"""What the app, the CLI and the report compute for identification and robust designs (issue 14).

* :func:`identify_chain` -- fit the chain to measurements at the chosen order and, for the order table,
  every order ``1..max_masses`` (AIC, BIC, residual), with ``progress``/``cancelled`` hooks;
* :func:`profile_with_fit` -- the profile with the fitted device and an ``identification``
  section (the 95 % intervals of the free parameters and the embedded measurements);
* :func:`robust_designs` -- on a profile that has intervals: the robust largest k_c at the
  current b_c (eq. 9 for every device in the box) on the impedance display, or the robust
  feasible b_c interval for the current m_c (eq. 21) on the admittance display, each with its
  binding device, and whether the current coupling holds for the whole box
  (:attr:`RobustDesigns.holds`, :meth:`RobustDesigns.verdict`);
* :func:`section_measurements`, :func:`fit_curves`, :func:`bode_data`, :func:`curves_goodness` --
  the embedded measurements, the profile device's response at their frequencies, the Bode curves
  with the informative bins and the goodness of fit (their home is
  :mod:`analysis.study.identify_curves`; re-exported here).

Numpy and scipy only; never imports Qt.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np

from analysis.chain.device import Device
from analysis.identify import (
    ChainFit,
    Measurement,
    OrderSelection,
    RobustDamping,
    RobustStiffness,
    fit_chain,
    open_intervals,
    robust_feasible_damping,
    robust_max_stiffness,
)
from analysis.profiles import Profile
from analysis.profiles.identification import IdentificationSection, MeasurementData
from analysis.profiles.schema import drop_per_mass
from analysis.progress import Cancelled, Progress, check_cancelled, none_if_cancelled, report_progress
from analysis.study.design_limits import BeyondLimit, design_beyond_limits
from analysis.study.displays import display_kind
from analysis.study.identify_curves import (  # the Bode curves (re-exported: their home until issue 23)
    UNUSED_BINS_LABEL,
    BodeData,
    bode_data,
    curves_goodness,
    fit_curves,
    section_measurements,
)
from analysis.study.measurement_files import MeasurementSpec, read_measurement_files
from analysis.study.quantities import format_number

__all__ = ["BodeData", "UNUSED_BINS_LABEL", "bins_summary", "curves_goodness", "IdentifyResult", "RobustDesigns", "bode_data", "fit_curves", "fit_notes", "identify_chain", "load_measurements", "parameter_rows",
           "parse_fixed", "profile_with_fit", "robust_designs", "section_measurements", "RobustRequest",
           "MAX_MASSES", "FIT_SECONDS", "fit_time_estimate"]


@dataclass(frozen=True, eq=False)
class IdentifyResult:
    """The fit at the chosen order and the order-selection table (``orders`` may be ``None``).

    Attributes
    ----------
    fit : ChainFit
        The fit at the chosen number of masses.
    orders : OrderSelection or None
        AIC, BIC and residual of every order ``1..max_masses``; ``None`` when no table was asked
        for.
    measurements : tuple of Measurement
        The measurements fitted.
    """

    fit: ChainFit
    orders: OrderSelection | None
    measurements: tuple[Measurement, ...]


#: The largest ``--masses`` of ``zwidth identify``: the largest order whose fit takes under a minute
#: of CPU time on the reference machine (issue 23; measured 2026-12-03, 2 shared cores, a random
#: chain with actuator + gauge FRFs at 0.5 % noise, 400 points each): 6 masses took 17 s, 7 masses
#: 69 s (and missed the truth: a local optimum).  ``--masses 600`` grew to 22 GB before this check.
MAX_MASSES = 6
#: CPU seconds of one fit by order on that case (800 complex points), for :func:`fit_time_estimate`
FIT_SECONDS = {1: 0.05, 2: 0.05, 3: 0.2, 4: 0.5, 5: 0.8, 6: 17.0}
_REFERENCE_POINTS = 800


def fit_time_estimate(n_masses: int, points: int = _REFERENCE_POINTS, orders: bool = False) -> float:
    """About how many CPU seconds a fit of ``n_masses`` takes (:data:`FIT_SECONDS`, in proportion to
    the measured points; ``orders``: the order table's fits ``1..n_masses`` too).

    Parameters
    ----------
    n_masses : int
        Number of masses, ``1..MAX_MASSES``.
    points : int, optional
        Measured frequency points of all measurements together.
    orders : bool, optional
        Whether the orders ``1..n_masses`` are fitted too (their fits use Wald intervals only,
        counted at the same cost: an upper estimate).

    Returns
    -------
    float
        Estimated CPU time [s] on the reference machine (a loaded machine takes longer; the
        actuator FRF alone at realistic noise takes up to 70 times longer, issue 14).
    """
    n = min(max(int(n_masses), 1), MAX_MASSES)
    seconds = sum(FIT_SECONDS[k] for k in range(1, n + 1)) if orders else FIT_SECONDS[n]
    return seconds * max(int(points), 1) / _REFERENCE_POINTS


def load_measurements(paths: Sequence[str | os.PathLike | MeasurementSpec], quantity: str = "actuator",
                      boundary: str = "free", sample_time: float | None = None, delay_samples: int = 0, *,
                      step_as_sample_time: bool = False) -> list[Measurement]:
    """:func:`analysis.identify.load_measurement` of each file (MeasurementError names file/row/column).

    Parameters
    ----------
    paths : sequence of str, os.PathLike or MeasurementSpec
        The measurement files (frequency-response or time-series CSV files); a
        :class:`~analysis.study.measurement_files.MeasurementSpec` carries its own quantity and
        boundary (``zwidth identify g.csv:gauge``).
    quantity : str, optional
        What was measured: ``"actuator"``, ``"handle"`` or ``"gauge"`` (the default for files
        that do not name their own).
    boundary : str, optional
        How the handle was held, ``"free"`` or ``"clamped"`` (the default likewise).
    sample_time : float or None, optional
        Controller sample period [s], or ``None`` for a continuous-time measurement.
    delay_samples : int, optional
        Computation delay in samples (sampled measurements only).
    step_as_sample_time : bool, optional
        With ``sample_time`` ``None``, a time series is sampled at its own time step (the command
        line's default); ``False`` (the default here) reads it as continuous-time.

    Returns
    -------
    list of Measurement
        One measurement per file, in the order of ``paths``.

    Raises
    ------
    MeasurementError
        When a file cannot be read or its data are unusable (it names the file, row and column).
    """
    return [r.measurement for r in read_measurement_files(paths, quantity, boundary, sample_time, delay_samples,
                                                          step_as_sample_time=step_as_sample_time)]


def parse_fixed(items: Sequence[str]) -> dict[str, float]:
    """``["masses[0]=0.2", ...]`` -> ``{"masses[0]": 0.2}`` (ValueError names the bad item).

    Parameters
    ----------
    items : sequence of str
        ``KEY=VALUE`` items (the CLI's ``--fix`` arguments), with parameter keys such as
        ``"masses[0]"`` and values in SI units.

    Returns
    -------
    dict of str to float
        Parameter key -> fixed value.

    Raises
    ------
    ValueError
        When an item is not ``KEY=VALUE`` with a finite value, > 0 for masses and stiffnesses and
        >= 0 for dampings and ground dampings (the message names it).
    """
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        # the rule of analysis.identify.fit_chain: masses and stiffnesses > 0, dampings >= 0
        positive = key.partition("[")[0].strip() in ("masses", "stiffnesses")
        if not sep or not key.strip() or not (math.isfinite(number) and (number > 0 if positive else number >= 0)):
            raise ValueError(f"--fix {item!r}: expected KEY=VALUE with a value > 0 (>= 0 for dampings and "
                             "ground_dampings), e.g. masses[0]=0.2")
        out[key.strip()] = number
    return out


def _ground(ground_dampings: Sequence[int] | None, n: int) -> tuple[int, ...] | None:
    if ground_dampings is None:
        return None
    kept = tuple(g for g in ground_dampings if 0 <= g < n)
    return kept or None


def _fit_or_error(measurements: Sequence[Measurement], n: int, fixed: Mapping[str, float],
                  ground: Sequence[int] | None, kwargs: Mapping) -> tuple[ChainFit | None, str | None]:
    try:
        return fit_chain(measurements, n, _ground(ground, n), dict(fixed), **kwargs), None
    except ValueError as exc:
        return None, str(exc)


@none_if_cancelled
def identify_chain(measurements: Sequence[Measurement], n_masses: int, fixed: Mapping[str, float] | None = None,
             ground_dampings: Sequence[int] | None = None, *, max_masses: int | None = None,
             progress: Progress | None = None, cancelled: Cancelled | None = None,
             **fit_kwargs) -> IdentifyResult | None:
    """Fit ``n_masses`` (raises ValueError for unusable input) and, when ``max_masses`` is given,
    the orders ``1..max_masses`` for the order table; ``None`` when cancelled (``cancelled()`` is
    asked before every model evaluation of every fit, so Cancel stops a long fit at once).

    Fixed keys outside a smaller chain make that order an error row (``nan``), as in
    :func:`analysis.identify.order_selection`.

    Parameters
    ----------
    measurements : sequence of Measurement
        The measurements, fitted together.
    n_masses : int
        Number of masses of the chosen order.
    fixed : mapping of str to float or None, optional
        Known parameter values by key, e.g. ``{"masses[0]": 0.2}`` (:func:`parse_fixed`).
    ground_dampings : sequence of int or None, optional
        The masses with a damper to ground (default: the last, the actuator).
    max_masses : int or None, optional
        Fit every order ``1..max_masses`` too, for the order table; ``None`` for no table.
    progress, cancelled : callable or None, optional
        ``progress(done, total)`` is called after each fit; once ``cancelled()`` returns true the
        fit stops and ``None`` is returned.
    **fit_kwargs
        Further keywords of :func:`analysis.identify.fit_chain` (``sample_time``, ``seed`` ...).

    Returns
    -------
    IdentifyResult or None
        The fit and the order table, or ``None`` when cancelled.

    Raises
    ------
    ValueError
        When the chosen order cannot be fitted to the measurements (unusable input)."""
    fixed = dict(fixed or {})
    orders = list(range(1, int(max_masses) + 1)) if max_masses else []
    total = 1 + len([n for n in orders if n != n_masses])
    fit_kwargs = {**fit_kwargs, "cancelled": cancelled}
    fit = fit_chain(measurements, int(n_masses), ground_dampings, fixed, **fit_kwargs)
    report_progress(progress, 1, total)
    rows: list[tuple[ChainFit | None, str | None]] = []
    for n in orders:
        check_cancelled(cancelled)
        rows.append((fit, None) if n == n_masses else _fit_or_error(measurements, n, fixed, ground_dampings,
                                                                     fit_kwargs))
        if n != n_masses:
            report_progress(progress, 1 + len(rows), total)
    table = _order_table(orders, rows) if orders else None
    return IdentifyResult(fit, table, tuple(measurements))


def _order_table(orders: list[int], rows: list[tuple[ChainFit | None, str | None]]) -> OrderSelection:
    nan = math.nan
    aic = np.array([f.aic if f else nan for f, _ in rows])
    bic = np.array([f.bic if f else nan for f, _ in rows])
    res = np.array([f.residual if f else nan for f, _ in rows])
    best = int(orders[int(np.nanargmin(bic))]) if np.any(np.isfinite(bic)) else None
    return OrderSelection(n=np.array(orders), aic=aic, bic=bic, residual=res, fits=tuple(f for f, _ in rows),
                          errors=tuple(e for _, e in rows), best_bic=best)


def parameter_rows(fit: ChainFit) -> list[dict]:
    """The parameter table as plain rows.

    Each row holds key, value, std_error, low, high, fixed, identifiable, method (how the
    interval was found: wald, profile, unbounded ..., fixed; numbers as floats) plus ``text``
    (the same numbers printed by :func:`format_number`).

    Parameters
    ----------
    fit : ChainFit
        The fit.

    Returns
    -------
    list of dict
        One row per parameter of the fit, values in SI units.
    """
    out = []
    for p in fit.parameters:
        text = {name: format_number(getattr(p, name)) for name in ("value", "std_error", "low", "high")}
        out.append({"key": p.key, "value": p.value, "std_error": p.std_error, "low": p.low, "high": p.high,
                    "fixed": p.fixed, "identifiable": p.identifiable, "method": p.method, "text": text})
    return out


def _data(m: Measurement) -> MeasurementData:
    return MeasurementData(frequency=m.frequency, response=m.response, quantity=m.quantity, boundary=m.boundary,
                           sample_time=m.sample_time, delay_samples=m.delay_samples, coherence=m.coherence,
                           source=None if m.source is None else os.path.basename(m.source),
                           input_power=m.input_power)


def profile_with_fit(profile: Profile, fit: ChainFit, measurements: Sequence[Measurement] | None = None,
                     name: str | None = None) -> Profile:
    """``profile`` with the fitted device (its band kept), the identification section and notes
    written for the fit.

    The section holds the 95 % intervals of the free parameters, the measurements embedded and
    the fit's warnings.  The notes (:func:`fit_notes`) say what was fitted; the base's notes,
    which describe its own device, are not kept.  Every list indexed by mass
    (:data:`analysis.profiles.schema.PER_MASS_LISTS`, the simulator's friction) that does not
    hold one value per fitted mass is dropped (:func:`analysis.profiles.schema.drop_per_mass`),
    and the notes say so, so the profile written loads and runs in every command.

    Parameters
    ----------
    profile : Profile
        The profile to update (the base: display, couplings, gains and sections).
    fit : ChainFit
        The fit.
    measurements : sequence of Measurement or None, optional
        The measurements to embed; ``None`` embeds the fit's own.
    name : str or None, optional
        A new profile name; ``None`` keeps the profile's.

    Returns
    -------
    Profile
        The updated profile (a new record; ``profile`` is unchanged).
    """
    used = tuple(measurements or fit.measurements)
    free = {k: iv for k, iv, fixed in zip(fit.keys, fit.intervals.values(), fit.fixed) if not fixed}
    section = IdentificationSection(free, tuple(_data(m) for m in used), tuple(fit.warnings))
    changes, dropped = drop_per_mass(profile, fit.device.n)
    notes = fit_notes(fit, used, profile.name, profile.device.n, dropped)
    return profile.replace(device=fit.device, identification=section, notes=notes, **changes,
                           **({} if name is None else {"name": name}))


def _plural(count: int, word: str) -> str:
    return f"{count} {word}{'' if count == 1 else 'es' if word.endswith('s') else 's'}"


def _values(values: Sequence[float]) -> str:
    return ", ".join(format_number(float(v)) for v in values)


def _measured(m: Measurement) -> str:
    timing = "continuous-time" if m.sample_time is None else f"sampled at T = {format_number(m.sample_time)} s"
    source = "" if m.source is None else f"{os.path.basename(m.source)}: "
    return f"{source}{m.quantity} response, {m.boundary} handle, {_plural(m.size, 'point')}, {timing}"


def bins_summary(fit: ChainFit) -> str:
    """:attr:`ChainFit.bins_summary <analysis.identify.ChainFit.bins_summary>` with each file's name
    rather than its path: the bins of each measurement fitted, and why the others were left out.

    Parameters
    ----------
    fit : ChainFit
        The fit.

    Returns
    -------
    str
        One line, e.g. ``"a.csv: 1221 of 2047 bins used (by coherence and input power); left out: 826
        with input power below 0.0001 of its peak"``; empty without bins.
    """
    return "; ".join(replace(b, source=None if b.source is None else os.path.basename(b.source)).summary
                     for b in fit.bins)


def fit_notes(fit: ChainFit, measurements: Sequence[Measurement], base: str, base_masses: int,
              dropped: Mapping[str, Sequence[float]] | None = None) -> str:
    """The profile notes of an identified device: what was fitted, to what, and what the base gave.

    Parameters
    ----------
    fit : ChainFit
        The fit.
    measurements : sequence of Measurement
        The measurements fitted.
    base : str
        The name of the base profile (its display, couplings, gains and sections are kept).
    base_masses : int
        The base device's number of masses.
    dropped : mapping of str to sequence of float or None, optional
        The base's per-mass lists dropped (JSON path -> values), see
        :func:`analysis.profiles.schema.drop_per_mass`.

    Returns
    -------
    str
        One paragraph, free of dates, e.g. ``"Identified by zwidth: a chain of 3 masses fitted to
        1 measurement (a.csv: actuator response, free handle, 300 points, sampled at T = 0.001 s).
        ..."``.
    """
    d = fit.device
    fixed = ", ".join(f"{p.key} = {format_number(p.value)}" for p in fit.parameters if p.fixed)
    parts = [f"Identified by zwidth: a chain of {_plural(d.n, 'mass')} fitted to "
             f"{_plural(len(measurements), 'measurement')} ({'; '.join(_measured(m) for m in measurements)}).",
             f"Masses {_values(d.masses)} kg"
             + (f"; stiffnesses {_values(d.stiffnesses)} N/m; element dampings {_values(d.dampings)} N·s/m"
                if d.n > 1 else "")
             + f"; dampings to ground {_values(d.ground_dampings)} N·s/m"
             + (f" ({fixed} fixed, not fitted)." if fixed else "."),
             f"Residual {format_number(fit.residual, 3)} (RMS of the weighted log-response)"
             + ("." if fit.converged else "; the fit did NOT converge."),
             f"The display, couplings, gains and other settings are those of the base profile \"{base}\" "
             f"(a chain of {_plural(base_masses, 'mass')})."]
    for path, values in (dropped or {}).items():
        parts.append(f"The base's {path} ({_values(values)}: one value per mass of its chain) was dropped, "
                     f"since the fitted chain has {_plural(d.n, 'mass')}; set it again for this device.")
    if fit.bins:
        parts.append(f"Bins: {bins_summary(fit)}.")
    goodness = fit.goodness
    if goodness is not None and goodness.passed:  # a failed test is the first warning
        parts.append(f"Goodness of fit: {goodness.message}.")
    parts += [f"Warning: {w}" for w in fit.warnings]
    return " ".join(parts)


@dataclass(frozen=True, eq=False)
class RobustDesigns:
    """Robust designs for the profile's display over its parameter box.

    ``stiffness`` (impedance: eq. 9 at the current b_c) or ``damping`` (admittance: eq. 21 for
    the current m_c) is set; ``holds`` says whether the current coupling is stable for every
    device in the box, ``coupling`` is the current (k_c or b_c) value checked.  ``unbounded``
    names the intervals the data do not bound (a fit's ``(0, inf)``): then there is no box to
    design over, neither design is set and ``holds`` is False.

    Attributes
    ----------
    impedance : bool
        ``True`` for the impedance display, ``False`` for the admittance display.
    intervals : dict
        The parameter box: parameter key -> ``(low, high)`` in SI units.
    stiffness : RobustStiffness or None
        Impedance: the robust largest k_c [N/m] at the current b_c (eq. 9) and its binding
        device.
    damping : RobustDamping or None
        Admittance: the robust feasible b_c interval [N·s/m] for the current m_c (eq. 21) and its
        binding devices.
    coupling : float
        The current coupling gain checked: k_c [N/m] or b_c [N·s/m].
    holds : bool
        Whether the current coupling is stable for every device in the box.
    unbounded : tuple of str
        The parameter keys whose intervals the data do not bound.
    """

    impedance: bool
    intervals: dict
    stiffness: RobustStiffness | None
    damping: RobustDamping | None
    coupling: float
    holds: bool
    unbounded: tuple[str, ...] = ()

    @property
    def beyond_limits(self) -> dict[str, BeyondLimit]:
        """The robust design values outside the physical range of the field they would set:
        ``"kc_max"`` (the robust largest k_c) or ``"bc_low"``/``"bc_high"`` (the robust b_c
        interval's edges) -> the crossing (:mod:`analysis.study.design_limits`)."""
        if self.stiffness is not None:
            return design_beyond_limits({"kc_max": self.stiffness.kc})
        if self.damping is not None:
            return design_beyond_limits({"bc_low": self.damping.low, "bc_high": self.damping.high})
        return {}

    def _value(self, key: str, value: float | None) -> str:
        beyond = self.beyond_limits.get(key)
        return format_number(value) if beyond is None else beyond.text()

    def verdict(self) -> str:
        """One line for the verdict: whether the current coupling holds for the whole box.

        Returns
        -------
        str
            The verdict with the robust limit, or why there is no robust design.
        """
        if self.unbounded:
            return (f"no robust design: the measurements do not bound {', '.join(self.unbounded)} "
                    f"(type intervals for them, or add the measurement the fit suggests)")
        n = len(self.intervals)
        box = f"the whole box ({n} parameter interval{'s' if n != 1 else ''})"
        if self.impedance:
            kc = self.stiffness.kc if self.stiffness else None
            limit = ("no k_c" if kc is None else f"k_c {self._value('kc_max', kc)}" if "kc_max" in self.beyond_limits
                     else f"k_c ≤ {format_number(kc)} N/m")
            word = "holds" if self.holds else "does NOT hold"
            return f"k_c = {format_number(self.coupling)} N/m {word} for {box}: robust {limit}"
        lo, hi = (self.damping.low, self.damping.high) if self.damping else (None, None)
        limit = ("no b_c" if lo is None else f"b_c in [{format_number(lo)}, {format_number(hi)}] N·s/m"
                 if not self.beyond_limits else f"b_c in [{self._value('bc_low', lo)}, {self._value('bc_high', hi)}]")
        word = "holds" if self.holds else "does NOT hold"
        return f"b_c = {format_number(self.coupling)} N·s/m {word} for {box}: robust {limit}"


@dataclass(frozen=True)
class RobustRequest:
    """What the robust design depends on: the display, the device, the identification intervals
    (not the embedded measurements), the design point (impedance: ``(b_c,)``; admittance:
    ``(m_c, k_p, k_d)``) and the coupling gain checked against the box (k_c or b_c).

    Attributes
    ----------
    display : str
        The display type: ``"impedance"`` or ``"admittance"``.
    device : Device
        The profile's device chain.
    intervals : tuple of (str, (float, float))
        The identification intervals: parameter key and ``(low, high)`` in SI units; empty
        without an identification section.
    design : tuple of float
        The design point: ``(b_c [N·s/m],)`` or ``(m_c [kg], k_p [N/m], k_d [N·s/m])``.
    coupling : float
        The coupling gain checked against the box: k_c [N/m] or b_c [N·s/m].
    """

    display: str
    device: Device
    intervals: tuple[tuple[str, tuple[float, float]], ...]
    design: tuple[float, ...]
    coupling: float

    @classmethod
    def of(cls, profile: Profile) -> RobustRequest:
        """The request of ``profile``'s display, device, intervals and coupling.

        Parameters
        ----------
        profile : Profile
            The device profile.

        Returns
        -------
        RobustRequest
            The request.
        """
        kind = display_kind(profile)
        sec = profile.identification
        intervals = () if sec is None else tuple((k, (float(lo), float(hi))) for k, (lo, hi) in sec.intervals.items())
        if kind.is_impedance:
            return cls(kind.name, profile.device, intervals, (float(profile.bc),), float(profile.kc))
        return cls(kind.name, profile.device, intervals, (float(profile.mc), float(profile.kp), float(profile.kd)),
                   float(profile.bc_adm))


@none_if_cancelled
def robust_designs(request: RobustRequest | Profile, *, seed: int = 0, progress: Progress | None = None,
                   cancelled: Cancelled | None = None) -> RobustDesigns | None:
    """The robust design of the display over the identification intervals.

    Parameters
    ----------
    request : RobustRequest or Profile
        The request, or a profile.
    seed : int, optional
        Seed of the search over the box.
    progress : callable or None, optional
        Called as ``progress(done, total)`` while it runs.
    cancelled : callable or None, optional
        Polled as ``cancelled() -> bool``; once true the computation stops and returns ``None``.

    Returns
    -------
    RobustDesigns or None
        The robust design, or ``None`` without intervals or when cancelled before the search.
    """
    req = RobustRequest.of(request) if isinstance(request, Profile) else request
    if not req.intervals:
        return None
    check_cancelled(cancelled)
    intervals = dict(req.intervals)
    impedance = display_kind(req.display).is_impedance
    loose = open_intervals(intervals, req.device.n)
    if loose:
        return RobustDesigns(impedance, intervals, None, None, req.coupling, False, loose)
    if impedance:
        rs = robust_max_stiffness(req.device, req.design[0], intervals, seed=seed)
        out = RobustDesigns(True, intervals, rs, None, req.coupling, rs.kc is not None and req.coupling <= rs.kc)
    else:
        rd = robust_feasible_damping(req.device, *req.design, intervals, seed=seed)
        ok = rd.low is not None and rd.low <= req.coupling <= rd.high
        out = RobustDesigns(False, intervals, None, rd, req.coupling, ok)
    report_progress(progress, 1, 1)
    return out
