"""The measured and model responses of an identification, for the Bode plots of the Identify view
and the report (issue 14; the informative bins and the goodness of fit, issue 23).

* :func:`section_measurements`, :func:`fit_curves` -- a profile's embedded measurements and the
  profile device's response at their frequencies;
* :func:`bode_data` -- ``(measurement, model response)`` pairs joined into curves, with the
  informative bins (:class:`BodeData`; the others are drawn greyed, :data:`UNUSED_BINS_LABEL`);
* :func:`curves_goodness` -- the goodness-of-fit test of such pairs on their informative bins.

Numpy and scipy only; never imports Qt.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analysis.identify import COHERENCE_THRESHOLD, Goodness, Measurement, device_response, goodness_of_fit, make_measurement
from analysis.profiles import Profile
from analysis.profiles.identification import IdentificationSection

__all__ = ["BodeData", "UNUSED_BINS_LABEL", "bode_data", "curves_goodness", "fit_curves", "section_measurements"]


#: The legend entry of the bins a fit leaves out (:attr:`analysis.identify.Measurement.informative`),
#: drawn greyed in the Identify view and the report; the numbers are the analysis module's thresholds.
UNUSED_BINS_LABEL = f"not used (coherence < {COHERENCE_THRESHOLD:g} or low input)"


@dataclass(frozen=True, eq=False)
class BodeData:
    """Measured and model responses of several measurements, joined with a ``nan`` between them
    (one curve each for plotting): frequency (rad/s), magnitudes, phases (degrees, unwrapped per
    measurement), the residual ``|ln(model/measured)|`` and the coherence (``nan`` where none).

    Every array has the same shape (N,): the measurements' frequency points and one ``nan`` between
    two measurements.

    Attributes
    ----------
    w : numpy.ndarray
        Angular frequencies [rad/s].
    measured_mag : numpy.ndarray
        Measured magnitude (m/N for ``actuator``/``handle``, N/N for ``gauge``).
    model_mag : numpy.ndarray
        The model's magnitude, in the same unit.
    measured_phase : numpy.ndarray
        Measured phase [deg], unwrapped per measurement.
    model_phase : numpy.ndarray
        The model's phase [deg], on the measured branch.
    residual : numpy.ndarray
        ``|ln(model/measured)|``.
    coherence : numpy.ndarray
        Magnitude-squared coherence in [0, 1] (``nan`` where none).
    used : numpy.ndarray or None
        Bool: whether each point is an informative bin (:attr:`analysis.identify.Measurement.used`;
        ``False`` at the gaps); ``None``: every point.
    """

    w: np.ndarray
    measured_mag: np.ndarray
    model_mag: np.ndarray
    measured_phase: np.ndarray
    model_phase: np.ndarray
    residual: np.ndarray
    coherence: np.ndarray
    used: np.ndarray | None = None

    @property
    def has_coherence(self) -> bool:
        return bool(np.any(np.isfinite(self.coherence)))

    @property
    def has_unused(self) -> bool:
        """Whether some bin is not informative (drawn greyed)."""
        return self.used is not None and bool(np.any(~self.used & np.isfinite(self.w)))

    def where_used(self, values: np.ndarray, used: bool = True) -> np.ndarray:
        """``values`` at the informative bins (``used=False``: at the others), ``nan`` elsewhere.

        Parameters
        ----------
        values : numpy.ndarray
            One of the arrays, shape (N,).
        used : bool, optional
            Keep the informative bins (default) or the others.

        Returns
        -------
        numpy.ndarray
            A float copy, shape (N,).
        """
        mask = np.isfinite(self.w) if self.used is None else np.asarray(self.used, bool)
        return np.where(mask if used else ~mask & np.isfinite(self.w), np.asarray(values, float), np.nan)


def bode_data(pairs: Sequence[tuple[Measurement, np.ndarray]]) -> BodeData:
    """The :class:`BodeData` of ``(measurement, model response)`` pairs (see :func:`fit_curves`).

    Parameters
    ----------
    pairs : sequence of (Measurement, numpy.ndarray)
        Each measurement with the model's complex response at its frequencies, shape (F,).

    Returns
    -------
    BodeData
        The curves joined with a ``nan`` between measurements (empty arrays for no pair), with
        each measurement's informative bins.
    """
    parts: list[list[np.ndarray]] = [[] for _ in range(7)]
    used: list[np.ndarray] = []
    for i, (m, model) in enumerate(pairs):
        h, g = m.response, np.asarray(model, complex)
        ph_m = np.degrees(np.unwrap(np.angle(h)))
        with np.errstate(invalid="ignore", divide="ignore"):
            ph_g = ph_m + np.degrees(np.angle(g / h))  # the model's phase on the measured branch
            res = np.abs(np.log(g / h))
        coh = m.coherence if m.coherence is not None else np.full(m.size, np.nan)
        cols = (m.frequency, np.abs(h), np.abs(g), ph_m, ph_g, res, coh)
        for part, col in zip(parts, cols):
            if i:
                part.append(np.array([np.nan]))
            part.append(np.asarray(col, float))
        used += [np.zeros(1, bool)] if i else []
        used.append(m.used)
    arrays = [np.concatenate(p) if p else np.array([]) for p in parts]
    return BodeData(*arrays, used=np.concatenate(used) if used else np.array([], bool))


def section_measurements(section: IdentificationSection) -> list[Measurement]:
    """The embedded measurements as :class:`~analysis.identify.Measurement` objects.

    Parameters
    ----------
    section : IdentificationSection
        A profile's identification section.

    Returns
    -------
    list of Measurement
        Its measurements, in order, each with its coherence and input power where embedded, so
        that its informative bins are those the fit used.
    """
    return [make_measurement(m.frequency, m.response, m.quantity, m.boundary, m.sample_time, m.delay_samples,
                             m.coherence, m.source, m.input_power) for m in section.measurements]


def fit_curves(profile: Profile) -> list[tuple[Measurement, np.ndarray]]:
    """Each embedded measurement with the profile device's response at its frequencies.

    Parameters
    ----------
    profile : Profile
        The profile (its device and its identification section).

    Returns
    -------
    list of (Measurement, numpy.ndarray)
        Each measurement with the device's complex response at its frequencies, shape (F,)
        (``nan`` where the device does not fit the measurement); empty without an
        identification section.
    """
    if profile.identification is None:
        return []
    dev = profile.device
    out = []
    for m in section_measurements(profile.identification):
        try:
            model = device_response(dev, m.frequency, m.quantity, m.boundary, m.sample_time, m.delay_samples)
        except ValueError:  # the device does not fit this measurement (e.g. a gauge beyond the chain)
            model = np.full(m.frequency.shape, np.nan + 0j)
        out.append((m, model))
    return out


def curves_goodness(pairs: Sequence[tuple[Measurement, np.ndarray]], n_params: int) -> Goodness | None:
    """The goodness-of-fit test (:func:`analysis.identify.goodness_of_fit`) of a model against
    measurements, on their informative bins (:attr:`~analysis.identify.Measurement.used`), e.g. the
    profile's device against its embedded measurements (:func:`fit_curves`).

    Parameters
    ----------
    pairs : sequence of (Measurement, numpy.ndarray)
        Each measurement with the model's complex response at its frequencies, shape (F,).
    n_params : int
        Number of free parameters of the fit (the identification section's intervals).

    Returns
    -------
    Goodness or None
        The test, or ``None`` without measurements.
    """
    if not pairs:
        return None
    used = [(m.used, m, np.asarray(h, complex)) for m, h in pairs]
    return goodness_of_fit([m.informative_only() for _, m, _ in used], [h[u] for u, _, h in used], int(n_params))
