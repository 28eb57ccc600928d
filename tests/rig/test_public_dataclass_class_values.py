"""A public dataclass's ClassVar (a controller config's name) belongs to its class: setting it
on an instance, or giving it to the constructor, is refused in one line naming it."""

import dataclasses

import pytest

from tegrasp_drake.control.controller_config import HeuristicControllerConfig


def test_a_class_value_cannot_be_set_on_an_instance():
    config = HeuristicControllerConfig()
    with pytest.raises(AttributeError) as refused:
        config.name = "memorized"
    message = str(refused.value)
    assert "\n" not in message and message.startswith(
        "HeuristicControllerConfig.name belongs to the class ('heuristic')"), message
    assert HeuristicControllerConfig().name == config.name == "heuristic"
    with pytest.raises(TypeError, match=r"HeuristicControllerConfig\.name belongs to the class"):
        HeuristicControllerConfig(name="memorized")


def test_a_fields_list_names_no_class_value():
    with pytest.raises(AttributeError) as refused:
        HeuristicControllerConfig().q = 1
    fields = str(refused.value).split("its fields: ")[1].split(", ")
    assert "heuristic" in fields and "name" not in fields and "events_folder" not in fields
    assert "heuristic" in {field.name for field in dataclasses.fields(HeuristicControllerConfig)}

