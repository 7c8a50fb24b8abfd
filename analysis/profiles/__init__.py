"""Device profiles: the Profile record, its schema, migrations and files.
"""

from __future__ import annotations

from .io import (  # noqa: F401
    DISPLAYS,
    MIGRATIONS,
    SCHEMA_VERSION,
    Profile,
    ProfileError,
    bundled_profiles,
    load_profile,
    migrate,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from .sections import (  # noqa: F401
    SECTION_KEYS,
    MIGRATION_STEPS,
    SimulationSection,
    parse_sections,
    sections_to_dict,
)

__all__ = [
    "DISPLAYS",
    "MIGRATIONS",
    "SCHEMA_VERSION",
    "Profile",
    "ProfileError",
    "bundled_profiles",
    "load_profile",
    "migrate",
    "profile_from_dict",
    "profile_to_dict",
    "save_profile",
    "SECTION_KEYS",
    "MIGRATION_STEPS",
    "SimulationSection",
    "parse_sections",
    "sections_to_dict",
]
