"""The emulated Robotiq 2F-85 driven by a client nobody here wrote: pyrobotiqgripper.

pyrobotiqgripper (a test-only dependency, pinned in pyproject's `test` extra) reads the
status with function 4, writes commands with function 16 and writes-and-reads in one
transaction with function 23. Its activate() writes rACT and rGTO in one register and then
moves only if gGTO, the echo of rGTO, is 1. The emulator serves it on a pseudo-terminal as
it serves the project's own driver; the client opens the pty's tty name.
"""

import logging

import pyrobotiqgripper  # a test-only dependency (the `test` extra): never skipped
import pytest

from tegrasp_drake.robotiq import units
from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
from tegrasp_drake.scenario.scenario import LoadScenario

pytestmark = pytest.mark.real_time  # conftest: runs at real-time scheduling

ACTIVATION = 0.3        # [s], the emulated activation (the real one takes seconds)
CLIENT_TIMEOUT = 30.0   # [s], the client's activation and motion wait, for a loaded host


@pytest.fixture(scope="module")
def box_width():
    return LoadScenario(name="box").object.width_along_stroke()


@pytest.fixture
def gripper(box_width):
    # The client sets the pymodbus logger to CRITICAL for the whole process; put it back.
    pymodbus_logger = logging.getLogger("pymodbus")
    level = pymodbus_logger.level
    config = RobotiqEmulatorConfig(activation_duration=ACTIVATION, object_opening=box_width)
    with RobotiqEmulator(config) as emulator:
        gripper = pyrobotiqgripper.RobotiqGripper(com_port=emulator.port)
        gripper.timeOut = CLIENT_TIMEOUT
        try:
            yield gripper
        finally:
            gripper.disconnect()
            pymodbus_logger.setLevel(level)


@pytest.fixture
def activated(gripper):
    gripper.activate()
    return gripper


def test_activate_completes_with_gripper_started(activated):
    status = activated.status()
    assert status["gSTA"] == units.ActivationStatus.ACTIVE
    assert status["gACT"] == 1
    assert status["gGTO"] == 1  # the echo of the rGTO that activate() wrote
    assert status["gFLT"] == 0
    assert activated.isStarted()


def test_open_stops_fully_open(activated):
    activated.open()
    status = activated.status()
    assert status["gOBJ"] == units.ObjectStatus.AT_REQUESTED_POSITION
    assert status["gPO"] == units.POSITION_OPEN_BYTE


def test_close_stops_on_the_box(activated, box_width):
    activated.open()
    activated.close()
    status = activated.status()
    assert status["gOBJ"] == units.ObjectStatus.STOPPED_ON_CONTACT_CLOSING
    assert status["gPO"] == round(units.position_from_opening(box_width))
    assert status["gPR"] == 255
    assert status["gCU"] == 0  # the screw holds (the manual's finished grasp reads 0x00)


def test_move_to_60_reaches_it(activated):
    activated.move(60)
    status = activated.status()
    assert status["gOBJ"] == units.ObjectStatus.AT_REQUESTED_POSITION
    assert status["gPO"] == 60 and status["gPR"] == 60
