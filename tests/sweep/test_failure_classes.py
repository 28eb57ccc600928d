import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (MemorizedControllerConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.controller_registry import rule_codes, rule_tables
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.control.taxel_aware.estimator import ContactEstimate
from tegrasp_drake.control.taxel_contact import grasp_contact
from tegrasp_drake.control.transition_logic import Observation, next_mode
from tegrasp_drake.rig.taxel_layout import COLUMNS, ROWS
from tegrasp_drake.scenario.trial_result import TrialResult
from tests.fake_trials import timeline_ending, whole_result
from tegrasp_drake.sweep.failure_classes import (FAILURE_CLASS_AFTER_LIFT_LOAD,
                                                 FAILURE_CLASS_OF_RULE, FAILURE_CLASSES,
                                                 failure_class, failure_class_counts,
                                                 failure_classes_markdown)


def result(**changes):
    """A held and unloaded trial's result, changed by `changes`."""
    base = {"hold_success": True, "unload_success": True, "failure": "", "final_mode": "Done",
            "lift_height_m": 0.06, "final_tilt_deg": 0.5, "released": True}
    changed = {**base, **changes}
    timeline = timeline_ending(changed["final_mode"], reason=changed["failure"])
    return whole_result(**{"transitions": timeline, **changed})


FAILED = dict(hold_success=False, unload_success=False, final_mode="Failed",
              lift_height_m=0.0)


@pytest.mark.parametrize("changes, expected", [
    ({}, None),
    ({**FAILED, "failure": "the gripper closed on nothing, after 2 Re-Reach attempts"},
     "closed on nothing"),
    ({**FAILED, "failure": "only the left finger touched, after 2 Re-Reach attempts"},
     "one finger only"),
    ({**FAILED, "failure": "no Reach-Load event 2 s after closing, after 2 Re-Reach attempts"},
     "event never matched"),
    ({**FAILED, "failure": "no Load-Lift event within 2 s; Re-Reach is switched off"},
     "event never matched"),
    ({**FAILED, "failure": "the object still slips after 2 Lift-Load corrections"},
     "slipped in Lift"),
    ({**FAILED, "failure": "no Load-Lift event within 2 s after Lift-Load"}, "slipped in Lift"),
    ({**FAILED, "failure": "object lost: no finger in contact", "lift_height_m": 0.03},
     "object lost"),
    ({**FAILED, "failure": "gripper fault overcurrent"}, "device fault"),
    ({**FAILED, "failure": "tactile: no new data for more than 500 ms",
      "transitions": [{"t": 5.0, "from": "Reach", "to": "Failed", "trigger": "fault",
                       "reason": "tactile: no new data for more than 500 ms"}]},
     "device fault"),
    ({**FAILED, "failure": "something new"}, "other"),
    ({"hold_success": False, "unload_success": False, "lift_height_m": 0.001}, "not lifted"),
    ({"hold_success": False, "unload_success": False, "lift_height_m": 0.05},
     "dropped in Hold"),
    ({"unload_success": False, "final_tilt_deg": 35.0}, "toppled at release"),
    ({"unload_success": False, "final_tilt_deg": 2.0}, "not placed"),
])
def test_each_failure_has_its_class(changes, expected):
    assert failure_class(TrialResult.from_dict(result(**changes))) == expected


def test_counts_per_controller_and_object_and_the_table():
    records = [
        {"status": "ok", "trial": {"controller": "memorized", "object_name": "box"},
         "result": result()},
        {"status": "ok", "trial": {"controller": "memorized", "object_name": "box"},
         "result": result(unload_success=False, final_tilt_deg=40.0)},
        {"status": "error", "trial": {"controller": "memorized", "object_name": "box"},
         "result": None},
        {"status": "ok", "trial": {"controller": "open_loop", "object_name": "thin_cylinder"},
         "result": result()},
    ]
    counts = failure_class_counts(records)
    assert counts["memorized"]["box"]["toppled at release"] == 1
    assert sum(counts["memorized"]["box"].values()) == 1
    assert set(counts["open_loop"]["thin_cylinder"]) == set(FAILURE_CLASSES)
    table = failure_classes_markdown(counts)
    assert "| box | 1 |" in table and "toppled at release" in table
    assert "not lifted" not in table  # only the classes that occur


# ---- by the code of the rule that went to Failed ---------------------------------------

def entry(t, from_mode, to_mode, reason, code, trigger="corrective"):
    return {"t": t, "from": from_mode, "to": to_mode, "trigger": trigger, "reason": reason,
            "code": code}


LIFT_LOAD = entry(2.5, "Lift", "Load", "slip during Lift (Lift-Load)", "lift_load")
RELIFT = entry(3.0, "Load", "Lift", "raised grip force reached (Lift-Load)", "relift")
# A grasp that runs as the paper's script does, its Lift-Load (if any) after the first Lift.
GRASP = (entry(1.0, "Reach", "Load", "Reach-Load event", "reach_event", "memorized_event"),
         entry(2.0, "Load", "Lift", "Load-Lift event", "load_lift_event", "memorized_event"),
         entry(3.5, "Lift", "Hold", "lift motion ended", "lift_ended", "timer"),
         entry(6.5, "Hold", "Place", "held 3 s", "hold_time", "timer"),
         entry(8.0, "Place", "Unload", "Place-Unload event", "place_event", "memorized_event"))


def timeline_to(mode: str, lift_loaded: bool = False) -> list[dict]:
    """The grasp's timeline (GRASP) until it enters `mode` ([] for Reach), through a Lift-Load
    and the Lift after it when `lift_loaded`."""
    steps = [*GRASP[:2], LIFT_LOAD, RELIFT, *GRASP[2:]] if lift_loaded else list(GRASP)
    timeline = []
    if mode == "Reach":
        return timeline
    for step in steps:
        timeline.append(step)
        if step["to"] == mode and (LIFT_LOAD in timeline or not lift_loaded):
            return timeline
    return timeline


def failed(reason, code, from_mode="Reach", *, lift_loaded=False, trigger="corrective"):
    """A result that the rule `code` sent from `from_mode` to Failed for `reason`, a second
    after the grasp (timeline_to) entered it."""
    before = timeline_to(from_mode, lift_loaded)
    t = before[-1]["t"] + 1.0 if before else 5.0
    return TrialResult.from_dict(result(
        **FAILED, failure=reason, corrective_actions=["lift_load"] if lift_loaded else [],
        transitions=[*before, entry(t, from_mode, "Failed", reason, code, trigger)]))


def without_codes(trial: TrialResult) -> TrialResult:
    """`trial` as a result written before timeline entries carried their rule's code."""
    data = trial.to_dict()
    for transition in data["transitions"]:
        transition.pop("code", None)
    return TrialResult.from_dict(data)


def test_a_reworded_reason_is_classed_by_its_rules_code():
    reworded = failed("the fingers met without the object between them, after 2 Re-Reach "
                      "attempts", "closed_on_nothing")
    assert failure_class(reworded) == "closed on nothing"
    assert failure_class(without_codes(reworded)) == "other"  # the words alone name nothing


def test_the_code_decides_where_the_words_would_mislead():
    # A watchdog's message that reads like an event timeout ("no ... event").
    watchdog = failed("no tactile event stream for 500 ms", "device_fault", "Load",
                      trigger="fault")
    assert failure_class(watchdog) == "device fault"
    assert failure_class(without_codes(watchdog)) == "event never matched"


def test_a_load_timeout_after_a_lift_load_slipped_in_lift():
    reason = "the Load-Lift event did not come in time"
    assert failure_class(failed(reason, "load_timeout", "Load", lift_loaded=True)) == \
        "slipped in Lift"
    assert failure_class(failed(reason, "load_timeout", "Load")) == "event never matched"


def test_a_rule_that_went_to_failed_without_a_class_is_refused():
    with pytest.raises(ValueError, match="'released' went to Failed but has no failure class"):
        failure_class(failed("released and retracted", "released", "Unload"))


def test_every_rule_that_can_go_to_failed_has_a_class():
    """Each rule whose `then` names Failed (the rule tables of docs/controller.md) has a class,
    and no other rule is listed, so a new rule cannot be left out."""
    failing = {rule.name for table in rule_tables().values() for rule in table.all_rules()
               if "Failed" in rule.then}
    assert failing <= rule_codes()
    assert set(FAILURE_CLASS_OF_RULE) == failing
    assert set(FAILURE_CLASS_AFTER_LIFT_LOAD) <= failing
    assert set(FAILURE_CLASS_OF_RULE.values()) | set(FAILURE_CLASS_AFTER_LIFT_LOAD.values()) \
        <= set(FAILURE_CLASSES)


USED_UP = Counters(re_reaches=MemorizedControllerConfig().re_reach.max_re_reaches,
                   lift_loads=MemorizedControllerConfig().lift_load.max_lift_loads)


@pytest.mark.parametrize("mode, observation, counters, lift_loaded, expected", [
    (Mode.REACH, Observation(device_fault="tactile: no new data for more than 500 ms"),
     Counters(), False, "device fault"),
    (Mode.REACH, Observation(gripper_fault="overcurrent"), Counters(), False, "device fault"),
    (Mode.HOLD, Observation(contact=(False, False)), Counters(), False, "object lost"),
    (Mode.REACH, Observation(closed_on_nothing=True), USED_UP, False, "closed on nothing"),
    (Mode.REACH, Observation(contact=(True, False), one_sided_s=10.0), USED_UP, False,
     "one finger only"),
    (Mode.REACH, Observation(closing_s=10.0), USED_UP, False, "event never matched"),
    (Mode.LOAD, Observation(time_in_mode=10.0), Counters(re_reaches=USED_UP.re_reaches),
     False, "event never matched"),
    (Mode.LOAD, Observation(time_in_mode=10.0), Counters(lift_loads=1), True,
     "slipped in Lift"),
    (Mode.LIFT, Observation(contact=(True, True), slip_s=10.0), USED_UP, True,
     "slipped in Lift"),
])
def test_the_paper_rules_failures_class_alike_by_code_and_by_their_words(
        mode, observation, counters, lift_loaded, expected):
    """The paper's rules' own failures: the same class by their code as by the words of their
    reasons, so records with codes class as those written before them."""
    decision = next_mode(mode, observation, counters, MemorizedControllerConfig(),
                         event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert decision.mode == Mode.FAILED
    trial = failed(decision.reason, decision.code, mode.label,
                   lift_loaded=lift_loaded, trigger=decision.trigger.value)
    assert (failure_class(trial), failure_class(without_codes(trial))) == (expected, expected)


TAXEL_AWARE = TaxelAwareControllerConfig()


def approach(contact=(False, False), **estimate) -> Observation:
    """An Observation in the approach: the gripper 80 mm open on the 45 mm box, no taxel
    pressed, the pads' contact as given, `estimate`: further ContactEstimate fields."""
    shape = grasp_contact(np.zeros(2 * ROWS * COLUMNS), TAXEL_AWARE.taxel_contact_n)
    sensed = ContactEstimate(shape=shape, sa_n=tuple(3.0 * c for c in contact),
                             contact=contact, opening_m=0.080, object_width_m=0.045,
                             gripper_y_m=0.0, approaching=True, **estimate)
    return Observation(contact=contact, estimate=sensed)


@pytest.mark.parametrize("rule, observation", [
    ("finger_strike", approach(strike_s=TAXEL_AWARE.taxel_aware.finger_strike.sustain_s,
                               strike_finger="left", strike_force_n=6.3)),
    ("approach_contact", approach(contact=(False, True),
                                  approach_contact_s=TAXEL_AWARE.re_reach.one_sided_contact_s)),
])
def test_a_gripper_that_ran_into_the_object_on_its_way_in_was_struck_on_approach(
        rule, observation):
    """The taxel-aware approach rules' failures, with the Re-Reaches used up: the same class
    by their code as by the words of their reasons."""
    used_up = Counters(re_reaches=TAXEL_AWARE.taxel_aware.max_re_reaches)
    decision = TAXEL_AWARE_TABLE.next_mode(Mode.REACH, observation, used_up, TAXEL_AWARE,
                                           event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert (decision.code, decision.mode) == (rule, Mode.FAILED)
    trial = failed(decision.reason, decision.code, trigger=decision.trigger.value)
    assert (failure_class(trial), failure_class(without_codes(trial))) == \
        ("struck on approach", "struck on approach")
