"""Optional profile sections added by later schema versions.

* schema 2: ``wall`` (the wall-controller design of Eom, Suh & Yi, :class:`WallSettings`) and
  ``observer`` (the disturbance observer, :class:`ObserverSettings`);
* schema 3: ``simulation`` (``{"options": SimulationOptions, "scenario": Scenario}``, the
  sampled-data simulator's settings and the chosen scenario);
* schema 4: ``identification`` (parameter intervals and embedded measurements, parsed by
  :mod:`analysis.profiles.identification`, which :mod:`analysis.profiles.fields` calls);
* schema 5: ``controller`` (the velocity filter, the Z-width region's B range and a trials
  file, parsed by :mod:`analysis.profiles.controller`, which :mod:`analysis.profiles.fields` calls);
* schema 6: ``renderable`` (the rendered environment ``F = M a^ + B v^ + K x``, the qualities'
  settings and the renderable space's grid; issue 24), declared key by key in
  :data:`analysis.profiles.schema.RENDERABLE` and parsed by :mod:`analysis.profiles.renderable`;
* schema 7: ``multidof`` (a multi-DOF linkage, its handle position, the wall and the workspace
  map's grid; issue 25), declared key by key in :data:`analysis.profiles.schema.MULTIDOF` and
  parsed by :mod:`analysis.profiles.multidof`.

Every section is optional; an older file simply has none of them, so the migrations only
raise the version number.  Errors name the JSON path, e.g. ``$.wall.mass`` or
``$.simulation.scenario.grasp.mass``.  The sections are the settings records' own
``to_dict``/``from_dict`` (:func:`analysis.checks.record_to_dict`, :func:`analysis.checks.record_from_dict`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from analysis.errors import ValidationError
from analysis.profiles.errors import ProfileError
from analysis.sampled.scenarios import Scenario, SimulationOptions
from analysis.transparency.settings import ObserverSettings, WallSettings

__all__ = ["SECTION_KEYS", "MIGRATION_STEPS", "SimulationSection", "parse_sections", "sections_to_dict"]

SECTION_KEYS = ("wall", "observer", "simulation", "identification", "controller", "renderable", "multidof")


@dataclass(frozen=True)
class SimulationSection:
    """The simulator's options and the scenario saved with a profile.

    Parameters
    ----------
    options : SimulationOptions
        The sampled-data simulator's options (substeps, sensor resolutions, friction, actuator
        limits, delay).
    scenario : Scenario
        The scenario to simulate (environment, human grasp and push, initial state, duration).

    Raises
    ------
    ValidationError
        When ``options`` or ``scenario`` is not of its type.
    """

    options: SimulationOptions
    scenario: Scenario

    def __post_init__(self) -> None:
        if not isinstance(self.options, SimulationOptions):
            raise ValidationError("options", "SimulationOptions", self.options)
        if not isinstance(self.scenario, Scenario):
            raise ValidationError("scenario", "a Scenario", self.scenario)


def _to_2(data: dict) -> dict:
    """Schema 1 -> 2: adds the optional ``wall`` and ``observer`` sections (nothing to change)."""
    return data


def _to_3(data: dict) -> dict:
    """Schema 2 -> 3: adds the optional ``simulation`` section (nothing to change)."""
    return data


def _to_4(data: dict) -> dict:
    """Schema 3 -> 4: adds the optional ``identification`` section (nothing to change)."""
    return data


def _to_5(data: dict) -> dict:
    """Schema 4 -> 5: adds the optional ``controller`` section (velocity filter, Z-width B range,
    trials file; :mod:`analysis.profiles.controller`) -- nothing to change: no section is the
    backward difference, every result as before."""
    return data


def _to_6(data: dict) -> dict:
    """Schema 5 -> 6: adds the optional ``renderable`` section (the rendered environment and the
    qualities, issue 24) -- nothing to change: without it the app renders no environment beyond the
    virtual coupling, and the renderable space uses the section's defaults."""
    return data


def _to_7(data: dict) -> dict:
    """Schema 6 -> 7: adds the optional ``multidof`` section (a linkage, its handle, the wall and the
    workspace map's grid, issue 25) -- nothing to change: a profile without it is a one-axis device,
    and the Workspace view shows the section's defaults."""
    return data


MIGRATION_STEPS = {1: _to_2, 2: _to_3, 3: _to_4, 4: _to_5, 5: _to_6, 6: _to_7}


#: The names the settings records give themselves in a "not an object" error (see ``from_dict``).
_RECORD_NAMES = ("transparency", "observer", "simulation options", "scenario")


def _section(kind: str, jp: str, value: object, cls: type) -> Any:
    """``cls.from_dict(value)``, a ValidationError as a ProfileError at its JSON path under ``jp``."""
    try:
        return cls.from_dict(value)
    except ValidationError as err:
        where = jp + "".join(f".{name}" for name in err.within)
        if err.field and err.field not in (kind, *_RECORD_NAMES):
            where += f".{err.field}"
        if err.index is not None:
            where += f"[{err.index}]"
        raise ProfileError.at(where, err.allowed, err.value) from err
    except (TypeError, ValueError) as exc:
        raise ProfileError.at(jp, f"a valid {kind} section ({exc})", value) from exc


def parse_sections(data: Mapping) -> dict[str, Any]:
    """The optional sections of a (migrated) profile dict as settings objects or ``None``.

    Parameters
    ----------
    data : Mapping
        The profile dict at the current schema version.

    Returns
    -------
    dict of str to Any
        ``wall`` (:class:`WallSettings`), ``observer`` (:class:`ObserverSettings`) and
        ``simulation`` (:class:`SimulationSection`), each ``None`` where the profile has no
        such section.

    Raises
    ------
    ProfileError
        At the JSON path of the first bad or unknown key of a section, e.g. ``$.wall.mass``.
    """
    out: dict[str, Any] = {"wall": None, "observer": None, "simulation": None}
    if "wall" in data:
        out["wall"] = _section("wall", "$.wall", data["wall"], WallSettings)
    if "observer" in data:
        out["observer"] = _section("observer", "$.observer", data["observer"], ObserverSettings)
    if "simulation" in data:
        sim = data["simulation"]
        if not isinstance(sim, Mapping):
            raise ProfileError.at("$.simulation", "a JSON object with keys options and scenario", sim)
        unknown = set(sim) - {"options", "scenario"}
        if unknown:
            raise ProfileError.at(f"$.simulation.{sorted(map(str, unknown))[0]}", "no such key (options, scenario)", None)
        options = _section("simulation options", "$.simulation.options", sim.get("options", {}),
                           SimulationOptions)
        scenario = _section("scenario", "$.simulation.scenario", sim.get("scenario", {}), Scenario)
        out["simulation"] = SimulationSection(options=options, scenario=scenario)
    return out


def sections_to_dict(wall: WallSettings | None, observer: ObserverSettings | None,
                     simulation: SimulationSection | None) -> dict[str, Any]:
    """The JSON-ready sections that are present (``inf`` written as ``"inf"``, see :mod:`analysis.checks`).

    Parameters
    ----------
    wall : WallSettings or None
        The wall-controller design settings, or ``None``.
    observer : ObserverSettings or None
        The disturbance observer settings, or ``None``.
    simulation : SimulationSection or None
        The simulator's options and scenario, or ``None``.

    Returns
    -------
    dict of str to Any
        ``wall``, ``observer`` and ``simulation`` (``{"options": ..., "scenario": ...}``), each
        only where it is not ``None``.
    """
    out: dict[str, Any] = {}
    if wall is not None:
        out["wall"] = wall.to_dict()
    if observer is not None:
        out["observer"] = observer.to_dict()
    if simulation is not None:
        out["simulation"] = {"options": simulation.options.to_dict(), "scenario": simulation.scenario.to_dict()}
    return out
