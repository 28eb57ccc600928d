"""A configuration list that names things (corrective events, object fields) names each once:
a repeated name is refused at load naming the field and the name (rig.ranges.distinct_names),
and every such list reachable from a Scenario or a hardware config is declared so."""

import pytest

from tegrasp_drake.hardware.config import HardwareStationConfig
from tegrasp_drake.rig.ranges import undeclared_name_lists
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario import LoadScenario
from tegrasp_drake.scenario.scenario import Scenario


@pytest.mark.parametrize("field, names", [
    ("controller.memorized_corrective.events", "[hold_avoid,hold_avoid]"),
    ("controller.memorized_corrective.events", "[lift_load,hold_avoid,lift_load]"),
    ("controller.event_object_may_differ", "[friction,mass,friction]")])
def test_a_name_listed_twice_is_refused_naming_field_and_name(field, names):
    repeated = names.strip("[]").split(",")[-1]
    with pytest.raises(ConfigError, match=f"field '{field}' names '{repeated}' twice"):
        LoadScenario(overrides=[f"{field}={names}"])


def test_distinct_names_load():
    scenario = LoadScenario(overrides=[
        "controller.memorized_corrective.events=[hold_avoid,lift_load]"])
    assert scenario.controller.memorized_corrective.events == ["hold_avoid", "lift_load"]


def test_every_list_of_names_in_the_configs_refuses_a_repeated_name():
    assert undeclared_name_lists(Scenario, HardwareStationConfig) == []
