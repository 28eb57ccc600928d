"""A trial log's 'phase' samples are its timeline's: each the mode of the last transition at or
before it (an ideal grasp's: the last phase started by then); a log whose samples disagree is
refused in one line naming the sample, its time, the value found and the one expected."""

import numpy as np

from tegrasp_drake.scenario.trial_log_file import load_trial_log
from tests.bad_input.probes import logged_phases, refused_log, trial_log_with

SECONDS = 1.0  # a log long enough for a 0.5 s shift


def _long_arrays(seconds=SECONDS) -> dict:
    """A trial log's arrays over `seconds` [s], each time base at the default scenario's
    logger period (108 Hz, 1 kHz, 10 ms), as probes.trial_log fills them."""
    n_sa, n_ra, n_slow = int(seconds * 108) + 1, int(round(seconds * 1000)) + 1, \
        int(round(seconds * 100)) + 1
    arrays = {"t_sa": np.arange(n_sa) / 108.0, "taxels": np.ones((n_sa, 24)),
              "true_taxels": np.ones((n_sa, 24)), "t_ra": np.linspace(0, seconds, n_ra),
              "pad_acceleration": np.zeros((n_ra, 6)), "t_slow": np.linspace(0, seconds, n_slow),
              "arm_q": np.zeros((n_slow, 6)), "arm_q_desired": np.zeros((n_slow, 6)),
              "gripper_command": np.zeros((n_slow, 3)), "gripper_status": np.zeros((n_slow, 8)),
              "object_state": np.zeros((n_slow, 13))}
    arrays["object_state"][:, 0] = 1.0
    for name in ("arm_q", "arm_q_desired"):
        arrays[name][:, 1:3] = [3.0, 1.0]
    return arrays


def _transition(t, from_mode, to_mode):
    return {"t": t, "from": from_mode, "to": to_mode, "trigger": "timer", "reason": "test"}


TIMELINE = {"controller": "open_loop", "transitions": [
    _transition(0.2, "Reach", "Load"), _transition(0.4, "Load", "Lift")]}
IDEAL = {"controller": "open_loop", "phases": ["settle", "reach", "load", "done"],
         "phase_starts": {"settle": 0.0, "reach": 0.1, "load": 0.3, "done": 0.6}}


def test_a_log_whose_phases_follow_its_timeline_is_read(tmp_path):
    for k, meta in enumerate((TIMELINE, IDEAL)):
        log = load_trial_log(trial_log_with(tmp_path / f"{k}.npz", meta, **_long_arrays()))
        assert np.any(log.phase != 0.0)


def test_a_sample_at_a_transitions_time_may_hold_either_mode(tmp_path):
    arrays = _long_arrays()
    phase = logged_phases(TIMELINE, arrays["t_slow"])
    assert phase[20] == 2.0  # t = 0.2 s, the Reach -> Load transition
    phase[20] = 0.0  # the logger sampled before the controller's update at that instant
    load_trial_log(trial_log_with(tmp_path / "trial.npz", TIMELINE, phase=phase, **arrays))


def test_a_log_whose_phases_lag_its_timeline_by_half_a_second_is_refused(tmp_path):
    arrays = _long_arrays()
    shifted = logged_phases(TIMELINE, arrays["t_slow"] - 0.5)
    message = refused_log(tmp_path, TIMELINE, phase=shifted, **arrays)
    assert "'phase' sample 21 " in message and "holds 0 (Reach)" in message, message
    assert "'transitions' give 2 (Load)" in message and "run the trial again" in message


def test_an_ideal_grasps_log_whose_phases_lag_its_starts_is_refused(tmp_path):
    arrays = _long_arrays()
    shifted = logged_phases(IDEAL, arrays["t_slow"] - 0.5)
    message = refused_log(tmp_path, IDEAL, phase=shifted, **arrays)
    assert "'phase' sample 11 " in message and "holds 0 (settle)" in message, message
    assert "give 1 (reach)" in message, message
