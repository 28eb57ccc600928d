"""A trial log's contents must be ones a trial could give: taxel, film and accelerometer
readings within what the sensors give, object positions and quaternions a workspace allows,
joint angles within the JACO2's limits, a timeline of transitions inside the log's span with
phase starts that agree, correlation scores in [-1, 1] and stored results the log agrees
with; anything else is refused in one line."""

import numpy as np
import pytest

from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.fake_trials import whole_result
from tests.bad_input.probes import (META, RESULT, SCENARIO, TIMELINE, assert_one_line_error,
                                    log_refusal, logged_transition, meta_refused, refused_log,
                                    refused_meta, result_refused, run_cli, spoiled, trial_log,
                                    trial_log_with)


# _trial_log's time span: every time base from 0 to 0.1 s.
_SPAN_END_S = 0.1


def _transition(t, from_mode, to_mode):
    return {"t": t, "from": from_mode, "to": to_mode, "trigger": "timer", "reason": "test"}


# Reach -> Load -> Lift, inside the log's 0.1 s.
_CHAIN = [_transition(0.02, "Reach", "Load"), _transition(0.05, "Load", "Lift")]


def test_a_trial_log_with_an_ordered_chained_timeline_inside_its_span_is_read(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz", {
        "transitions": _CHAIN, "phase_starts": {"Load": 0.02, "Lift": 0.05},
        "events": {"reach_load": 0.015, "place_unload": None}, "grip_force": 25.0,
        "sim_time_s": _SPAN_END_S, "wall_time_s": 3.0})
    assert len(load_trial_log(path).meta["transitions"]) == 2


def test_a_trial_log_keeps_its_transitions_rule_codes_and_refuses_an_unknown_one(tmp_path):
    coded = [{**_CHAIN[0], "code": "reach_event"}, {**_CHAIN[1], "code": "load_lift_event"}]
    path = trial_log_with(tmp_path / "coded.npz", {"transitions": coded})
    assert [t["code"] for t in load_trial_log(path).meta["transitions"]] == [
        "reach_event", "load_lift_event"]
    message = refused_log(tmp_path, {"transitions": [{**_CHAIN[0], "code": "reach_evnt"}]})
    assert "meta 'transitions[0]'" in message and "'reach_evnt'" in message, message


# Rule: a trial log's metadata is checked as a whole against the log: the timeline holds at
# most as many transitions as a controller can take, in time order, inside the log's time
# span, each starting where the one before ended; phase start and event times lie in the span.
@pytest.mark.parametrize("meta, expected", [
    ({"transitions": [_CHAIN[1], _CHAIN[0]]}, "meta 'transitions[1]' at 0.02 s comes before"),
    ({"transitions": [_CHAIN[0], _transition(0.02, "Load", "Lift")]},
     "meta 'transitions[1]' at 0.02 s comes before"),
    ({"transitions": [_CHAIN[0], _transition(5.0, "Load", "Lift")]},
     "meta 'transitions[1]' at 5 s lies outside the log's time span"),
    ({"transitions": [_CHAIN[0], _transition(0.05, "Lift", "Hold")]},
     "meta 'transitions[1]' starts from 'Lift', but transitions[0] went to 'Load'"),
    ({"phase_starts": {"Hold": -1e308}}, "meta 'phase_starts' time of 'Hold'"),
    ({"events": {"reach_load": 1e9}}, "meta 'events' time of 'reach_load'"),
], ids=["order", "same-time", "outside", "chain", "phase-start", "event"])
def test_trial_log_timeline_is_checked_against_the_log(tmp_path, meta, expected):
    assert expected in refused_log(tmp_path, meta)


def test_a_timeline_of_more_transitions_than_a_controller_takes_is_refused_in_one_line(
        tmp_path, capfd):
    from tegrasp_drake.scenario.trial_log_file import most_transitions
    step = _SPAN_END_S / (3 * most_transitions(_SPAN_END_S))
    modes = ["Hold", "Avoid"]
    timeline = [_transition(step * (k + 1), modes[k % 2], modes[(k + 1) % 2])
                for k in range(most_transitions(_SPAN_END_S) + 1)]
    path = trial_log_with(tmp_path / "trial.npz", {"transitions": timeline})
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "o.png")], capfd)
    assert_one_line_error(code, text, f"meta 'transitions' holds {len(timeline)} entries",
                          f"at most {most_transitions(_SPAN_END_S)}")
    assert not (tmp_path / "o.png").exists()


# Rule: each logged channel with a physical range is checked against it when the log is read,
# by every reader: the gripper's request and status registers are bytes (0-255), RA is a
# magnitude (Eq. 2, >= 0).
@pytest.mark.parametrize("arrays, expected", [
    ({"gripper_command": spoiled((11, 3), 0, 1e9)},
     "'gripper_command' column 0 (rPR) holds 1000000000, outside 0 to 255"),
    ({"gripper_command": spoiled((11, 3), 2, -1.0)}, "'gripper_command' column 2 (rFR) holds -1"),
    ({"gripper_status": spoiled((11, 8), 6, 300.0)}, "'gripper_status' column 6 (gPO) holds 300"),
    ({"channels": spoiled((101, 4), 3, -2.0)}, "'channels' column 3 (ra_right) holds -2"),
], ids=["command-1e9", "command-negative", "status", "ra-negative"])
def test_logged_channels_are_checked_against_their_physical_range(tmp_path, arrays, expected):
    message = refused_log(tmp_path, None, **arrays)
    assert expected in message, message


def _object_state(quaternion):
    """_trial_log's 11 object states, sample 5's orientation `quaternion` (w, x, y, z)."""
    state = np.zeros((11, 13))
    state[:, 0] = 1.0
    state[5, :4] = quaternion
    return state


def test_a_trial_log_with_unit_object_quaternions_is_read(tmp_path):
    turned = [np.cos(0.3), 0.0, 0.0, np.sin(0.3)]  # 0.6 rad about z
    log = load_trial_log(trial_log(tmp_path / "trial.npz", object_state=_object_state(turned)))
    assert log.object_state.shape == (11, 13)


# Rule: the object's orientation is a unit quaternion (the state of a rigid body), within the
# drift its integration leaves.
@pytest.mark.parametrize("quaternion", [[0.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 0.0]],
                         ids=["zero", "norm-2"])
def test_a_trial_log_with_an_object_quaternion_far_from_unit_is_refused(tmp_path, quaternion):
    log_refusal(trial_log(tmp_path / "trial.npz", object_state=_object_state(quaternion)),
             "'object_state' sample 5 holds an orientation quaternion of norm")


# Reach -> Load -> Lift -> Hold -> Re-Reach -> Reach -> Load, inside _trial_log's 0.1 s.
_TIMELINE = [_transition(0.02, "Reach", "Load"), _transition(0.03, "Load", "Lift"),
             _transition(0.04, "Lift", "Hold"), _transition(0.05, "Hold", "Re-Reach"),
             _transition(0.06, "Re-Reach", "Reach"), _transition(0.07, "Reach", "Load")]


# When each mode was first entered, as runs/trial.py writes it.
_STARTS = {"Load": 0.02, "Lift": 0.03, "Hold": 0.04, "Re-Reach": 0.05, "Reach": 0.06}


def test_a_trial_log_whose_phase_starts_are_the_first_entries_is_read(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz",
                           {"transitions": _TIMELINE, "phase_starts": _STARTS})
    assert load_trial_log(path).meta["phase_starts"] == _STARTS


# Rule: phase_starts says when the timeline first entered each mode it entered: a Hold
# starting before the Load and Lift that led to it is not what the trial did.
@pytest.mark.parametrize("starts, expected", [
    ({**_STARTS, "Hold": 0.01}, "gives 'Hold' starting at 0.01 s, but the transitions first "
                                "enter it at 0.04 s"),
    ({**_STARTS, "Load": 0.07}, "gives 'Load' starting at 0.07 s"),
    ({**_STARTS, "Place": 0.08}, "names 'Place', which no transition enters"),
    ({k: v for k, v in _STARTS.items() if k != "Hold"}, "lacks 'Hold'"),
], ids=["before", "last-entry", "never-entered", "missing"])
def test_a_trial_log_whose_phase_starts_contradict_its_transitions_is_refused(
        tmp_path, starts, expected):
    refused_meta(tmp_path, {"transitions": _TIMELINE, "phase_starts": starts},
                  f"meta 'phase_starts' {expected}")


# Rule: without a timeline (an ideal grasp's log), the phases start in the order `phases`
# lists them.
def test_an_ideal_grasp_log_whose_phase_starts_are_out_of_order_is_refused(tmp_path):
    phases = ["approach", "close", "lift"]
    path = trial_log_with(tmp_path / "ok.npz", {
        "phases": phases, "phase_starts": {"approach": 0.0, "close": 0.02, "lift": 0.05}})
    assert load_trial_log(path).meta["phases"] == phases
    refused_meta(tmp_path, {"phases": phases, "phase_starts": {"approach": 0.0, "close": 0.06,
                                                                "lift": 0.05}},
                  "meta 'phase_starts' gives 'lift' starting at 0.05 s, before 'close'")
    refused_meta(tmp_path, {"phases": phases, "phase_starts": {"hover": 0.0}},
                  "meta 'phase_starts' names 'hover', which is not one of the phases")


# Rule: the JACO2's logged joint angles lie within the joints' declared limits (joints 2 and 3;
# the others turn without end): 1e300 rad is not an arm's pose.
@pytest.mark.parametrize("name", ["arm_q", "arm_q_desired"])
def test_a_trial_log_with_joint_angles_beyond_the_jaco2s_limits_is_refused(tmp_path, name):
    q = np.tile([0.0, 3.0, 1.0, 0.0, 0.0, 0.0], (11, 1))
    assert load_trial_log(trial_log(tmp_path / "ok.npz", **{name: q})) is not None
    q[4, :] = 1e300
    log_refusal(trial_log(tmp_path / "trial.npz", **{name: q}),
             f"'{name}' column 1 (joint 2) holds 1e+300 rad, outside")

FORCE_TAXELS = SCENARIO + "tactile:\n  transducer: force\n  noise_std_n: 0.005\n"


def _log(tmp_path, scenario, name, row, values):
    """trial_log_with's log storing `scenario` (None: none), its array `name` (ones but for
    taxels' rest readings) with `values` written into sample `row`."""
    with np.load(trial_log(tmp_path / "base.npz")) as base:
        array = base[name].copy()
    array[row, ...] = values
    meta = {"scenario": scenario} if scenario is not None else {}
    return trial_log_with(tmp_path / "trial.npz", meta, **{name: array})


# Rule: a taxel reads what its transducer's model gives: the capacitive taxel's calibrated
# newtons are clipped at zero; the force transducer's reading dips below zero by its noise (to
# 10 sigma), and neither reads past its full scale.
@pytest.mark.parametrize("scenario, value, expected", [
    (SCENARIO, -1e6, "holds -1000000 N, outside 0 to"),
    (SCENARIO, -0.5, "holds -0.5 N, outside 0 to"),
    (FORCE_TAXELS, -1e6, "holds -1000000 N, outside -0.0505 to 235.05 N"),
    (FORCE_TAXELS, 1e4, "holds 10000 N, outside -0.0505 to 235.05 N"),
    (None, -1e6, "holds -1000000 N or counts, outside -32768 to"),
], ids=["capacitive-huge", "capacitive-negative", "force-huge", "force-past-grip", "any"])
def test_taxel_readings_no_transducer_of_the_trial_gives_are_refused(tmp_path, scenario, value,
                                                                    expected):
    log_refusal(_log(tmp_path, scenario, "taxels", 5, value),
             f"'taxels' sample 5 column 0 {expected}")


@pytest.mark.parametrize("scenario, value", [(SCENARIO, 0.0), (FORCE_TAXELS, -0.03)],
                         ids=["capacitive-rest", "force-noise"])
def test_taxel_readings_a_transducer_gives_at_rest_are_read(tmp_path, scenario, value):
    log = load_trial_log(_log(tmp_path, scenario, "taxels", 5, value))
    assert log.taxels[5, 0] == value


# Rule: a pad's RA reading lies within its transducer's full scale (the film's readout clips
# at the amplifier's swing or the converter's last code).
@pytest.mark.parametrize("scenario, value, expected", [
    (SCENARIO, 1e300, "holds 1e+300 m/s^2, outside -2526.62 to 2526.62 m/s^2"),
    (SCENARIO, -3000.0, "holds -3000 m/s^2, outside -2526.62 to 2526.62 m/s^2"),
    (None, 1e300, "holds 1e+300 m/s^2, outside"),
], ids=["huge", "past-full-scale", "any"])
def test_pad_accelerations_past_the_transducers_full_scale_are_refused(tmp_path, scenario, value,
                                                                      expected):
    log_refusal(_log(tmp_path, scenario, "pad_acceleration", 50, value),
             f"'pad_acceleration' sample 50 column 0 {expected}")


def test_pad_accelerations_within_the_films_full_scale_are_read(tmp_path):
    log = load_trial_log(_log(tmp_path, SCENARIO, "pad_acceleration", 50, -2500.0))
    assert log.pad_acceleration[50, 0] == -2500.0


# Rule: the object starts on the table and moves no faster than the hand or a hit can drive it
# (or falls): 100 m away after 0.1 s is not where an object can be.
@pytest.mark.parametrize("column, value, expected", [
    (4, 100.0, "column 4 (x) holds 100 m, outside"),
    (6, 100.0, "column 6 (z) holds 100 m, outside"),
    (6, -100.0, "column 6 (z) holds -100 m, outside"),
], ids=["x", "z-up", "z-down"])
def test_an_object_position_beyond_where_it_can_be_is_refused(tmp_path, column, value, expected):
    path = _log(tmp_path, SCENARIO, "object_state", 5, 0.0)
    with np.load(path) as data:
        state = data["object_state"].copy()
    state[:, 0] = 1.0
    state[5, column] = value
    path = trial_log_with(tmp_path / "moved.npz", {"scenario": SCENARIO}, object_state=state)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert (f"'object_state' sample 5 {expected}" in message and str(path) in message
            and "\n" not in message), message


def test_an_object_carried_within_the_reach_is_read(tmp_path):
    state = np.zeros((11, 13))
    state[:, 0] = 1.0
    state[:, 4:7] = [0.72, 0.0, 0.4]  # lifted 40 cm above its marker
    path = trial_log_with(tmp_path / "trial.npz", {"scenario": SCENARIO}, object_state=state)
    assert load_trial_log(path).object_state[3, 6] == 0.4


# Rule: Eq. 1's SA is a pad's 12 taxels' sum and Eq. 2's RA the size of its 3 axes' vector, so
# each lies within 12 times, or sqrt(3) times, what the scenario's sensors read.
@pytest.mark.parametrize("column, value, expected", [
    (0, -1e6, "column 0 (sa_left) holds -1000000 N, outside 0 to 8136.93 N"),
    (3, 1e300, "column 3 (ra_right) holds 1e+300 m/s^2, outside 0 to 4376.23 m/s^2"),
], ids=["sa", "ra"])
def test_sa_and_ra_beyond_what_the_sensors_give_are_refused(tmp_path, column, value, expected):
    log_refusal(_log(tmp_path, SCENARIO, "channels", 50, [1.0] * column + [value]
                  + [1.0] * (3 - column)), f"'channels' sample 50 {expected}")


# Rule: the accelerometer transducer (no electronics) reads at most twice (its high-pass) the
# pad's largest acceleration: its top speed reversed within one plant step, and gravity.
def test_an_accelerometer_reading_no_pad_motion_gives_is_refused(tmp_path):
    scenario = SCENARIO + "vibration:\n  transducer: accelerometer\n"
    assert load_trial_log(_log(tmp_path, scenario, "pad_acceleration", 50, 3000.0)) is not None
    log_refusal(_log(tmp_path, scenario, "pad_acceleration", 50, 1e6),
             "'pad_acceleration' sample 50 column 0 holds 1000000 m/s^2, outside")


# Rule: a timeline's length is bounded by its own log's span and its controller's Avoid timing
# (two transitions an Avoid cycle, at least a controller update apart), not by the default
# timing over the longest run: a user's short Avoid timings over a long run fit, a 12 s log
# cannot hold the 461 entries the longest default run could.
def test_the_most_transitions_follow_the_logs_span_and_its_avoid_timing():
    import dataclasses

    from tegrasp_drake.control.controller_config import GraspControllerConfig
    from tegrasp_drake.scenario.trial_log_file import most_transitions
    quick = GraspControllerConfig()
    quick = dataclasses.replace(quick, avoid=dataclasses.replace(
        quick.avoid, hit_refractory_s=0.05, sense_s=0.01, move_s=0.04))
    corrections_only = most_transitions(0.0)  # and one Avoid cycle begun at the end
    assert most_transitions(12.0) - corrections_only == 2 * 12  # 0.93 s cycles
    assert abs(most_transitions(85.0, quick) - corrections_only - 2 * 850) <= 2  # 0.1 s
    assert most_transitions(12.0) < 461 < most_transitions(85.0, quick)
    no_pause = dataclasses.replace(quick, avoid=dataclasses.replace(
        quick.avoid, hit_refractory_s=0.0, sense_s=0.0, move_s=0.0))
    assert abs(most_transitions(1.0, no_pause) - corrections_only - 2 * 100) <= 2  # 5 ms updates


# Rule: a result's success flags are what judge_trial makes of its other fields: a hold
# succeeds exactly when held 3 s, and an unload only in a trial that ends Done.
@pytest.mark.parametrize("data, expected", [
    ({"hold_success": True, "unload_success": True, "final_mode": "Failed", "hold_time_s": 0.0},
     "field 'unload_success' is true but 'final_mode' is Failed"),
    ({"hold_success": True, "final_mode": "Failed", "hold_time_s": 0.0},
     "field 'hold_success' is true but 'hold_time_s' is 0 s (a hold succeeds when held at "
     "least 3 s)"),
    ({"hold_success": False, "final_mode": "Done", "hold_time_s": 4.5},
     "field 'hold_success' is false but 'hold_time_s' is 4.5 s"),
], ids=["unload-in-failed", "held-0-s", "not-held-4.5-s"])
def test_success_flags_contradicting_the_result_are_refused(data, expected):
    result_refused(data, expected)


def test_a_result_held_then_failed_is_read():
    """Hold, then a drop while placing: 8 committed records end so (held, final Failed)."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    timeline = [logged_transition(1.0, "Reach", "Load"), logged_transition(1.5, "Load", "Lift"),
                {"t": 2.5, "from": "Lift", "to": "Hold", "trigger": "timer", "reason": "lifted"},
                {"t": 5.7, "from": "Hold", "to": "Place", "trigger": "timer", "reason": "held"},
                {"t": 6.5, "from": "Place", "to": "Failed", "trigger": "threshold",
                 "reason": "object lost"}]
    result = TrialResult.from_dict(whole_result(**{"hold_success": True, "final_mode": "Failed",
                                    "hold_time_s": 3.2, "transitions": timeline,
                                    "failure": "object lost"}))
    assert result.hold_success and not result.unload_success


# Rule: the memorized detector's scores are Eq. 3 correlations, in [-1, 1]; the heuristic
# detector's are channel/threshold ratios (above 1 on a firm grasp), so only finite.
@pytest.mark.parametrize("controller", ["memorized", "fixed_load_time", "taxel_aware"])
def test_correlation_scores_outside_minus_one_to_one_are_refused(controller):
    transitions = [logged_transition(1.0, "Reach", "Load", [7.0, 9.0, -3.0, 1e300])]
    result_refused({"hold_success": False, "controller": controller, "final_mode": "Load",
                     "transitions": transitions},
                    "field 'transitions[0].scores' holds 7, outside -1 to 1 (Eq. 3 scores are "
                    f"correlations, from the {controller} controller's detector)")


def test_the_heuristic_detectors_ratios_are_read():
    from tegrasp_drake.scenario.trial_result import TrialResult
    transitions = [logged_transition(1.0, "Reach", "Load", [5.2, 4.35, 0.5, 0.1],
                                     trigger="heuristic_event")]
    result = TrialResult.from_dict(whole_result(**{"hold_success": False, "controller": "heuristic",
                                    "final_mode": "Load", "transitions": transitions}))
    assert result.transitions[0].scores[0] > 1.0


# Rule: the stored result's transitions are the log's timeline, entry for entry; two entries
# that differ are named with the fields they differ in, both values in full (an entry's
# summary, mode to mode at a rounded time, may print the same for both).
@pytest.mark.parametrize("transitions, expected", [
    ([TIMELINE[0], {**TIMELINE[1], "to": "Hold"}],
     "meta 'result' transitions[1] and the log's 'transitions[1]' (Load -> Lift at 0.05 s "
     "(memorized_event)) differ in 'to': 'Hold' in the result, 'Lift' in the log (a trial has "
     "one timeline)"),
    ([{**TIMELINE[0], "scores": [0.5, 0.5, 0.5, 0.5]}, TIMELINE[1]],
     "meta 'result' transitions[0] and the log's 'transitions[0]' (Reach -> Load at 0.02 s "
     "(memorized_event)) differ in 'scores': [0.5, 0.5, 0.5, 0.5] in the result, "
     "[0.9, 0.8, 0.7, 0.95] in the log"),
    ([{**TIMELINE[0], "t": 0.0200000001, "reason": "edited"}, TIMELINE[1]],
     "differ in 't': 0.0200000001 in the result, 0.02 in the log; 'reason': 'edited' in the "
     "result, 'event' in the log"),
    (TIMELINE + [logged_transition(0.08, "Lift", "Hold")],
     "meta 'result' transitions[2] is Lift -> Hold at 0.08 s (memorized_event), but the log's "
     "'transitions[2]' is absent"),
    (TIMELINE[:1], "meta 'result' transitions[1] is absent"),
], ids=["to-hold", "scores", "time-and-reason", "one-more", "one-fewer"])
def test_a_stored_result_with_another_timeline_is_refused(tmp_path, transitions, expected):
    result = {**RESULT, "transitions": transitions, "final_mode": transitions[-1]["to"]}
    meta_refused(tmp_path, {**META, "result": result}, expected)


# Rule: the stored result is of the log's scenario's object and of a registered controller,
# its own fields consistent (TrialResult's relations).
@pytest.mark.parametrize("change, expected", [
    ({"result": {**RESULT, "object": "../../../etc/passwd"}},
     "meta 'result' is of object '../../../etc/passwd', but its 'scenario' grasps 'box'"),
    ({"controller": "evil", "result": {**RESULT, "controller": "evil"}},
     "meta 'controller' must be a controller name, one of memorized, heuristic"),
    ({"result": {**RESULT, "hold_success": True, "unload_success": True,
                 "final_mode": "Failed"}},
     "meta 'result' is not a trial result's JSON form: TrialResult: field 'unload_success' is "
     "true but 'final_mode' is Failed"),
    ({"result": {**RESULT, "corrective_actions": ["x" * 100_000] * 30}},
     "field 'corrective_actions[0]' must be one of"),
], ids=["object", "controller", "unload-in-failed", "actions"])
def test_a_stored_result_the_log_contradicts_is_refused(tmp_path, change, expected):
    meta_refused(tmp_path, {**META, **change}, expected)


# Rule: a memorized detector's scores are correlations, in the result and the timeline alike.
def test_correlation_scores_out_of_range_in_a_log_are_refused(tmp_path):
    bad = [{**TIMELINE[0], "scores": [7.0, 9.0, -3.0, 1e300]}, TIMELINE[1]]
    meta_refused(tmp_path, {**META, "transitions": bad, "result": {**RESULT, "transitions": bad}},
                  "field 'transitions[0].scores' holds 7, outside -1 to 1")
    no_result = {key: value for key, value in META.items() if key != "result"}
    meta_refused(tmp_path, {**no_result, "transitions": bad},
                  "meta 'transitions[0].scores' holds 7, outside -1 to 1")


# Rule: a controller without a detector (the open-loop script) logs no scores on any
# transition; a hand-edited record or log that gives its timer transitions some is corrupt.
def test_scores_on_the_transitions_of_a_controller_without_a_detector_are_refused():
    from tegrasp_drake.scenario.trial_result import TrialResult
    timeline = [logged_transition(1.0, "Reach", "Load", trigger="timer")]
    fields = {"controller": "open_loop", "final_mode": "Load", "transitions": timeline}
    assert TrialResult.from_dict(whole_result(**fields)).transitions[0].scores is None
    scored = [logged_transition(1.0, "Reach", "Load", [5.0] * 4, trigger="timer")]
    result_refused({**fields, "transitions": scored},
                   "field 'transitions[0].scores' (at 1 s) is set, but the open_loop "
                   "controller has no event detector, so its transitions carry no scores")


def test_a_correlation_one_round_off_past_one_is_read():
    """The streaming matcher's running window energy can put a true 1 a few ulps past it."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    transitions = [logged_transition(1.0, "Reach", "Load", [1.0 + 1e-12, 1.0, -1.0 - 1e-12, 0.5])]
    result = TrialResult.from_dict(whole_result(**{"hold_success": False, "controller": "memorized",
                                    "final_mode": "Load", "transitions": transitions}))
    assert result.transitions[0].scores[0] > 1.0


def test_a_trial_log_whose_scenario_names_the_real_devices_is_refused(tmp_path):
    """A trial log comes from a simulated trial; a run on the devices is an LCM log."""
    hardware = SCENARIO + "station: !HardwareStationConfig {}\n"
    log_refusal(trial_log_with(tmp_path / "trial.npz", {"scenario": hardware}),
                "meta 'scenario' names the real devices (station: !HardwareStationConfig), but "
                "a trial log is written by a simulated trial (tegrasp trial)")


def _varying_log(tmp_path, name="trial.npz", **changes):
    """trial_log_with's log whose taxels and pad accelerations change from sample to sample
    (its channels computed from them, as the loggers record them)."""
    rng = np.random.default_rng(7)
    taxels = rng.uniform(0.0, 2.0, (11, 24))
    accelerations = rng.uniform(-5.0, 5.0, (101, 6))
    arrays = {"taxels": taxels, "true_taxels": taxels, "pad_acceleration": accelerations}
    arrays.update(changes)
    return trial_log_with(tmp_path / name, {"scenario": FORCE_TAXELS}, **arrays)


def test_a_trial_log_whose_channels_are_eq_1_and_2_of_its_samples_is_read(tmp_path):
    log = load_trial_log(_varying_log(tmp_path))
    assert log.channels[20, 0] == pytest.approx(log.taxels[3, :12].sum())


# Rule: the logged channels are Eq. 1 of the taxels (held between taxel samples) and Eq. 2 of
# the pad accelerations: taxels reversed in time, pads swapped or a channel edited no longer
# agree with them, and the log is refused rather than drawn as one trial.
@pytest.mark.parametrize("change, expected", [
    ("taxels reversed", "'channels' sample 0 (t = 0 s) column 0 (sa_left) holds"),
    ("pads swapped", "column 2 (ra_left) holds"),
    ("sa edited", "'channels' sample 40 (t = 0.04 s) column 1 (sa_right) holds 3, but the "
                  "pad's 12 taxels at sample 5 sum to"),
], ids=["reversed", "swapped", "edited"])
def test_channels_that_disagree_with_the_taxels_or_accelerations_are_refused(tmp_path, change,
                                                                            expected):
    with np.load(_varying_log(tmp_path, "whole.npz")) as whole:
        taxels, axes, channels = (whole[n].copy() for n in ("taxels", "pad_acceleration",
                                                           "channels"))
    if change == "taxels reversed":
        spoilt = {"taxels": taxels[::-1], "true_taxels": taxels[::-1], "channels": channels}
    elif change == "pads swapped":
        spoilt = {"pad_acceleration": axes[:, [3, 4, 5, 0, 1, 2]], "channels": channels}
    else:
        channels[40, 1] = 3.0
        spoilt = {"channels": channels}
    log_refusal(_varying_log(tmp_path, **spoilt), expected)
    log_refusal(_varying_log(tmp_path, **spoilt), "the taxels or the channels were changed"
                if change != "pads swapped" else "the accelerations or the channels were changed")


# Rule: a trial log's hit marker (meta 'events' 'hit', the figures' "hit" line) is its
# scenario's hit (disturbance.hit_time_s), present when the hit came within the log and only
# then, and no scenario hit lies before the log's first sample; a marker that disagrees is
# refused naming the file and the field, by the reader every figure reads through. A hit
# after the log's end is a trial that ended first, and is read.
_HIT_SCENARIO = "random_seed: 600\nobject:\n  name: box\ndisturbance:\n  hit_time_s: {}\n"
_LATE = {"t_sa": 1.0 + np.arange(11) / 108.0, "t_ra": np.linspace(1.0, 1.1, 101),
         "t_slow": np.linspace(1.0, 1.1, 11)}


@pytest.mark.parametrize("meta, arrays, expected", [
    ({"scenario": _HIT_SCENARIO.format(0.5)}, _LATE,
     "meta 'scenario' field 'disturbance.hit_time_s' (0.5 s) lies before the log's start, 1 s"),
    ({"scenario": _HIT_SCENARIO.format(-1.0), "events": {"hit": 0.05}}, {},
     "meta 'events' marks a 'hit' at 0.05 s, but its 'scenario' has none"),
    ({"scenario": _HIT_SCENARIO.format(0.02), "events": {"hit": 0.05}}, {},
     "meta 'events' marks the 'hit' at 0.05 s, but its 'scenario' hits at 0.02 s"),
    ({"scenario": _HIT_SCENARIO.format(0.02), "events": {"reach_load": None}}, {},
     "meta 'events' marks no 'hit', but its 'scenario' hits at 0.02 s"),
    ({"scenario": _HIT_SCENARIO.format(0.02), "events": {"hit": 5.0}}, {},
     "meta 'events' time of 'hit' (5 s) lies outside the log's time span"),
    ({"scenario": _HIT_SCENARIO.format(0.02), "events": {"hit": -0.05}}, {},
     "meta 'events' time of 'hit' (-0.05 s) lies outside the log's time span"),
    ({"scenario": _HIT_SCENARIO.format(".nan")}, {},
     "field 'disturbance.hit_time_s' must be a finite number"),
], ids=["scenario-hit-before-start", "marker-without-hit", "marker-elsewhere", "marker-missing",
        "marker-after-end", "marker-before-start", "nan"])
def test_a_hit_marker_that_disagrees_with_the_log_is_refused(meta, arrays, expected, tmp_path,
                                                              capfd):
    assert expected in refused_log(tmp_path, meta, **arrays)
    path = trial_log_with(tmp_path / "hit.npz", meta, **arrays)
    code, text = run_cli(["plot", "avoid", str(path), "--out", str(tmp_path / "o.png")], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, str(path), expected)
    assert not (tmp_path / "o.png").exists()


@pytest.mark.parametrize("meta", [
    {"scenario": _HIT_SCENARIO.format(0.02), "events": {"hit": 0.02}},
    {"scenario": _HIT_SCENARIO.format(7.0), "events": {"reach_load": None}},
    {"scenario": _HIT_SCENARIO.format(-1.0), "events": {"reach_load": None}},
], ids=["marked", "after-the-end", "no-hit"])
def test_a_hit_marker_that_agrees_with_the_log_is_read(meta, tmp_path):
    path = trial_log_with(tmp_path / "trial.npz", meta)
    assert load_trial_log(path).meta["events"] == meta["events"]
