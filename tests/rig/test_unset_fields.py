"""Fields whose empty value means "not set": refused when a user writes them empty, left out
of the stored scenario text."""

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_from_yaml, scenario_to_yaml
from tegrasp_drake.sweep.spec_file import LoadSweepSpec


@pytest.mark.parametrize("field, text", [
    ("object.size", "object: {size: []}"),
    ("object.shape", "object: {shape: ''}"),
    ("object.file", "object: {file: ''}"),
    ("object.color", "object: {name: box, color: []}"),
    ("controller.taxel_aware.place_unload_thresholds",
     "controller: {name: taxel_aware, taxel_aware: {place_unload_thresholds: []}}"),
])
def test_an_empty_not_set_field_in_a_hand_written_file_is_refused_by_name(tmp_path, field, text):
    path = tmp_path / "mine.yaml"
    path.write_text(f"mine:\n  {text}\n")
    with pytest.raises(ConfigError) as error:
        LoadScenario(path, name="mine")
    message = str(error.value)
    assert "\n" not in message and str(path) in message
    assert f"field '{field}' is empty: give a value, or leave it out for " in message


def test_an_empty_list_that_is_an_ordinary_value_is_accepted(tmp_path):
    path = tmp_path / "mine.yaml"
    path.write_text("mine:\n  controller: {name: memorized, event_object_may_differ: [],\n"
                    "               memorized_corrective: {events: []}}\n")
    scenario = LoadScenario(path, name="mine")
    assert scenario.controller.event_object_may_differ == []


def test_a_sweep_specs_own_object_with_an_empty_size_is_refused(tmp_path):
    path = tmp_path / "spec.yaml"
    path.write_text("objects: [mug]\nuser_objects:\n  mug: {shape: cylinder, "
                    "size: []}\n")
    with pytest.raises(ConfigError, match=r"size' is empty: give a value"):
        LoadSweepSpec(path)


@pytest.mark.parametrize("name, controller", [("box", "taxel_aware"),
                                              ("thin_cylinder", "memorized")])
def test_the_stored_text_leaves_the_empty_fields_out_and_reads_back(tmp_path, name, controller):
    scenario = LoadScenario(name=name, controller=controller)
    stored = scenario_to_yaml(scenario)
    assert "[]\n" not in stored.replace("event_object_may_differ: []\n", "").replace(
        "events: []\n", "")
    assert scenario_to_yaml(scenario_from_yaml(stored)) == stored
    path = tmp_path / "copied.yaml"
    path.write_text("x:\n" + "".join(f"  {line}\n" for line in stored.splitlines()))
    assert scenario_to_yaml(LoadScenario(path, name="x")) == stored
