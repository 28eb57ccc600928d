"""Re-Reach, Lift-Load and Avoid, each decision and action alone (no state machine)."""

import dataclasses

import numpy as np
import pytest

from tegrasp_drake.control.controller_config import GraspControllerConfig
from tegrasp_drake.control.corrective_actions import (
    Counters, approach_retreat_target, avoid_direction, avoid_move, avoid_on_hit,
    corrective_action_of, is_hit, lift_load_grip_force, lift_load_or_fail,
    pad_accelerations_in_world, ra_history, ra_level, re_reach_shift, re_reach_target,
    relift_after_lift_load)
from tegrasp_drake.control.grasp_modes import Mode, Trigger

CONFIG = GraspControllerConfig()
BOX_WIDTH_M = 0.045
CONTACT_N = CONFIG.contact_force_n  # 0.3 N


# ---- Re-Reach -------------------------------------------------------------------------


def test_re_reach_shifts_toward_the_left_finger_by_half_the_gap():
    # The left finger stopped on a 45 mm box with the gripper 70 mm open: the box's centre
    # is (70 - 45) / 2 = 12.5 mm toward the left finger, on the +y side.
    shift = re_reach_shift([2.0, 0.0, 0.5, 0.5], 0.070, BOX_WIDTH_M, CONTACT_N)
    assert shift == pytest.approx(0.0125, abs=1e-12)


def test_re_reach_shifts_toward_the_right_finger_along_minus_y():
    shift = re_reach_shift([0.0, 2.0], 0.060, BOX_WIDTH_M, CONTACT_N)
    assert shift == pytest.approx(-0.0075, abs=1e-12)


@pytest.mark.parametrize("sa_n", [[0.0, 0.0], [2.0, 2.0], [CONTACT_N, 0.0]])
def test_re_reach_does_not_shift_unless_exactly_one_finger_touches(sa_n):
    assert re_reach_shift(sa_n, 0.070, BOX_WIDTH_M, CONTACT_N) == 0.0


def test_re_reach_never_shifts_away_when_the_opening_is_narrower_than_the_object():
    assert re_reach_shift([2.0, 0.0], 0.040, BOX_WIDTH_M, CONTACT_N) == 0.0


def test_re_reach_target_moves_along_world_y_only():
    target = re_reach_target(np.array([0.72, 0.0, 0.06]), 0.0125)
    np.testing.assert_array_equal(target, [0.72, 0.0125, 0.06])


# The default Reach: from 3 cm behind and 9 cm above the grasp (docs/model.md, "The scene")
GRASP_XYZ = (0.72, 0.0, 0.055)
START_XYZ = (0.69, 0.0, 0.145)


def test_an_approach_retreat_retraces_the_reach_and_so_lifts():
    # a finger struck on the way down, 25 mm above the grasp: 2 cm back along the path lifts
    # it 2 cm x 90 / 94.9 = 19 mm, where a retreat along -x alone lifts nothing
    here = np.array([0.72 - 0.025 / 3, 0.0, 0.08])
    target = approach_retreat_target(here, 0.02, start_xyz=START_XYZ, grasp_xyz=GRASP_XYZ)
    assert np.linalg.norm(target - here) == pytest.approx(0.02)
    assert target[2] - here[2] == pytest.approx(0.02 * 0.09 / np.hypot(0.03, 0.09))
    assert target[0] < here[0]


def test_an_approach_retreat_stops_at_the_start_pose():
    # retreats one after another never take the arm behind its start, toward its singularity
    here = np.array([0.69 + 0.005 / 3, 0.0, 0.14])
    target = approach_retreat_target(here, 0.02, start_xyz=START_XYZ, grasp_xyz=GRASP_XYZ)
    np.testing.assert_allclose(target, START_XYZ, atol=1e-12)


def test_an_approach_retreat_keeps_the_shift_along_the_stroke():
    here = np.array([0.71, 0.02, 0.085])
    target = approach_retreat_target(here, 0.02, start_xyz=START_XYZ, grasp_xyz=GRASP_XYZ)
    assert target[1] == pytest.approx(0.02)


# ---- Lift-Load ------------------------------------------------------------------------


def test_lift_load_doubles_the_grip_force():
    assert lift_load_grip_force(50.0, CONFIG) == 100.0


def test_lift_load_grip_force_stops_at_the_grippers_largest():
    assert lift_load_grip_force(150.0, CONFIG) == 235.0


def test_a_slip_shorter_than_slip_s_keeps_lifting():
    assert lift_load_or_fail(0.5 * CONFIG.lift_load.slip_s, Counters(), CONFIG) is None


def test_a_slip_of_slip_s_goes_back_to_load():
    decision = lift_load_or_fail(CONFIG.lift_load.slip_s, Counters(lift_loads=1), CONFIG)
    assert (decision.mode, decision.trigger) == (Mode.LOAD, Trigger.CORRECTIVE)


def test_a_slip_after_max_lift_loads_fails():
    decision = lift_load_or_fail(CONFIG.lift_load.slip_s, Counters(lift_loads=2), CONFIG)
    assert decision.mode == Mode.FAILED
    assert decision.reason == "the object still slips after 2 Lift-Load corrections"


def test_lift_load_switched_off_ignores_a_slip():
    off = dataclasses.replace(CONFIG,
                              lift_load=dataclasses.replace(CONFIG.lift_load, enabled=False))
    assert lift_load_or_fail(1.0, Counters(), off) is None


def test_relift_waits_for_the_raised_force_quiet_ra_and_settling():
    ready = dict(grip_reached=True, slip_quiet=True, time_in_load_s=CONFIG.lift_load.relift_settle_s,
                 counters=Counters(lift_loads=1), config=CONFIG)
    decision = relift_after_lift_load(**ready)
    assert (decision.mode, decision.trigger) == (Mode.LIFT, Trigger.CORRECTIVE)
    assert relift_after_lift_load(**{**ready, "grip_reached": False}) is None
    assert relift_after_lift_load(**{**ready, "slip_quiet": False}) is None
    assert relift_after_lift_load(**{**ready, "time_in_load_s": 0.1}) is None


def test_the_first_load_never_relifts():
    assert relift_after_lift_load(grip_reached=True, slip_quiet=True, time_in_load_s=5.0,
                                  counters=Counters(), config=CONFIG) is None


# ---- Avoid ----------------------------------------------------------------------------


def test_a_hit_is_ra_above_the_threshold_after_the_refractory_time():
    assert is_hit(3.5, 0.3, CONFIG)
    assert not is_hit(3.5, 0.29, CONFIG)  # the stop of the lift still rings
    assert not is_hit(3.0, 1.0, CONFIG)  # at the threshold, not above


def test_a_hit_counts_from_each_films_level():
    # A creeping grip holds the left film at a steady 1.9 m/s^2 (its force falling at 0.57
    # N/s): a reading 3.03 m/s^2 above that level is a hit, one at its noise is not.
    assert is_hit([4.93, 0.0], 1.0, CONFIG, level_mps2=[1.9, 0.0])
    assert not is_hit([3.7, 0.0], 1.0, CONFIG, level_mps2=[1.9, 0.0])
    # each film against its own level: the quiet right film's burst is a hit
    assert is_hit([3.7, 3.7], 1.0, CONFIG, level_mps2=[1.9, 0.4])
    assert not is_hit([10.0, 0.0], 0.29, CONFIG, level_mps2=[1.9, 0.0])  # still refractory


def test_the_hit_level_is_the_mean_of_the_last_hit_level_s_of_ticks():
    period = CONFIG.update_period_s
    keep = round(CONFIG.avoid.hit_level_s / period)
    history = ()
    for k in range(keep + 5):
        history = ra_history(history, (float(k), 1.0), CONFIG.avoid.hit_level_s, period)
    assert len(history) == keep and history[-1] == (float(keep + 4), 1.0)
    assert ra_level(history) == pytest.approx((np.mean(range(5, keep + 5)), 1.0))
    assert ra_level(()) == (0.0, 0.0)  # nothing yet: the number alone
    assert ra_history(history, (9.0, 9.0), 0.0, period) == ()  # hit_level_s 0: no level


def test_a_hit_starts_avoid_unless_switched_off():
    decision = avoid_on_hit(True, Counters(), CONFIG)
    assert (decision.mode, decision.trigger) == (Mode.AVOID, Trigger.THRESHOLD)
    assert avoid_on_hit(False, Counters(), CONFIG) is None
    off = dataclasses.replace(CONFIG, avoid=dataclasses.replace(CONFIG.avoid, enabled=False))
    assert avoid_on_hit(True, Counters(), off) is None


def test_hits_past_max_avoids_are_not_avoided():
    limit = CONFIG.avoid.max_avoids
    assert avoid_on_hit(True, Counters(avoids=limit - 1), CONFIG) is not None
    assert avoid_on_hit(True, Counters(avoids=limit), CONFIG) is None
    none = dataclasses.replace(CONFIG, avoid=dataclasses.replace(CONFIG.avoid, max_avoids=0))
    assert avoid_on_hit(True, Counters(), none) is None


def test_pad_frames_and_hit_direction():
    # Each pad's normal (its z) points at the other finger: left pad toward -y, right +y.
    normals = pad_accelerations_in_world(np.array([0, 0, 1.0, 0, 0, 1.0]))
    np.testing.assert_allclose(normals, [[0, -1, 0], [0, 1, 0]], atol=1e-12)
    # Pushed into the left pad (+y side): away is +y; into the right pad: -y.
    np.testing.assert_allclose(avoid_direction([3.0, -2.0], np.zeros(3), 1.0), [0, 1, 0])
    np.testing.assert_allclose(avoid_direction([-1.0, 2.0], np.zeros(3), 1.0), [0, -1, 0])
    # Even pads: the common horizontal acceleration, else up.
    np.testing.assert_allclose(avoid_direction([0.2, 0.1], [3.0, 0.0, 9.0], 1.0), [1, 0, 0])
    np.testing.assert_allclose(avoid_direction([0.0, 0.0], np.zeros(3), 1.0), [0, 0, 1])


def test_avoid_moves_away_from_the_pad_the_hit_pushed_into():
    # 30 ms of sensing at 5 ms ticks: 6 ticks; the left pad gained 3 N a tick on average.
    p_WG = np.array([0.72, 0.0, 0.11])
    move = avoid_move(p_WG, [18.0, -12.0], [0.0, -40.0, 0.0], CONFIG)
    np.testing.assert_allclose(move.delta_sa_n, [3.0, -2.0])
    np.testing.assert_array_equal(move.direction_W, [0.0, 1.0, 0.0])
    np.testing.assert_allclose(move.p_end_W, [0.72, 0.05, 0.11], atol=1e-15)


def test_avoid_follows_the_common_acceleration_when_the_pads_gain_alike():
    move = avoid_move(np.zeros(3), [1.2, 0.6], [-6.0, 8.0, 50.0], CONFIG)
    np.testing.assert_allclose(move.direction_W, [-0.6, 0.8, 0.0])
    np.testing.assert_allclose(move.p_end_W, [-0.03, 0.04, 0.0])


# ---- Which transition starts which action ---------------------------------------------


def test_each_corrective_transition_names_its_action():
    assert corrective_action_of(Mode.REACH, Mode.RE_REACH) == "re_reach"
    assert corrective_action_of(Mode.LOAD, Mode.RE_REACH) == "re_reach"
    assert corrective_action_of(Mode.LIFT, Mode.LOAD) == "lift_load"
    assert corrective_action_of(Mode.HOLD, Mode.AVOID) == "avoid"
    assert corrective_action_of(Mode.REACH, Mode.LOAD) is None
    assert corrective_action_of(Mode.RE_REACH, Mode.REACH) is None
