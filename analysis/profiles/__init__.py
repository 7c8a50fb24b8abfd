"""Device profiles: the Profile record, its schema, migrations and files.

The modules are layered, each importing only those listed before it (no cycle):

* :mod:`.errors` -- :class:`ProfileError` (file and JSON path of the offending value);
* :mod:`.sections` -- the optional sections (wall, observer, simulation) and the migration steps;
* :mod:`.schema` -- the one declaration of each field (type, range, unit; its JSON path is where
  it sits), from which the loader reads and names the JSON path of every error;
* :mod:`.model` -- the :class:`Profile` record (light: it holds the settings records of
  :mod:`analysis.transparency.settings` and :mod:`analysis.sampled.scenarios`, never the wall
  design or the simulator);
* :mod:`.fields` -- reading a current-schema profile dict by the schema;
* :mod:`.files` -- strict JSON reading, the one atomic file writer (:func:`atomic_write`, used by
  the app's saves, exports and reports too), the bundled presets;
* :mod:`.io` -- schema version, migrations, ``load_profile``/``save_profile``.
"""

from __future__ import annotations

from .errors import ProfileError
from .controller import ControllerSection, parse_controller
from .renderable import RenderableSection, parse_renderable
from .multidof import MultiDofSection, parse_multidof
from .files import WriteError, atomic_write, bundled_profiles, read_json, sweep_temporaries, write_atomically
from .fields import error_at, profile_from_current
from .io import (
    MIGRATIONS,
    SCHEMA_VERSION,
    load_profile,
    migrate,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from .model import DISPLAYS, SCALAR_FIELDS, Profile, ScalarField, per_mass_changes
from .schema import Field, path_of
from .sections import (
    MIGRATION_STEPS,
    SECTION_KEYS,
    SimulationSection,
    parse_sections,
    sections_to_dict,
)

__all__ = [
    "ControllerSection",
    "parse_controller",
    "RenderableSection",
    "parse_renderable",
    "MultiDofSection",
    "parse_multidof",
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
    "SCALAR_FIELDS",
    "ScalarField",
    "profile_from_current",
    "error_at",
    "per_mass_changes",
    "Field",
    "path_of",
    "read_json",
    "write_atomically",
    "atomic_write",
    "WriteError",
    "sweep_temporaries",
]
