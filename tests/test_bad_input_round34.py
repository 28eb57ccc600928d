"""Trial logs whose time bases do not cover one run, or whose stored result disagrees with the
log: each reader refuses them in one line."""

import numpy as np
import pytest

from tests.test_bad_input import _trial_log
from tests.test_bad_input_round2 import _trial_log_with
from tests.test_bad_input_round28 import _refused

# A stored scenario as runs/trial.py logs it (the defaults: SA at 108 Hz, RA at 1 kHz).
SCENARIO = "random_seed: 600\nobject:\n  name: box\n"


def _with_times(tmp_path, scenario, name, change):
    """The small trial log storing `scenario` (None: none) with time base `name` changed."""
    with np.load(_trial_log(tmp_path / "base.npz")) as base:
        times = change(base[name].copy())
    meta = {"scenario": scenario} if scenario is not None else {}
    return _trial_log_with(tmp_path / "trial.npz", meta, **{name: times})


# Rule: each time base is sampled at the period its logger writes at in the log's scenario
# (a 1e-9-scaled RA base drew a raster-overflowing plot, exit 70).
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t * 1e-9, "'t_ra' is sampled every 1e-12 s, but its scenario's logger "
                                 "writes it every 0.001 s"),
    ("t_slow", lambda t: t * 2.0, "'t_slow' is sampled every 0.02 s, but its scenario's logger "
                                  "writes it every 0.01 s"),
    ("t_sa", lambda t: np.arange(len(t)) / 100.0, "'t_sa' is sampled every 0.01 s, but its "
                                                  "scenario's logger writes it every 0.00925926 s"),
], ids=["ra-scaled", "slow-doubled", "sa-at-100-hz"])
def test_a_time_base_not_at_its_loggers_period_is_refused(tmp_path, name, change, expected):
    _refused(_with_times(tmp_path, SCENARIO, name, change), expected)


# Rule: the three time bases cover one run: they start and end together, within the slower
# period (a log storing no scenario, or a bare recording, included).
@pytest.mark.parametrize("scenario", [SCENARIO, None], ids=["scenario", "none"])
@pytest.mark.parametrize("name, change, expected", [
    ("t_ra", lambda t: t - 100.0, "'t_sa' starts at 0 s but 't_ra' at -100 s; a trial's time "
                                  "bases cover one run"),
    ("t_slow", lambda t: t + 0.05, "'t_sa' starts at 0 s but 't_slow' at 0.05 s"),
    ("t_sa", lambda t: t + 0.0925926 * 2, "'t_sa' starts at 0.185185 s but 't_ra' at 0 s"),
], ids=["ra-100-s-early", "slow-late", "sa-late"])
def test_time_bases_that_do_not_cover_one_run_are_refused(tmp_path, scenario, name, change,
                                                         expected):
    _refused(_with_times(tmp_path, scenario, name, change), expected)


def test_a_scaled_time_base_ends_apart_from_the_others_without_a_scenario(tmp_path):
    _refused(_with_times(tmp_path, None, "t_ra", lambda t: t * 1e-9),
             "'t_sa' ends at 0.0925926 s but 't_ra' at 1e-10 s")


def _result_refused(data, expected):
    """TrialResult's JSON form `data` is refused (result.json, a sweep record, a trial log's
    stored result all read it so) with one line naming `expected`."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ValueError) as refused:
        TrialResult.from_dict(data)
    message = str(refused.value)
    assert expected in message and "\n" not in message, message


def _event(t, from_mode, to_mode, scores=None):
    entry = {"t": t, "from": from_mode, "to": to_mode, "trigger": "memorized_event",
             "reason": "event"}
    return {**entry, "scores": scores} if scores is not None else entry


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
    _result_refused(data, expected)


def test_a_result_held_then_failed_is_read():
    """Hold, then a drop while placing: 8 committed records end so (held, final Failed)."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    timeline = [_event(1.0, "Reach", "Load"), _event(1.5, "Load", "Lift"),
                {"t": 2.5, "from": "Lift", "to": "Hold", "trigger": "timer", "reason": "lifted"},
                {"t": 5.7, "from": "Hold", "to": "Place", "trigger": "timer", "reason": "held"},
                {"t": 6.5, "from": "Place", "to": "Failed", "trigger": "threshold",
                 "reason": "object lost"}]
    result = TrialResult.from_dict({"hold_success": True, "final_mode": "Failed",
                                    "hold_time_s": 3.2, "transitions": timeline,
                                    "failure": "object lost"})
    assert result.hold_success and not result.unload_success


# Rule: a result names a registered controller and the corrective actions controllers take.
@pytest.mark.parametrize("data, expected", [
    ({"controller": "evil"}, "field 'controller' must be one of memorized, heuristic"),
    ({"corrective_actions": ["re_reach", "x" * 100_000]},
     "field 'corrective_actions[1]' must be one of avoid, lift_load, load_without_event, "
     "re_reach, regrasp, got 'xxxx"),
], ids=["controller", "action"])
def test_unknown_controllers_and_actions_are_refused(data, expected):
    _result_refused({"hold_success": False, **data}, expected)


# Rule: the memorized detector's scores are Eq. 3 correlations, in [-1, 1]; the heuristic
# detector's are channel/threshold ratios (above 1 on a firm grasp), so only finite.
@pytest.mark.parametrize("controller", ["memorized", "fixed_load_time", "taxel_aware"])
def test_correlation_scores_outside_minus_one_to_one_are_refused(controller):
    transitions = [_event(1.0, "Reach", "Load", [7.0, 9.0, -3.0, 1e300])]
    _result_refused({"hold_success": False, "controller": controller, "final_mode": "Load",
                     "transitions": transitions},
                    "field 'transitions[0].scores' holds 7, outside -1 to 1 (Eq. 3 scores are "
                    f"correlations, from the {controller} controller's detector)")


def test_the_heuristic_detectors_ratios_are_read():
    from tegrasp_drake.scenario.trial_result import TrialResult
    transitions = [_event(1.0, "Reach", "Load", [5.2, 4.35, 0.5, 0.1])]
    result = TrialResult.from_dict({"hold_success": False, "controller": "heuristic",
                                    "final_mode": "Load", "transitions": transitions})
    assert result.transitions[0].scores[0] > 1.0


# A controller trial's metadata as runs/trial.py writes it, on the small log (0 to 0.1 s).
TIMELINE = [_event(0.02, "Reach", "Load", [0.9, 0.8, 0.7, 0.95]),
            _event(0.05, "Load", "Lift", [0.9, 0.8, 0.7, 0.95])]
RESULT = {"object": "box", "controller": "memorized", "seed": 600, "hold_success": False,
          "final_mode": "Lift", "hold_time_s": 0.0, "transitions": TIMELINE,
          "corrective_actions": [], "sim_time_s": 0.1}
META = {"scenario": SCENARIO, "controller": "memorized", "transitions": TIMELINE,
        "phase_starts": {"Load": 0.02, "Lift": 0.05}, "result": RESULT}


def _meta_refused(tmp_path, meta, expected):
    _refused(_trial_log_with(tmp_path / "trial.npz", meta), expected)


def test_a_controller_trials_metadata_is_read(tmp_path):
    from tegrasp_drake.scenario.trial_log_file import load_trial_log
    log = load_trial_log(_trial_log_with(tmp_path / "trial.npz", META))
    assert log.meta["result"]["transitions"] == TIMELINE


# Rule: the stored result's transitions are the log's timeline, entry for entry.
@pytest.mark.parametrize("transitions, expected", [
    ([TIMELINE[0], {**TIMELINE[1], "to": "Hold"}],
     "meta 'result' transitions[1] is Load -> Hold at 0.05 s (memorized_event), but the log's "
     "'transitions[1]' is Load -> Lift at 0.05 s (memorized_event) (a trial has one timeline)"),
    (TIMELINE + [_event(0.08, "Lift", "Hold")],
     "meta 'result' transitions[2] is Lift -> Hold at 0.08 s (memorized_event), but the log's "
     "'transitions[2]' is absent"),
    (TIMELINE[:1], "meta 'result' transitions[1] is absent"),
], ids=["to-hold", "one-more", "one-fewer"])
def test_a_stored_result_with_another_timeline_is_refused(tmp_path, transitions, expected):
    result = {**RESULT, "transitions": transitions, "final_mode": transitions[-1]["to"]}
    _meta_refused(tmp_path, {**META, "result": result}, expected)


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
    _meta_refused(tmp_path, {**META, **change}, expected)


# Rule: a memorized detector's scores are correlations, in the result and the timeline alike.
def test_correlation_scores_out_of_range_in_a_log_are_refused(tmp_path):
    bad = [{**TIMELINE[0], "scores": [7.0, 9.0, -3.0, 1e300]}, TIMELINE[1]]
    _meta_refused(tmp_path, {**META, "transitions": bad, "result": {**RESULT, "transitions": bad}},
                  "field 'transitions[0].scores' holds 7, outside -1 to 1")
    no_result = {key: value for key, value in META.items() if key != "result"}
    _meta_refused(tmp_path, {**no_result, "transitions": bad},
                  "meta 'transitions[0].scores' holds 7, outside -1 to 1")


# Rule: a log with a timeline says when each of its phases began.
def test_a_log_without_phase_starts_is_refused(tmp_path):
    meta = {key: value for key, value in META.items() if key != "phase_starts"}
    _meta_refused(tmp_path, meta, "meta lacks 'phase_starts'")


def test_a_correlation_one_round_off_past_one_is_read():
    """The streaming matcher's running window energy can put a true 1 a few ulps past it."""
    from tegrasp_drake.scenario.trial_result import TrialResult
    transitions = [_event(1.0, "Reach", "Load", [1.0 + 1e-12, 1.0, -1.0 - 1e-12, 0.5])]
    result = TrialResult.from_dict({"hold_success": False, "controller": "memorized",
                                    "final_mode": "Load", "transitions": transitions})
    assert result.transitions[0].scores[0] > 1.0
