"""The myRIO emulator's replay follows the emulated gripper: at each of the recording's
gripper commands it holds until the gripper has been commanded likewise, then plays on
without skipping a sample."""

import time

import numpy as np
import pytest

from tegrasp_drake.emulators.myrio_emulator import (
    GripperCommandChange, MyRioEmulator, MyRioEmulatorConfig, TactileRecording,
    TactileRecordingError, gripper_command_changes, gripper_followed, load_tactile_recording,
    save_tactile_recording)
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

PERIOD = 1e-3           # [s] the emulator's frame period
GRIP, OPEN = 230, 3     # rPR bytes, as the simulated box trial commands them
RELEASE_AFTER = 0.49    # [s] the last logged time of the grip request
HANG_GUARD_S = 30.0     # a guard against a hang on a busy host, not a criterion


def released_trial() -> TactileRecording:
    """1 s of a gripped pad (10 N per taxel) released at once after RELEASE_AFTER, with
    the gripper's requests logged every 10 ms."""
    t = np.arange(0.0, 1.0, PERIOD)
    forces = np.where(t[:, None] <= RELEASE_AFTER, 10.0, 0.0) * np.ones((1, 12))
    gripper_times = np.arange(0.0, 1.0, 0.01)
    requests = np.where(gripper_times <= RELEASE_AFTER + 1e-9, GRIP, OPEN)
    return TactileRecording(t, forces, forces, t, np.zeros((len(t), 3)), np.zeros(len(t)),
                            gripper_times, requests)


def wait_for(condition, what):
    deadline = time.monotonic() + HANG_GUARD_S
    while not condition():
        assert time.monotonic() < deadline, f"no {what} within {HANG_GUARD_S} s"
        time.sleep(0.01)


def test_each_change_of_the_recorded_request_is_a_command_change_after_its_last_log():
    changes = gripper_command_changes([0.0, 0.01, 0.02, 0.03, 0.04], [3, 230, 230, 3, 3])
    assert changes == [GripperCommandChange(0.0, 3, 230), GripperCommandChange(0.02, 230, 3)]
    assert gripper_command_changes(None, None) == []


def test_the_gripper_has_followed_once_its_request_is_nearer_the_new_one():
    release = GripperCommandChange(0.02, GRIP, OPEN)
    assert not gripper_followed(release, None)
    assert not gripper_followed(release, GRIP)
    assert not gripper_followed(release, 200)
    assert gripper_followed(release, OPEN)
    assert gripper_followed(release, 0)


def test_the_gripper_requests_of_a_saved_recording_load_back(tmp_path):
    trial = released_trial()
    loaded = load_tactile_recording(save_tactile_recording(tmp_path / "r.npz", trial))
    np.testing.assert_array_equal(loaded.gripper_times, trial.gripper_times)
    np.testing.assert_array_equal(loaded.gripper_requests, trial.gripper_requests)


def test_the_replay_holds_before_the_release_until_the_gripper_is_commanded_open():
    request = [GRIP]
    clock = [0.0]
    config = MyRioEmulatorConfig(start_on_trigger=True, lead_in=0.0)
    with MyRioEmulator(released_trial(), config, trial_clock=lambda: clock[0],
                       gripper_request=lambda: request[0]) as emulator, \
            TactileSerialReader(emulator.port):
        emulator.start_trial()
        clock[0] = 0.6  # the controller is 0.11 s past the recorded release
        # Every frame up to the clock's time is out: 491 samples, then 110 held frames.
        wait_for(lambda: emulator.counters().held_frames >= 110, "held frames")
        before_open = emulator.sent()
        request[0] = OPEN
        clock[0] = 0.7
        wait_for(lambda: emulator.sent()[-1].sequence >= before_open[-1].sequence + 100,
                 "frames after the open command")
        after_open = emulator.sent()[len(before_open):]
    trial_times = np.array([f.trial_time for f in before_open if f.trial_time >= 0])
    assert trial_times.max() == pytest.approx(RELEASE_AFTER)
    assert np.count_nonzero(trial_times == trial_times.max()) > 100  # held there
    assert emulator.counters().held_frames == np.count_nonzero(
        trial_times == trial_times.max()) - 1
    # Then on from the next sample, each once, the trial now 0.11 s behind the clock.
    resumed = np.round(np.array([f.trial_time for f in after_open]) / PERIOD).astype(int)
    np.testing.assert_array_equal(resumed, np.arange(491, 491 + len(resumed)))
    assert resumed[-1] == 590


def test_a_gripper_that_opened_before_the_recorded_release_holds_nothing():
    clock = [0.0]
    config = MyRioEmulatorConfig(start_on_trigger=True, lead_in=0.0)
    with MyRioEmulator(released_trial(), config, trial_clock=lambda: clock[0],
                       gripper_request=lambda: OPEN) as emulator, \
            TactileSerialReader(emulator.port):
        emulator.start_trial()
        clock[0] = 0.6
        wait_for(lambda: emulator.sent() and emulator.sent()[-1].trial_time >= 0.6,
                 "frames up to the clock")
        assert emulator.counters().held_frames == 0


def test_a_log_with_unreadable_gripper_commands_is_refused_naming_them(tmp_path):
    path = save_tactile_recording(tmp_path / "r.npz", released_trial())
    arrays = dict(np.load(path))
    arrays["gripper_command"][3, 0] = np.nan
    np.savez(path, **arrays)
    with pytest.raises(TactileRecordingError, match="r.npz.*gripper_command") as error:
        load_tactile_recording(path)
    assert "\n" not in str(error.value)
