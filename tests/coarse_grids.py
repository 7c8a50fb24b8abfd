"""Profiles on coarse grids, for tests about the form or the flow of a result, not its resolution.

A full workspace map, renderable space or Z-width region costs seconds per case; what a CSV's
header says, or which study a figure calls, does not depend on the grid's size (issue 21).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from analysis.profiles import ControllerSection, MultiDofSection, Profile, RenderableSection, load_profile, save_profile

#: the coarse grids (section, the section's own default, its grid fields): a handful of points each
COARSE = {"multidof": (MultiDofSection, {"x_points": 5, "y_points": 4}),
          "renderable": (RenderableSection, {"mass_points": 4, "damping_points": 5}),
          "controller": (ControllerSection, {"b_points": 12})}


def coarse_sections(profile: Profile, *sections: str, **fields: object) -> Profile:
    """``profile`` with a coarse grid in each of its ``sections`` that it has (the section's defaults
    when there is only one section and the profile has none); ``fields`` set more of each section."""
    changed = {}
    for section in sections:
        cls, grid = COARSE[section]
        current = getattr(profile, section)
        if current is None and len(sections) > 1:
            continue
        changed[section] = dataclasses.replace(current or cls(), **grid, **fields)
    return profile.replace(**changed)


def coarse(profile: Path, section: str, tmp_path: Path, **fields: object) -> Path:
    """``profile`` with a coarse grid in its ``section`` (the section's defaults where it has none),
    saved in ``tmp_path``; ``fields`` set more of the section."""
    path = tmp_path / f"coarse-{section}-{profile.name}"
    save_profile(coarse_sections(load_profile(profile), section, **fields), path)
    return path
