"""A trial log's object positions are bounded sample by sample (trial_log_file
.object_path_problem): where the object can be by that sample's time, and how far it can
have moved since the sample before. The logs here store the default scenario (no hit: the
hand's 4.5 m/s bounds the object's speed); a log with none is bounded by any scenario's
hardest hit on the lightest object, far looser."""

import numpy as np
import pytest

from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.bad_input.probes import trial_log_with


def _trial_log(path, object_state):
    return trial_log_with(path, {"scenario": scenario_to_yaml(LoadScenario())},
                           object_state=object_state)


def _object_state(column, values):
    """_trial_log's 11 object states (identity orientation, at the world origin, on the
    table), `column` (4-6: x, y, z) set to `values`."""
    state = np.zeros((11, 13))
    state[:, 0] = 1.0
    state[:, column] = values
    return state


def test_an_object_above_the_arms_reach_within_10_ms_is_refused(tmp_path):
    # 1.2 m up at 0.01 s: within the whole 0.11 s log's bound (0.9 m reach + 4.5 m/s), not by then.
    z = np.zeros(11)
    z[1:] = 1.2
    path = _trial_log(tmp_path / "trial.npz", object_state=_object_state(6, z))
    with pytest.raises(TrialLogError, match=r"'object_state' sample 1 \(t = 0.01 s\) puts the "
                       r"object's z at 1.2 m, outside .* where its scenario's object can be by "
                       "then"):
        load_trial_log(path)


def test_an_object_that_jumps_10_cm_in_one_10_ms_sample_is_refused(tmp_path):
    y = np.zeros(11)
    y[5:] = 0.1
    path = _trial_log(tmp_path / "trial.npz", object_state=_object_state(5, y))
    with pytest.raises(TrialLogError, match=r"'object_state' sample 5 \(t = 0.05 s\) puts the "
                       r"object 0.1 m sideways from the sample before, more than the .* m its "
                       "scenario's object can move sideways in 0.01 s"):
        load_trial_log(path)


def test_an_object_carried_at_3_m_per_s_is_read(tmp_path):
    y = 0.03 * np.arange(11)  # 3 m/s, below the hand's 4.5 m/s
    log = load_trial_log(_trial_log(tmp_path / "trial.npz", object_state=_object_state(5, y)))
    assert log.object_state[-1, 5] == pytest.approx(0.3)


def _long_trial_log(path, object_state):
    """_trial_log over 6.01 s (601 slow samples, each time base at its logger's period), the
    object at `object_state`."""
    n_slow = len(object_state)
    duration = (n_slow - 1) / 100.0
    n_sa, n_ra = int(duration * 108.0) + 1, int(round(duration * 1000.0)) + 1
    slow = {"arm_q": np.zeros((n_slow, 6)), "arm_q_desired": np.zeros((n_slow, 6)),
            "gripper_command": np.zeros((n_slow, 3)), "gripper_status": np.zeros((n_slow, 8)),
            "phase": np.zeros(n_slow)}
    for name in ("arm_q", "arm_q_desired"):
        slow[name][:, 1:3] = [3.0, 1.0]
    return trial_log_with(
        path, {"scenario": scenario_to_yaml(LoadScenario())},
        t_sa=np.arange(n_sa) / 108.0, taxels=np.ones((n_sa, 24)),
        true_taxels=np.ones((n_sa, 24)), t_ra=np.arange(n_ra) / 1000.0,
        pad_acceleration=np.zeros((n_ra, 6)),
        t_slow=np.arange(n_slow) / 100.0, object_state=object_state, **slow)


def _held_object(samples=602, height=0.2):
    """An object held still `height` above the table (origin at the table's centre marker)."""
    state = np.zeros((samples, 13))
    state[:, 0] = 1.0
    state[:, 4] = 0.72
    state[:, 6] = height
    return state


def test_a_sideways_jump_late_in_a_trial_is_refused(tmp_path):
    # Gravity speeds a fall, not a sideways step: 0.5 m in x within 10 ms at t = 6 s is refused
    # though free fall by then (59 m/s) would cover it.
    state = _held_object()
    state[600:, 4] += 0.5
    path = _long_trial_log(tmp_path / "trial.npz", state)
    with pytest.raises(TrialLogError, match=r"'object_state' sample 600 \(t = 6 s\) puts the "
                       r"object 0.5 m sideways from the sample before, more than the .* m its "
                       "scenario's object can move sideways in 0.01 s"):
        load_trial_log(path)


def test_a_fall_late_in_a_trial_is_read(tmp_path):
    # Dropped at 1 s from 0.2 m above the table, off its edge: 0.59 m/s per 10 ms by t = 6 s.
    state = _held_object()
    t = np.arange(len(state)) / 100.0
    falling = t > 1.0
    state[falling, 6] = 0.2 - 9.81 * (t[falling] - 1.0) ** 2 / 2
    log = load_trial_log(_long_trial_log(tmp_path / "trial.npz", state))
    assert log.object_state[-1, 6] < -100.0


def test_a_npz_without_a_trial_logs_arrays_is_named_in_a_sentence(tmp_path):
    path = tmp_path / "other.npz"
    np.savez(path, t_sa=np.zeros(3))
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    assert f"trial log '{path}' lacks the arrays [" in str(refused.value), refused.value
