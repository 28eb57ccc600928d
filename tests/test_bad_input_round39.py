"""Public constructors and builders refuse what the loaders refuse: a choice field handed to
a builder, a transition that does not change mode, a result's latency longer than any run."""

import pytest

from tegrasp_drake.rig.typed_yaml import ConfigError


# Rule: a builder given a config checks its choices as the loader does, not only its ranges
# (scheduling='rr' went on to open the devices).
@pytest.mark.parametrize("mutate", [False, True], ids=["built", "changed-after"])
def test_a_hardware_config_with_an_unknown_scheduling_is_refused_by_the_builder(mutate):
    from tegrasp_drake import MakeHardwareStation
    from tegrasp_drake.hardware.config import HardwareStationConfig
    with pytest.raises(ConfigError, match="field 'scheduling' must be one of 'fifo', 'nice', "
                                          "'normal', got str 'rr'"):
        if mutate:
            config = HardwareStationConfig()
            config.scheduling = "rr"
        else:
            config = HardwareStationConfig(scheduling="rr")
        MakeHardwareStation(config)


# Rule: a timeline entry leaves one mode for another (no rule's `then` keeps its mode).
def test_a_transition_that_keeps_its_mode_is_refused():
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    with pytest.raises(ConfigError, match="Transition: field 'to_mode' must differ from "
                                          "'from_mode'"):
        Transition(t=1.0, from_mode=Mode.LOAD, to_mode=Mode.LOAD, trigger=Trigger.TIMER,
                   reason="x")


# Rule: without sim_time_s, a time of a result is still bounded by the longest run a trial
# can last (the longest grasp script plus the time for corrections).
# (A latency far below zero meets the stricter rule first: no detection is earlier than its
# physical event by more than the false-trigger margin.)
@pytest.mark.parametrize("field, value, words", [
    ("detection_latency_s", {"reach_load": 1e300}, "the longest run a trial can last"),
    ("detection_latency_s", {"reach_load": -1e300}, "at least -0.01 s"),
    ("physical_events", {"hit": 1e300}, "the longest run a trial can last"),
])
def test_a_result_time_longer_than_any_run_is_refused_without_sim_time(field, value, words):
    from tegrasp_drake.scenario.trial_result import TrialResult
    key = next(iter(value))
    with pytest.raises(ConfigError, match=f"TrialResult: field '{field}.{key}' must be .*"
                                          f"{words}"):
        TrialResult(**{field: value})


def test_a_result_time_within_the_longest_run_is_accepted_without_sim_time():
    from tegrasp_drake.scenario.trial_result import TrialResult
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    detected = Transition(1.0, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "Reach-Load event")
    result = TrialResult(transitions=(detected,), final_mode=Mode.LOAD,
                         detection_latency_s={"reach_load": 0.2},
                         physical_events={"reach_load": 0.8, "hit": 9.0})
    assert result.detection_latency_s == {"reach_load": 0.2}


def test_a_simulated_time_longer_than_any_run_is_refused():
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ConfigError, match="TrialResult: field 'sim_time_s' must be at most .*"
                                          "the longest run a trial can last"):
        TrialResult(sim_time_s=1e300, detection_latency_s={"reach_load": 1e299})


# Rule: a result's fields are checked for their types before the relations that read them
# (a mapping where a Transition belongs, with sim_time_s set, was an AttributeError).
def test_a_result_with_a_mapping_for_a_transition_names_the_field():
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ConfigError, match=r"TrialResult: field 'transitions\[0\]'"):
        TrialResult(transitions=({"t": 1.0},), sim_time_s=10.0)
