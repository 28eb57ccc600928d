"""Which station a scenario runs on: the simulation, or the real devices (typed config).

A scenario's `station` field is a tagged variant (experiments/scenario.py `StationConfig`),
as in Drake's hardware_sim:

    station: !SimulatedStationConfig {}          # the default: MakeGraspStation

    station: !HardwareStationConfig              # MakeHardwareStation
      arm: {lcm_url: "udpm://239.255.76.67:7667?ttl=0"}
      gripper: {port: /dev/ttyUSB0, device_id: 9}
      tactile: {port: /dev/ttyACM0, calibration_file: pads.yaml}
      watchdog: {arm_timeout: 0.05, gripper_timeout: 0.1, tactile_timeout: 0.05}

`tegrasp hardware --config FILE` reads a file holding only the HardwareStationConfig
mapping (the lines under `station:` above, untagged) with `LoadHardwareConfig`, checked
field by field like a scenario (rig/typed_yaml.py) and with the same `--set key=value`
overrides; `tegrasp emulate ... --write-config FILE` writes one for the emulators it started.
"""

import dataclasses
import typing

from pydrake.common.yaml import yaml_dump_typed

from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL
from tegrasp_drake.hardware.jaco.velocity_tracker import JacoVelocityTrackerConfig
from tegrasp_drake.hardware.robotiq.modbus_client import RobotiqModbusConfig
from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS
from tegrasp_drake.rig.typed_yaml import apply_override, load_typed, read_yaml_file

DEFAULT_LCM_URL = "udpm://239.255.76.67:7667?ttl=0"


@dataclasses.dataclass
class JacoLcmDriver:
    """The JACO2 through the Kinova LCM driver (joint-velocity mode, 100 Hz).

    lcm_url: the bus; `?ttl=0` keeps multicast on this host. The channels are Drake's
    KINOVA_JACO_COMMAND and KINOVA_JACO_STATUS."""
    lcm_url: str = DEFAULT_LCM_URL
    tracker: JacoVelocityTrackerConfig = dataclasses.field(
        default_factory=JacoVelocityTrackerConfig)

    @property
    def channels(self) -> tuple[str, str]:
        return JACO_COMMAND_CHANNEL, JACO_STATUS_CHANNEL


@dataclasses.dataclass
class SerialTactileDriver:
    """The myRIO tactile stream (drivers/TACTILE_FRAME.md) on a serial port.

    calibration_file: a TactileCalibration YAML (LoadTactileCalibration); empty for the
    defaults. stale_timeout [s]: the receiver's `stale` flag (the watchdog trips on its own
    timeout). max_backlog [frames]: the receiver plays received frames one per 1 ms tick
    and at most this many wait (TactileSerialReceiver), so bursts keep every piezo sample
    at a latency of at most max_backlog ms."""
    port: str = "/dev/ttyACM0"
    baudrate: int = 921600
    calibration_file: str = ""
    stale_timeout: float = 0.05
    max_backlog: int = 8


@dataclasses.dataclass
class DeviceWatchdogConfig:
    """Silence [s] after which a device trips the watchdog (drivers/watchdog.py), and the
    extra time a device may take to say anything at all after the start."""
    arm_timeout: float = DEFAULT_TIMEOUTS["arm"]
    gripper_timeout: float = DEFAULT_TIMEOUTS["gripper"]
    tactile_timeout: float = DEFAULT_TIMEOUTS["tactile"]
    startup_grace: float = 1.0

    def timeouts(self) -> dict[str, float]:
        """{device: timeout} in the watchdog's device order."""
        return {"arm": self.arm_timeout, "gripper": self.gripper_timeout,
                "tactile": self.tactile_timeout}


@dataclasses.dataclass
class HardwareStationConfig:
    """The real devices (or their emulators): MakeHardwareStation."""
    arm: JacoLcmDriver = dataclasses.field(default_factory=JacoLcmDriver)
    gripper: RobotiqModbusConfig = dataclasses.field(default_factory=RobotiqModbusConfig)
    tactile: SerialTactileDriver = dataclasses.field(default_factory=SerialTactileDriver)
    watchdog: DeviceWatchdogConfig = dataclasses.field(default_factory=DeviceWatchdogConfig)
    # How long [s] to wait, before the control loop starts, for the arm's first status,
    # the gripper's activation and the first tactile frame.
    ready_timeout: float = 10.0


def LoadHardwareConfig(filename, overrides: typing.Sequence[str] = ()
                         ) -> HardwareStationConfig:
    """Reads a HardwareStationConfig mapping from YAML; ConfigError names a bad field."""
    data = read_yaml_file(filename, "the hardware config") or {}
    if isinstance(data, dict):
        data.pop("_tag", None)
    for assignment in overrides:
        apply_override(data, assignment)
    return load_typed(data, HardwareStationConfig, str(filename))


def hardware_config_to_yaml(config: HardwareStationConfig) -> str:
    return yaml_dump_typed(config)
