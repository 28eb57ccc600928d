"""The launcher of `tegrasp emulate`: the emulated devices' config as data, and its line."""

import os

import numpy as np

from tegrasp_drake.emulators.launcher import (
    EMULATED_WATCHDOG_TIMEOUT_S, Emulators, devices_from_line, hardware_config_for)
from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS
from tegrasp_drake.emulators.myrio_emulator import TactileRecording, save_tactile_recording
from tegrasp_drake.scenario.scenario import LoadScenario


def quiet_recording() -> TactileRecording:
    t = np.arange(0.0, 0.2, 1e-3)
    return TactileRecording(t, np.zeros((len(t), 12)), np.zeros((len(t), 12)), t,
                            np.zeros(len(t)), np.zeros(len(t)))


def test_started_devices_are_reported_as_hardware_config_fields(tmp_path):
    trial = save_tactile_recording(tmp_path / "trial.npz", quiet_recording())
    lines = []
    with Emulators(lcm_url="memq://", out=lines.append).start(
            ("robotiq", "myrio"), LoadScenario(name="box"), trial=trial) as emulators:
        devices = emulators.devices
        assert set(devices) == {"gripper", "tactile"}
        assert all(os.path.exists(fields["port"]) for fields in devices.values())
        config = emulators.hardware_config()
        assert config.gripper.port == devices["gripper"]["port"]
        assert config.tactile.port == devices["tactile"]["port"]
        assert config.arm.lcm_url == "memq://"
        assert devices_from_line(emulators.devices_line()) == devices
        # The emulated devices' watchdog tolerates a stall of this shared host; the arm, not
        # emulated here, keeps a real arm's timeout.
        assert config.watchdog.timeouts() == {"arm": DEFAULT_TIMEOUTS["arm"],
                                              "gripper": EMULATED_WATCHDOG_TIMEOUT_S,
                                              "tactile": EMULATED_WATCHDOG_TIMEOUT_S}
    started, closed = lines[:2], lines[2:]
    assert [line.split(":")[0] for line in started] == ["robotiq", "myrio"]
    # On closing, what the gripper received: its requests, none of them malformed.
    assert closed == ["robotiq: Modbus requests: 0 messages, 0 rejected"]


def test_devices_line_is_the_only_line_read_as_data():
    assert devices_from_line("robotiq: Robotiq 2F-85 (...) on /dev/pts/3, object ...") is None
    assert devices_from_line("ready") is None
    assert devices_from_line('devices: {"gripper": {"port": "/dev/pts/3"}}') == {
        "gripper": {"port": "/dev/pts/3"}}


def test_hardware_config_for_sets_only_the_given_fields():
    config = hardware_config_for({"arm": {"lcm_url": "memq://"},
                                  "tactile": {"port": "/dev/pts/9"}})
    default = hardware_config_for({})
    assert config.arm.lcm_url == "memq://"
    assert config.tactile.port == "/dev/pts/9"
    assert config.gripper == default.gripper
    assert config.tactile.baudrate == default.tactile.baudrate


def test_a_myrio_following_the_gripper_here_says_at_which_commands_it_waits(tmp_path):
    recording = quiet_recording()
    recording.gripper_times = np.array([0.0, 0.05, 0.1, 0.15])
    recording.gripper_requests = np.array([3, 230, 230, 3])
    trial = save_tactile_recording(tmp_path / "trial.npz", recording)
    lines = []
    with Emulators(lcm_url="memq://", out=lines.append).start(
            ("robotiq", "myrio"), LoadScenario(name="box"), trial=trial, follow_gripper=True):
        pass
    waits = [line for line in lines if "waits for the gripper" in line]
    assert len(waits) == 1
    assert "close after 0.00 s, open after 0.10 s" in waits[0]
    assert "the Robotiq emulator here" in waits[0]
