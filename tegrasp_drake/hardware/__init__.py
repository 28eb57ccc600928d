"""The real devices behind the station's ports (Fig. 7b); each receiver has its simulated
twin's ports plus `time_measured`, and blocking I/O lives on reader threads. The emulators
(tegrasp_drake.emulators) are never imported from here.

station.py: MakeHardwareStation, the devices wired to the controller's ports.
config.py: HardwareStationConfig and LoadHardwareConfig (the `station:` tag's schema).
serial_urls.py: the pyserial URLs a device's port may be, checked from their text.
jaco/: the JACO2 on LCM. robotiq/: the 2F-85 on Modbus RTU. myrio/: the tactile stream.
watchdog.py: DeviceWatchdog, which trips on a silent device.
fault_latch.py: FaultLatch, every fault kept and the arm's stop.
device_fault.py: DeviceFault, a named fault with its time.
message_boundary.py: decode, check, count and skip what a device sends.
lcm_boundary.py: LCM messages through that boundary.
device_log_messages.py: tactile and gripper data as LCM messages for logs.
realtime.py: real-time scheduling of the control loop.
lcm_time.py, state_outputs.py: utime conversion; scalar ports from a receiver's state."""

from tegrasp_drake.hardware.device_fault import (
    DEVICE_FAULT, DRIVER_ERROR, IMPLAUSIBLE, SILENT, DeviceFault, describe_faults)
from tegrasp_drake.hardware.device_log_messages import (
    FAULT_CHANNEL, GRIPPER_CHANNEL, RUN_INFO_CHANNEL, TACTILE_CHANNEL, TRANSITION_CHANNEL,
    GripperStatusSender, TactileStatusSender, tactile_arrays)
from tegrasp_drake.hardware.fault_latch import FaultLatch, latched_faults
from tegrasp_drake.hardware.lcm_time import utime_from_time
from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_LCM_PERIOD, JACO_NUM_JOINTS, JACO_STATUS_CHANNEL,
    JacoCommandReceiver, JacoCommandSender, JacoStatusReceiver, JacoStatusSender,
    make_jaco_command, make_jaco_status)
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import (
    AddJacoLcmDriver, AddJacoLcmEmulator, JacoLcmDriverSystems, JacoLcmEmulatorSystems)
from tegrasp_drake.rig.jaco_velocity_tracker import (
    JacoVelocityTracker, JacoVelocityTrackerConfig, velocity_command)
from tegrasp_drake.hardware.robotiq.robotiq_driver import RobotiqDriver, gripper_faults
from tegrasp_drake.hardware.robotiq.modbus_client import (
    RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig, RobotiqStatusSample)
from tegrasp_drake.hardware.myrio.tactile_calibration import (
    LoadTactileCalibration, PadCalibration, SaveTactileCalibration, TactileCalibration,
    acceleration_from_piezo, counts_from_forces, forces_from_counts, piezo_from_acceleration)
from tegrasp_drake.hardware.myrio.tactile_frame import (
    TactileDecoderCounters, TactileFrame, TactileFrameDecoder, encode_frame)
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import (
    TactileSerialReceiver, receiver_state_after_tick)
from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS, DeviceWatchdog
