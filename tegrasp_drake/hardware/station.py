"""MakeHardwareStation: the real devices behind the simulated station's ports (Fig. 7b),
so the controller runs unchanged on either: the JACO2 on LCM, the 2F-85 on Modbus RTU and
the myRIO stream, each on its own thread; a DeviceWatchdog and a FaultLatch that hold the arm
still; tactile and gripper data republished on the bus for the log. Use it in a `with`
block, call `wait_until_ready()` before Initialize() and run at real-time rate 1."""

import logging
import time

from pydrake.lcm import DrakeLcm
from pydrake.systems.framework import Diagram, DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem, LcmPublisherSystem
from serial import SerialException

from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.rig.channels import FINGER_NAMES
from tegrasp_drake.hardware.device_log_messages import (
    GRIPPER_CHANNEL, GRIPPER_PUBLISH_PERIOD, TACTILE_CHANNEL, TACTILE_PUBLISH_PERIOD,
    GripperStatusSender, TactileStatusSender)
from tegrasp_drake.hardware.fault_latch import FaultLatch
from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_STATUS_CHANNEL
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver
from tegrasp_drake.hardware.lcm_boundary import WaitTally, wait_for_checked_message
from tegrasp_drake.hardware.message_boundary import MessageBoundary
from tegrasp_drake.hardware.robotiq.robotiq_driver import RobotiqDriver
from tegrasp_drake.hardware.robotiq.modbus_client import RobotiqActivationError, RobotiqModbusClient
from tegrasp_drake.hardware.myrio.tactile_calibration import (LoadTactileCalibration,
                                                              TactileCalibration)
from tegrasp_drake.hardware.myrio.serial_reader import (
    TactileSerialReader, no_valid_frame_problem, zeroing_problem)
from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver
from tegrasp_drake.hardware.watchdog import DeviceWatchdog
from tegrasp_drake.hardware.config import (HardwareStationConfig, lcm_url_origin,
                                           lcm_url_problem)
from tegrasp_drake.hardware.serial_urls import device_file
from tegrasp_drake.lcmtypes import lcmt_tegrasp_gripper, lcmt_tegrasp_tactile
from tegrasp_drake.rig.api_boundary import public_api
from tegrasp_drake.rig.echo import shorten, shown
from tegrasp_drake.rig.number_text import count_text

logger = logging.getLogger(__name__)


def serial_port_in_use(port: str) -> bool:
    """Whether another process holds `port` (a device path) open exclusively, as pyserial's
    `exclusive=True` and this station's readers do (an advisory flock on POSIX); False for a
    pyserial URL that opens no device file (spy:// is its wrapped device's), a path that is no
    device, or one that cannot be opened (the reader that opens it says why)."""
    import fcntl
    import os
    import stat
    port = device_file(port)
    if port is None:
        return False
    try:
        if not stat.S_ISCHR(os.stat(port).st_mode):
            return False
        descriptor = os.open(port, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return False
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    except OSError:
        return False
    finally:
        os.close(descriptor)  # releases a lock this took
    return False


def arm_not_ready_words(tally, url: str, timeout: float) -> str:
    """Why the arm is not ready after waiting `timeout` [s] on `url`, from what the wait saw
    (lcm_boundary.WaitTally): no status at all, or statuses that came and were all refused,
    with how many, why (by reason, the first in words) and what to check."""
    if not tally.arrived:
        return (f"arm: no lcmt_jaco_status on {JACO_STATUS_CHANNEL} at {url} within "
                f"{timeout:g} s (is the Kinova driver, or `tegrasp emulate jaco`, running on "
                "that URL?)")
    reasons = ", ".join(f"{reason} {count}" for reason, count in sorted(tally.rejected.items()))
    return (f"arm: {count_text(tally.arrived, 'message')} on {JACO_STATUS_CHANNEL} at {url} "
            f"within {timeout:g} s, none a status the JACO2 can send: "
            f"{tally.rejected_total} read and refused ({reasons}; the first: "
            f"{shorten(tally.first_rejection, 240)}); check that "
            "the Kinova driver on that URL publishes lcmt_jaco_status for the 6 joints, in "
            "radians, within the JACO2's ranges (docs/hardware.md), and that nothing else "
            f"publishes on {JACO_STATUS_CHANNEL}")


class HardwareNotReadyError(RuntimeError):
    """A device did not come up; the message names it and where it was looked for."""


class DeviceAbsentError(HardwareNotReadyError):
    """A serial device's port (the config field the message names) is not there to open."""


# Each serial device the station opens: its config section and what it is, for the messages.
SERIAL_DEVICES = (("gripper", "Robotiq 2F-85's USB-RS485 adapter"),
                  ("tactile", "myRIO's serial line"))


def absent_device_problem(config: HardwareStationConfig) -> str | None:
    """Why a serial device's port cannot be opened (its path not there: not plugged in, a
    mistyped name), naming its config field, the OS's reason and what to do; None if every
    port is there (what else keeps it from opening is the device's own open to say)."""
    import os
    for device, what in SERIAL_DEVICES:
        port = getattr(config, device).port
        path = device_file(port)  # a URL other than spy:// names no file: pyserial's to open
        if path is None:
            continue
        try:
            os.stat(path)
        except OSError as error:
            wraps = f" (the device it wraps, {shown(path)})" if path != port else ""
            return (f"field '{device}.port' {shown(port)}{wraps}: {error.strerror}: plug in the "
                    f"{what}, or give its port in {device}.port; `tegrasp emulate all "
                    "--write-config FILE` writes a config of emulated devices to try without "
                    "hardware")
    return None


class HardwareStation(Diagram):
    """The hardware interface Diagram (module docstring). Build with MakeHardwareStation.

    .. pydrake_system::

        name: HardwareStation
        input_ports:
        - arm.desired_state
        - gripper.command
        output_ports:
        - arm.position_measured
        - arm.velocity_measured
        - arm.torque_measured
        - arm.time_measured
        - arm.commanded_state
        - gripper.status
        - gripper.time_measured
        - tactile.left_taxel_forces
        - tactile.left_pad_acceleration
        - tactile.right_taxel_forces
        - tactile.right_pad_acceleration
        - tactile.pad_acceleration_samples
        - tactile.time_measured
        - tactile.stale
        - tactile.zeroing
        - fault
        - device_fault
        - stop

    Ports (sizes in rig/station_interface.py): arm.* in joint space [rad, rad/s, N m],
    arm.commanded_state (12) what the tracker sent; gripper.* Robotiq bytes; tactile.* as the
    simulated station's [N, m/s^2], with pad_acceleration_samples every film sample of the tick
    (TactileSerialReceiver); *.time_measured the device's time [s] (gripper: host monotonic);
    fault, device_fault, stop: the FaultLatch's (empty, "" and 0 while all is well).
    """

    def __init__(self, config: HardwareStationConfig, *, lcm: DrakeLcm | None = None):
        super().__init__()
        self._config = config
        problem = None if lcm is not None else lcm_url_problem(config.arm.lcm_url)
        if problem:
            origin = lcm_url_origin(config.arm.lcm_url, "the LCM URL")
            raise HardwareNotReadyError(f"arm: {origin} {shown(config.arm.lcm_url)} {problem}")
        self._lcm = lcm or DrakeLcm(config.arm.lcm_url)
        self._gripper_client = None
        self._tactile_reader = None
        try:
            self._open_devices()
            self._build()
        except BaseException:
            self.close()
            raise

    @property
    def lcm(self) -> DrakeLcm:
        return self._lcm

    @property
    def config(self) -> HardwareStationConfig:
        return self._config

    @property
    def gripper_client(self) -> RobotiqModbusClient:
        return self._gripper_client

    @property
    def tactile_reader(self) -> TactileSerialReader:
        return self._tactile_reader

    @property
    def arm_status_boundary(self) -> MessageBoundary:
        """Where the arm's KINOVA_JACO_STATUS messages are checked and counted."""
        return self._arm_status_boundary

    def message_boundaries(self) -> dict:
        """{device: MessageBoundary}: where each device's refused messages are counted."""
        return {"arm": self._arm_status_boundary, "gripper": self._gripper_client.boundary,
                "tactile": self._tactile_reader.boundary}

    def _open_devices(self):
        config = self._config
        problem = absent_device_problem(config)
        if problem:
            raise DeviceAbsentError(problem)
        for device, port in (("gripper", config.gripper.port), ("tactile", config.tactile.port)):
            if serial_port_in_use(port):
                raise HardwareNotReadyError(
                    f"{device}: the serial port {port} is in use by another process (another "
                    "tegrasp hardware run?); end it, or give this run other devices")
        logger.debug(f"station: arm on {self._lcm.get_lcm_url()}, gripper on "
                     f"{config.gripper.port} (Modbus slave {config.gripper.device_id}, "
                     f"{config.gripper.baudrate} baud), tactile on {config.tactile.port} "
                     f"({config.tactile.baudrate} baud)")
        self._gripper_client = RobotiqModbusClient(config.gripper).start()
        try:
            self._tactile_reader = TactileSerialReader(
                config.tactile.port, baudrate=config.tactile.baudrate).start()
        except (SerialException, OSError) as e:
            raise HardwareNotReadyError(
                f"tactile: cannot open the myRIO serial port {config.tactile.port}: {e}"
            ) from None

    def _build(self):
        config = self._config
        builder = DiagramBuilder()
        builder.AddNamedSystem("lcm", LcmInterfaceSystem(self._lcm))

        # Arm.
        jaco = AddJacoLcmDriver(builder, lcm=self._lcm, tracker_config=config.arm.tracker)
        builder.ExportInput(jaco.tracker.GetInputPort("desired_state"), ports.ARM_DESIRED_STATE)
        for name, port in (("position_measured", ports.ARM_POSITION_MEASURED),
                           ("velocity_measured", ports.ARM_VELOCITY_MEASURED),
                           ("torque_measured", ports.ARM_TORQUE_MEASURED),
                           ("time_measured", ports.ARM_TIME_MEASURED)):
            builder.ExportOutput(jaco.status_receiver.GetOutputPort(name), port)
        builder.ExportOutput(jaco.tracker.GetOutputPort("commanded_state"),
                             ports.ARM_COMMANDED_STATE)
        self._status_subscriber = jaco.status_subscriber
        self._arm_status_boundary = jaco.status_boundary

        # Gripper.
        gripper = builder.AddNamedSystem("gripper_driver", RobotiqDriver(
            self._gripper_client, stale_timeout=config.watchdog.gripper_timeout))
        builder.ExportInput(gripper.GetInputPort("command"), ports.GRIPPER_COMMAND)
        builder.ExportOutput(gripper.GetOutputPort("status"), ports.GRIPPER_STATUS)
        builder.ExportOutput(gripper.GetOutputPort("time_measured"), ports.GRIPPER_TIME_MEASURED)

        # Tactile pads.
        calibration = (LoadTactileCalibration(config.tactile.calibration_file)
                       if config.tactile.calibration_file else TactileCalibration())
        tactile = builder.AddNamedSystem("tactile_receiver", TactileSerialReceiver(
            self._tactile_reader, calibration=calibration,
            stale_timeout=config.tactile.stale_timeout, max_backlog=config.tactile.max_backlog))
        self._tactile_receiver = tactile
        for finger in FINGER_NAMES:
            builder.ExportOutput(tactile.GetOutputPort(f"{finger}_taxel_forces"),
                                 ports.taxel_forces(finger))
            builder.ExportOutput(tactile.GetOutputPort(f"{finger}_pad_acceleration"),
                                 ports.pad_acceleration(finger))
        for name, port in (("pad_acceleration_samples", ports.TACTILE_PAD_ACCELERATION_SAMPLES),
                           ("time_measured", ports.TACTILE_TIME_MEASURED),
                           ("stale", ports.TACTILE_STALE), ("zeroing", ports.TACTILE_ZEROING)):
            builder.ExportOutput(tactile.GetOutputPort(name), port)

        # Watchdog and faults; any fault holds the arm still.
        watchdog = builder.AddNamedSystem("watchdog", DeviceWatchdog(
            config.watchdog.timeouts(), startup_grace=config.watchdog.startup_grace))
        builder.Connect(jaco.status_receiver.GetOutputPort("time_measured"),
                        watchdog.GetInputPort("arm_time_measured"))
        builder.Connect(gripper.GetOutputPort("time_measured"),
                        watchdog.GetInputPort("gripper_time_measured"))
        builder.Connect(tactile.GetOutputPort("time_measured"),
                        watchdog.GetInputPort("tactile_time_measured"))
        faults = builder.AddNamedSystem("fault_latch", FaultLatch(["watchdog", "gripper",
                                                                   "tactile"]))
        builder.Connect(watchdog.GetOutputPort("fault"), faults.GetInputPort("watchdog_fault"))
        builder.Connect(gripper.GetOutputPort("fault"), faults.GetInputPort("gripper_fault"))
        builder.Connect(tactile.GetOutputPort("fault"), faults.GetInputPort("tactile_fault"))
        builder.Connect(faults.GetOutputPort("stop"), jaco.tracker.GetInputPort("stop"))
        builder.ExportOutput(faults.GetOutputPort("fault"), ports.FAULT)
        builder.ExportOutput(faults.GetOutputPort("message"), ports.DEVICE_FAULT)
        builder.ExportOutput(faults.GetOutputPort("stop"), ports.STOP)

        # Device data on the bus.
        tactile_sender = builder.AddNamedSystem("tactile_status_sender", TactileStatusSender())
        for name in ("left_taxel_forces", "right_taxel_forces", "left_pad_acceleration",
                     "right_pad_acceleration", "time_measured", "stale", "zeroing",
                     "arrival_time"):
            builder.Connect(tactile.GetOutputPort(name), tactile_sender.GetInputPort(name))
        gripper_sender = builder.AddNamedSystem("gripper_status_sender", GripperStatusSender())
        builder.ConnectInput(ports.GRIPPER_COMMAND, gripper_sender.GetInputPort("command"))
        builder.Connect(gripper.GetOutputPort("status"), gripper_sender.GetInputPort("status"))
        builder.Connect(gripper.GetOutputPort("time_measured"),
                        gripper_sender.GetInputPort("time_measured"))
        for sender, channel, lcm_type, period in (
                (tactile_sender, TACTILE_CHANNEL, lcmt_tegrasp_tactile, TACTILE_PUBLISH_PERIOD),
                (gripper_sender, GRIPPER_CHANNEL, lcmt_tegrasp_gripper, GRIPPER_PUBLISH_PERIOD)):
            publisher = builder.AddNamedSystem(f"{channel.lower()}_publisher",
                                               LcmPublisherSystem.Make(
                                                   channel=channel, lcm_type=lcm_type,
                                                   lcm=self._lcm, publish_period=period))
            builder.Connect(sender.get_output_port(), publisher.get_input_port())

        builder.BuildInto(self)
        self.set_name("hardware_station")

    def wait_until_ready(self, timeout: float | None = None):
        """Blocks, before the Simulator starts, until the arm's status arrived, the gripper is
        active and the pads are zeroed; else HardwareNotReadyError naming what is missing."""
        timeout = self._config.ready_timeout if timeout is None else timeout
        deadline = time.monotonic() + timeout
        tally = WaitTally()
        if not wait_for_checked_message(self._lcm, self._status_subscriber, deadline, tally):
            raise HardwareNotReadyError(arm_not_ready_words(
                tally, self._lcm.get_lcm_url(), timeout))
        try:
            self._gripper_client.wait_until_active(max(deadline - time.monotonic(), 0.0),
                                                   configured_s=timeout)
        except RobotiqActivationError as e:
            raise HardwareNotReadyError(f"gripper: {e}") from None
        while self._tactile_reader.counters().decoder.frames == 0:
            if time.monotonic() > deadline:
                raise HardwareNotReadyError(
                    f"tactile: no valid frame on {self._tactile_reader.port} within "
                    f"{timeout:g} s: "
                    f"{no_valid_frame_problem(self._tactile_reader.counters())}")
            time.sleep(0.005)
        if not self._tactile_receiver.zero_before_start(deadline):
            raise HardwareNotReadyError(
                f"tactile: the pads on {self._tactile_reader.port} were not zeroed within "
                f"{timeout:g} s: " + zeroing_problem(self._tactile_reader.counters(),
                                                    self._tactile_receiver.zero_samples))
        self._tactile_reader.discard_pending()
        logger.info(f"station: devices ready (arm status on {self._lcm.get_lcm_url()}, "
                    f"gripper active on {self._config.gripper.port}, pads zeroed from "
                    f"{self._tactile_reader.port})")
        logger.debug(f"station: at the start: {self._tactile_reader.counters()}")

    def close(self):
        """Stops the device threads and closes their ports (idempotent)."""
        if self._tactile_reader is not None:
            self._tactile_reader.close()
            self._tactile_reader = None
        if self._gripper_client is not None:
            self._gripper_client.close()
            self._gripper_client = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


@public_api
def MakeHardwareStation(config: HardwareStationConfig, *,
                        lcm: DrakeLcm | None = None) -> HardwareStation:
    """The hardware interface for `config`; `lcm` overrides its URL (e.g. memq:// in tests).
    A config changed after loading is checked against its declared ranges by public_api."""
    return HardwareStation(config, lcm=lcm)
