"""Bad inputs the fourteenth hostile pass found in trial logs, one test per rule."""

import io
import json
import warnings
import zipfile

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError, load_tactile_recording
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.test_bad_input import _trial_log
from tests.test_bad_input_round2 import _trial_log_with


def _npy(array) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array)
    return buffer.getvalue()


def _rezipped(path, extra_members):
    """`path` (an .npz) rewritten with `extra_members` ((member name, array) pairs) appended."""
    with np.load(path) as data:
        contents = {name: data[name] for name in data.files}
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, array in contents.items():
            archive.writestr(f"{name}.npy", _npy(array))
        with warnings.catch_warnings():  # zipfile warns of the duplicate this makes
            warnings.simplefilter("ignore", UserWarning)
            for name, array in extra_members:
                archive.writestr(name, _npy(array))
    return path


def _refused(path, expected):
    """Both readers of a trial log refuse `path` in one line naming it and `expected`."""
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message
    with pytest.raises(TactileRecordingError) as refused:
        load_tactile_recording(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message


# Rule: a trial log's zip holds each array once and only the arrays the format has: with two
# members of one name, which one is read is the zip library's choice.
@pytest.mark.parametrize("member, expected", [
    ("meta.npy", "'meta.npy' is stored twice"),
    ("zzz.npy", "'zzz.npy' is not an array a trial log has"),
], ids=["duplicate", "unknown"])
def test_a_trial_log_with_duplicate_or_unknown_members_is_refused_naming_the_member(
        tmp_path, member, expected):
    path = _rezipped(_trial_log(tmp_path / "trial.npz"),
                     [(member, np.array(json.dumps({"format_version": 1})))])
    _refused(path, expected)


def _with_last(times, value):
    times = times.copy()
    times[-1] = value
    return times


# Rule: each time base is sampled at one period (the logger's): a last sample 1e12 s after the
# others would make a 0.1 s log span 31,700 years.
@pytest.mark.parametrize("name, times", [
    ("t_ra", _with_last(np.linspace(0, 0.1, 101), 1e12)),
    ("t_sa", _with_last(np.linspace(0, 0.1, 11), 0.1005)),
    ("t_slow", np.concatenate([np.linspace(0, 0.05, 6), np.linspace(0.07, 0.12, 5)])),
], ids=["huge-last", "late-last", "gap"])
def test_a_trial_log_time_base_not_sampled_at_one_period_is_refused(tmp_path, name, times):
    _refused(_trial_log(tmp_path / "trial.npz", **{name: times}),
             f"'{name}' is not sampled at one period")


def _object_state(quaternion):
    """_trial_log's 11 object states, sample 5's orientation `quaternion` (w, x, y, z)."""
    state = np.zeros((11, 13))
    state[:, 0] = 1.0
    state[5, :4] = quaternion
    return state


def test_a_trial_log_with_unit_object_quaternions_is_read(tmp_path):
    turned = [np.cos(0.3), 0.0, 0.0, np.sin(0.3)]  # 0.6 rad about z
    log = load_trial_log(_trial_log(tmp_path / "trial.npz", object_state=_object_state(turned)))
    assert log.object_state.shape == (11, 13)


# Rule: the object's orientation is a unit quaternion (the state of a rigid body), within the
# drift its integration leaves.
@pytest.mark.parametrize("quaternion", [[0.0, 0.0, 0.0, 0.0], [2.0, 0.0, 0.0, 0.0]],
                         ids=["zero", "norm-2"])
def test_a_trial_log_with_an_object_quaternion_far_from_unit_is_refused(tmp_path, quaternion):
    _refused(_trial_log(tmp_path / "trial.npz", object_state=_object_state(quaternion)),
             "'object_state' sample 5 holds an orientation quaternion of norm")


def _refused_meta(tmp_path, meta, expected):
    path = _trial_log_with(tmp_path / "trial.npz", meta)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and expected in message and "\n" not in message, message


def test_a_trial_log_with_the_controllers_mode_names_is_read(tmp_path):
    from tegrasp_drake.control.grasp_modes import Mode
    names = [mode.label for mode in Mode]
    path = _trial_log_with(tmp_path / "trial.npz", {"mode_names": names})
    assert load_trial_log(path).meta["mode_names"] == names


# Rule: mode_names (what `phase` indexes) are the controllers' modes' labels, in their order,
# as the trial writes them: other names would label the phase plot with what never ran.
@pytest.mark.parametrize("names", [["A"] * 10, ["Reach", "Load"]], ids=["renamed", "short"])
def test_a_trial_log_whose_mode_names_are_not_the_modes_is_refused(tmp_path, names):
    _refused_meta(tmp_path, {"mode_names": names}, "meta 'mode_names' must be the modes' labels")


def _transition(t, from_mode, to_mode):
    return {"t": t, "from": from_mode, "to": to_mode, "trigger": "timer", "reason": "test"}


# Reach -> Load -> Lift -> Hold -> Re-Reach -> Reach -> Load, inside _trial_log's 0.1 s.
_TIMELINE = [_transition(0.02, "Reach", "Load"), _transition(0.03, "Load", "Lift"),
             _transition(0.04, "Lift", "Hold"), _transition(0.05, "Hold", "Re-Reach"),
             _transition(0.06, "Re-Reach", "Reach"), _transition(0.07, "Reach", "Load")]
# When each mode was first entered, as runs/trial.py writes it.
_STARTS = {"Load": 0.02, "Lift": 0.03, "Hold": 0.04, "Re-Reach": 0.05, "Reach": 0.06}


def test_a_trial_log_whose_phase_starts_are_the_first_entries_is_read(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz",
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
    _refused_meta(tmp_path, {"transitions": _TIMELINE, "phase_starts": starts},
                  f"meta 'phase_starts' {expected}")


# Rule: without a timeline (an ideal grasp's log), the phases start in the order `phases`
# lists them.
def test_an_ideal_grasp_log_whose_phase_starts_are_out_of_order_is_refused(tmp_path):
    phases = ["approach", "close", "lift"]
    path = _trial_log_with(tmp_path / "ok.npz", {
        "phases": phases, "phase_starts": {"approach": 0.0, "close": 0.02, "lift": 0.05}})
    assert load_trial_log(path).meta["phases"] == phases
    _refused_meta(tmp_path, {"phases": phases, "phase_starts": {"approach": 0.0, "close": 0.06,
                                                                "lift": 0.05}},
                  "meta 'phase_starts' gives 'lift' starting at 0.05 s, before 'close'")
    _refused_meta(tmp_path, {"phases": phases, "phase_starts": {"hover": 0.0}},
                  "meta 'phase_starts' names 'hover', which is not one of the phases")


# Rule: the log's controller is the one its trial result names: a figure labels the run with
# one and annotates it with the other's outcome.
def test_a_trial_log_whose_controller_differs_from_its_results_is_refused(tmp_path):
    path = _trial_log_with(tmp_path / "ok.npz", {"controller": "memorized", "phase_starts": {},
                                                  "result": {"controller": "memorized"}})
    assert load_trial_log(path).meta["controller"] == "memorized"
    _refused_meta(tmp_path, {"controller": "heuristic", "result": {"controller": "memorized"}},
                  "meta 'controller' is 'heuristic', but its 'result' is of 'memorized'")


# Rule: the log's trial result is of the seed its scenario ran with.
def test_a_trial_log_whose_result_seed_differs_from_its_scenarios_is_refused(tmp_path):
    scenario = "random_seed: 680\nobject:\n  name: box\n"
    path = _trial_log_with(tmp_path / "ok.npz", {"scenario": scenario, "result": {"seed": 680},
                                                 "phase_starts": {}})
    assert load_trial_log(path).meta["result"]["seed"] == 680
    _refused_meta(tmp_path, {"scenario": scenario, "result": {"seed": 681}},
                  "meta 'result' is of seed 681, but its 'scenario' ran with random_seed 680")


# Rule: the JACO2's logged joint angles lie within the joints' declared limits (joints 2 and 3;
# the others turn without end): 1e300 rad is not an arm's pose.
@pytest.mark.parametrize("name", ["arm_q", "arm_q_desired"])
def test_a_trial_log_with_joint_angles_beyond_the_jaco2s_limits_is_refused(tmp_path, name):
    q = np.tile([0.0, 3.0, 1.0, 0.0, 0.0, 0.0], (11, 1))
    assert load_trial_log(_trial_log(tmp_path / "ok.npz", **{name: q})) is not None
    q[4, :] = 1e300
    _refused(_trial_log(tmp_path / "trial.npz", **{name: q}),
             f"'{name}' column 1 (joint 2) holds 1e+300 rad, outside")
