"""Device faults on the hardware station, against emulators in their own processes: a
device that dies mid-grasp trips the watchdog, which holds the arm still within 100 ms
after its timeout and names the device and since when; a gripper fault code is named.
"""

import os
import threading
import time

import numpy as np
import pytest

from tegrasp_drake.hardware.device_fault import DEVICE_FAULT, SILENT
from tegrasp_drake.emulators.emulator_process import EmulatedDevices
from tegrasp_drake.runs.hardware_run import END_MARGIN_S, run_on_hardware
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tegrasp_drake.scenario.scenario import LoadScenario

pytestmark = pytest.mark.slow

# Watchdog timeouts of the test (see test_hardware_hil.py: a loaded host's pty can be
# 50-100 ms late); the reaction after the timeout is what is measured.
TIMEOUT_S = 0.5
REACTION_S = 0.1     # safe state at most this long after the watchdog's timeout
STILL_RAD_S = 0.01   # an arm slower than this on every joint is holding still [rad/s]
KILL_AT_S = 4.6      # in the lift, the arm moving up with the box


SHORT_HOLD = ["grasp.hold_s=0.5"]


def lcm_url(offset):
    return f"udpm://239.255.76.67:{7300 + (os.getpid() * 7 + offset) % 400}?ttl=0"


@pytest.fixture(scope="module")
def box_trial(tmp_path_factory):
    """A recorded trial for the myRIO to replay: the simulated grasp of the box up to just
    after the kill (the rest is not needed)."""
    from tegrasp_drake.runs.trial import run_trial
    scenario = LoadScenario(name="box", overrides=SHORT_HOLD)
    trial = run_trial(scenario, max_time=KILL_AT_S + 1.0)
    return trial.log.save(tmp_path_factory.mktemp("trial") / "box.npz")


def devices_for(url, trial, *robotiq_args) -> EmulatedDevices:
    devices = EmulatedDevices(lcm_url=url, trial=trial, robotiq_args=robotiq_args)
    watchdog = devices.config.watchdog
    watchdog.arm_timeout = watchdog.gripper_timeout = watchdog.tactile_timeout = TIMEOUT_S
    return devices


def first_still_command(log):
    """(Context time [s], wall time [us]) of the first command after which every command
    is zero velocity."""
    moving = [np.any(np.abs(m.joint_velocity) > 0) for _, m in log.arm_commands]
    last_moving = np.flatnonzero(moving)[-1]
    assert last_moving + 1 < len(moving), "the arm was never commanded to hold still"
    wall, message = log.arm_commands[last_moving + 1]
    return message.utime * 1e-6, wall


def arm_still_wall_time(log) -> float:
    """Wall time [us] from which the arm's status shows it still until the end."""
    moving = [np.max(np.abs(m.joint_velocity)) > STILL_RAD_S for _, m in log.arm_status]
    last_moving = np.flatnonzero(moving)[-1]
    return log.arm_status[last_moving + 1][0]


def wall_time_of_context_time(log, t: float) -> float:
    """Wall time [us] the log received the first tactile tick at Context time >= t."""
    index = np.searchsorted(log.tactile["t"], t)
    assert index < len(log.tactile["t"]), f"no tactile tick at t >= {t}"
    return log.tactile["wall_us"][index]


def test_killed_myrio_trips_the_watchdog_and_the_arm_holds_still(box_trial, tmp_path):
    url = lcm_url(1)
    scenario = LoadScenario(name="box", overrides=SHORT_HOLD)
    lines = []
    killed_at = []

    with devices_for(url, box_trial) as devices:
        def kill():
            devices.myrio.kill()
            killed_at.append(time.time())
        killer = threading.Timer(KILL_AT_S, kill)

        def out(line):
            lines.append(line)
            if line.startswith("devices ready"):
                killer.start()
        result = run_on_hardware(scenario, config=devices.config,
                                 log_path=tmp_path / "kill.lcmlog", out=out)
        killer.cancel()
    fault = result.faults[0]
    assert (fault.device, fault.kind) == ("tactile", SILENT), "\n".join(lines)
    # The last frame came just before the kill (wall clock: the loop may lag real time).
    assert killed_at[0] - 0.3 < fault.since_wall_time < killed_at[0] + 0.01
    assert f"tactile: silent: no new data for more than {TIMEOUT_S * 1e3:.0f} ms; since t = " \
        in str(fault)
    assert any(line.startswith("[") and "FAULT tactile: silent" in line for line in lines)
    log = read_run_log(tmp_path / "kill.lcmlog")
    tripped = fault.since_sim_time + TIMEOUT_S
    still_command_time, _ = first_still_command(log)
    assert still_command_time <= tripped + REACTION_S
    assert arm_still_wall_time(log) <= wall_time_of_context_time(log, tripped) + REACTION_S * 1e6
    assert result.sim_time < tripped + END_MARGIN_S + 0.1
    assert result.transitions[-1]["to"] == "Failed"
    assert result.transitions[-1]["trigger"] == "fault"
    assert "tactile: silent" in result.transitions[-1]["reason"]


def test_gripper_fault_code_is_named_and_the_arm_holds_still(box_trial, tmp_path):
    url = lcm_url(2)
    scenario = LoadScenario(name="box", overrides=SHORT_HOLD)
    lines = []
    with devices_for(url, box_trial, "--inject-fault", "0x0E@3.0") as devices:
        result = run_on_hardware(scenario, config=devices.config,
                                 log_path=tmp_path / "fault.lcmlog", out=lines.append)
    fault = result.faults[0]
    assert (fault.device, fault.kind, fault.code) == ("gripper", DEVICE_FAULT, 0x0E), \
        "\n".join(lines)
    assert "gripper: device (code 0x0E): overcurrent triggered; since t = " in str(fault)
    log = read_run_log(tmp_path / "fault.lcmlog")
    still_command_time, _ = first_still_command(log)
    assert still_command_time <= fault.since_sim_time + REACTION_S
    assert [f.code for f in log.faults] == [0x0E]
    assert result.transitions[-1]["to"] == "Failed"
    assert "code 0x0E" in result.transitions[-1]["reason"]
