"""Each controller's settings are its own config class, selected by the YAML tag of the
scenario's `controller` field (or the shorthand controller.name)."""

import pytest

from tegrasp_drake.control.controller_config import (
    CONTROLLER_CLASSES, CONTROLLER_NAMES, HeuristicControllerConfig, MemorizedControllerConfig,
    OpenLoopControllerConfig, TaxelAwareControllerConfig, controller_named)
from tegrasp_drake.scenario.scenario import (LoadScenario, scenario_from_yaml, scenario_to_yaml,
                                             with_controller)


def test_the_default_is_the_papers_algorithm():
    assert isinstance(LoadScenario().controller, MemorizedControllerConfig)
    assert CONTROLLER_NAMES == ("memorized", "heuristic", "open_loop", "taxel_aware")


def test_a_yaml_tag_selects_the_controller_and_its_settings(tmp_path):
    path = tmp_path / "scenarios.yaml"
    path.write_text("tilted:\n  controller: !TaxelAwareControllerConfig\n"
                    "    taxel_aware: {tilt_limit_deg: 0.2}\n"
                    "plain:\n  controller: !HeuristicControllerConfig {}\n")
    tilted = LoadScenario(path, "tilted").controller
    assert isinstance(tilted, TaxelAwareControllerConfig)
    assert tilted.taxel_aware.tilt_limit_deg == 0.2
    assert isinstance(LoadScenario(path, "plain").controller, HeuristicControllerConfig)


@pytest.mark.parametrize("cls", CONTROLLER_CLASSES)
def test_each_controller_round_trips_through_its_yaml(cls):
    scenario = LoadScenario(controller=cls.name)
    assert type(scenario.controller) is cls
    assert scenario_from_yaml(scenario_to_yaml(scenario)).controller == scenario.controller


def test_the_name_shorthand_selects_the_same_class():
    scenario = LoadScenario(overrides=["controller.name=open_loop"])
    assert scenario.controller == OpenLoopControllerConfig()


def test_a_log_with_one_flat_controller_section_loads_as_its_controller():
    """A log written when one config served every controller: its name selects the class,
    the other controllers' settings are dropped."""
    text = scenario_to_yaml(LoadScenario(name="box")).replace(
        "controller:\n", "controller:\n  name: taxel_aware\n  heuristic: {contact_force_n: 1.0}\n")
    assert isinstance(scenario_from_yaml(text).controller, TaxelAwareControllerConfig)


def test_switching_controllers_keeps_the_settings_they_share():
    taxel = controller_named("taxel_aware", like=HeuristicControllerConfig(hit_ra_mps2=5.0))
    assert isinstance(taxel, TaxelAwareControllerConfig) and taxel.hit_ra_mps2 == 5.0
    scenario = with_controller(LoadScenario(), "open_loop")
    assert scenario.controller == OpenLoopControllerConfig()
    assert with_controller(scenario, "memorized").controller == MemorizedControllerConfig()
