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
                       r"object 0.1 m from the sample before, more than the .* m its "
                       "scenario's object can move in 0.01 s"):
        load_trial_log(path)


def test_an_object_carried_at_3_m_per_s_is_read(tmp_path):
    y = 0.03 * np.arange(11)  # 3 m/s, below the hand's 4.5 m/s
    log = load_trial_log(_trial_log(tmp_path / "trial.npz", object_state=_object_state(5, y)))
    assert log.object_state[-1, 5] == pytest.approx(0.3)
