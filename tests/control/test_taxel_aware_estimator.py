"""The ContactEstimator, pure: what it senses from a reading and what it remembers, tick
to tick and across a change of mode."""

import dataclasses
import types

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import (GraspControllerConfig, TaxelAwareConfig,
                                                     TaxelAwareControllerConfig)
from tegrasp_drake.control.grasp_modes import Mode, Stage
from tegrasp_drake.control.taxel_aware import (ContactEstimator, ContactMemory,
                                               ContactReading, ObjectGeometry,
                                               estimator_for_plan)
from tegrasp_drake.control.taxel_aware.contact_geometry import FaceTouch
from tegrasp_drake.control.taxel_aware.touch_confirmed import match_confirm_window_s
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.rig.taxel_layout import COLUMNS, ROWS

TAXEL = TaxelAwareConfig()
THIN = BUILTIN_OBJECTS["thin_cylinder"]
CONTACT_N = GraspControllerConfig().taxel_contact_n  # the ideal force taxels' number
# The capacitive pads' frame rate and the controller's tick (docs/model.md, docs/controller.md).
SA_RATE_HZ = 108.0
CONFIRM_S = match_confirm_window_s(SA_RATE_HZ, GraspControllerConfig().update_period_s)
ESTIMATOR = ContactEstimator(
    taxel_config=TAXEL, taxel_contact_n=CONTACT_N, match_confirm_window_s=CONFIRM_S,
    geometry=ObjectGeometry(width_m=THIN.width_along_stroke(), height_m=THIN.height(),
                            grasp_height_m=0.055), film_strike=False)
# The linkage hand's: one film's RA onset in the approach is also a finger strike.
FILM_ESTIMATOR = ContactEstimator(
    taxel_config=TAXEL, taxel_contact_n=CONTACT_N, match_confirm_window_s=CONFIRM_S,
    geometry=ESTIMATOR._geometry, film_strike=True)


def taxels(left_row=None, right_row=None, force=0.15):
    forces = np.zeros((2, ROWS, COLUMNS))
    for k, row in enumerate((left_row, right_row)):
        if row is not None:
            forces[k, row, :] = force
    return tuple(forces.reshape(-1))


def reading(t=1.0, mode=Mode.REACH, stage=Stage.CLOSING, forces=taxels(), contact=(False, False),
            opening_m=0.0719, wrench=None, stopped_on_object=False, event_matched=False,
            **changes):
    return ContactReading(t=t, mode=mode, stage=stage, lift_loads=0, taxel_forces=forces,
                          sa_n=(0.0, 0.0), contact=contact, opening_m=opening_m,
                          at_requested_position=False, stopped_on_object=stopped_on_object,
                          wrench=wrench, gripper_y_m=0.0, event_matched=event_matched,
                          **changes)


def test_the_first_touch_on_one_distal_row_of_a_thin_rod_stops_the_close():
    """The thin cylinder beyond the fingertips: the right pad's distal row alone at 71.9 mm,
    23.5 mm of push to come against its 11.5 mm tipping limit."""
    memory, estimate = ESTIMATOR.update(ContactMemory(), reading(forces=taxels(None, 3)))
    assert (memory.first_touch_opening_m, memory.first_touch_finger) == (0.0719, "right")
    assert estimate.touched_beyond_pads and estimate.topples_if_released
    later, again = ESTIMATOR.update(memory, reading(t=1.005, forces=taxels(2, 3),
                                                    opening_m=0.060))
    assert later.first_touch_opening_m == 0.0719  # the first touch is kept
    assert again.touched_beyond_pads


def test_no_touch_while_approaching_records_nothing():
    memory, estimate = ESTIMATOR.update(ContactMemory(), reading(stage=Stage.MOVING))
    assert memory == ContactMemory() and not estimate.touched_beyond_pads
    assert estimate.approaching and estimate.strike_s == 0.0


def test_a_sustained_force_on_the_wrist_in_the_approach_is_a_strike():
    push = np.array([0.0, 0.0, 0.5, -TAXEL.finger_strike.force_n - 1.0, 0.0, 0.0])
    memory, _ = ESTIMATOR.update(ContactMemory(), reading(stage=Stage.MOVING,
                                                          wrench=tuple(np.zeros(6))))
    estimates = []
    for k in range(1, 4):
        memory, estimate = ESTIMATOR.update(memory, reading(
            t=1.0 + 0.005 * k, stage=Stage.MOVING, wrench=tuple(push)))
        estimates.append(estimate)
    assert estimates[0].strike_s == 0.0 and estimates[-1].strike_s == pytest.approx(0.01)
    assert estimates[-1].strike_finger == "left"  # the moment about z is positive
    off = ContactEstimator(taxel_config=TaxelAwareConfig(finger_strike=type(
        TAXEL.finger_strike)(enabled=False)), taxel_contact_n=CONTACT_N,
        match_confirm_window_s=CONFIRM_S, geometry=ESTIMATOR._geometry, film_strike=False)
    assert off.update(memory, reading(stage=Stage.MOVING, wrench=tuple(push)))[1].strike_s == 0


def approach_with_films(estimator, ra_mps2, ticks=3, wrench=tuple(np.zeros(6)),
                        stage=Stage.MOVING):
    """The estimates of `ticks` 5 ms ticks of the approach (or `stage`) with the films
    reading ra_mps2 [m/s^2] and the wrist its approach-start wrench."""
    memory, estimates = ContactMemory(), []
    for k in range(ticks):
        memory, estimate = estimator.update(memory, reading(
            t=1.0 + 0.005 * k, stage=stage, wrench=wrench, ra_mps2=ra_mps2))
        estimates.append(estimate)
    return estimates


def test_one_film_above_the_ra_onset_in_the_approach_is_a_strike_of_its_finger():
    """The linkage hand: a light strike, nothing at the wrist, the right film alone rings."""
    onset = TAXEL.ra_onset_mps2
    estimates = approach_with_films(FILM_ESTIMATOR, (0.5 * onset, 2 * onset))
    assert estimates[0].strike_s == 0.0 and estimates[-1].strike_s == pytest.approx(0.01)
    assert estimates[-1].strike_s >= TAXEL.finger_strike.sustain_s
    assert estimates[-1].strike_finger == "right" and estimates[-1].strike_by_film
    assert estimates[-1].strike_force_n == 0.0
    left = approach_with_films(FILM_ESTIMATOR, (-2 * onset, 0.0))[-1]  # RA's size counts
    assert left.strike_finger == "left" and left.strike_s == pytest.approx(0.01)


def test_a_ring_between_the_ticks_reads_sample_strikes_by_its_peak():
    """The wide light box's strike rang one film 6 ms: the tick's sample can miss it, the
    tick's peak (ra_peak_mps2) does not, and the film strike is there at that tick."""
    onset = TAXEL.ra_onset_mps2
    _, estimate = FILM_ESTIMATOR.update(ContactMemory(), reading(
        stage=Stage.MOVING, ra_mps2=(0.0, 0.0), ra_peak_mps2=(2.2 * onset, 0.0)))
    assert estimate.strike_by_film and estimate.strike_finger == "left"
    _, missed = FILM_ESTIMATOR.update(ContactMemory(), reading(
        stage=Stage.MOVING, ra_mps2=(0.0, 0.0)))
    assert not missed.strike_by_film


def test_one_film_counts_without_a_wrist_force_sense():
    onset = TAXEL.ra_onset_mps2
    estimate = approach_with_films(FILM_ESTIMATOR, (2 * onset, 0.0), wrench=None)[-1]
    assert estimate.strike_finger == "left" and estimate.strike_s == pytest.approx(0.01)


@pytest.mark.parametrize("films", [(2.0, 2.0), (0.5, 0.5), (0.0, 0.0)])
def test_both_films_or_neither_above_the_ra_onset_is_no_film_strike(films):
    onset = TAXEL.ra_onset_mps2
    estimate = approach_with_films(FILM_ESTIMATOR, tuple(f * onset for f in films))[-1]
    assert estimate.strike_s == 0.0 and not estimate.strike_by_film
    assert estimate.strike_finger == ""


def test_the_prismatic_hand_has_no_film_strike():
    estimate = approach_with_films(ESTIMATOR, (0.0, 2 * TAXEL.ra_onset_mps2))[-1]
    assert estimate.strike_s == 0.0 and estimate.strike_finger == ""
    assert approach_with_films(ESTIMATOR, (0.0, 10.0), wrench=None)[-1].strike_s == 0.0


def test_one_film_in_the_close_is_not_a_strike():
    estimate = approach_with_films(FILM_ESTIMATOR, (0.0, 2 * TAXEL.ra_onset_mps2),
                                   stage=Stage.CLOSING)[-1]
    assert estimate.strike_s == 0.0 and not estimate.strike_by_film
    assert estimate.ra_onset_finger == "right"  # the close's own rule reads it


def test_a_film_strike_is_off_with_the_finger_strike_or_the_ra_onset():
    strike_off = ContactEstimator(
        taxel_config=TaxelAwareConfig(finger_strike=type(TAXEL.finger_strike)(enabled=False)),
        taxel_contact_n=CONTACT_N, match_confirm_window_s=CONFIRM_S,
        geometry=ESTIMATOR._geometry, film_strike=True)
    onset_off = ContactEstimator(
        taxel_config=TaxelAwareConfig(ra_onset_mps2=0.0), taxel_contact_n=CONTACT_N,
        match_confirm_window_s=CONFIRM_S, geometry=ESTIMATOR._geometry, film_strike=True)
    for estimator in (strike_off, onset_off):
        assert approach_with_films(estimator, (0.0, 10.0))[-1].strike_s == 0.0


def test_the_film_strike_is_the_linkage_hands():
    for hand, films in (("linkage", True), ("prismatic", False)):
        # what estimator_for_plan reads of a GraspPlan
        plan = types.SimpleNamespace(object_width=0.045, object_height=0.11,
                                     grasp_height=0.055, gripper_model=hand)
        estimator = estimator_for_plan(TaxelAwareControllerConfig(), plan,
                                       sa_rate_hz=SA_RATE_HZ)
        struck = approach_with_films(estimator, (0.0, 10.0))[-1].strike_finger
        assert struck == ("right" if films else ""), hand


def test_a_finger_touching_alone_after_the_other_brackets_the_object():
    memory = ContactMemory(touched_faces=(FaceTouch("right", -0.040),))
    _, estimate = ESTIMATOR.update(memory, reading(contact=(True, False), opening_m=0.040))
    assert estimate.bracket == pytest.approx((-0.010, 0.060))  # faces -40 and +20 mm
    assert estimate.touched_now == (FaceTouch("left", pytest.approx(0.020)),)


def test_the_memory_keeps_the_first_touch_into_load_and_the_faces_until_a_re_reach():
    memory = ContactMemory(first_touch_opening_m=0.07, first_touch_offset_m=0.009,
                           first_touch_finger="right", strike_since=0.5, tilted_since=0.2,
                           touched_faces=(FaceTouch("left", 0.01),))
    load = memory.after_transition(Mode.REACH, Mode.LOAD, ())
    assert (load.first_touch_opening_m, load.first_touch_finger) == (0.07, "right")
    assert (load.strike_since, load.tilted_since) == (-1.0, -1.0)
    relift = memory.after_transition(Mode.LIFT, Mode.LOAD, ())
    assert relift.first_touch_opening_m == -1.0 and relift.first_touch_offset_m == 0.009
    right = (FaceTouch("right", -0.03),)
    re_reach = memory.after_transition(Mode.REACH, Mode.RE_REACH, right)
    assert re_reach.first_touch_offset_m == 0.0
    assert re_reach.touched_faces == (FaceTouch("left", 0.01), *right)
    assert memory.after_transition(Mode.PLACE, Mode.RE_REACH, ()).touched_faces == ()


@pytest.mark.parametrize("contact,stopped,settling", [
    ((True, True), True, False),
    ((True, False), True, True),  # one pad: the fingers cannot have stopped at the grip force
    ((True, True), False, True),  # both pads, the fingers still closing
    ((False, False), True, True),
])
def test_the_grip_settles_with_both_pads_on_and_the_fingers_stopped_on_the_object(
        contact, stopped, settling):
    _, estimate = ESTIMATOR.update(ContactMemory(), reading(
        mode=Mode.LOAD, stage=Stage.NONE, contact=contact, stopped_on_object=stopped))
    assert estimate.grip_settling is settling


def test_the_confirmation_window_is_two_taxel_frames_and_a_controller_tick():
    assert match_confirm_window_s(108.0, 0.005) == pytest.approx(2 / 108.0 + 0.005)
    assert match_confirm_window_s(54.0, 0.005) > match_confirm_window_s(108.0, 0.005)
    with pytest.raises(ValueError, match="sample rate"):
        match_confirm_window_s(0.0, 0.005)


def confirm_run(touch_after_s, *, matched=(True,), mode=Mode.REACH, t0=3.0):
    """The estimates of a Reach-Load match on the first ticks (`matched`), no pad touching,
    then a pad's SA above contact_force_n from `touch_after_s` [s] after the first match
    (None: never), over 0.1 s of 5 ms ticks."""
    memory, estimates = ContactMemory(), []
    for k in range(21):
        t = t0 + 0.005 * k
        touching = touch_after_s is not None and t - t0 >= touch_after_s - 1e-9
        memory, estimate = ESTIMATOR.update(memory, reading(
            t=t, mode=mode, contact=(touching, False),
            event_matched=k < len(matched) and matched[k]))
        estimates.append(estimate)
    return estimates


def test_a_touch_within_the_window_confirms_the_reach_load_match():
    estimates = confirm_run(0.015)  # the real grasps' +3.9 to +13.9 ms, read on a tick
    assert [e.match_confirmed_s >= 0 for e in estimates[:4]] == [False, False, False, True]
    assert estimates[3].match_confirmed_s == pytest.approx(0.015)


def test_a_pad_touching_at_the_match_confirms_it_at_once():
    assert confirm_run(0.0)[0].match_confirmed_s == pytest.approx(0.0, abs=1e-12)


def test_a_match_no_pad_confirms_in_the_window_is_dropped():
    late = confirm_run(CONFIRM_S + 0.005)
    assert all(e.match_confirmed_s < 0 for e in late)
    assert all(e.match_confirmed_s < 0 for e in confirm_run(None))


def test_the_window_runs_from_the_latest_match():
    # matched on the first three ticks: a touch 25 ms after the first is 15 ms after the last
    estimates = confirm_run(0.025, matched=(True, True, True))
    assert estimates[5].match_confirmed_s == pytest.approx(0.015)


def test_no_match_is_confirmed_out_of_reach():
    assert all(e.match_confirmed_s < 0 for e in confirm_run(0.0, mode=Mode.LOAD))


def test_a_reach_load_match_no_pad_confirms_is_still_remembered_as_a_match_in_this_reach():
    """closed_untouched reads it: a match with no pad touching can be a backing's push."""
    memory, estimate = ESTIMATOR.update(ContactMemory(), reading(event_matched=True))
    assert estimate.match_confirmed_s < 0.0 and estimate.reach_matched
    _, later = ESTIMATOR.update(memory, reading(t=1.5))
    assert later.reach_matched
    reset = memory.after_transition(Mode.REACH, Mode.RE_REACH, ())
    _, after_re_reach = ESTIMATOR.update(reset, reading(t=2.0))
    assert not after_re_reach.reach_matched


def test_the_estimate_carries_the_untouched_reach_of_the_object():
    _, estimate = ESTIMATOR.update(ContactMemory(), reading())
    assert estimate.untouched_reach_m == pytest.approx(0.012 + THIN.width_along_stroke() / 2)


def test_a_touch_or_strike_at_an_earlier_close_is_remembered_for_the_rest_of_the_trial():
    """closed_untouched reads it: an object once touched or struck lies within the pads'
    reach, so a later close on nothing means it moved, not that it lies beyond."""
    untouched = ContactMemory()
    assert not untouched.after_transition(Mode.REACH, Mode.RE_REACH, ()).touched_before
    touched = dataclasses.replace(untouched, first_touch_opening_m=0.06)
    struck = dataclasses.replace(untouched, strike_finger="left")
    for memory in (touched, struck):
        re_reach = memory.after_transition(Mode.REACH, Mode.RE_REACH, ())
        reach = re_reach.after_transition(Mode.RE_REACH, Mode.REACH, ())
        assert re_reach.touched_before and reach.touched_before
        _, estimate = ESTIMATOR.update(reach, reading(t=3.0))
        assert estimate.touched_before


def test_the_first_ra_onset_of_the_close_is_remembered_with_its_film_and_opening():
    """The thin cylinder: the right film at 71.9 mm open, 23.5 mm of push to come against its
    11.5 mm tipping limit."""
    threshold = TAXEL.ra_onset_mps2
    memory, estimate = ESTIMATOR.update(ContactMemory(), reading(ra_mps2=(0.5 * threshold, 0.0)))
    assert estimate.ra_onset_finger == "" and estimate.ra_onset_opening_m < 0.0
    memory, estimate = ESTIMATOR.update(memory, reading(t=1.005, ra_mps2=(0.0, 2 * threshold)))
    assert (estimate.ra_onset_finger, estimate.ra_onset_opening_m) == ("right", 0.0719)
    assert estimate.ra_onset_topples
    memory, estimate = ESTIMATOR.update(memory, reading(
        t=1.010, ra_mps2=(2 * threshold, 2 * threshold), opening_m=0.070))
    assert (estimate.ra_onset_finger, estimate.ra_onset_opening_m) == ("right", 0.0719)
    assert memory.after_transition(Mode.REACH, Mode.RE_REACH, ()).ra_onset_opening_m < 0.0


def test_the_close_reads_an_ra_onset_between_the_ticks_by_its_peak():
    """A touch whose ring has died down by the tick's sample is still the close's onset."""
    threshold = TAXEL.ra_onset_mps2
    _, estimate = ESTIMATOR.update(ContactMemory(), reading(
        ra_mps2=(0.0, 0.0), ra_peak_mps2=(0.0, 2 * threshold)))
    assert (estimate.ra_onset_finger, estimate.ra_onset_opening_m) == ("right", 0.0719)


def test_an_ra_onset_on_both_films_in_one_tick_names_no_film():
    _, estimate = ESTIMATOR.update(ContactMemory(), reading(ra_mps2=(10.0, 10.0)))
    assert estimate.ra_onset_finger == "" and estimate.ra_onset_opening_m == 0.0719


def test_an_ra_onset_outside_the_close_is_not_remembered():
    memory, _ = ESTIMATOR.update(ContactMemory(), reading(stage=Stage.MOVING,
                                                          ra_mps2=(0.0, 10.0)))
    assert memory.ra_onset_opening_m < 0.0


def test_an_ra_onset_near_the_width_does_not_topple_the_object():
    _, estimate = ESTIMATOR.update(ContactMemory(), reading(ra_mps2=(0.0, 10.0),
                                                            opening_m=0.035))
    assert estimate.ra_onset_finger == "right" and not estimate.ra_onset_topples
