"""The optional ``controller`` section (schema 5): the controller as built (issue 15).

It holds the controller's velocity estimate (:class:`~analysis.chain.velocity_filter.VelocityFilter`,
Chawda, Celik & O'Malley 2015), the B range of the Z-width region of Colgate & Brown (ICRA 1994)
and, optionally, the path of a CSV of hardware trials (columns ``b``, ``k``, ``stable``; read by
:func:`analysis.sampled.load_trials`)::

    "controller": {"velocity_filter": {"kind": "lowpass1", "cutoff": 188.5},
                   "b_range": {"min": 0.1, "max": 100.0, "points": 100},
                   "trials": "trials.csv", "encoder_resolution": 1e-5, "force_noise": 0.1}

Every key is optional (a missing ``velocity_filter`` is the backward difference, a missing
``b_range`` the default 0.1-100 N s/m at 100 points).  ``encoder_resolution`` (m, at the handle)
turns on the noise criterion of the region (:mod:`analysis.sampled.velocity_noise`: a wall
damping whose quantization force noise exceeds ``force_noise``, N rms, default 0.1, is not
renderable); ``force_noise`` needs ``encoder_resolution``.  Files without them load unchanged.  Errors are :class:`ProfileError` at the
JSON path, e.g. ``$.controller.velocity_filter.cutoff``.

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from analysis.chain.velocity_filter import BACKWARD, VelocityFilter
from analysis.errors import ValidationError
from analysis.profiles.errors import ProfileError
from analysis.sampled.velocity_noise import ENCODER_RESOLUTION, FORCE_NOISE

__all__ = ["ControllerSection", "DEFAULT_B_RANGE", "DEFAULT_B_POINTS", "parse_controller"]

#: The default B range of the Z-width region (N s/m) and its number of values.
DEFAULT_B_RANGE = (0.1, 100.0)
DEFAULT_B_POINTS = 100
_MAX_B_POINTS = 1000
_KEYS = ("velocity_filter", "b_range", "trials", "encoder_resolution", "force_noise")


@dataclass(frozen=True)
class ControllerSection:
    """The controller as built: velocity filter, the region's B range (N s/m) and a trials file.

    Parameters
    ----------
    velocity_filter : VelocityFilter, optional
        The controller's velocity estimate; default the backward difference.
    b_range : tuple of (float, float), optional
        ``(min, max)`` of the Z-width region's wall damping B [N s/m], ``0 < min < max``,
        finite; default :data:`DEFAULT_B_RANGE`.
    b_points : int, optional
        Number of B values of the region, 2 to 1000; default :data:`DEFAULT_B_POINTS`.
    trials : str or None, optional
        Path of a CSV of hardware trials (the command line and the app read a relative one
        from the profile's folder: :func:`analysis.study.resolve_trials`), or ``None``.
    encoder_resolution : float or None, optional
        Encoder resolution at the handle [m], 1e-9 to 1e-2; turns on the noise criterion of the
        region. ``None``: off.
    force_noise : float or None, optional
        The largest quantization force noise a renderable wall damping may cause [N rms], 1e-6
        to 1e3; ``None`` with a resolution is the default 0.1 N. Must be ``None`` without
        ``encoder_resolution``.

    Raises
    ------
    ValidationError
        When a field is outside its range (or ``force_noise`` is given without
        ``encoder_resolution``).
    """

    velocity_filter: VelocityFilter = field(default=BACKWARD)
    b_range: tuple[float, float] = DEFAULT_B_RANGE
    b_points: int = DEFAULT_B_POINTS
    trials: str | None = None
    encoder_resolution: float | None = None
    force_noise: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.velocity_filter, VelocityFilter):
            raise ValidationError("velocity_filter", "a VelocityFilter", self.velocity_filter)
        try:
            lo, hi = (float(x) for x in self.b_range)
        except (TypeError, ValueError):
            raise ValidationError("b_range", "two numbers (min, max) in N s/m", self.b_range) from None
        if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
            raise ValidationError("b_range", "0 < min < max, finite (N s/m)", self.b_range)
        object.__setattr__(self, "b_range", (lo, hi))
        n = self.b_points
        if isinstance(n, bool) or not isinstance(n, int) or not 2 <= n <= _MAX_B_POINTS:
            raise ValidationError("b_points", f"an integer from 2 to {_MAX_B_POINTS}", n)
        if self.trials is not None and (not isinstance(self.trials, str) or not self.trials.strip()):
            raise ValidationError("trials", "a non-empty path string or null", self.trials)
        if self.encoder_resolution is not None:
            object.__setattr__(self, "encoder_resolution",
                               ENCODER_RESOLUTION("encoder_resolution", self.encoder_resolution))
        if self.force_noise is not None:
            if self.encoder_resolution is None:
                raise ValidationError("force_noise", "null unless encoder_resolution is given", self.force_noise)
            object.__setattr__(self, "force_noise", FORCE_NOISE("force_noise", self.force_noise))

    def check(self, sample_time: float) -> None:
        """Check the velocity filter against a sample period.

        Parameters
        ----------
        sample_time : float
            The controller's sample period [s].

        Raises
        ------
        ValidationError
            Field ``cutoff``, when the filter's cut-off is above the Nyquist frequency
            ``pi / sample_time`` (or at it, for ``"butter2"``: :meth:`VelocityFilter.check`).
        """
        self.velocity_filter.check(sample_time)

    def replace(self, **changes: Any) -> ControllerSection:
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New values of fields, by name (``velocity_filter``, ``b_range``, ...).

        Returns
        -------
        ControllerSection
            The new section.
        """
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready section (``inf`` cut-off written as ``"inf"``).

        Returns
        -------
        dict of str to Any
            ``velocity_filter`` and ``b_range`` {``min``, ``max``, ``points``}, and ``trials``,
            ``encoder_resolution`` and ``force_noise`` where they are not ``None``.
        """
        out: dict[str, Any] = {
            "velocity_filter": self.velocity_filter.to_dict(),
            "b_range": {"min": self.b_range[0], "max": self.b_range[1], "points": self.b_points},
        }
        if self.trials is not None:
            out["trials"] = self.trials
        for key in ("encoder_resolution", "force_noise"):
            if getattr(self, key) is not None:
                out[key] = getattr(self, key)
        return out


def _b_range(value: object) -> tuple[tuple[float, float], int]:
    if not isinstance(value, Mapping):
        raise ProfileError.at("$.controller.b_range", "a JSON object with keys min, max, points", value)
    unknown = set(value) - {"min", "max", "points"}
    if unknown:
        raise ProfileError.at(f"$.controller.b_range.{sorted(map(str, unknown))[0]}", "no such key (min, max, points)",
                              None)
    out = []
    for key, default in (("min", DEFAULT_B_RANGE[0]), ("max", DEFAULT_B_RANGE[1])):
        x = value.get(key, default)
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x <= 0:
            raise ProfileError.at(f"$.controller.b_range.{key}", "a number > 0 and finite (N s/m)", x)
        out.append(float(x))
    if not out[0] < out[1]:
        raise ProfileError.at("$.controller.b_range.max", f"a number > min = {out[0]:g} (N s/m)", out[1])
    n = value.get("points", DEFAULT_B_POINTS)
    if isinstance(n, bool) or not isinstance(n, int) or not 2 <= n <= _MAX_B_POINTS:
        raise ProfileError.at("$.controller.b_range.points", f"an integer from 2 to {_MAX_B_POINTS}", n)
    return (out[0], out[1]), n


def parse_controller(data: object) -> ControllerSection:
    """The ``controller`` section of a (migrated) profile dict.

    Parameters
    ----------
    data : object
        The value of the profile's ``controller`` key (a JSON object).

    Returns
    -------
    ControllerSection
        The section, every missing key at its default.

    Raises
    ------
    ProfileError
        At the JSON path of the first bad or unknown key, e.g. ``$.controller.velocity_filter.cutoff``.
    """
    if not isinstance(data, Mapping):
        raise ProfileError.at("$.controller", "a JSON object with keys " + ", ".join(_KEYS), data)
    unknown = set(data) - set(_KEYS)
    if unknown:
        raise ProfileError.at(f"$.controller.{sorted(map(str, unknown))[0]}", "no such key (" + ", ".join(_KEYS) + ")",
                              None)
    vf = BACKWARD
    if "velocity_filter" in data:
        try:
            vf = VelocityFilter.from_dict(data["velocity_filter"])
        except ValidationError as err:
            where = "$.controller.velocity_filter"
            if err.field and err.field != VelocityFilter.record_name:
                where += f".{err.field}"
            raise ProfileError.at(where, err.allowed, err.value) from err
    b_range, points = _b_range(data.get("b_range", {}))
    trials = data.get("trials")
    if trials is not None and (not isinstance(trials, str) or not trials.strip()):
        raise ProfileError.at("$.controller.trials", "a non-empty path string or null", trials)
    noise = {}
    for key, rule in (("encoder_resolution", ENCODER_RESOLUTION), ("force_noise", FORCE_NOISE)):
        if data.get(key) is not None:
            try:
                noise[key] = rule(key, data[key])
            except ValidationError as err:
                raise ProfileError.at(f"$.controller.{key}", err.allowed, err.value) from err
    if "force_noise" in noise and "encoder_resolution" not in noise:
        raise ProfileError.at("$.controller.force_noise", "null unless encoder_resolution is given",
                              noise["force_noise"])
    return ControllerSection(velocity_filter=vf, b_range=b_range, b_points=points, trials=trials, **noise)
