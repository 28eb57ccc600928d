"""Bad inputs the twentieth review found, one test per rule."""

import json
import shutil

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import TactileRecordingError, load_tactile_recording
from tegrasp_drake.events.event_file import MemorizedEventError
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.rig import paths
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tests.test_bad_input import assert_one_line_error, run_cli
from tests.test_bad_input_round2 import _trial_log_with

# _trial_log's time span: every time base from 0 to 0.1 s.
_SPAN_END_S = 0.1


def _transition(t, from_mode, to_mode):
    return {"t": t, "from": from_mode, "to": to_mode, "trigger": "timer", "reason": "test"}


# Reach -> Load -> Lift, inside the log's 0.1 s.
_CHAIN = [_transition(0.02, "Reach", "Load"), _transition(0.05, "Load", "Lift")]


def _refused_log(tmp_path, meta=None, **arrays) -> str:
    path = _trial_log_with(tmp_path / "trial.npz", meta, **arrays)
    with pytest.raises(TrialLogError) as refused:
        load_trial_log(path)
    message = str(refused.value)
    assert str(path) in message and "\n" not in message, message
    return message


def test_a_trial_log_with_an_ordered_chained_timeline_inside_its_span_is_read(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz", {
        "transitions": _CHAIN, "phase_starts": {"Load": 0.02, "Lift": 0.05},
        "events": {"reach_load": 0.015, "place_unload": None}, "grip_force": 25.0,
        "sim_time_s": _SPAN_END_S, "wall_time_s": 3.0})
    assert len(load_trial_log(path).meta["transitions"]) == 2


def test_a_trial_log_keeps_its_transitions_rule_codes_and_refuses_an_unknown_one(tmp_path):
    coded = [{**_CHAIN[0], "code": "reach_event"}, {**_CHAIN[1], "code": "load_lift_event"}]
    path = _trial_log_with(tmp_path / "coded.npz", {"transitions": coded})
    assert [t["code"] for t in load_trial_log(path).meta["transitions"]] == [
        "reach_event", "load_lift_event"]
    message = _refused_log(tmp_path, {"transitions": [{**_CHAIN[0], "code": "reach_evnt"}]})
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
    assert expected in _refused_log(tmp_path, meta)


def test_a_timeline_of_more_transitions_than_a_controller_takes_is_refused_in_one_line(
        tmp_path, capfd):
    from tegrasp_drake.scenario.trial_log_file import most_transitions
    step = _SPAN_END_S / (3 * most_transitions(_SPAN_END_S))
    modes = ["Hold", "Avoid"]
    timeline = [_transition(step * (k + 1), modes[k % 2], modes[(k + 1) % 2])
                for k in range(most_transitions(_SPAN_END_S) + 1)]
    path = _trial_log_with(tmp_path / "trial.npz", {"transitions": timeline})
    code, text = run_cli(["plot", "trial", str(path), "--out", str(tmp_path / "o.png")], capfd)
    assert_one_line_error(code, text, f"meta 'transitions' holds {len(timeline)} entries",
                          f"at most {most_transitions(_SPAN_END_S)}")
    assert not (tmp_path / "o.png").exists()


# Rule: every metadata field the writer stores has a declared range (a grip force the
# gripper can exert, durations >= 0).
@pytest.mark.parametrize("meta, expected", [
    ({"grip_force": -5}, "meta 'grip_force' must be"),
    ({"grip_force": "strong"}, "meta 'grip_force' must be"),
    ({"sim_time_s": -1.0}, "meta 'sim_time_s' must be"),
    ({"wall_time_s": "3 s"}, "meta 'wall_time_s' must be"),
    ({"versions": {"drake": 1}}, "meta 'versions' must map"),
], ids=["grip-negative", "grip-text", "sim-time", "wall-time", "versions"])
def test_trial_log_meta_fields_have_ranges(tmp_path, meta, expected):
    assert expected in _refused_log(tmp_path, meta)


def _spoiled(shape, column, value):
    array = np.zeros(shape)
    array[:, column] = value
    return array


# Rule: each logged channel with a physical range is checked against it when the log is read,
# by every reader: the gripper's request and status registers are bytes (0-255), RA is a
# magnitude (Eq. 2, >= 0).
@pytest.mark.parametrize("arrays, expected", [
    ({"gripper_command": _spoiled((11, 3), 0, 1e9)},
     "'gripper_command' column 0 (rPR) holds 1000000000, outside 0 to 255"),
    ({"gripper_command": _spoiled((11, 3), 2, -1.0)}, "'gripper_command' column 2 (rFR) holds -1"),
    ({"gripper_status": _spoiled((11, 8), 6, 300.0)}, "'gripper_status' column 6 (gPO) holds 300"),
    ({"channels": _spoiled((101, 4), 3, -2.0)}, "'channels' column 3 (ra_right) holds -2"),
], ids=["command-1e9", "command-negative", "status", "ra-negative"])
def test_logged_channels_are_checked_against_their_physical_range(tmp_path, arrays, expected):
    message = _refused_log(tmp_path, None, **arrays)
    assert expected in message, message


def test_the_myrio_emulator_refuses_gripper_requests_a_2f85_cannot_take(tmp_path):
    path = _trial_log_with(tmp_path / "trial.npz",
                           gripper_command=_spoiled((11, 3), 0, 1e9))
    with pytest.raises(TactileRecordingError, match=r"'gripper_command' column 0 \(rPR\)"):
        load_tactile_recording(path)
    bare = tmp_path / "bare.npz"  # a bare recording (no meta) is checked alike
    with np.load(path) as data:
        np.savez(bare, **{name: data[name] for name in
                          ("t_sa", "taxels", "t_ra", "pad_acceleration", "t_slow",
                           "gripper_command")})
    with pytest.raises(TactileRecordingError, match=r"'gripper_command' column 0 \(rPR\)"):
        load_tactile_recording(bare)


# Rule: an RA window is a normalised vibration magnitude (Eq. 2), so no sample is negative;
# a memorized event holding one is refused naming its file and channel. (SA windows may dip
# below zero: the committed events' reach SA windows reach -0.67 of their peak.)
def test_a_memorized_event_with_a_negative_ra_window_is_refused(tmp_path, capfd):
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events,
                    ignore=shutil.ignore_patterns("__init__.py", "__pycache__"))
    path = events / "box" / "load_lift.json"
    data = json.loads(path.read_text())
    data["samples"]["ra_left"] = [-1.0] * len(data["samples"]["ra_left"])
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError, match=r"load_lift\.json.*'ra_left'.*negative"):
        load_memorized_events(events, "box")
    code, text = run_cli(["plot", "events", "--events", str(events), "--out",
                          str(tmp_path / "p.png")], capfd)
    assert_one_line_error(code, text, "load_lift.json", "'ra_left'")
