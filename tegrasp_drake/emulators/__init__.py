"""Emulated devices that speak the real protocols on this host; imported only by tests,
commands and benchmarks, never by the controller or the hardware station.

launcher.py: Emulators, the devices of one `tegrasp emulate` started together.
emulator_process.py: EmulatorProcess, `tegrasp emulate` in a child process.
jaco_arm_emulator.py: the JACO2 as a Drake simulation on LCM.
robotiq_emulator.py: the 2F-85 model served over Modbus RTU.
modbus_request_framer.py: whole, CRC-valid Modbus requests out of a byte stream.
null_modem.py: two joined pseudo-terminals.
myrio_emulator.py: the myRIO replaying a recorded trial as tactile frames.
controller_clock.py: the controller's clock from its arm commands, to pace the replay.
gripper_link.py: the emulated gripper's request, for the replay to follow."""

from tegrasp_drake.emulators.controller_clock import ControllerClock, follow_jaco_commands
from tegrasp_drake.emulators.emulator_process import (
    EmulatedDevices, EmulatorProcess, EmulatorProcessError)
from tegrasp_drake.emulators.gripper_link import (
    GRIPPER_STATE_CHANNEL, GripperRequestFollower, follow_gripper_state, publish_gripper_state)
from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
from tegrasp_drake.emulators.launcher import (
    Emulators, FaultInjection, devices_from_line, hardware_config_for)
from tegrasp_drake.emulators.myrio_emulator import (
    GripperCommandChange, MyRioEmulator, MyRioEmulatorConfig, StreamFaults, TactileFrameSource,
    TactileRecording, TactileRecordingError, load_tactile_recording, save_tactile_recording)
from tegrasp_drake.emulators.null_modem import NullModem
from tegrasp_drake.emulators.robotiq_emulator import (
    RobotiqEmulator, RobotiqEmulatorConfig, RobotiqGripperModel)
