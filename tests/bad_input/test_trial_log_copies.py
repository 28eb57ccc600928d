"""A trial log's copied metadata equals its source ('grip_force' its scenario's
grasp.grip_force, 'events' its result's physical_events), its noise-free taxel forces lie in
the ideal force transducer's range and every array is float64; anything else is refused in
one line naming the field."""

import numpy as np

from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tests.bad_input.probes import META, RESULT, SCENARIO, refused_log, trial_log_with


def test_a_grip_force_other_than_its_scenarios_is_refused_to_the_last_digit(tmp_path):
    load_trial_log(trial_log_with(tmp_path / "same.npz", {"scenario": SCENARIO,
                                                          "grip_force": 25.0}))
    message = refused_log(tmp_path, {"scenario": SCENARIO, "grip_force": 25.000000001})
    assert "meta 'grip_force' is 25.000000001 N" in message, message
    assert "grips with 25.0 N (grasp.grip_force" in message, message


def test_events_other_than_its_results_physical_events_are_refused(tmp_path):
    physical = {"reach_load": 0.015, "load_lift": None}
    result = {**RESULT, "physical_events": physical}
    load_trial_log(trial_log_with(tmp_path / "same.npz", {**META, "result": result,
                                                          "events": dict(physical)}),
                   rejudge=False)  # a hand-made result: the judge's own is another test's
    message = refused_log(tmp_path, {**META, "result": result,
                                     "events": {"reach_load": 0.016, "load_lift": None}})
    assert "meta 'events' gives 'reach_load' 0.016 s" in message, message
    assert "'result' physical_events 0.015 s" in message, message
    message = refused_log(tmp_path, {**META, "result": result, "events": {"reach_load": 0.015}})
    assert "'load_lift' absent" in message and "physical_events null" in message, message


def test_noise_free_taxel_forces_outside_the_ideal_transducers_range_are_refused(tmp_path):
    for value, shown in ((-0.5, "-0.5"), (236.0, "236")):
        true_taxels = np.ones((11, 24))
        true_taxels[3, 5] = value
        message = refused_log(tmp_path, true_taxels=true_taxels)
        assert f"'true_taxels' sample 3 column 5 holds {shown} N, outside 0 to 235 N" in message
    load_trial_log(trial_log_with(tmp_path / "full.npz", true_taxels=np.full((11, 24), 235.0)))


def test_an_array_of_another_type_than_float64_is_refused(tmp_path):
    message = refused_log(tmp_path, arm_q=np.zeros((11, 6), dtype=np.float32))
    assert "'arm_q' holds float32 values, but a trial log's arrays are float64" in message
    message = refused_log(tmp_path, phase=np.zeros(11, dtype=np.int64))
    assert "'phase' holds int64 values" in message, message
