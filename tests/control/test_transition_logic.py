"""The paper's rule table (transition_logic.PAPER_TABLE): each rule fires on the situation
it is written for and not on a near miss, and the table exhaustively over its
observations."""

import dataclasses
import itertools

import pytest

from tegrasp_drake.control.controller_config import (GraspControllerConfig,
                                                     MemorizedCorrectiveConfig)
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import (HOLDING_MODES, MAX_REASON_CHARS, TERMINAL_MODES,
                                              Mode, Transition, Trigger)
from tegrasp_drake.control.rule_actions import ReReach
from tegrasp_drake.control.transition_logic import PAPER_TABLE, Observation, next_mode
from tegrasp_drake.hardware.device_fault import DRIVER_ERROR, SILENT, DeviceFault, describe_faults

HOLD_S = 3.0
# Fig. 6b: where each mode may go.
ALLOWED = {Mode.REACH: {Mode.LOAD, Mode.RE_REACH, Mode.FAILED},
           Mode.RE_REACH: {Mode.REACH, Mode.FAILED},
           Mode.LOAD: {Mode.LIFT, Mode.RE_REACH, Mode.FAILED},
           Mode.LIFT: {Mode.LOAD, Mode.HOLD, Mode.FAILED},
           Mode.HOLD: {Mode.AVOID, Mode.PLACE, Mode.FAILED},
           Mode.AVOID: {Mode.HOLD, Mode.FAILED},
           Mode.PLACE: {Mode.UNLOAD, Mode.FAILED},
           Mode.UNLOAD: {Mode.DONE, Mode.FAILED}}
EVENT_TRANSITIONS = {(Mode.REACH, Mode.LOAD), (Mode.LOAD, Mode.LIFT), (Mode.PLACE, Mode.UNLOAD)}


def decide(mode, config=None, counters=Counters(), **fields):
    return next_mode(mode, Observation(**fields), counters, config or GraspControllerConfig(),
                     event_trigger=Trigger.MEMORIZED_EVENT, hold_s=HOLD_S)


CONFIG = GraspControllerConfig()
ONE_SIDED = dict(contact=(False, True), one_sided_s=CONFIG.re_reach.one_sided_contact_s)
HELD = dict(contact=(True, True))
# (rule, mode, the observation it fires on, a near miss, counters, config changes)
CASES = [
    ("device_fault", Mode.HOLD, dict(device_fault="arm silent", **HELD), HELD, Counters(), {}),
    ("gripper_fault", Mode.REACH, dict(gripper_fault="gFLT_0x08"), {}, Counters(), {}),
    ("object_lost", Mode.LIFT, dict(contact=(False, False)), dict(contact=(True, False)),
     Counters(), {}),
    ("reach_event", Mode.REACH, dict(event_matched=True), dict(closing_s=0.5), Counters(), {}),
    ("one_sided", Mode.REACH, ONE_SIDED,
     dict(contact=(False, True), one_sided_s=0.5 * CONFIG.re_reach.one_sided_contact_s), Counters(), {}),
    ("closed_on_nothing", Mode.REACH, dict(closed_on_nothing=True, closing_s=0.5),
     dict(closing_s=0.5), Counters(), {}),
    ("reach_timeout", Mode.REACH, dict(closing_s=CONFIG.re_reach.reach_event_timeout_s),
     dict(closing_s=0.9 * CONFIG.re_reach.reach_event_timeout_s), Counters(), {}),
    ("re_centred", Mode.RE_REACH, dict(motion_done=True), {}, Counters(), {}),
    ("load_lift_event", Mode.LOAD, dict(event_matched=True, **HELD), HELD, Counters(), {}),
    ("relift", Mode.LOAD,
     dict(grip_reached=True, time_in_mode=CONFIG.lift_load.relift_settle_s, **HELD),
     dict(grip_reached=False, time_in_mode=CONFIG.lift_load.relift_settle_s, **HELD),
     Counters(lift_loads=1), {}),
    ("load_timeout", Mode.LOAD, dict(time_in_mode=CONFIG.load_event_timeout_s, **HELD),
     dict(time_in_mode=0.9 * CONFIG.load_event_timeout_s, **HELD), Counters(), {}),
    ("lift_load", Mode.LIFT, dict(slip_s=CONFIG.lift_load.slip_s, **HELD),
     dict(slip_s=0.5 * CONFIG.lift_load.slip_s, **HELD), Counters(), {}),
    ("lift_load", Mode.LIFT, dict(corrective_event_matched=True, slip_s=0.0, **HELD),
     dict(slip_s=CONFIG.lift_load.slip_s, **HELD), Counters(),
     dict(memorized_corrective=MemorizedCorrectiveConfig(events=["lift_load"]))),
    ("lift_ended", Mode.LIFT, dict(motion_done=True, **HELD), HELD, Counters(), {}),
    ("avoid_hit", Mode.HOLD, dict(hit=True, **HELD), HELD, Counters(), {}),
    ("avoid_hit", Mode.HOLD,
     dict(corrective_event_matched=True, time_in_mode=CONFIG.memorized_corrective.hit_armed_s,
          **HELD),
     dict(corrective_event_matched=True, hit=True,
          time_in_mode=0.5 * CONFIG.memorized_corrective.hit_armed_s, **HELD), Counters(),
     dict(memorized_corrective=MemorizedCorrectiveConfig(events=["hold_avoid"]))),
    ("hold_time", Mode.HOLD, dict(time_in_mode=HOLD_S, **HELD),
     dict(time_in_mode=HOLD_S - 0.01, **HELD), Counters(), {}),
    ("avoid_ended", Mode.AVOID, dict(motion_done=True, **HELD), HELD, Counters(), {}),
    ("place_event", Mode.PLACE, dict(event_matched=True, **HELD), HELD, Counters(), {}),
    ("place_timeout", Mode.PLACE,
     dict(motion_done=True, time_since_motion_done=CONFIG.place.event_timeout_s, **HELD),
     dict(motion_done=True, time_since_motion_done=0.5 * CONFIG.place.event_timeout_s,
          **HELD), Counters(), {}),
    ("released", Mode.UNLOAD, dict(motion_done=True), {}, Counters(), {}),
]


@pytest.mark.parametrize("rule,mode,fires,misses,counters,changes", CASES,
                         ids=[case[0] for case in CASES])
def test_the_rule_fires_on_its_situation_and_not_on_a_near_miss(rule, mode, fires, misses,
                                                                counters, changes):
    config = dataclasses.replace(CONFIG, **changes)
    assert decide(mode, config, counters, **fires).code == rule
    near_miss = decide(mode, config, counters, **misses)
    assert near_miss is None or near_miss.code != rule


def test_every_rule_of_the_table_has_a_case():
    assert {rule.name for rule in PAPER_TABLE.all_rules()} == {case[0] for case in CASES}
    assert PAPER_TABLE.all_guards() == ()


def test_the_papers_re_reach_leaves_its_shift_to_the_state_machine():
    decision = decide(Mode.REACH, **ONE_SIDED)
    assert decision.action == ReReach(shift=None, counted=True)


def all_observations():
    """Every combination of the observation's flags, with durations below and above their
    thresholds."""
    config = GraspControllerConfig()
    values = dict(
        time_in_mode=(0.0, 10.0), event_matched=(False, True), motion_done=(False, True),
        time_since_motion_done=(0.0, 5.0), closing_s=(-1.0, 0.5, 5.0),
        contact=((False, False), (True, False), (True, True)),
        one_sided_s=(0.0, config.re_reach.one_sided_contact_s), closed_on_nothing=(False, True),
        slip_s=(0.0, config.lift_load.slip_s), hit=(False, True), gripper_fault=("", "gFLT_0x08"),
        device_fault=("", "arm silent since 1.0 s"))
    names = list(values)
    for combination in itertools.product(*values.values()):
        yield Observation(**dict(zip(names, combination)))


OBSERVATIONS = list(all_observations())


@pytest.mark.parametrize("mode", list(Mode))
@pytest.mark.parametrize("counters", [Counters(), Counters(re_reaches=2, lift_loads=2)])
def test_every_transition_is_one_of_fig_6b(mode, counters):
    config = GraspControllerConfig()
    for observation in OBSERVATIONS:
        decision = next_mode(mode, observation, counters, config,
                             event_trigger=Trigger.MEMORIZED_EVENT, hold_s=HOLD_S)
        if mode in TERMINAL_MODES:
            assert decision is None
            continue
        if observation.device_fault or observation.gripper_fault:
            assert decision.mode == Mode.FAILED and decision.trigger == Trigger.FAULT
            continue
        if decision is None:
            continue
        assert decision.mode in ALLOWED[mode], (mode, observation, decision)
        if decision.trigger == Trigger.MEMORIZED_EVENT:
            assert observation.event_matched and (mode, decision.mode) in EVENT_TRANSITIONS
        if (mode, decision.mode) in EVENT_TRANSITIONS and decision.trigger != Trigger.TIMER:
            assert decision.trigger == Trigger.MEMORIZED_EVENT
        # Corrections used up never start another one.
        if counters.re_reaches >= config.re_reach.max_re_reaches:
            assert decision.mode != Mode.RE_REACH
        if counters.lift_loads >= config.lift_load.max_lift_loads:
            assert not (mode == Mode.LIFT and decision.mode == Mode.LOAD)


@pytest.mark.parametrize("mode", [m for m in Mode if m not in TERMINAL_MODES])
def test_nothing_happening_keeps_the_mode(mode):
    assert decide(mode, contact=(True, True)) is None


def test_event_transitions():
    assert decide(Mode.REACH, event_matched=True).mode == Mode.LOAD
    assert decide(Mode.LOAD, event_matched=True, contact=(True, True)).mode == Mode.LIFT
    decision = decide(Mode.PLACE, event_matched=True, contact=(True, True))
    assert (decision.mode, decision.trigger) == (Mode.UNLOAD, Trigger.MEMORIZED_EVENT)


def test_re_reach_triggers_and_their_bound():
    config = GraspControllerConfig()
    one_sided = dict(contact=(False, True), one_sided_s=config.re_reach.one_sided_contact_s)
    decision = decide(Mode.REACH, **one_sided)
    assert (decision.mode, decision.trigger) == (Mode.RE_REACH, Trigger.CORRECTIVE)
    assert "right finger" in decision.reason
    assert decide(Mode.REACH, closed_on_nothing=True).mode == Mode.RE_REACH
    assert decide(Mode.REACH, closing_s=config.re_reach.reach_event_timeout_s).mode == Mode.RE_REACH
    assert decide(Mode.REACH, contact=(False, True), one_sided_s=0.5 * config.re_reach.one_sided_contact_s
                  ) is None
    used_up = decide(Mode.REACH, counters=Counters(re_reaches=config.re_reach.max_re_reaches),
                     **one_sided)
    assert used_up.mode == Mode.FAILED and "after 2 Re-Reach attempts" in used_up.reason
    no_re_reach = dataclasses.replace(config,
                                      re_reach=dataclasses.replace(config.re_reach, enabled=False))
    switched_off = decide(Mode.REACH, no_re_reach,
                          **one_sided)
    assert switched_off.mode == Mode.FAILED
    assert decide(Mode.RE_REACH, motion_done=True).mode == Mode.REACH


def test_lift_load_and_its_switch():
    config = GraspControllerConfig()
    slipping = dict(slip_s=config.lift_load.slip_s, contact=(True, True), motion_done=True)
    decision = decide(Mode.LIFT, **slipping)
    assert (decision.mode, decision.trigger) == (Mode.LOAD, Trigger.CORRECTIVE)
    no_lift_load = dataclasses.replace(
        config, lift_load=dataclasses.replace(config.lift_load, enabled=False))
    off = decide(Mode.LIFT, no_lift_load, **slipping)
    assert off.mode == Mode.HOLD
    assert decide(Mode.LIFT, counters=Counters(lift_loads=config.lift_load.max_lift_loads),
                  **slipping).mode == Mode.FAILED
    # After a Lift-Load, a Load without its event fails rather than re-reaching.
    assert decide(Mode.LOAD, counters=Counters(lift_loads=1), contact=(True, True),
                  time_in_mode=config.load_event_timeout_s).mode == Mode.FAILED


def test_hold_avoid_place():
    decision = decide(Mode.HOLD, hit=True, contact=(True, True))
    assert (decision.mode, decision.trigger) == (Mode.AVOID, Trigger.THRESHOLD)
    no_avoid = dataclasses.replace(CONFIG, avoid=dataclasses.replace(CONFIG.avoid, enabled=False))
    assert decide(Mode.HOLD, no_avoid, hit=True, contact=(True, True)) is None
    assert decide(Mode.HOLD, time_in_mode=HOLD_S - 0.01, contact=(True, True)) is None
    assert decide(Mode.HOLD, time_in_mode=HOLD_S, contact=(True, True)).mode == Mode.PLACE
    assert decide(Mode.AVOID, motion_done=True, contact=(True, True)).mode == Mode.HOLD


def test_place_without_event_unloads_on_timer():
    config = GraspControllerConfig()
    waiting = dict(motion_done=True, contact=(True, True))
    assert decide(Mode.PLACE, time_since_motion_done=0.5 * config.place.event_timeout_s,
                  **waiting) is None
    decision = decide(Mode.PLACE, time_since_motion_done=config.place.event_timeout_s, **waiting)
    assert (decision.mode, decision.trigger) == (Mode.UNLOAD, Trigger.TIMER)


@pytest.mark.parametrize("mode", HOLDING_MODES)
def test_losing_the_object_fails(mode):
    decision = decide(mode, contact=(False, False))
    assert (decision.mode, decision.code) == (Mode.FAILED, "object_lost")


def test_faults_name_the_device():
    assert "gFLT_0x08" in decide(Mode.HOLD, gripper_fault="gFLT_0x08").reason
    assert decide(Mode.LIFT, device_fault="tactile silent since 2.1 s").reason == \
        "tactile silent since 2.1 s"


# Rule: a fault's text is the device's or its library's (pymodbus errors, two faults at one
# tick): whatever it holds, the Failed transition is written, one timeline line, so the run
# ends on the fault rather than on the reason's check.
@pytest.mark.parametrize("fault_text", [
    describe_faults([DeviceFault("gripper", DRIVER_ERROR, "no answer: Modbus Error:\n[I/O]"),
                     DeviceFault("tactile", SILENT, "no new data for more than 500 ms")]),
    "arm: silent\nsince t = 1.0 s\x1b[31m",
    "gripper: driver: " + "Modbus Error " * 200,
])
def test_a_fault_of_any_text_fails_the_grasp_with_a_one_line_reason(fault_text):
    for fields in (dict(device_fault=fault_text), dict(gripper_fault=fault_text)):
        decision = decide(Mode.HOLD, **fields)
        entry = Transition(t=1.0, from_mode=Mode.HOLD, to_mode=decision.mode,
                           trigger=decision.trigger, reason=decision.reason, code=decision.code)
        assert entry.to_mode == Mode.FAILED
        assert entry.reason.isprintable() and len(entry.reason) <= MAX_REASON_CHARS
        assert fault_text.split()[0].rstrip(":") in entry.reason


def test_relift_after_lift_load_waits_for_force_and_quiet():
    config = GraspControllerConfig()
    ready = dict(contact=(True, True), grip_reached=True, slip_quiet=True,
                 time_in_mode=config.lift_load.relift_settle_s)
    decision = decide(Mode.LOAD, counters=Counters(lift_loads=1), **ready)
    assert (decision.mode, decision.trigger) == (Mode.LIFT, Trigger.CORRECTIVE)
    assert decide(Mode.LOAD, counters=Counters(lift_loads=1), **{**ready, "slip_quiet": False}) \
        is None
    assert decide(Mode.LOAD, counters=Counters(lift_loads=1),
                  **{**ready, "time_in_mode": 0.5 * config.lift_load.relift_settle_s}) is None
    # The first Load waits for its memorized event, whatever the force.
    assert decide(Mode.LOAD, **ready) is None
