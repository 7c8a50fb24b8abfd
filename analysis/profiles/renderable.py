"""The optional ``renderable`` section (schema 6, issue 24): the rendered environment and the qualities.

The impedance display renders ``F = M a^ + B v^ + K x`` (:mod:`analysis.sampled.rendered`); the
renderable (M, B, K) space and the M-width of Colonnese & Chan (IEEE Haptics Symposium 2016) and
Colonnese & Okamura (RSS 2012) are computed with the qualities of :mod:`analysis.sampled.qualities`
over an (M, B) grid.  The section holds all of it::

    "renderable": {
      "environment": {"mass": -0.05, "damping": 2.0, "stiffness": 500.0},
      "acceleration": {"kind": "second_difference", "lowpass": "butter2", "cutoff": 300.0},
      "qualities": {"names": ["stable", "passive"], "grasps": "hands_off",
                    "band": {"min": 3.1416, "max": 31.416}, "tolerance": 0.1,
                    "encoder_resolution": 1e-5, "force_noise": 0.1},
      "grid": {"mass": {"min": -1.0, "max": 1.0, "points": 41},
               "damping": {"min": -10.0, "max": 100.0, "points": 41}}}

Every key is optional (its default is :class:`RenderableSection`'s).  Each key is declared once, with
its rule (type, range, unit), in :data:`analysis.profiles.schema.RENDERABLE`; :func:`parse_renderable`
reads by those declarations, so an error names the JSON path (``$.renderable.grid.mass.points``),
and :class:`RenderableSection` validates with the same rules, under the API names the schema maps
back to those paths.  The damping grid is uniform on the signed-log axis
``u(B) = sign(B) log10(1 + |B|/(1 N s/m))`` of the space's volume (:mod:`analysis.sampled.renderable`).

Numerics only: this module never imports Qt.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from analysis.errors import ValidationError
from analysis.profiles.declared import declared_tree, declared_value, read_declared
from analysis.profiles.errors import ProfileError
from analysis.profiles.schema import FIELDS_BY_NAME, RENDERABLE
from analysis.sampled.rendered import AccelerationEstimate, RenderedEnvironment
from analysis.sampled.velocity_noise import DEFAULT_FORCE_NOISE

__all__ = ["RenderableSection", "parse_renderable", "RENDERABLE_NAMES"]

#: The API names of the section's values (its record's fields), in the schema's order.
RENDERABLE_NAMES: tuple[str, ...] = tuple(
    name for name, (path, _) in FIELDS_BY_NAME.items() if path.startswith("$.renderable.")
)


@dataclass(frozen=True)
class RenderableSection:
    """The rendered environment, its acceleration estimate, the qualities and the (M, B) grid.

    Parameters
    ----------
    virtual_mass, virtual_damping, virtual_stiffness : float, optional
        The rendered ``M`` [kg] (either sign), ``B`` [N s/m] (either sign) and ``K`` [N/m] (>= 0).
    acceleration_kind, acceleration_lowpass : str, optional
        The acceleration estimate (:data:`analysis.sampled.ACCELERATION_KINDS`) and its low-pass
        (:data:`analysis.sampled.LOWPASS_KINDS`).
    acceleration_cutoff : float, optional
        The low-pass cut-off [rad/s]; ``inf`` without one.
    qualities : tuple of str, optional
        The qualities asked (:data:`analysis.sampled.QUALITIES`), default ``("stable",)``.
    grasps : str, optional
        The grasp set of ``"stable"`` (:data:`analysis.profiles.schema.GRASP_SETS`).
    band_low, band_high : float, optional
        The band ``[w1, w2]`` [rad/s] of ``"accurate"`` (default 0.5 to 5 Hz).
    tolerance : float, optional
        The relative tolerance ``eps`` of ``"accurate"``.
    quiet_resolution : float or None, optional
        The encoder resolution [m] of ``"quiet"`` (needed by it).
    quiet_force_noise : float, optional
        The force-noise limit [N rms] of ``"quiet"``.
    mass_min, mass_max : float, optional
        The grid's virtual masses [kg], linear, ``min < max``.
    mass_points : int, optional
        Number of masses, 2 to :data:`~analysis.profiles.schema.MAX_GRID_POINTS`.
    damping_min, damping_max : float, optional
        The grid's virtual dampings [N s/m], uniform on the signed-log axis, ``min < max``.
    damping_points : int, optional
        Number of dampings, 2 to :data:`~analysis.profiles.schema.MAX_GRID_POINTS`.

    Raises
    ------
    ValidationError
        Naming the field (its JSON path: :func:`analysis.profiles.path_of`) when a value is out of
        range, the ranges are not increasing, or a low-pass has no finite cut-off.
    """

    virtual_mass: float = 0.0
    virtual_damping: float = 0.0
    virtual_stiffness: float = 0.0
    acceleration_kind: str = "second_difference"
    acceleration_lowpass: str = "none"
    acceleration_cutoff: float = math.inf
    qualities: tuple[str, ...] = ("stable",)
    grasps: str = "hands_off"
    band_low: float = math.pi
    band_high: float = 10.0 * math.pi
    tolerance: float = 0.1
    quiet_resolution: float | None = None
    quiet_force_noise: float = DEFAULT_FORCE_NOISE
    mass_min: float = -1.0
    mass_max: float = 1.0
    mass_points: int = 41
    damping_min: float = -10.0
    damping_max: float = 100.0
    damping_points: int = 41

    def __post_init__(self) -> None:
        for name in RENDERABLE_NAMES:
            value = getattr(self, name)
            if value is not None or name != "quiet_resolution":
                object.__setattr__(self, name, declared_value(name, value))
        for lo, hi, unit in (("band_low", "band_high", "rad/s"), ("mass_min", "mass_max", "kg"),
                             ("damping_min", "damping_max", "N s/m")):
            if not getattr(self, lo) < getattr(self, hi) and not (lo == "band_low" and self.band_low == self.band_high):
                raise ValidationError(hi, f"above {lo.split('_')[0]} min = {getattr(self, lo):g} ({unit})",
                                      getattr(self, hi))
        if self.acceleration_lowpass != "none" and not math.isfinite(self.acceleration_cutoff):
            raise ValidationError("acceleration_cutoff", f"> 0 and finite (rad/s) for a {self.acceleration_lowpass} "
                                  "low-pass", self.acceleration_cutoff)
        if "quiet" in self.qualities and self.quiet_resolution is None:
            raise ValidationError("quiet_resolution", "an encoder resolution (m) for the quiet quality", None)

    @property
    def environment(self) -> RenderedEnvironment:
        """The rendered ``(M, B, K)``."""
        return RenderedEnvironment(self.virtual_mass, self.virtual_damping, self.virtual_stiffness)

    @property
    def acceleration(self) -> AccelerationEstimate:
        """The acceleration estimate."""
        return AccelerationEstimate(self.acceleration_kind, self.acceleration_lowpass, self.acceleration_cutoff)

    def check(self, sample_time: float) -> None:
        """Check the band (with ``"accurate"``) and the low-pass cut-off against Nyquist ``pi/T``.

        Parameters
        ----------
        sample_time : float
            The controller's sample period [s].

        Raises
        ------
        ValidationError
            ``band_high`` or ``acceleration_cutoff``, at or above Nyquist.
        """
        nyquist = math.pi / sample_time
        if "accurate" in self.qualities and not self.band_high < nyquist:
            raise ValidationError("band_high", f"below Nyquist pi/T = {nyquist:.6g} (rad/s)", self.band_high)
        if self.acceleration_lowpass != "none":
            try:
                self.acceleration.lowpass_filter.check(sample_time)
            except ValidationError as err:
                raise ValidationError("acceleration_cutoff", err.allowed, self.acceleration_cutoff) from err

    def replace(self, **changes: Any) -> RenderableSection:
        """A copy with some fields changed, validated again.

        Parameters
        ----------
        **changes
            New values of fields, by name (``virtual_mass``, ``qualities``, ...).

        Returns
        -------
        RenderableSection
            The new section.
        """
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready section, every key written (``inf`` as ``"inf"``; no resolution: ``null``).

        Returns
        -------
        dict of str to Any
            The tree of :data:`analysis.profiles.schema.RENDERABLE`.
        """
        return declared_tree(RENDERABLE, self)


def parse_renderable(data: object) -> RenderableSection:
    """The ``renderable`` section of a (migrated) profile dict, read by the schema's declarations.

    Parameters
    ----------
    data : object
        The value of the profile's ``renderable`` key (a JSON object).

    Returns
    -------
    RenderableSection
        The section, every missing key at its default.

    Raises
    ------
    ProfileError
        At the JSON path of the first bad or unknown key, e.g. ``$.renderable.grid.mass.points``.
    """
    values: dict[str, Any] = {}
    read_declared(RENDERABLE, data, "$.renderable", values, frozenset({"quiet_resolution"}))
    try:
        return RenderableSection(**values)
    except ValidationError as err:
        path = FIELDS_BY_NAME[err.field][0] if err.field in FIELDS_BY_NAME else "$.renderable"
        raise ProfileError.at(path, err.allowed, err.value) from err
