"""Profile files: round trip, validation with JSON paths, atomic save, migrations, fuzzing."""

from __future__ import annotations

import copy
import json
import math
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from analysis.profiles import io as profiles
from analysis.chain.device import Device
from analysis.errors import ValidationError
from analysis.profiles.errors import element_label
from analysis.profiles.io import (
    Profile,
    ProfileError,
    bundled_profiles,
    load_profile,
    migrate,
    profile_from_dict,
    profile_to_dict,
    save_profile,
)
from import_probe import import_probe

HBFD = bundled_profiles()["hbfd"]


def hbfd_dict() -> dict:
    return json.loads(HBFD.read_text())


def write(tmp_path: Path, data, name: str = "p.json") -> Path:
    path = tmp_path / name
    path.write_text(data if isinstance(data, str) else json.dumps(data))
    return path


def rejected(tmp_path: Path, data, name: str = "p.json") -> ProfileError:
    path = write(tmp_path, data, name)
    with pytest.raises(ProfileError) as info:
        load_profile(path)
    assert info.value.path == str(path)
    assert str(info.value).startswith(f"{path}: ")
    return info.value


# -- bundled presets -----------------------------------------------------------------------------


def test_bundled_profiles_present():
    assert set(bundled_profiles()) >= {"hbfd", "rigid", "eom"}
    for path in bundled_profiles().values():
        assert path.is_file() and path.suffix == ".json"


@pytest.mark.parametrize("key", ["hbfd", "rigid", "eom"])
def test_round_trip_every_bundled_profile(tmp_path, key):
    original = load_profile(bundled_profiles()[key])
    out = tmp_path / f"{key}.json"
    save_profile(original, out)
    again = load_profile(out)
    assert again == original
    assert again.device == original.device
    np.testing.assert_array_equal(again.device.dampings, original.device.dampings)
    # the saved text is the canonical form: saving again gives the same bytes
    save_profile(again, tmp_path / "second.json")
    assert (tmp_path / "second.json").read_bytes() == out.read_bytes()
    assert json.loads(out.read_text())["schema_version"] == profiles.SCHEMA_VERSION


def test_hbfd_values():
    p = load_profile(HBFD)
    d = p.device
    assert p.name == "HBFD (worst case)"
    np.testing.assert_array_equal(d.masses, [0.2, 2.3, 2.0, 0.5])
    np.testing.assert_array_equal(d.stiffnesses, [130000.0, 84000.0, 874000.0])
    # eq. (28): b = 2 zeta sqrt(k mu), mu the reduced mass of the two masses joined
    np.testing.assert_allclose(d.dampings, [30.93, 59.95, 118.25], atol=0.01)
    np.testing.assert_allclose(d.damping_ratios, [0.1, 0.1, 0.1], rtol=1e-12)
    np.testing.assert_array_equal(d.ground_dampings, [0.0, 0.0, 0.0, 5.0])
    assert d.sensor_element == 0 and d.sample_time == 0.001 and d.band_min == 1.0
    assert p.display == "impedance"
    assert (p.kc, p.bc, p.mc, p.bc_adm, p.kp, p.kd) == (50000.0, 100.0, 8.0, 400.0, 50000.0, 100.0)


def test_rigid_and_eom_values():
    rigid = load_profile(bundled_profiles()["rigid"])
    assert rigid.device.n == 1 and rigid.device.total_mass == 0.5
    assert rigid.device.total_ground_damping == 2.0
    assert (rigid.kc, rigid.bc, rigid.mc, rigid.bc_adm) == (2000.0, 5.0, 1.0, 50.0)
    eom = load_profile(bundled_profiles()["eom"])
    assert eom.device.n == 1 and eom.device.total_mass == 0.01
    assert eom.device.total_ground_damping == pytest.approx(0.022)
    assert eom.device.sample_time == 0.001
    assert (eom.kc, eom.bc, eom.mc, eom.bc_adm, eom.kp, eom.kd) == (1000.0, 1.0, 0.1, 10.0, 1000.0, 1.0)


def test_optional_fields_default(tmp_path):
    d = hbfd_dict()
    del d["notes"], d["band"], d["device"]["ground_dampings"], d["device"]["sensor_element"]
    p = load_profile(write(tmp_path, d))
    assert p.notes == ""
    assert p.device.band_min == 1.0 and p.device.sensor_element == 0
    np.testing.assert_array_equal(p.device.ground_dampings, np.zeros(4))


def test_dampings_instead_of_ratios(tmp_path):
    d = hbfd_dict()
    del d["device"]["damping_ratios"]
    d["device"]["dampings"] = [10.0, 20.0, 30.0]
    p = load_profile(write(tmp_path, d))
    np.testing.assert_array_equal(p.device.dampings, [10.0, 20.0, 30.0])


# -- rejected files ------------------------------------------------------------------------------


def test_missing_masses(tmp_path):
    d = hbfd_dict()
    del d["device"]["masses"]
    err = rejected(tmp_path, d)
    assert err.json_path == "$.device.masses"
    assert "$.device.masses: expected" in str(err) and "missing" in str(err)


def test_missing_top_level_field(tmp_path):
    d = hbfd_dict()
    del d["pd_gains"]
    assert rejected(tmp_path, d).json_path == "$.pd_gains"


def test_negative_mass(tmp_path):
    d = hbfd_dict()
    d["device"]["masses"][1] = -1.0
    err = rejected(tmp_path, d, "hbfd.json")
    assert err.json_path == "$.device.masses[1]"
    assert (
        str(err)
        == f"{tmp_path / 'hbfd.json'}: $.device.masses[1] (mass 2): expected a number > 0 and finite, "
        "within the physical range [1e-06, 1000] (kg), got -1.0"
    )
    assert "> 0" in err.expected


def test_nan_literal(tmp_path):
    text = HBFD.read_text().replace('"sample_time": 0.001', '"sample_time": NaN')
    assert "NaN" in text
    err = rejected(tmp_path, text)
    assert err.json_path == "$.sample_time"
    assert "NaN" in str(err)


@pytest.mark.parametrize("literal", ["Infinity", "-Infinity"])
def test_infinity_literal_in_list(tmp_path, literal):
    text = json.dumps(hbfd_dict()).replace("[0.2, 2.3, 2.0, 0.5]", f"[0.2, {literal}, 2.0, 0.5]")
    assert literal in text
    err = rejected(tmp_path, text)
    assert err.json_path == "$.device.masses[1]"
    assert literal in str(err)


def test_string_where_number_belongs(tmp_path):
    d = hbfd_dict()
    d["impedance_coupling"]["stiffness"] = "50000"
    err = rejected(tmp_path, d)
    assert err.json_path == "$.impedance_coupling.stiffness"
    assert 'the string "50000"' in str(err)


def test_boolean_where_number_belongs(tmp_path):
    d = hbfd_dict()
    d["device"]["stiffnesses"][2] = True
    err = rejected(tmp_path, d)
    assert err.json_path == "$.device.stiffnesses[2]"
    assert "got true" in str(err)


@pytest.mark.parametrize("version", [99, profiles.SCHEMA_VERSION + 1, 0, -1, "1", 1.0, None, True])
def test_bad_schema_version(tmp_path, version):
    d = hbfd_dict()
    d["schema_version"] = version
    err = rejected(tmp_path, d)
    assert err.json_path == "$.schema_version"
    if version == 99:
        assert "newer zwidth" in str(err) and "got 99" in str(err)


def test_missing_schema_version(tmp_path):
    d = hbfd_dict()
    del d["schema_version"]
    assert rejected(tmp_path, d).json_path == "$.schema_version"


def test_truncated_file(tmp_path):
    text = HBFD.read_text()
    err = rejected(tmp_path, text[: len(text) // 2])
    assert err.json_path is None
    assert "invalid JSON at line" in str(err) and "column" in str(err)


@pytest.mark.parametrize("text", ["[1, 2]", '"HBFD"', "42", "null", "true"])
def test_wrong_top_level_type(tmp_path, text):
    err = rejected(tmp_path, text)
    assert err.json_path == "$"
    assert "expected a JSON object" in str(err)


def test_both_dampings_and_ratios(tmp_path):
    d = hbfd_dict()
    d["device"]["dampings"] = [30.0, 60.0, 118.0]
    err = rejected(tmp_path, d)
    assert err.json_path == "$.device"
    assert "dampings" in str(err) and "damping_ratios" in str(err) and "both" in str(err)


def test_neither_dampings_nor_ratios(tmp_path):
    d = hbfd_dict()
    del d["device"]["damping_ratios"]
    assert "neither" in str(rejected(tmp_path, d))


@pytest.mark.parametrize(
    ("mutate", "json_path"),
    [
        (lambda d: d["device"].update(stiffnesses=[1.0, 2.0]), "$.device.stiffnesses"),
        (lambda d: d["device"].update(masses=[]), "$.device.masses"),
        (lambda d: d["device"].update(masses="heavy"), "$.device.masses"),
        (lambda d: d["device"].update(ground_dampings=[0, 0, 0, -5.0]), "$.device.ground_dampings[3]"),
        (lambda d: d["device"].update(damping_ratios=[0.1, -0.1, 0.1]), "$.device.damping_ratios[1]"),
        (lambda d: d["device"].update(sensor_element=3), "$.device.sensor_element"),
        (lambda d: d["device"].update(sensor_element=0.0), "$.device.sensor_element"),
        (lambda d: d["device"].update(colour="red"), "$.device.colour"),
        (lambda d: d.update(device=[1, 2]), "$.device"),
        (lambda d: d.update(sample_time=0), "$.sample_time"),
        (lambda d: d.update(sample_time=1e400), "$.sample_time"),
        (lambda d: d.update(band={"min": 5000.0}), "$.band.min"),
        (lambda d: d.update(band={"min": 1.0, "max": 10.0}), "$.band.max"),
        (lambda d: d.update(display="hybrid"), "$.display"),
        (lambda d: d.update(name=""), "$.name"),
        (lambda d: d.update(name=7), "$.name"),
        (lambda d: d.update(notes=None), "$.notes"),
        (lambda d: d.update(nmae="typo"), "$.nmae"),
        (lambda d: d["admittance_coupling"].update(mass=0.0), "$.admittance_coupling.mass"),
        (lambda d: d["admittance_coupling"].update(damping=-1), "$.admittance_coupling.damping"),
        (lambda d: d["impedance_coupling"].update(damping=-1.0), "$.impedance_coupling.damping"),
        (lambda d: d["pd_gains"].pop("damping"), "$.pd_gains.damping"),
        (lambda d: d["pd_gains"].update(stiffness=10**400), "$.pd_gains.stiffness"),
        (lambda d: d.update(pd_gains=None), "$.pd_gains"),
    ],
)
def test_bad_values_name_their_json_path(tmp_path, mutate, json_path):
    d = hbfd_dict()
    mutate(d)
    err = rejected(tmp_path, d)
    assert err.json_path == json_path
    label = element_label(json_path)  # an element's GUI name (1-based) follows its 0-based path
    assert f": {json_path} ({label}): " in str(err) if label else f": {json_path}: " in str(err)


def test_band_above_nyquist_message(tmp_path):
    d = hbfd_dict()
    d["band"]["min"] = 5000.0
    err = rejected(tmp_path, d)
    assert "Nyquist" in str(err) and "got 5000.0" in str(err)


def test_unreadable_files(tmp_path):
    with pytest.raises(ProfileError, match="cannot read the file") as info:
        load_profile(tmp_path / "absent.json")
    assert info.value.path == str(tmp_path / "absent.json") and info.value.json_path is None
    with pytest.raises(ProfileError, match="cannot read the file"):
        load_profile(tmp_path)  # a directory
    (tmp_path / "bin.json").write_bytes(b"\xff\xfe\x00{")
    with pytest.raises(ProfileError, match="not UTF-8"):
        load_profile(tmp_path / "bin.json")


def test_duplicate_key_rejected(tmp_path):
    text = HBFD.read_text().replace(
        '"display": "impedance"', '"display": "impedance", "display": "admittance"'
    )
    assert "duplicate key" in str(rejected(tmp_path, text))


def test_profile_from_dict_without_path():
    d = hbfd_dict()
    d["device"]["masses"][2] = -1.0
    with pytest.raises(ProfileError) as info:
        profile_from_dict(d)
    assert info.value.path is None
    assert str(info.value).startswith("$.device.masses[2] (mass 3): expected a number > 0")
    with pytest.raises(ProfileError) as info:
        profile_from_dict(d, path="hbfd.json")
    assert str(info.value).startswith("hbfd.json: $.device.masses[2] (mass 3): expected a number > 0 and finite")


def test_profile_from_dict_does_not_modify_input():
    d = hbfd_dict()
    before = copy.deepcopy(d)
    profile_from_dict(d)
    assert d == before


# -- the Profile dataclass -----------------------------------------------------------------------


def test_profile_replace_revalidates():
    p = load_profile(HBFD)
    q = p.replace(kc=1234, display="admittance")
    assert q.kc == 1234.0 and isinstance(q.kc, float) and q.display == "admittance"
    assert p.kc == 50000.0  # frozen, unchanged
    with pytest.raises(ValidationError) as info:
        p.replace(mc=0.0)
    assert info.value.field == "mc"
    with pytest.raises(ValidationError) as info:
        p.replace(kd=math.nan)
    assert info.value.field == "kd"
    with pytest.raises(ValidationError) as info:
        p.replace(display="both")
    assert info.value.field == "display"
    with pytest.raises(ValidationError) as info:
        p.replace(bc=True)
    assert info.value.field == "bc"
    with pytest.raises(ValidationError) as info:
        p.replace(name="  ")
    assert info.value.field == "name"
    with pytest.raises(TypeError):
        p.replace(stiffness=1.0)
    with pytest.raises(AttributeError):
        p.kc = 1.0  # type: ignore[misc]


def test_profile_to_dict_matches_documented_format():
    d = profile_to_dict(load_profile(HBFD))
    assert list(d) == [
        "schema_version",
        "name",
        "notes",
        "device",
        "sample_time",
        "band",
        "display",
        "impedance_coupling",
        "admittance_coupling",
        "pd_gains",
        "simulation",
    ]
    assert set(d["device"]) == {"masses", "stiffnesses", "dampings", "ground_dampings", "sensor_element"}
    assert d["band"] == {"min": 1.0}
    assert d["admittance_coupling"] == {"mass": 8.0, "damping": 400.0}
    json.dumps(d, allow_nan=False)


# -- atomic save ---------------------------------------------------------------------------------


def _leftovers(folder: Path, keep: set[str]) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name not in keep)


@pytest.mark.parametrize("target", ["os.replace", "os.fsync", "json.dumps"])
def test_failed_save_leaves_original_untouched(tmp_path, monkeypatch, target):
    path = tmp_path / "mine.json"
    path.write_bytes(HBFD.read_bytes())
    os.chmod(path, 0o640)
    before = path.read_bytes()
    changed = load_profile(HBFD).replace(name="changed", kc=1.0)

    def boom(*args, **kwargs):
        raise OSError(28, "No space left on device")

    module, name = target.split(".")
    monkeypatch.setattr({"os": os, "json": json}[module], name, boom)
    with pytest.raises(ProfileError, match="cannot save") as info:
        save_profile(changed, path)
    monkeypatch.undo()
    assert info.value.path == str(path)
    assert path.read_bytes() == before
    assert _leftovers(tmp_path, {"mine.json"}) == []
    # and a save that works replaces the file, keeping its permissions
    save_profile(changed, path)
    assert load_profile(path) == changed
    assert (os.stat(path).st_mode & 0o777) == 0o640
    assert _leftovers(tmp_path, {"mine.json"}) == []


def test_save_into_missing_directory(tmp_path):
    with pytest.raises(ProfileError, match="cannot save"):
        save_profile(load_profile(HBFD), tmp_path / "no" / "such" / "dir.json")


def test_save_refuses_non_finite(tmp_path):
    # Profile validation keeps NaN out; a forged one must still not be written
    p = load_profile(HBFD)
    object.__setattr__(p, "kc", math.inf)
    with pytest.raises(ProfileError, match="cannot save"):
        save_profile(p, tmp_path / "x.json")
    assert list(tmp_path.iterdir()) == []


# -- migrations ----------------------------------------------------------------------------------


def test_migration_hook(tmp_path, monkeypatch):
    """A schema-1 file read by a zwidth whose schema is 2 goes through MIGRATIONS[1]."""
    calls = []

    def one_to_two(d: dict) -> dict:
        calls.append(d["schema_version"])
        d = dict(d)
        d["name"] = d.pop("title")  # pretend version 1 called the name "title"
        return d

    monkeypatch.setattr(profiles, "SCHEMA_VERSION", 2)
    monkeypatch.setattr(profiles, "MIGRATIONS", {1: one_to_two})
    d1 = hbfd_dict()
    d1["title"] = d1.pop("name")
    d1["schema_version"] = 1
    original = copy.deepcopy(d1)

    migrated = migrate(d1)
    assert migrated["schema_version"] == 2 and migrated["name"] == "HBFD (worst case)"
    assert "title" not in migrated
    assert d1 == original  # input untouched

    p = load_profile(write(tmp_path, d1))
    assert p.name == "HBFD (worst case)"
    assert calls == [1, 1]
    # saving writes the new version, which loads without migrating
    save_profile(p, tmp_path / "v2.json")
    assert json.loads((tmp_path / "v2.json").read_text())["schema_version"] == 2
    assert load_profile(tmp_path / "v2.json") == p
    assert calls == [1, 1]
    # a file newer than this "version 2" zwidth is refused
    d3 = dict(migrated, schema_version=3)
    with pytest.raises(ProfileError, match="newer zwidth"):
        profile_from_dict(d3)


def test_migration_failure_and_gap(monkeypatch):
    monkeypatch.setattr(profiles, "SCHEMA_VERSION", 3)
    monkeypatch.setattr(profiles, "MIGRATIONS", {1: lambda d: d["title"]})  # KeyError; no 2 -> 3
    d = hbfd_dict()
    d["schema_version"] = 1
    with pytest.raises(ProfileError, match="cannot migrate from schema version 1 to 2"):
        profile_from_dict(d)
    monkeypatch.setattr(profiles, "MIGRATIONS", {1: lambda d: d})
    with pytest.raises(ProfileError, match="no migration from schema version 2 to 3"):
        profile_from_dict(d)


# -- fuzzing -------------------------------------------------------------------------------------

json_scalars = (
    st.none()
    | st.booleans()
    | st.integers(min_value=-(10**400), max_value=10**400)
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=8)
)
json_values = st.recursive(
    json_scalars,
    lambda children: (
        st.lists(children, max_size=5) | st.dictionaries(st.text(max_size=8), children, max_size=5)
    ),
    max_leaves=20,
)


def _check(data) -> None:
    try:
        result = profile_from_dict(data, path="fuzz.json")
    except ProfileError as err:
        assert str(err).startswith("fuzz.json: ")
        return
    assert isinstance(result, Profile)
    assert isinstance(result.device, Device)
    # anything accepted must save and load back to itself
    assert profile_from_dict(json.loads(json.dumps(profile_to_dict(result), allow_nan=False))) == result


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(json_values)
def test_fuzz_random_json(data):
    _check(data)


def _keys_of(node) -> list:
    if isinstance(node, dict):
        return list(node)
    if isinstance(node, list):
        return list(range(len(node)))
    return []


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_fuzz_mutated_hbfd(data):
    d = hbfd_dict()
    for _ in range(data.draw(st.integers(1, 3))):
        # walk down to a random container, then replace, delete or add one entry
        node = d
        while True:
            keys = _keys_of(node)
            if not keys:
                break
            key = data.draw(st.sampled_from(keys))
            child = node[key]
            if not _keys_of(child) or data.draw(st.booleans()):
                break
            node = child
        if not isinstance(node, (dict, list)) or not _keys_of(node):
            continue
        action = data.draw(st.sampled_from(["replace", "delete", "add"]))
        if action == "replace":
            node[key] = data.draw(json_values)
        elif action == "delete":
            del node[key]
        elif isinstance(node, dict):
            node[data.draw(st.text(max_size=12))] = data.draw(json_values)
        else:
            node.append(data.draw(json_values))
    _check(d)


@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=-1e100, max_value=1e100), st.integers(0, 3))
def test_fuzz_numbers_in_hbfd(x, i):
    """A number at a mass is accepted iff it is in the physical range of masses [1e-6, 1e3] kg."""
    d = hbfd_dict()
    d["device"]["masses"][i] = x
    if 1e-6 <= x <= 1e3:
        p = profile_from_dict(d)
        assert p.device.masses[i] == x
    else:
        with pytest.raises(ProfileError, match=rf"\$\.device\.masses\[{i}\]"):
            profile_from_dict(d)


# -- layering ------------------------------------------------------------------------------------

REPO = Path(__file__).resolve().parent.parent


def test_profile_record_does_not_load_the_design_stack():
    """Importing the Profile record loads only the light settings records (a fresh interpreter: the
    first stage of :func:`import_probe.import_probe`), and the design stack's lazy names resolve."""
    record = import_probe()["profile record"]
    assert record["after model"] == [] and record["after io"] == []  # none of import_probe.HEAVY
    assert record["all listed"] and record["all resolve"]
    assert record["names"] == ["WallDesign", "simulate"]


def test_profiles_package_has_no_import_cycle():
    """The imports among analysis/profiles/*.py (module- and function-level) form no cycle."""
    import ast

    folder = REPO / "analysis" / "profiles"
    graph: dict[str, set[str]] = {}
    for path in folder.glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("analysis.profiles."):
                deps.add(node.module.rsplit(".", 1)[1])
            elif isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
                deps.add(node.module)
        graph[path.stem] = deps - {path.stem}
    graph.pop("__init__")
    done: set[str] = set()

    def visit(name: str, stack: tuple[str, ...]) -> None:
        assert name not in stack, f"import cycle: {' -> '.join((*stack, name))}"
        if name in done:
            return
        for dep in graph.get(name, ()):
            visit(dep, (*stack, name))
        done.add(name)

    for name in graph:
        visit(name, ())
    assert "io" in done and graph["sections"] <= {"errors"}
