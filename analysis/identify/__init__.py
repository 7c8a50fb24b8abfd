"""Identification: from measurements of your own device to a chain model with uncertainty, and
designs that hold for every model the data allow (issue 14).

Adams, Moreyra & Hannaford obtained the HBFD model from measurements and blame part of the gap
between eq. (9) and their experiment on uncertain damping: with b4 = 1.2 N s/m instead of 5,
eq. (9) predicts their experimental 50 kN/m (section VI).  This package closes that loop:

* measurements (:class:`Measurement`): FRF and time-series CSV (:func:`load_measurement`),
  Welch H1 estimation with coherence (:func:`estimate_frf`); quantities ``actuator``,
  ``handle``, ``gauge``, boundary ``free`` or ``clamped``, continuous or through the sampled
  controller (exact ZOH-sampled model with a delay), see :mod:`analysis.identify.model`;
* the chain fit (:func:`fit_chain`, :func:`order_selection`): weighted least squares on the
  complex log-response in log-parameters, automatic start from the measured resonances and
  antiresonances (Stieltjes / Lanczos inverse, :mod:`analysis.identify.start`), Jacobian
  covariance, 95 % intervals (Wald, or profile likelihood where the Wald interval is unreliable,
  :mod:`analysis.identify.profile`; referred to the chain without a handle when the data do not
  show the handle mode, :mod:`analysis.identify.hidden`), correlations and identifiability
  (:class:`ChainFit`);
* robust designs over a parameter box (:func:`robust_max_stiffness` for eq. 9,
  :func:`robust_feasible_damping` for eq. 21, :func:`robust_critical_stiffness` for the exact
  sampled-data limit), each naming its binding device.

Numpy and scipy only; results are frozen dataclasses, nothing draws.
"""

from __future__ import annotations

import numpy as np

from analysis.chain.device import Device
from analysis.identify.boxsearch import ParameterBox, SearchTrace, box_search, open_intervals, parameter_box
from analysis.identify.csvio import load_measurement, read_frf, read_timeseries
from analysis.identify.errors import FitCancelled, MeasurementError, ParameterKeyError
from analysis.identify.fit import fit_chain, order_selection
from analysis.identify.goodness import GOODNESS_THRESHOLD, Goodness, goodness_of_fit
from analysis.identify.hidden import MERGED_SHARE, HiddenHandle, handle_family, hidden_handle, merged_fit
from analysis.identify.measurement import (
    COHERENCE_THRESHOLD,
    POWER_FRACTION,
    BinSelection,
    Measurement,
    informative_bins,
    make_measurement,
)
from analysis.identify.model import (
    BOUNDARIES,
    MEASURED_QUANTITIES,
    QUANTITIES,
    continuous_response,
    response,
    sampled_response,
)
from analysis.identify.params import ChainParameters, device_value, device_with, parameter_keys, parameter_symbol
from analysis.identify.problem import FitProblem
from analysis.identify.profile import Profiler, profile_critical_value
from analysis.identify.results import ChainFit, OrderSelection, Parameter
from analysis.identify.robust import (
    RobustDamping,
    RobustStiffness,
    robust_critical_stiffness,
    robust_feasible_damping,
    robust_max_stiffness,
)
from analysis.identify.start import chain_from_spectrum, spectrum_from_chain
from analysis.identify.uncertainty import INTERVAL_MODES, profile_selection
from analysis.identify.welch import estimate_frf

__all__ = [
    "BOUNDARIES",
    "COHERENCE_THRESHOLD",
    "GOODNESS_THRESHOLD",
    "INTERVAL_MODES",
    "MEASURED_QUANTITIES",
    "MERGED_SHARE",
    "POWER_FRACTION",
    "QUANTITIES",  # deprecated alias of MEASURED_QUANTITIES (one release)
    "BinSelection",
    "ChainFit",
    "ChainParameters",
    "FitCancelled",
    "FitProblem",
    "Goodness",
    "HiddenHandle",
    "Measurement",
    "MeasurementError",
    "OrderSelection",
    "Parameter",
    "Profiler",
    "ParameterBox",
    "ParameterKeyError",
    "RobustDamping",
    "RobustStiffness",
    "SearchTrace",
    "box_search",
    "chain_from_spectrum",
    "continuous_response",
    "device_response",
    "device_value",
    "device_with",
    "estimate_frf",
    "fit_chain",
    "goodness_of_fit",
    "handle_family",
    "hidden_handle",
    "informative_bins",
    "load_measurement",
    "make_measurement",
    "merged_fit",
    "open_intervals",
    "order_selection",
    "parameter_box",
    "parameter_keys",
    "parameter_symbol",
    "profile_critical_value",
    "profile_selection",
    "read_frf",
    "read_timeseries",
    "response",
    "robust_critical_stiffness",
    "robust_feasible_damping",
    "robust_max_stiffness",
    "sampled_response",
    "spectrum_from_chain",
]


def device_response(device: Device, w: np.ndarray, quantity: str = "actuator", boundary: str = "free",
                    sample_time: float | None = None, delay_samples: int = 0) -> np.ndarray:
    """Model response of one :class:`~analysis.Device` at ``w`` (rad/s), shape (F,): continuous
    when ``sample_time`` is ``None``, else exact ZOH-sampled (:mod:`analysis.identify.model`);
    the gauge sits on ``device.sensor_element``.

    Parameters
    ----------
    device : Device
        The chain.
    w : numpy.ndarray
        Angular frequencies [rad/s], shape (F,).
    quantity : str, optional
        ``"actuator"`` (m/N), ``"handle"`` (m/N) or ``"gauge"`` (N/N).
    boundary : str, optional
        ``"free"`` or ``"clamped"`` (handle held).
    sample_time : float or None, optional
        Sample period [s] of a response through the sampled controller; ``None``: continuous.
    delay_samples : int, optional
        Output delay [samples] (sampled only).

    Returns
    -------
    numpy.ndarray
        Complex response in the quantity's unit, shape (F,).

    Raises
    ------
    ValidationError
        For an unknown quantity or boundary, a clamped handle or 1-mass chain, or a gauge
        without an element (a 1-mass chain).
    """
    return response(ChainParameters.from_device(device), w, quantity, boundary, device.sensor_element,
                    sample_time, delay_samples)[0]
