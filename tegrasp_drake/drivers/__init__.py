"""Hardware drivers: the Jaco on LCM, the Robotiq 2F-85 on Modbus RTU, the myRIO tactile
stream on a serial port, their emulators (the Jaco's a Drake simulation on LCM), the device
watchdog and fault latch, and the device data as LCM messages for logs.

Each receiver exposes the same ports as its simulated twin in the station, plus
`time_measured` and a staleness flag; blocking I/O lives on reader threads.
"""

from tegrasp_drake.drivers.controller_clock import ControllerClock, follow_jaco_commands
from tegrasp_drake.drivers.device_fault import (
    DEVICE_FAULT, DRIVER_ERROR, SILENT, DeviceFault, describe_faults)
from tegrasp_drake.drivers.device_log_messages import (
    FAULT_CHANNEL, GRIPPER_CHANNEL, RUN_INFO_CHANNEL, TACTILE_CHANNEL, TRANSITION_CHANNEL,
    GripperStatusSender, TactileStatusSender, tactile_arrays)
from tegrasp_drake.drivers.fault_latch import FaultLatch, latched_faults
from tegrasp_drake.drivers.jaco_arm_emulator import MakeJacoArmEmulator
from tegrasp_drake.drivers.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_LCM_PERIOD, JACO_NUM_JOINTS, JACO_STATUS_CHANNEL,
    JacoCommandReceiver, JacoCommandSender, JacoStatusReceiver, JacoStatusSender,
    make_jaco_command, make_jaco_status)
from tegrasp_drake.drivers.jaco_lcm_interface import (
    AddJacoLcmDriver, AddJacoLcmEmulator, JacoLcmDriverSystems, JacoLcmEmulatorSystems)
from tegrasp_drake.drivers.jaco_velocity_tracker import (
    JacoVelocityTracker, JacoVelocityTrackerConfig, velocity_command)
from tegrasp_drake.drivers.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, StreamFaults, TactileFrameSource, TactileTrial)
from tegrasp_drake.drivers.null_modem import NullModem
from tegrasp_drake.drivers.robotiq_driver import RobotiqDriver, gripper_faults
from tegrasp_drake.drivers.robotiq_emulator import (
    RobotiqEmulator, RobotiqEmulatorConfig, RobotiqGripperModel)
from tegrasp_drake.drivers.robotiq_modbus import (
    RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig, RobotiqStatusSample)
from tegrasp_drake.drivers.robotiq_registers import (
    command_registers, command_registers_from_vector, decode_command_registers,
    status_from_registers, status_registers)
from tegrasp_drake.drivers.tactile_calibration import (
    LoadTactileCalibration, PadCalibration, SaveTactileCalibration, TactileCalibration,
    acceleration_from_piezo, counts_from_forces, forces_from_counts, piezo_from_acceleration)
from tegrasp_drake.drivers.tactile_frame import (
    TactileDecoderCounters, TactileFrame, TactileFrameDecoder, encode_frame)
from tegrasp_drake.drivers.tactile_serial_reader import TactileSerialReader
from tegrasp_drake.drivers.tactile_serial_receiver import (
    TactileSerialReceiver, receiver_state_after_tick)
from tegrasp_drake.drivers.watchdog import DEFAULT_TIMEOUTS, DeviceWatchdog
