"""Lists indexed by mass (issue 23): :func:`analysis.profiles.per_mass_changes` resizes every list the
schema declares per mass (:data:`analysis.profiles.schema.PER_MASS_LISTS`, one declaration) when a mass
is added or removed, and a :class:`~analysis.profiles.Profile` refuses a per-mass list of another length
than its device's masses, naming the field, which the loader puts at its JSON path."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import pytest

from analysis import Device
from analysis.errors import ValidationError
from analysis.profiles import ProfileError, load_profile, per_mass_changes, save_profile
from analysis.profiles.fields import error_at
from analysis.profiles.io import bundled_profiles, profile_from_dict, profile_to_dict
from analysis.profiles.schema import PER_MASS_LISTS, Field, per_mass_values
from analysis.profiles.sections import SimulationSection

FRICTION = "$.simulation.options.friction"
HBFD_FRICTION = (0.0, 1.0, 0.0, 0.5)
LOADER_TEXT = ("expected a list of exactly 3 values (one per mass, 3 masses), each >= 0 and finite (N), "
               "or an empty list")


@pytest.fixture(scope="module")
def hbfd():
    return load_profile(bundled_profiles()["hbfd"])


def without(dev: Device, i: int) -> Device:
    """``dev`` with mass ``i`` removed, and the element that joined it (as the chain editor does)."""
    e = min(i, dev.n - 2)
    return Device(masses=np.delete(dev.masses, i), stiffnesses=np.delete(dev.stiffnesses, e),
                  dampings=np.delete(dev.dampings, e), ground_dampings=np.delete(dev.ground_dampings, i),
                  sample_time=dev.sample_time, band_min=dev.band_min)


def with_more(dev: Device, extra: int) -> Device:
    """``dev`` with ``extra`` masses appended at the actuator end."""
    return Device(masses=np.append(dev.masses, [0.1] * extra), stiffnesses=np.append(dev.stiffnesses, [1e5] * extra),
                  dampings=np.append(dev.dampings, [5.0] * extra),
                  ground_dampings=np.append(dev.ground_dampings, [0.0] * extra), sample_time=dev.sample_time,
                  band_min=dev.band_min)


def _friction_lists(p) -> dict[str, tuple[float, ...]]:
    return {path: values for path, values in per_mass_values(p).items() if path == FRICTION}


# -- per_mass_changes ----------------------------------------------------------------------------------


@pytest.mark.parametrize("removed", range(4))
def test_removing_each_mass_drops_its_friction_and_the_profile_round_trips(hbfd, removed, tmp_path):
    new = without(hbfd.device, removed)
    changes = per_mass_changes(hbfd, new.n, removed=removed)
    assert set(changes) == {"simulation"}
    p = hbfd.replace(device=new, **changes)
    assert p.simulation.options.friction == tuple(np.delete(HBFD_FRICTION, removed))
    # everything but the list is kept, and every declared per-mass list now holds one value per mass
    assert p.simulation.scenario == hbfd.simulation.scenario
    assert p.simulation.options.replace(friction=HBFD_FRICTION) == hbfd.simulation.options
    assert {path: len(v) for path, v in per_mass_values(p).items()} == {path: 3 for path, _ in PER_MASS_LISTS}
    save_profile(p, tmp_path / "p.json")
    assert load_profile(tmp_path / "p.json") == p
    assert hbfd.simulation.options.friction == HBFD_FRICTION  # the base is unchanged


@pytest.mark.parametrize("extra", [1, 3])
def test_adding_masses_gives_them_no_friction_and_removing_them_restores_the_list(hbfd, extra):
    bigger = with_more(hbfd.device, extra)
    p = hbfd.replace(device=bigger, **per_mass_changes(hbfd, bigger.n))
    assert p.simulation.options.friction == HBFD_FRICTION + (0.0,) * extra
    back = p.replace(device=hbfd.device, **per_mass_changes(p, hbfd.device.n))  # dropped from the actuator end
    assert back == hbfd


def test_nothing_changes_when_the_lists_fit_or_are_empty(hbfd):
    assert per_mass_changes(hbfd, 4) == {} and per_mass_changes(hbfd, 4, removed=2) == {}
    none = hbfd.replace(simulation=SimulationSection(options=hbfd.simulation.options.replace(friction=()),
                                                     scenario=hbfd.simulation.scenario))
    assert per_mass_changes(none, 2, removed=0) == {}  # no friction stays no friction
    assert per_mass_changes(hbfd.replace(simulation=None), 2) == {}


def test_a_removed_index_outside_the_list_truncates_at_the_actuator_end(hbfd):
    changes = per_mass_changes(hbfd, 3, removed=7)
    assert changes["simulation"].options.friction == HBFD_FRICTION[:3]


@dataclass(frozen=True)
class _Grasp:
    weights: tuple[float, ...] = ()


@dataclass(frozen=True)
class _Options:
    friction: tuple[float, ...] = ()


@dataclass(frozen=True)
class _Simulation:
    options: _Options = _Options()


@dataclass(frozen=True)
class _Record:
    simulation: _Simulation
    grasp: _Grasp


def test_every_declared_per_mass_list_is_resized_not_only_friction(monkeypatch):
    """per_mass_changes goes over the schema's declaration: a second per-mass list declared there is
    resized the same way (a record whose attributes follow the declared paths)."""
    import analysis.profiles.schema as schema

    extra = ("$.grasp.weights", Field("weights", "numbers", name="weights", length=schema.PER_MASS, empty_ok=True))
    monkeypatch.setattr(schema, "PER_MASS_LISTS", (*schema.PER_MASS_LISTS, extra))
    record = _Record(_Simulation(_Options((0.0, 1.0, 0.0, 0.5))), _Grasp((1.0, 2.0, 3.0, 4.0)))
    changes = per_mass_changes(record, 3, removed=1)  # type: ignore[arg-type]
    assert changes == {"simulation": _Simulation(_Options((0.0, 0.0, 0.5))), "grasp": _Grasp((1.0, 3.0, 4.0))}
    grown = dataclasses.replace(record, grasp=_Grasp(()))  # an empty list stays empty
    assert per_mass_changes(grown, 5) == {"simulation": _Simulation(_Options((0.0, 1.0, 0.0, 0.5, 0.0)))}  # type: ignore[arg-type]


# -- the Profile's own check ---------------------------------------------------------------------------


def test_a_profile_refuses_a_device_its_friction_does_not_fit(hbfd):
    three = without(hbfd.device, 3)
    with pytest.raises(ValidationError) as info:
        hbfd.replace(device=three)  # the script of the issue: the simulator then failed with no path
    err = info.value
    assert err.field == "friction" and list(err.value) == list(HBFD_FRICTION)
    mapped = error_at(err)
    assert isinstance(mapped, ProfileError) and mapped.json_path == FRICTION
    assert str(mapped) == f"{FRICTION}: {LOADER_TEXT}, got a list of 4 items"  # the loader's own words
    with pytest.raises(ValidationError, match="friction"):
        dataclasses.replace(hbfd, device=with_more(hbfd.device, 1))


def test_the_loader_and_the_profile_say_the_same(hbfd):
    data = profile_to_dict(hbfd.replace(device=without(hbfd.device, 0), **per_mass_changes(hbfd, 3, removed=0)))
    data["simulation"]["options"]["friction"] = list(HBFD_FRICTION)
    with pytest.raises(ProfileError) as info:
        profile_from_dict(data)
    assert info.value.json_path == FRICTION and str(info.value) == f"{FRICTION}: {LOADER_TEXT}, got a list of 4 items"


def test_an_empty_list_fits_every_device_and_a_fitting_list_is_accepted(hbfd):
    none = hbfd.replace(simulation=SimulationSection(options=hbfd.simulation.options.replace(friction=()),
                                                     scenario=hbfd.simulation.scenario))
    for dev in (without(hbfd.device, 2), with_more(hbfd.device, 2)):
        assert none.replace(device=dev).device.n == dev.n
    three = without(hbfd.device, 2)
    p = hbfd.replace(device=three, simulation=SimulationSection(
        options=hbfd.simulation.options.replace(friction=(0.2, 0.0, 0.1)), scenario=hbfd.simulation.scenario))
    assert _friction_lists(p) == {FRICTION: (0.2, 0.0, 0.1)}
