"""Memorized corrective triggers: the pure decisions, the switch, the committed
corrective events matched by the EventMatcher on recorded held-out runs, and the slip's
physical event. The recorded channels are tests/data/corrective_windows.npz
(analysis/make_corrective_test_windows.py: held-out runs that made no template)."""

import dataclasses
import pathlib
import types

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (GraspControllerConfig,
                                                     MemorizedCorrectiveConfig)
from tegrasp_drake.control.corrective_actions import (Counters, avoid_on_hit_event,
                                                      lift_load_on_slip_event)
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.grasp_state_machine import GraspStateMachine
from tegrasp_drake.control.transition_logic import Observation, next_mode
from tegrasp_drake.events import EventMatcherConfig, replay_event_held
from tegrasp_drake.events.extraction import TactileTrial
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
from tegrasp_drake.recording.corrective_events import CORRECTIVE_RUNS, slip_onset_time
from tegrasp_drake.scenario.scenario import LoadScenario, grasp_plan
from tegrasp_drake.rig.typed_yaml import ConfigError

# The recorded held-out windows (tests/data) were simulated on the prismatic hand: they are
# matched against that hand's corrective events.
EVENTS = pathlib.Path(__file__).parents[2] / "events" / "prismatic" / "corrective"
WINDOWS = pathlib.Path(__file__).parents[1] / "data" / "corrective_windows.npz"
CONFIG = GraspControllerConfig()
MEMORIZED_HIT = dataclasses.replace(CONFIG, memorized_corrective=MemorizedCorrectiveConfig(
    events=["hold_avoid"]))
HELD_OUT_HIT_S = 7.4  # the held-out hit of the recorded windows (tests/data), at 7.4 s


def decide(mode, config, **fields):
    return next_mode(mode, Observation(contact=(True, True), **fields), Counters(), config,
                     event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)


def test_a_memorized_hit_event_avoids_once_the_window_is_clear_of_the_stop():
    decision = avoid_on_hit_event(True, CONFIG.memorized_corrective.hit_armed_s, Counters(), CONFIG)
    assert (decision.mode, decision.trigger) == (Mode.AVOID, Trigger.CORRECTIVE_EVENT)
    # The heuristic's refractory time is not enough: the window still holds the stop.
    assert avoid_on_hit_event(True, CONFIG.avoid.hit_refractory_s + 0.2, Counters(), CONFIG) is None
    assert avoid_on_hit_event(False, 1.0, Counters(), CONFIG) is None
    no_avoid = dataclasses.replace(CONFIG, avoid=dataclasses.replace(CONFIG.avoid, enabled=False))
    assert avoid_on_hit_event(True, 1.0, Counters(), no_avoid) is None
    used_up = Counters(avoids=CONFIG.avoid.max_avoids)
    assert avoid_on_hit_event(True, 1.0, used_up, CONFIG) is None


def test_a_memorized_slip_event_lift_loads_until_they_are_used_up():
    decision = lift_load_on_slip_event(True, Counters(), CONFIG)
    assert (decision.mode, decision.trigger) == (Mode.LOAD, Trigger.CORRECTIVE_EVENT)
    assert lift_load_on_slip_event(False, Counters(), CONFIG) is None
    used_up = lift_load_on_slip_event(True, Counters(lift_loads=CONFIG.lift_load.max_lift_loads), CONFIG)
    assert used_up.mode == Mode.FAILED
    assert lift_load_on_slip_event(
        True, Counters(), dataclasses.replace(
            CONFIG, lift_load=dataclasses.replace(CONFIG.lift_load, enabled=False))) is None


def test_the_switch_selects_the_trigger_of_each_corrective_event():
    # Heuristic (the default): the RA threshold's hit; the corrective matcher is not read.
    assert decide(Mode.HOLD, CONFIG, time_in_mode=1.0, hit=True).mode == Mode.AVOID
    assert decide(Mode.HOLD, CONFIG, time_in_mode=1.0, corrective_event_matched=True) is None
    # Memorized hit: the other way round; the slip stays heuristic.
    assert decide(Mode.HOLD, MEMORIZED_HIT, time_in_mode=1.0, hit=True) is None
    assert decide(Mode.HOLD, MEMORIZED_HIT, time_in_mode=1.0,
                  corrective_event_matched=True).trigger == Trigger.CORRECTIVE_EVENT
    assert decide(Mode.LIFT, MEMORIZED_HIT, slip_s=CONFIG.lift_load.slip_s).trigger == Trigger.CORRECTIVE
    memorized_slip = dataclasses.replace(CONFIG, memorized_corrective=MemorizedCorrectiveConfig(
        events=["lift_load"]))
    assert decide(Mode.LIFT, memorized_slip, slip_s=CONFIG.lift_load.slip_s) is None
    assert decide(Mode.LIFT, memorized_slip,
                  corrective_event_matched=True).trigger == Trigger.CORRECTIVE_EVENT


def test_the_switch_names_a_bad_event_and_needs_the_events():
    with pytest.raises(ConfigError, match=r"controller.memorized_corrective.events\[0\]"):
        LoadScenario(overrides=["controller.memorized_corrective.events=[hold_hit]"])
    with pytest.raises(ValueError, match="hold_avoid"):
        GraspStateMachine(plan=grasp_plan(LoadScenario()), config=MEMORIZED_HIT,
                          event_indices={"reach_load": 0, "load_lift": 1, "place_unload": 2},
                          event_trigger=Trigger.MEMORIZED_EVENT)


def _recorded(name) -> TactileTrial:
    data = np.load(WINDOWS)
    start = float(data[f"{name}_t_ra"][0])  # replays start at 0
    return TactileTrial(t_sa=data[f"{name}_t_sa"] - start, sa=data[f"{name}_sa"],
                        t_ra=data[f"{name}_t_ra"] - start, ra=data[f"{name}_ra"],
                        transition_times={}), start


def _match_rises(name, transition, thresholds):
    events = load_memorized_events(EVENTS, "box", required=CORRECTIVE_TRANSITIONS)
    trial, start = _recorded(name)
    config = EventMatcherConfig(event_thresholds={transition: tuple(thresholds)})
    replay = replay_event_held(trial, {transition: events[transition]}, transition,
                               config=config)
    full = replay.times >= events[transition].window_s  # a full window was sampled
    on = (replay.match > 0.5) & full
    rises = replay.times[on & ~np.concatenate([[False], on[:-1]])]
    return rises + start


def test_the_hit_event_matches_a_held_out_hit_and_no_normal_hold():
    rises = _match_rises("hit", "hold_avoid", CONFIG.memorized_corrective.hold_avoid_thresholds)
    assert rises.size >= 1
    assert 0.0 <= rises[0] - HELD_OUT_HIT_S <= 0.06  # the hit matched within 60 ms
    assert _match_rises("normal_hold", "hold_avoid", CONFIG.memorized_corrective.hold_avoid_thresholds).size == 0


def test_the_slip_event_also_matches_a_normal_lift():
    # Why lift_load stays heuristic (docs/controller.md): Eq. 3 is scale invariant, and the film's
    # signal around a slip has the shape of any lift's; the slip differs in amplitude.
    assert _match_rises("normal_lift", "lift_load", CONFIG.memorized_corrective.lift_load_thresholds).size


def _slow_log(name):
    data = np.load(WINDOWS)
    return types.SimpleNamespace(t_slow=data[f"{name}_t_slow"], arm_q=data[f"{name}_arm_q"],
                                 object_state=data[f"{name}_object_state"])


def test_slip_onset_is_found_in_a_slip_run_and_not_in_a_normal_lift():
    # The recorded windows' script had a 1.3 s Load phase: its Lift began at 4.1 s.
    scenario = LoadScenario(name="box", overrides=["grasp.load_s=1.3"])
    assert slip_onset_time(_slow_log("normal_lift"), scenario) is None
    onset = slip_onset_time(_slow_log("slip"), scenario)
    lift_start = 4.1
    assert onset is not None and lift_start < onset < lift_start + 0.5


def test_the_corrective_runs_have_template_and_held_out_runs_of_each_event():
    for transition in CORRECTIVE_TRANSITIONS:
        roles = {run.role for run in CORRECTIVE_RUNS if run.transition == transition}
        assert roles == {"template", "held_out"}
    assert len({run.seed for run in CORRECTIVE_RUNS}) == len(CORRECTIVE_RUNS)


def test_a_memorized_hits_baseline_is_the_sa_before_the_match():
    from tegrasp_drake.control.corrective_actions import hit_baseline_history
    history = ()
    for k in range(20):  # 5 ms ticks, SA rising 1 N a tick
        history = hit_baseline_history(history, (float(k), 2.0 * k), 0.06, 0.005)
    assert len(history) == 13  # 60 ms back, and now
    assert history[0] == (7.0, 14.0) and history[-1] == (19.0, 38.0)


def test_an_object_without_corrective_events_names_the_command(tmp_path):
    from tegrasp_drake.scenario.scenario_events import load_corrective_events
    from tegrasp_drake.events import MemorizedEventError
    scenario = LoadScenario(name="custom_can", overrides=[
        "controller.name=heuristic", "controller.memorized_corrective.events=[hold_avoid]"])
    with pytest.raises(MemorizedEventError, match="record_corrective_events.py"):
        load_corrective_events(scenario, tmp_path)


def test_the_boxs_corrective_events_load_for_the_box():
    from tegrasp_drake.scenario.scenario_events import load_corrective_events
    events = load_corrective_events(LoadScenario(name="box"),
                                    EVENTS.parent)  # the package's events folder
    assert set(events) == set(CORRECTIVE_TRANSITIONS)
