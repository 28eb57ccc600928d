"""The events a scenario's controller reads: the hand they were recorded on, and the warning
when it is not the scenario's."""

import dataclasses
import logging

import pytest

from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.scenario.scenario_events import (another_worlds_events,
                                                    load_controller_events, recorded_hand)
from tegrasp_drake.sweep.trial_function import check_sweep_events


def test_each_packaged_event_names_the_hand_it_was_recorded_on():
    linkage = load_controller_events(LoadScenario())
    prismatic = load_controller_events(LoadScenario(), paths.package_events_dir() / "prismatic")
    assert {recorded_hand(e) for e in linkage.values()} == {"linkage"}
    # Recorded before the hand was a setting: the prismatic fingers were the only hand.
    assert {recorded_hand(e) for e in prismatic.values()} == {"prismatic"}
    note = dataclasses.replace(next(iter(linkage.values())), scenario="run0 seed 7; mean of 8")
    assert recorded_hand(note) is None


def test_events_of_another_hand_give_a_warning_naming_both_hands():
    scenario = LoadScenario()  # the linkage hand
    prismatic = load_controller_events(scenario, paths.package_events_dir() / "prismatic")
    warning = another_worlds_events(scenario, prismatic)
    assert "'box' were recorded on the prismatic hand" in warning
    assert "matched on the linkage hand" in warning
    assert another_worlds_events(scenario, load_controller_events(scenario)) is None
    on_prismatic = LoadScenario(overrides=["gripper.model=prismatic"])
    assert another_worlds_events(on_prismatic, prismatic) is None



@pytest.mark.parametrize("setting, recorded, live", [
    ("tactile.transducer", "capacitive taxels", "force taxels"),
    ("vibration.transducer", "film RA transducer", "accelerometer RA transducer"),
])
def test_events_recorded_through_other_transducers_give_a_warning_naming_both(setting, recorded,
                                                                              live):
    # The package's events were recorded in the default world (capacitive taxels, the film).
    events = load_controller_events(LoadScenario())
    value = live.split()[0]
    scenario = LoadScenario(overrides=[f"{setting}={value}"])
    warning = another_worlds_events(scenario, events)
    assert f"'box' were recorded with {recorded} and are matched with {live}" in warning
    assert "\n" not in warning

def test_a_sweep_warns_once_before_it_runs_when_its_events_are_another_hands(caplog):
    trial = {"trial_id": "memorized/box/m00/a0", "controller": "memorized",
             "object_name": "box", "object_definition": None, "marker": "m00",
             "marker_dx_m": 0.0, "marker_dy_m": 0.0, "attempt": 0, "seed": 1,
             "base_seed": 600, "pair_id": "box/m00/a0", "well_placed": True,
             "sensor_noise": True, "scenario_overrides": [],
             "perturbation": {"dx_m": 0.0, "dy_m": 0.0, "yaw_rad": 0.0,
                              "friction_scale": 1.0, "mass_scale": 1.0}}
    with caplog.at_level(logging.WARNING):
        check_sweep_events([trial, dict(trial, attempt=1)],
                           paths.package_events_dir() / "prismatic")
    assert [r.levelno for r in caplog.records] == [logging.WARNING]
    assert "recorded on the prismatic hand" in caplog.records[0].getMessage()
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        check_sweep_events([trial])
    assert not caplog.records


def test_a_recorded_scenario_is_read_as_every_scenario_is():
    event = next(iter(load_controller_events(LoadScenario()).values()))
    tagged = "gripper: {model: prismatic}\nstation: !SimStationConfig {}\n"
    assert recorded_hand(dataclasses.replace(event, scenario=tagged)) == "prismatic"
    assert recorded_hand(dataclasses.replace(event, scenario="")) is None
    assert recorded_hand(dataclasses.replace(event, scenario="note: a: b")) is None  # not YAML


def test_a_recorded_scenario_past_the_readers_limits_is_a_one_line_error_naming_the_event():
    event = next(iter(load_controller_events(LoadScenario()).values()))
    for text, words in [("gripper: {model: linkage}\ngripper: {model: prismatic}\n",
                         "key 'gripper' appears twice"),
                        ("a: !!python/object:os.system {}\n", "a Python object tag")]:
        with pytest.raises(ConfigError) as error:
            recorded_hand(dataclasses.replace(event, scenario=text))
        assert f"memorized event {event.relative_path()}" in str(error.value)
        assert words in str(error.value) and "\n" not in str(error.value)
