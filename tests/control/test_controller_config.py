"""Each controller's settings are its own config class, selected by the YAML tag of the
scenario's `controller` field (or the shorthand controller.name)."""

import dataclasses
import typing

import pytest

from tegrasp_drake.control.controller_config import (
    AvoidConfig, HeuristicControllerConfig, LiftLoadConfig, MemorizedControllerConfig,
    MemorizedCorrectiveConfig, OpenLoopControllerConfig, PlaceConfig, ReReachConfig,
    TaxelAwareConfig, TaxelAwareControllerConfig)
from tegrasp_drake.control.controller_registry import (CONTROLLER_CLASSES, CONTROLLER_NAMES,
                                                       controller_class, controller_named)
from tegrasp_drake.rig.event_matching import EventMatchingConfig
from tegrasp_drake.rig.ranges import check_ranges
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import (LoadScenario, scenario_from_yaml, scenario_to_yaml,
                                             with_controller)
from tests.rig.test_api_boundary import assignment_error_in_a_fresh_interpreter


def test_the_default_is_the_papers_algorithm():
    assert isinstance(LoadScenario().controller, MemorizedControllerConfig)
    assert CONTROLLER_NAMES[:4] == ("memorized", "heuristic", "open_loop", "taxel_aware")


def test_a_yaml_tag_selects_the_controller_and_its_settings(tmp_path):
    path = tmp_path / "scenarios.yaml"
    path.write_text("tilted:\n  controller: !TaxelAwareControllerConfig\n"
                    "    taxel_aware: {regrasp: {tilt_limit_deg: 0.2}}\n"
                    "plain:\n  controller: !HeuristicControllerConfig {}\n")
    tilted = LoadScenario(path, "tilted").controller
    assert isinstance(tilted, TaxelAwareControllerConfig)
    assert tilted.taxel_aware.regrasp.tilt_limit_deg == 0.2
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


# ---- Each section of the settings: its ranges and what relates its fields ---------------

def _refused(config, words: str) -> None:
    """check_ranges refuses `config` with `words` in its one-line message."""
    with pytest.raises(ConfigError) as refused:
        check_ranges(config, "here")
    assert words in str(refused.value) and "\n" not in str(refused.value)


def test_re_reach_settings_declare_their_units_and_ranges():
    assert check_ranges(ReReachConfig(), "here") is None
    _refused(ReReachConfig(opened_m=0.09), "field 'opened_m' must lie in [0, 0.085] m (the "
             "2F-85's 85 mm stroke)")
    _refused(ReReachConfig(max_re_reaches=-1), "field 'max_re_reaches' must be zero or positive")


def test_lift_load_settings_declare_their_ranges_and_keep_the_band_below_half_the_ra_rate():
    _refused(LiftLoadConfig(force_factor=0.5), "field 'force_factor' must be at least 1")
    _refused(LiftLoadConfig(max_grip_force_n=300.0), "the 2F-85 grips with 20 to 235 N")
    assert LiftLoadConfig().problem(ra_rate_hz=1000.0) is None
    field, words, value = LiftLoadConfig().problem(ra_rate_hz=100.0)
    assert (field, value) == ("slip_band_hz", 80.0) and "half the RA rate (50 Hz" in words


def test_avoid_and_place_settings_declare_their_units_and_ranges():
    _refused(AvoidConfig(distance_m=1.0), "field 'distance_m' must lie in [0, 0.3] m")
    _refused(AvoidConfig(hit_ra_sigmas=-1.0), "field 'hit_ra_sigmas' must be zero (the number "
             "alone) or positive [noise sigmas]")
    _refused(PlaceConfig(event_timeout_s=-1.0), "field 'event_timeout_s' must be positive [s]")
    _refused(PlaceConfig(event_timeout_s=0.0), "field 'event_timeout_s' must be positive [s]")


def test_memorized_corrective_settings_name_corrective_events_and_pairs_of_scores():
    _refused(MemorizedCorrectiveConfig(hold_avoid_thresholds=[0.4, 0.4, 0.4]),
             "field 'hold_avoid_thresholds' must hold 2 numbers")
    _refused(MemorizedCorrectiveConfig(lift_load_thresholds=[0.4, 1.5]),
             "field 'lift_load_thresholds[1]' must lie in [-1, 1] (Eq. 3 scores")
    assert MemorizedCorrectiveConfig(events=["hold_avoid", "lift_load"]).problem() is None
    field, words, value = MemorizedCorrectiveConfig(events=["hold_avoid", "hold_hit"]).problem()
    assert (field, value) == ("events[1]", "hold_hit") and "corrective event" in words


def test_the_controller_names_a_sections_problem_by_its_path():
    config = MemorizedControllerConfig(
        memorized_corrective=MemorizedCorrectiveConfig(events=["hold_hit"]))
    assert config.problem(ra_rate_hz=1000.0, approach_s=2.8)[0] == \
        "memorized_corrective.events[0]"
    config = MemorizedControllerConfig(matching=EventMatchingConfig(ra_envelope_hz=600.0))
    assert config.problem(ra_rate_hz=1000.0, approach_s=2.8)[0] == "matching.ra_envelope_hz"
    config = HeuristicControllerConfig(event_object_may_differ=["colour"])
    assert config.problem(ra_rate_hz=1000.0, approach_s=2.8)[:3:2] == (
        "event_object_may_differ[0]", "colour")
    config = HeuristicControllerConfig(sensor_block_s=0.025)  # 25 samples at 1 kHz
    assert config.problem(ra_rate_hz=1000.0, approach_s=2.8)[0] == "sensor_block_s"
    assert MemorizedControllerConfig().problem(ra_rate_hz=1000.0, approach_s=2.8) is None


def test_a_sections_problem_reaches_the_user_by_its_scenario_path():
    with pytest.raises(ConfigError, match=r"field 'controller.lift_load.slip_band_hz' must lie "
                       r"below half the RA rate \(50 Hz"):
        LoadScenario(overrides=["vibration.sample_rate_hz=100", "controller.matching."
                                "ra_noise_quiet_s=0.5"])


def test_no_controller_config_class_holds_more_than_15_fields():
    classes = [controller_class(name) for name in CONTROLLER_NAMES]
    sections = {hint for cls in classes for hint in typing.get_type_hints(cls).values()
                if dataclasses.is_dataclass(hint)}
    for cls in [*classes, *sections]:
        assert len(dataclasses.fields(cls)) <= 15, cls.__name__


def test_the_taxel_aware_event_thresholds_are_empty_or_pairs():
    assert TaxelAwareConfig(load_lift_thresholds=[0.8, 0.5]).problem() is None
    config = TaxelAwareControllerConfig(taxel_aware=TaxelAwareConfig(load_lift_thresholds=[0.8]))
    field, words, value = config.problem(ra_rate_hz=1000.0, approach_s=2.8)
    assert (field, value) == ("taxel_aware.load_lift_thresholds", [0.8]) and "[SA, RA]" in words


def test_a_moved_setting_names_its_new_path_with_only_this_module_imported():
    """A script that builds a controller config without the scenario package gets the new
    path of a moved setting, not the nearest field's name."""
    out = assignment_error_in_a_fresh_interpreter(
        "tegrasp_drake.control.controller_config", "MemorizedControllerConfig",
        "re_reach_enabled = False")
    assert out == ("MemorizedControllerConfig has no field 're_reach_enabled': it is now "
                   "'re_reach.enabled'")
