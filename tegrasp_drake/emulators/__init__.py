"""Emulated devices that speak the real protocols on this host: the JACO2 as a Drake
simulation on LCM, the Robotiq 2F-85 on a pseudo-terminal (Modbus RTU), the myRIO tactile
stream on a pseudo-terminal (its replay following the emulated gripper's commands), the
launcher that starts them together (`tegrasp emulate`) and the one that runs that command
in a child process.

Imported only by tests, commands and benchmarks: the controller and the hardware station
never depend on them.
"""

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
