"""The taxel-aware rule table, one pure test per rule: the rule fires on the situation it
is written for and does not on a near miss (the paper's rules too, read with the
ContactEstimate); one per guard: it holds back each of its rules, and only while its
condition holds; and what the actions carry."""

import dataclasses

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (MemorizedControllerConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.corrective_actions import Counters
from tegrasp_drake.control.finger_strike import FINGER_FRONT_M
from tegrasp_drake.control.grasp_modes import Mode, Trigger
from tegrasp_drake.control.rule_actions import Failed, Regrasp, ReReach
from tegrasp_drake.control.taxel_aware import TAXEL_AWARE_TABLE
from tegrasp_drake.control.taxel_aware.contact_geometry import Shift
from tegrasp_drake.control.taxel_aware.estimator import ContactEstimate
from tegrasp_drake.control.taxel_contact import grasp_contact
from tegrasp_drake.control.transition_logic import PAPER_TABLE, Observation
from tegrasp_drake.rig.taxel_layout import CELL_Y, COLUMNS, ROWS

CONFIG = TaxelAwareControllerConfig()
TAXEL = CONFIG.taxel_aware
WIDTH_M = 0.045  # the box
USED_UP = Counters(re_reaches=TAXEL.max_re_reaches)


def pads(left_row=None, right_row=None, force=1.0):
    """The GraspContact of a line contact across the given row of each pad (None: off)."""
    taxels = np.zeros((2, ROWS, COLUMNS))
    for k, row in enumerate((left_row, right_row)):
        if row is not None:
            taxels[k, row, :] = force
    return grasp_contact(taxels.reshape(-1), CONFIG.taxel_contact_n)


def situation(*, contact=(False, False), shape=None, estimate=None, **observation):
    """An Observation with a ContactEstimate: the contact (SA) and the shape as given, the
    gripper 80 mm open on the 45 mm box, a Reach-Load match this tick confirmed when a pad
    touches (as the estimator finds it); `estimate`: further ContactEstimate fields."""
    confirmed_now = observation.get("event_matched", False) and any(contact)
    sensed = ContactEstimate(shape=shape or pads(), sa_n=tuple(3.0 * c for c in contact),
                             contact=contact, opening_m=0.080, object_width_m=WIDTH_M,
                             gripper_y_m=0.0, approaching=False,
                             match_confirmed_s=0.0 if confirmed_now else -1.0)
    sensed = dataclasses.replace(sensed, **(estimate or {}))
    return Observation(contact=contact, estimate=sensed, **observation)


def decide(mode, obs, counters=Counters(), config=CONFIG):
    return TAXEL_AWARE_TABLE.next_mode(mode, obs, counters, config,
                                       event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)


def code(mode, obs, counters=Counters(), config=CONFIG):
    decision = decide(mode, obs, counters, config)
    return None if decision is None else decision.code


ONE_SIDED = dict(contact=(False, True), one_sided_s=CONFIG.re_reach.one_sided_contact_s)
REACH_LATE = dict(closing_s=CONFIG.re_reach.reach_event_timeout_s)
LOAD_LATE = dict(time_in_mode=CONFIG.load_event_timeout_s)
# (rule, mode, the situation it fires on, a near miss, counters)
CASES = [
    ("device_fault", Mode.HOLD, dict(device_fault="arm silent"), dict(), Counters()),
    ("gripper_fault", Mode.REACH, dict(gripper_fault="gFLT_0x08"), dict(), Counters()),
    ("object_lost", Mode.HOLD, dict(), dict(contact=(True, True)), Counters()),
    ("finger_strike", Mode.REACH,
     dict(estimate=dict(strike_s=TAXEL.finger_strike.sustain_s, strike_finger="left")),
     dict(estimate=dict(strike_s=0.5 * TAXEL.finger_strike.sustain_s)), Counters()),
    ("approach_contact", Mode.REACH,
     dict(contact=(False, True), estimate=dict(approach_contact_s=CONFIG.re_reach.one_sided_contact_s,
                                               approaching=True)),
     dict(contact=(False, True), estimate=dict(approach_contact_s=0.02, approaching=True)),
     Counters()),
    ("ra_onset_one_film", Mode.REACH,
     dict(estimate=dict(ra_onset_finger="right", ra_onset_opening_m=0.078,
                        ra_onset_topples=True)),
     dict(estimate=dict(ra_onset_finger="right", ra_onset_opening_m=0.078)), Counters()),
    ("curled_fingertips", Mode.REACH,
     dict(contact=(True, True), shape=pads(3, 3), event_matched=True,
          estimate=dict(hooked_object_dx_m=-0.0255, first_touch_opening_m=0.0045)),
     dict(contact=(True, True), shape=pads(3, 3), event_matched=True), Counters()),
    ("beyond_pads", Mode.REACH,
     dict(estimate=dict(touched_beyond_pads=True, first_touch_finger="right",
                        first_touch_opening_m=0.0719)),
     dict(estimate=dict(touched_beyond_pads=False)), Counters()),
    ("off_centre", Mode.REACH,
     dict(contact=(True, True), shape=pads(3, 3), event_matched=True),
     dict(contact=(True, True), shape=pads(1, 2), event_matched=True), Counters()),
    ("reach_event", Mode.REACH, dict(contact=(True, True), event_matched=True),
     dict(contact=(True, True)), Counters()),
    ("touch_confirmed", Mode.REACH,
     dict(contact=(True, False), estimate=dict(match_confirmed_s=0.015)),
     dict(contact=(True, False), estimate=dict(match_confirmed_s=-1.0)), Counters()),
    ("one_sided_at_width", Mode.REACH, dict(**ONE_SIDED, estimate=dict(opening_m=0.0452)),
     dict(**ONE_SIDED, estimate=dict(opening_m=0.0530)), Counters()),
    ("bracket_recentre", Mode.REACH,
     dict(**ONE_SIDED, estimate=dict(opening_m=0.0577, bracket=(0.01, 0.0514))),
     dict(**ONE_SIDED, estimate=dict(opening_m=0.0577)), Counters()),
    ("one_sided", Mode.REACH, dict(**ONE_SIDED),
     dict(contact=(False, True), one_sided_s=0.02), Counters()),
    ("closed_untouched", Mode.REACH, dict(closed_on_nothing=True),
     dict(closed_on_nothing=True, estimate=dict(first_touch_opening_m=0.06)), Counters()),
    ("closed_on_nothing", Mode.REACH,
     dict(closed_on_nothing=True, estimate=dict(first_touch_opening_m=0.06)),
     dict(closing_s=0.5, estimate=dict(first_touch_opening_m=0.06)), Counters()),
    ("reach_timeout_both_pads", Mode.REACH, dict(contact=(True, True), **REACH_LATE),
     dict(contact=(True, True), closing_s=0.5), Counters()),
    ("reach_timeout_caged", Mode.REACH,
     dict(**REACH_LATE, estimate=dict(caged_behind_pads=True)),
     dict(closing_s=0.5, estimate=dict(caged_behind_pads=True)), Counters()),
    ("reach_timeout", Mode.REACH, dict(**REACH_LATE), dict(closing_s=0.5), Counters()),
    ("re_centred", Mode.RE_REACH, dict(motion_done=True), dict(), Counters()),
    ("load_lift_event", Mode.LOAD, dict(contact=(True, True), event_matched=True),
     dict(contact=(True, True)), Counters()),
    ("relift", Mode.LOAD,
     dict(contact=(True, True), grip_reached=True, time_in_mode=CONFIG.lift_load.relift_settle_s),
     dict(contact=(True, True), grip_reached=True, time_in_mode=0.5 * CONFIG.lift_load.relift_settle_s),
     Counters(lift_loads=1)),
    ("load_timeout_both_pads", Mode.LOAD, dict(contact=(True, True), **LOAD_LATE),
     dict(contact=(True, False), **LOAD_LATE), Counters()),
    ("load_timeout_caged", Mode.LOAD, dict(**LOAD_LATE, estimate=dict(
        caged_behind_pads=True)), dict(estimate=dict(caged_behind_pads=True)), Counters()),
    ("load_timeout", Mode.LOAD, dict(contact=(True, False), **LOAD_LATE),
     dict(contact=(True, False)), Counters()),
    ("lift_load", Mode.LIFT, dict(contact=(True, True), slip_s=CONFIG.lift_load.slip_s),
     dict(contact=(True, True), slip_s=0.5 * CONFIG.lift_load.slip_s), Counters()),
    ("lift_ended", Mode.LIFT, dict(contact=(True, True), motion_done=True),
     dict(contact=(True, True)), Counters()),
    ("avoid_hit", Mode.HOLD, dict(contact=(True, True), hit=True), dict(contact=(True, True)),
     Counters()),
    ("held_tilted", Mode.HOLD,
     dict(contact=(True, True), estimate=dict(tilted_s=TAXEL.regrasp.tilt_sustain_s)),
     dict(contact=(True, True), estimate=dict(tilted_s=0.5 * TAXEL.regrasp.tilt_sustain_s)),
     Counters()),
    ("hold_time", Mode.HOLD, dict(contact=(True, True), time_in_mode=3.0),
     dict(contact=(True, True), time_in_mode=2.9), Counters()),
    ("avoid_ended", Mode.AVOID, dict(contact=(True, True), motion_done=True),
     dict(contact=(True, True)), Counters()),
    ("regrasp_after_place", Mode.PLACE,
     dict(contact=(True, True), event_matched=True, motion_done=True, regrasp_pending=True),
     dict(contact=(True, True), event_matched=True, regrasp_pending=True),
     Counters(regrasps=1)),
    ("place_event", Mode.PLACE, dict(contact=(True, True), event_matched=True, motion_done=True),
     dict(contact=(True, True), motion_done=True), Counters()),
    ("place_timeout", Mode.PLACE,
     dict(contact=(True, True), motion_done=True,
          time_since_motion_done=CONFIG.place.event_timeout_s),
     dict(contact=(True, True), motion_done=True), Counters()),
    ("released", Mode.UNLOAD, dict(motion_done=True), dict(), Counters()),
]


@pytest.mark.parametrize("rule,mode,fires,misses,counters", CASES,
                         ids=[case[0] for case in CASES])
def test_the_rule_fires_on_its_situation_and_not_on_a_near_miss(rule, mode, fires, misses,
                                                                counters):
    assert code(mode, situation(**fires), counters) == rule
    assert code(mode, situation(**misses), counters) != rule


# (guard, a rule it holds back, mode, the situation in which that rule fires, the
# Observation fields, `estimate` the ContactEstimate's, under which the guard holds)
GUARD_CASES = [
    ("caged", "object_lost", Mode.HOLD, dict(), dict(estimate=dict(caged_behind_pads=True))),
    ("caged", "avoid_hit", Mode.HOLD, dict(contact=(True, True), hit=True),
     dict(estimate=dict(caged_behind_pads=True))),
    ("caged", "lift_load", Mode.LIFT, dict(contact=(True, True), slip_s=1.0),
     dict(estimate=dict(caged_behind_pads=True))),
    ("tipping_guard", "off_centre", Mode.REACH,
     dict(contact=(True, True), shape=pads(3, 3), event_matched=True),
     dict(estimate=dict(topples_if_released=True))),
    ("grip_settling", "load_lift_event", Mode.LOAD,
     dict(contact=(True, True), event_matched=True), dict(estimate=dict(grip_settling=True))),
    ("touch_unconfirmed", "reach_event", Mode.REACH,
     dict(contact=(True, True), event_matched=True),
     dict(estimate=dict(match_confirmed_s=-1.0))),
    ("regrasp_set_down", "place_event", Mode.PLACE,
     dict(contact=(True, True), event_matched=True, motion_done=True),
     dict(regrasp_pending=True)),
    ("regrasp_set_down", "place_timeout", Mode.PLACE,
     dict(contact=(True, True), motion_done=True,
          time_since_motion_done=CONFIG.place.event_timeout_s), dict(regrasp_pending=True)),
    ("place_set_down", "place_event", Mode.PLACE,
     dict(contact=(True, True), event_matched=True, motion_done=True), dict(motion_done=False)),
]


@pytest.mark.parametrize("guard,rule,mode,fires,holds", GUARD_CASES,
                         ids=[f"{case[0]}-{case[1]}" for case in GUARD_CASES])
def test_the_guard_holds_back_its_rule_only_while_its_condition_holds(guard, rule, mode, fires,
                                                                      holds):
    assert code(mode, situation(**fires)) == rule
    assert code(mode, situation(**{**fires, **holds})) != rule


def test_every_rule_and_guard_of_the_table_has_a_case():
    assert {rule.name for rule in TAXEL_AWARE_TABLE.all_rules()} == {case[0] for case in CASES}
    guards = {guard.name: set(guard.holds_back) for guard in TAXEL_AWARE_TABLE.all_guards()}
    assert guards == {name: {case[1] for case in GUARD_CASES if case[0] == name}
                      for name in guards}


def test_a_caged_object_in_lift_stays_however_it_slips_and_holds_when_lifted():
    """The guard holds back Lift-Load, whose squeeze cannot reach it; the paper's end of the
    lift still decides."""
    slipping = dict(slip_s=1.0, estimate=dict(caged_behind_pads=True))
    assert decide(Mode.LIFT, situation(**slipping)) is None
    lifted = decide(Mode.LIFT, situation(**slipping, motion_done=True))
    assert (lifted.code, lifted.mode) == ("lift_ended", Mode.HOLD)
    assert decide(Mode.LIFT, situation(contact=(True, True), slip_s=1.0)).mode == Mode.LOAD


def test_the_tipping_guard_loads_the_pushed_object_where_it_is_by_the_event():
    decision = decide(Mode.REACH, situation(contact=(True, True), shape=pads(3, 3),
                                            event_matched=True,
                                            estimate=dict(topples_if_released=True)))
    assert (decision.code, decision.mode, decision.trigger) == (
        "reach_event", Mode.LOAD, Trigger.MEMORIZED_EVENT)


def test_the_strike_backs_off_and_shifts_toward_the_struck_finger():
    decision = decide(Mode.REACH, situation(estimate=dict(
        strike_s=TAXEL.finger_strike.sustain_s, strike_finger="left", strike_force_n=6.3)))
    assert decision.reason == ("the left finger struck the object during the approach "
                               "(6.3 N at the wrist)")
    assert decision.action == ReReach(Shift(
        -TAXEL.approach_retreat_m, pytest.approx((0.080 - WIDTH_M + FINGER_FRONT_M) / 2)))


def test_the_wrist_strike_waits_for_sustain_s():
    sustain_s = TAXEL.finger_strike.sustain_s
    wrist = dict(strike_finger="left", strike_force_n=6.3)
    assert code(Mode.REACH, situation(estimate=dict(wrist, strike_s=0.5 * sustain_s))) != (
        "finger_strike")


def test_one_films_strike_backs_off_toward_that_finger_at_once():
    """A light strike's ring lasts 6 ms: the film's onset acts in its first tick."""
    film = dict(strike_by_film=True, strike_finger="right", strike_force_n=0.1)
    decision = decide(Mode.REACH, situation(estimate=dict(film, strike_s=0.0)))
    assert decision.reason == ("the right finger struck the object during the approach "
                               "(its film's RA, 0.1 N at the wrist)")
    assert decision.action == ReReach(Shift(
        -TAXEL.approach_retreat_m, pytest.approx(-(0.080 - WIDTH_M + FINGER_FRONT_M) / 2)))


def test_the_approach_contact_backs_off_with_the_papers_shift_along_the_stroke():
    decision = decide(Mode.REACH, situation(contact=(False, True), estimate=dict(
        approach_contact_s=CONFIG.re_reach.one_sided_contact_s, approaching=True)))
    assert decision.action.shift == Shift(-TAXEL.approach_retreat_m,
                                          pytest.approx(-(0.080 - WIDTH_M) / 2))


def test_an_ra_onset_on_one_film_re_reaches_toward_its_finger_by_the_offset_it_implies():
    decision = decide(Mode.REACH, situation(estimate=dict(
        ra_onset_finger="right", ra_onset_opening_m=0.078, ra_onset_topples=True)))
    assert decision.action.shift == Shift(0.0, pytest.approx(-(0.078 - WIDTH_M) / 2))
    assert decision.trigger == Trigger.CORRECTIVE


@pytest.mark.parametrize("estimate,contact", [
    (dict(ra_onset_finger="", ra_onset_opening_m=0.078, ra_onset_topples=True),
     (False, False)),  # both films at once
    (dict(ra_onset_finger="right", ra_onset_opening_m=0.078, ra_onset_topples=True),
     (False, True)),  # the SA sees it
])
def test_an_ra_onset_on_both_films_or_one_the_taxels_see_is_no_one_film_onset(estimate,
                                                                                  contact):
    assert code(Mode.REACH, situation(contact=contact, estimate=estimate)) != "ra_onset_one_film"


def test_an_ra_onset_with_no_re_reach_left_lets_the_close_go_on():
    obs = situation(closing_s=0.2, estimate=dict(ra_onset_finger="left",
                                                 ra_onset_opening_m=0.078,
                                                 ra_onset_topples=True))
    assert decide(Mode.REACH, obs, USED_UP) is None


def test_curled_fingertips_re_reach_along_the_approach_to_the_hooked_objects_centre():
    obs = situation(contact=(True, True), shape=pads(3, 3), event_matched=True,
                    estimate=dict(hooked_object_dx_m=-0.0255, first_touch_opening_m=0.0045))
    assert decide(Mode.REACH, obs).action.shift == Shift(-0.0255, 0.0)
    # with no Re-Reach left it stands aside, and off_centre's forward move with it
    assert decide(Mode.REACH, obs, USED_UP).code == "reach_event"


def test_beyond_the_pads_moves_forward_by_half_a_pad_and_by_the_push_toward_the_pad():
    decision = decide(Mode.REACH, situation(estimate=dict(
        touched_beyond_pads=True, first_touch_finger="right", first_touch_opening_m=0.0719)))
    assert decision.action.shift == Shift(pytest.approx(2 * CELL_Y),
                                          pytest.approx(-(0.0719 - WIDTH_M) / 2))


def test_beyond_the_pads_with_no_re_reach_left_lets_the_close_go_on():
    obs = situation(closing_s=0.2, estimate=dict(touched_beyond_pads=True,
                                                 first_touch_finger="right"))
    assert decide(Mode.REACH, obs, USED_UP) is None


def test_an_off_centre_contact_is_centred_along_both_axes():
    decision = decide(Mode.REACH, situation(contact=(True, True), shape=pads(3, 3),
                                            event_matched=True))
    assert decision.action.shift == Shift(pytest.approx(1.5 * CELL_Y), 0.0)
    assert decide(Mode.REACH, situation(contact=(True, True), shape=pads(3, 3),
                                        event_matched=True), USED_UP).code == "reach_event"


def test_the_bracket_re_centres_on_the_middle_of_the_two_faces():
    obs = situation(**ONE_SIDED, estimate=dict(opening_m=0.0577, bracket=(-0.0348, 0.0514),
                                               gripper_y_m=-0.0379))
    decision = decide(Mode.REACH, obs, Counters(re_reaches=3))
    assert decision.action.shift.dy_m == pytest.approx(-0.0348 + 0.0379)
    assert decide(Mode.REACH, obs, USED_UP).action == Failed()


def test_without_the_bracket_rule_one_finger_alone_re_reaches_by_the_papers_shift():
    """The faces' midpoint is bracket_recentre's move alone: a table without the rule
    Re-Reaches one finger alone by the same shift, a bracket standing or not."""
    table = dataclasses.replace(TAXEL_AWARE_TABLE, rules=tuple(
        rule for rule in TAXEL_AWARE_TABLE.rules if rule.name != "bracket_recentre"))

    def shift(bracket):
        obs = situation(**ONE_SIDED, estimate=dict(opening_m=0.0577, bracket=bracket,
                                                   gripper_y_m=-0.0379))
        decision = table.next_mode(Mode.REACH, obs, Counters(), CONFIG,
                                   event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
        assert decision.code == "one_sided"
        return decision.action.shift

    assert shift((-0.0348, 0.0514)) == shift(None)


def test_the_regrasp_puts_down_and_re_reaches_without_a_shift_or_a_count():
    hold = decide(Mode.HOLD, situation(contact=(True, True),
                                       estimate=dict(tilted_s=TAXEL.regrasp.tilt_sustain_s)))
    assert (hold.mode, hold.trigger, hold.action) == (Mode.PLACE, Trigger.CORRECTIVE,
                                                      Regrasp())
    place = decide(Mode.PLACE, situation(contact=(True, True), event_matched=True,
                                         motion_done=True, regrasp_pending=True),
                   Counters(regrasps=1))
    assert place.action == ReReach(Shift(0.0, 0.0), counted=False)
    once = decide(Mode.HOLD, situation(contact=(True, True), estimate=dict(
        tilted_s=TAXEL.regrasp.tilt_sustain_s)), Counters(regrasps=TAXEL.regrasp.max_regrasps))
    assert once is None  # at most max_regrasps


def test_a_regrasps_place_neither_opens_nor_lets_go_while_the_place_move_is_on():
    """A Place-Unload match while the arm still carries the object down (one matched 0.145 s
    into the move, the object 61 mm up) is no set-down: the gripper stays closed."""
    held = Counters(regrasps=1)
    moving = dict(contact=(True, True), regrasp_pending=True, motion_done=False)
    assert decide(Mode.PLACE, situation(**moving, event_matched=True), held) is None
    assert decide(Mode.PLACE, situation(**moving, time_in_mode=10.0), held) is None
    done = dict(moving, motion_done=True)
    assert decide(Mode.PLACE, situation(**done), held) is None  # the event or its timeout
    for ended in (dict(event_matched=True),
                  dict(time_since_motion_done=CONFIG.place.event_timeout_s)):
        assert code(Mode.PLACE, situation(**done, **ended), held) == "regrasp_after_place"


def test_a_place_lets_go_only_once_the_place_move_has_set_the_object_down():
    """A Place-Unload match while the arm still carries the object down is no set-down: on
    the linkage hand the event's thresholds pass on a held object's rest signals (one matched
    10 ms into the move, the object 58 mm up). The paper's memorized controller keeps the
    paper's rule: it lets go on the match."""
    moving = dict(contact=(True, True), motion_done=False, event_matched=True)
    assert decide(Mode.PLACE, situation(**moving)) is None
    assert decide(Mode.PLACE, situation(**moving, time_in_mode=10.0)) is None
    ended = decide(Mode.PLACE, situation(**dict(moving, motion_done=True)))
    assert (ended.code, ended.mode, ended.trigger) == (
        "place_event", Mode.UNLOAD, Trigger.MEMORIZED_EVENT)
    paper = PAPER_TABLE.next_mode(Mode.PLACE, Observation(**moving), Counters(),
                                  MemorizedControllerConfig(),
                                  event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert (paper.code, paper.mode) == ("place_event", Mode.UNLOAD)


@pytest.mark.parametrize("obs,counters", [
    (situation(**REACH_LATE), Counters(re_reaches=TAXEL.max_re_reaches)),
    (situation(contact=(True, False), **LOAD_LATE), Counters(re_reaches=CONFIG.re_reach.max_re_reaches)),
    (situation(contact=(True, False), **LOAD_LATE), Counters(lift_loads=1))])
def test_corrections_used_up_fail(obs, counters):
    mode = Mode.REACH if obs.closing_s >= 0 else Mode.LOAD
    decision = decide(mode, obs, counters)
    assert decision.mode == Mode.FAILED and decision.action == Failed()


def test_the_table_asks_the_devices_first_and_the_approach_before_the_papers_reach():
    reach = [rule.name for rule, _ in TAXEL_AWARE_TABLE.ordered(Mode.REACH)]
    assert reach[:6] == ["device_fault", "gripper_fault", "object_lost", "finger_strike",
                         "approach_contact", "ra_onset_one_film"]
    assert reach.index("off_centre") < reach.index("reach_event") < reach.index("one_sided")
    assert TAXEL_AWARE_TABLE.ordered(Mode.DONE) == ()
    assert decide(Mode.DONE, situation(device_fault="x")) is None


def test_a_one_sided_re_reach_centres_along_both_axes():
    """The left finger alone touches, on its fingertip row; the gripper stopped 60 mm open
    on the 45 mm box: 7.5 mm toward the left (+y), 9 mm forward (+x)."""
    obs = situation(contact=(True, False), one_sided_s=CONFIG.re_reach.one_sided_contact_s,
                    shape=pads(3, None), estimate=dict(opening_m=0.060))
    shift = decide(Mode.REACH, obs).action.shift
    assert shift == Shift(pytest.approx(1.5 * CELL_Y), pytest.approx(0.0075))
    wide = decide(Mode.REACH, obs, Counters(re_reaches=TAXEL.max_re_reaches - 1))
    assert wide.code == "one_sided" and wide.mode == Mode.RE_REACH
    assert decide(Mode.REACH, obs, USED_UP).mode == Mode.FAILED


def test_an_empty_pad_is_no_lost_object_while_the_fingers_cage_it():
    caged = situation(hit=True, estimate=dict(caged_behind_pads=True))
    assert decide(Mode.HOLD, caged) is None  # and its rattle is no hit
    assert code(Mode.HOLD, situation(hit=True)) == "object_lost"


def test_the_papers_controller_reads_no_estimate():
    from tegrasp_drake.control.transition_logic import next_mode as paper_next_mode
    paper = MemorizedControllerConfig()
    obs = situation(**ONE_SIDED, estimate=dict(opening_m=0.0452, tilted_s=1.0,
                                               caged_behind_pads=True))
    reach = paper_next_mode(Mode.REACH, obs, Counters(), paper,
                            event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert (reach.mode, reach.code, reach.action) == (Mode.RE_REACH, "one_sided", ReReach())
    assert code(Mode.REACH, obs) == "one_sided_at_width"
    hold = situation(contact=(True, True), estimate=dict(tilted_s=1.0))
    assert paper_next_mode(Mode.HOLD, hold, Counters(), paper,
                           event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0) is None


def test_the_load_timeout_lifts_only_a_grip_the_drop_check_will_not_call_lost():
    """On the capacitive pads (thresholds raised to their noise), a grip reading just above
    contact_force_n is one the drop check finds lost within a few samples of noise: the Load
    timeout Re-Reaches it; a grip clear of it by the noise margin is lifted."""
    from tegrasp_drake.control.noise_thresholds import resolve_noise_thresholds
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
    resolved = resolve_noise_thresholds(CONFIG, ra_noise_std_mps2=0.0, ra_rate_hz=1000.0,
                                        tactile=TactileSensorConfig(), sa_rate_hz=108.0)
    drop = resolved.contact_force_n
    lift = resolved.taxel_aware.lift_pad_sum_n
    assert lift > drop
    near_drop = situation(contact=(True, True), **LOAD_LATE,
                          estimate=dict(sa_n=(drop + 0.6, drop + 0.9)))
    assert code(Mode.LOAD, near_drop, config=resolved) == "load_timeout"
    one_pad_short = situation(contact=(True, True), **LOAD_LATE,
                              estimate=dict(sa_n=(lift + 5.0, lift - 0.1)))
    assert code(Mode.LOAD, one_pad_short, config=resolved) == "load_timeout"
    clear = situation(contact=(True, True), **LOAD_LATE,
                      estimate=dict(sa_n=(lift + 0.1, lift + 0.1)))
    assert code(Mode.LOAD, clear, config=resolved) == "load_timeout_both_pads"


def test_a_reach_load_match_no_pad_confirms_stays_in_reach_where_the_paper_loads():
    from tegrasp_drake.control.transition_logic import next_mode as paper_next_mode
    untouched = situation(event_matched=True)
    assert decide(Mode.REACH, untouched) is None
    paper = paper_next_mode(Mode.REACH, untouched, Counters(), MemorizedControllerConfig(),
                            event_trigger=Trigger.MEMORIZED_EVENT, hold_s=3.0)
    assert paper.code == "reach_event"  # the paper's controller is unchanged
    confirmed = decide(Mode.REACH, situation(contact=(False, True),
                                             estimate=dict(match_confirmed_s=0.010)))
    assert (confirmed.mode, confirmed.trigger, confirmed.code) == (
        Mode.LOAD, Trigger.MEMORIZED_EVENT, "touch_confirmed")
    assert "right pad" in confirmed.reason


def test_off_centre_acts_only_on_a_reach_load_match_a_pads_touch_confirms():
    """The taxels show the rod off the pads' centres, but no pad's SA sum reads above
    contact_force_n: the match is unconfirmed, so off_centre waits as the paper's reach_event
    does; once a pad's touch confirms the match (after the matching tick), off_centre acts."""
    unconfirmed = situation(shape=pads(3, 3), event_matched=True)
    assert decide(Mode.REACH, unconfirmed) is None
    confirmed_later = situation(contact=(True, True), shape=pads(3, 3),
                                estimate=dict(match_confirmed_s=0.015))
    assert code(Mode.REACH, confirmed_later) == "off_centre"
    centred = situation(contact=(True, True), shape=pads(1, 2),
                        estimate=dict(match_confirmed_s=0.015))
    assert code(Mode.REACH, centred) == "touch_confirmed"


def test_a_close_that_touched_nothing_re_reaches_forward_by_the_untouched_reach():
    decision = decide(Mode.REACH, situation(closed_on_nothing=True,
                                            estimate=dict(untouched_reach_m=0.025)))
    assert decision.code == "closed_untouched"
    assert decision.action == ReReach(Shift(0.025, 0.0))


def test_a_close_on_nothing_after_an_earlier_touch_is_the_papers():
    """The object was within the pads' reach at an earlier close: it moved (pushed or
    toppled), so no forward search."""
    obs = situation(closed_on_nothing=True, estimate=dict(touched_before=True))
    assert code(Mode.REACH, obs, Counters(re_reaches=1)) == "closed_on_nothing"


def test_a_close_on_nothing_after_a_reach_load_match_is_the_papers():
    """A match with no pad touching can be a finger's backing on the object (docs/controller.md,
    "Known failure: a Reach-Load event with no pad touching"): no forward search."""
    obs = situation(closed_on_nothing=True, estimate=dict(reach_matched=True))
    assert code(Mode.REACH, obs) == "closed_on_nothing"
