"""The uncertain parameters' table: every entry is a scenario setting at its scenario
default, its range lies inside the setting's declared range and brackets the default, each
end loads as a scenario, and docs/model.md shows the table generated from the data."""

import pathlib

import pytest

from tegrasp_drake.events.extraction import DEFAULT_WINDOW_S
from tegrasp_drake.scenario.scenario import LoadScenario, sample_rates_hz, scenario_to_yaml
from tegrasp_drake.tactile.sampling import samples_per_window
from tegrasp_drake.sensitivity.parameters import (UNCERTAIN_PARAMETERS, documented_table,
                                                  parameter, parameters_markdown,
                                                  scenario_setting)

ROOT = pathlib.Path(__file__).resolve().parents[2]
PARAMETERS = pytest.mark.parametrize("entry", UNCERTAIN_PARAMETERS, ids=lambda p: p.key)


@PARAMETERS
def test_each_parameter_is_a_scenario_setting_at_its_default(entry):
    value, declared = scenario_setting(LoadScenario(), entry.key)
    assert declared is not None, f"{entry.key} declares no validation range"
    assert value == pytest.approx(entry.default, rel=1e-12)


@PARAMETERS
def test_each_parameter_set_to_its_default_with_its_partners_is_the_default_scenario(entry):
    """The table's default is the scenario's, and so are its partners' values there: the
    study's default point and a point at the default are one world."""
    assert scenario_to_yaml(LoadScenario(overrides=entry.assignments(entry.default))) == \
        scenario_to_yaml(LoadScenario())


@PARAMETERS
def test_each_range_lies_inside_the_validation_range_and_brackets_the_default(entry):
    _, declared = scenario_setting(LoadScenario(), entry.key)
    assert entry.low < entry.high
    assert entry.low <= entry.default <= entry.high
    assert declared.contains(entry.low) and declared.contains(entry.high)
    assert entry.kind in ("datasheet", "paper", "handbook", "closed-form estimate")
    assert entry.source


@PARAMETERS
def test_each_end_loads_as_a_scenario_with_the_setting_there(entry):
    for end in (entry.low, entry.high):
        scenario = LoadScenario(overrides=entry.assignments(end))
        assert scenario_setting(scenario, entry.key)[0] == pytest.approx(end, rel=1e-12)


@PARAMETERS
def test_each_end_fills_the_event_window_with_whole_samples(entry):
    """The memorized events' 0.5 s window holds a whole number of samples of each stream
    at either end (the matcher refuses a trial otherwise)."""
    for end in (entry.low, entry.high):
        scenario = LoadScenario(overrides=entry.assignments(end))
        for rate_hz in sample_rates_hz(scenario):
            assert samples_per_window(DEFAULT_WINDOW_S, rate_hz) >= 2


def test_the_model_page_shows_the_table_generated_from_the_data():
    text = (ROOT / "docs" / "model.md").read_text(encoding="utf-8")
    assert documented_table(text) == parameters_markdown(), (
        "run python -m tegrasp_drake.sensitivity.parameters --write docs/model.md")


def test_a_discrete_setting_takes_its_choices_a_stepped_one_its_steps_partners_follow():
    decimation = parameter("tactile.capacitive.decimation")
    assert [decimation.at_fraction(u) for u in (0.0, 0.49, 0.5, 0.99)] == [64, 64, 128, 128]
    assert decimation.assignments(128) == ("tactile.capacitive.decimation=128",
                                           "tactile.sample_rate_hz=54.0")
    latency = parameter("arm.command_latency_s")
    assert latency.at_fraction(0.41) == pytest.approx(0.015)  # 0.01525 on the 1 ms grid
    modulus = parameter("tactile.pad_modulus_pa")  # the film's stiffness follows it when built
    assert modulus.assignments(4.0e6) == ("tactile.pad_modulus_pa=4000000.0",)
    film = parameter("vibration.film.film_charge_gain_c_per_m")
    (assignment,) = film.assignments(1e-6)
    assert LoadScenario(overrides=[assignment]).vibration.film.film_charge_gain_c_per_m \
        == pytest.approx(1e-6)


def test_an_unknown_key_is_named_with_the_known_ones():
    with pytest.raises(KeyError, match="gripper.position_loop_hz"):
        parameter("gripper.pad_length")
