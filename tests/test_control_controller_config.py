"""Each controller's settings are its own config class, selected by the YAML tag of the
scenario's `controller` field (or the shorthand controller.name)."""

import pytest

from tegrasp_drake.control.controller_config import (
    AvoidConfig, HeuristicControllerConfig, MemorizedControllerConfig, OpenLoopControllerConfig,
    TaxelAwareControllerConfig)
from tegrasp_drake.control.controller_registry import (CONTROLLER_CLASSES, CONTROLLER_NAMES,
                                                       controller_named)
from tegrasp_drake.scenario.scenario import (LoadScenario, scenario_from_yaml, scenario_to_yaml,
                                             with_controller)


def test_the_default_is_the_papers_algorithm():
    assert isinstance(LoadScenario().controller, MemorizedControllerConfig)
    assert CONTROLLER_NAMES[:4] == ("memorized", "heuristic", "open_loop", "taxel_aware")


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
    heuristic = HeuristicControllerConfig(avoid=AvoidConfig(hit_ra_mps2=5.0))
    taxel = controller_named("taxel_aware", like=heuristic)
    assert isinstance(taxel, TaxelAwareControllerConfig) and taxel.avoid.hit_ra_mps2 == 5.0
    taxel.avoid.hit_ra_mps2 = 4.0  # its own section, not the one it was made like
    assert heuristic.avoid.hit_ra_mps2 == 5.0
    scenario = with_controller(LoadScenario(), "open_loop")
    assert scenario.controller == OpenLoopControllerConfig()
    assert with_controller(scenario, "memorized").controller == MemorizedControllerConfig()


def _memorized_scenario_file(tmp_path, settings="{event_object_may_differ: [mass], "
                                              "matching: {sa_threshold: 0.8}}"):
    path = tmp_path / "scenarios.yaml"
    path.write_text(f"tuned:\n  controller: !MemorizedControllerConfig {settings}\n")
    return path


def test_another_controller_runs_a_scenario_with_the_settings_it_shares(tmp_path):
    ignored = []
    scenario = LoadScenario(_memorized_scenario_file(tmp_path), "tuned",
                            controller="heuristic", on_ignored=ignored.append)
    assert isinstance(scenario.controller, HeuristicControllerConfig)
    assert scenario.controller.event_object_may_differ == ["mass"]  # shared: kept
    assert ignored == [["matching.sa_threshold"]]  # the memorized controllers' own: named


def test_the_open_loop_controller_ignores_every_closed_loop_setting(tmp_path):
    ignored = []
    scenario = LoadScenario(_memorized_scenario_file(tmp_path), "tuned",
                            controller="open_loop", on_ignored=ignored.append)
    assert scenario.controller == OpenLoopControllerConfig()
    assert ignored == [["event_object_may_differ", "matching.sa_threshold"]]


def test_nothing_is_named_when_nothing_is_ignored(tmp_path):
    ignored = []
    LoadScenario(_memorized_scenario_file(tmp_path, "{matching: {sa_threshold: 0.8}}"),
                 "tuned", controller="taxel_aware", on_ignored=ignored.append)
    assert ignored == []


def test_a_setting_of_no_controller_is_still_refused_with_another_controller(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    path = _memorized_scenario_file(tmp_path, "{sa_treshold: 0.8}")
    with pytest.raises(ConfigError, match="controller.sa_treshold"):
        LoadScenario(path, "tuned", controller="open_loop")


def test_the_command_line_names_the_ignored_settings_in_one_line(tmp_path, capsys):
    import argparse
    from tegrasp_drake.commands.scenario_args import scenario_from_arguments
    args = argparse.Namespace(scenario=str(_memorized_scenario_file(tmp_path)),
                              scenario_name="tuned", overrides=[], controller="open_loop")
    assert scenario_from_arguments(args).controller == OpenLoopControllerConfig()
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1
    assert "--controller open_loop ignores" in lines[0]
    assert "event_object_may_differ, matching.sa_threshold" in lines[0]
