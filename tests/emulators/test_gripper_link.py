"""The emulated gripper's state on the bus, as the emulated myRIO follows it."""

import os
import threading
import time

from tegrasp_drake.emulators.gripper_link import (
    GripperRequestFollower, follow_gripper_state, publish_gripper_state)
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulatorConfig, RobotiqGripperModel
from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper
from tegrasp_drake.robotiq import registers, units

GRIP, OPEN = 230, 3     # rPR bytes
HANG_GUARD_S = 30.0     # a guard against a hang on a busy host, not a criterion


def test_the_follower_reads_the_position_request_of_the_published_status():
    follower = GripperRequestFollower()
    assert follower() is None
    message = lcmt_tegrasp_gripper()
    status = [0] * units.STATUS_SIZE
    status[units.STATUS_PR], status[units.STATUS_PO] = OPEN, 110
    message.command, message.status = [OPEN, 157, 6], status
    follower.on_message(message.encode())
    assert follower() == OPEN


def test_a_request_written_to_the_gripper_reaches_a_follower_on_the_bus():
    url = f"udpm://239.255.76.67:{8100 + os.getpid() % 500}?ttl=0"
    model = RobotiqGripperModel(RobotiqEmulatorConfig(activation_duration=0.0),
                                time.monotonic())
    stop = threading.Event()
    try:
        follower = follow_gripper_state(url, stop)
        publish_gripper_state(url, model, stop)
        model.write(registers.COMMAND_ADDRESS, registers.command_registers(GRIP, 255, 50),
                    time.monotonic())
        deadline = time.monotonic() + HANG_GUARD_S
        while follower() != GRIP:
            assert time.monotonic() < deadline, f"the follower still reads {follower()}"
            time.sleep(0.01)
    finally:
        stop.set()
