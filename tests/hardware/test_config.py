"""The hardware config (HardwareStationConfig) and the scenario's `station` variant."""

import pytest

from tegrasp_drake.hardware.config import (HardwareStationConfig, hardware_config_to_yaml,
                                           LoadHardwareConfig)
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.rig import station_interface as ports
from tegrasp_drake.simulation.station import SimulatedStationConfig


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_hardware_config_loads_ports_url_and_timeouts_with_overrides(tmp_path, monkeypatch):
    from tegrasp_drake.hardware.myrio.tactile_calibration import (SaveTactileCalibration,
                                                                  TactileCalibration)
    monkeypatch.chdir(tmp_path)  # calibration_file is read (at load) from the working folder
    SaveTactileCalibration(TactileCalibration(), tmp_path / "pads.yaml")
    path = write(tmp_path, "hw.yaml", """
arm: {lcm_url: "udpm://239.255.76.67:7700?ttl=0"}
gripper: {port: /dev/ttyUSB3, device_id: 9}
tactile: {port: /dev/ttyACM1, calibration_file: pads.yaml}
watchdog: {tactile_timeout: 0.08}
""")
    config = LoadHardwareConfig(path, ["gripper.port=/dev/ttyUSB4"])
    assert config.arm.lcm_url == "udpm://239.255.76.67:7700?ttl=0"
    assert (config.gripper.port, config.gripper.device_id) == ("/dev/ttyUSB4", 9)
    assert config.tactile.calibration_file == "pads.yaml"
    assert config.watchdog.timeouts() == {"arm": 0.05, "gripper": 0.1, "tactile": 0.08}


def test_hardware_config_round_trips_through_yaml(tmp_path):
    config = HardwareStationConfig()
    config.tactile.port = "/dev/pts/7"
    path = write(tmp_path, "hw.yaml", hardware_config_to_yaml(config))
    assert LoadHardwareConfig(path) == config


# Rule: LoadHardwareConfig's overrides may not set one key twice to two values, as
# --config-set given twice and a key repeated in the file may not: neither silently wins.
@pytest.mark.parametrize("overrides", [
    ["gripper.port=/dev/ttyUSB4", "gripper.port=/dev/ttyUSB5"],
    ["gripper.port=/dev/ttyUSB4", "tactile.port=/dev/ttyACM1", "gripper.port = /dev/ttyUSB5"],
])
def test_hardware_config_overrides_setting_a_key_twice_are_refused(tmp_path, overrides):
    path = write(tmp_path, "hw.yaml", "gripper: {port: /dev/ttyUSB3}\n")
    with pytest.raises(ConfigError) as refused:
        LoadHardwareConfig(path, overrides)
    message = str(refused.value)
    assert str(path) in message and "argument 'overrides' sets gripper.port twice" in message
    assert "\n" not in message, message
    same = ["gripper.port=/dev/ttyUSB4", "gripper.port=/dev/ttyUSB4"]
    assert LoadHardwareConfig(path, same).gripper.port == "/dev/ttyUSB4"


def test_a_misspelt_hardware_field_is_named(tmp_path):
    path = write(tmp_path, "hw.yaml", "gripper: {prot: /dev/ttyUSB0}\n")
    with pytest.raises(ConfigError, match="unknown field 'gripper.prot'"):
        LoadHardwareConfig(path)


def test_scenarios_run_on_the_simulated_station_unless_tagged(tmp_path):
    assert LoadScenario(name="box").station == SimulatedStationConfig()
    path = write(tmp_path, "s.yaml", """
real_box:
  object: {name: box}
  station: !HardwareStationConfig
    tactile: {port: /dev/ttyACM0}
""")
    station = LoadScenario(path, "real_box").station
    assert isinstance(station, HardwareStationConfig)
    assert station.tactile.port == "/dev/ttyACM0"


def test_an_unknown_station_tag_is_named(tmp_path):
    path = write(tmp_path, "s.yaml", "bad:\n  station: !RobotStation {}\n")
    with pytest.raises(ConfigError, match="unknown tag !RobotStation.*!HardwareStationConfig"):
        LoadScenario(path, "bad")


def test_the_station_tag_picks_the_station_builder(tmp_path):
    from tegrasp_drake.scenario.grasp_diagram import MakeStation
    from tegrasp_drake.hardware.station import HardwareNotReadyError
    assert MakeStation(LoadScenario(name="box")).HasOutputPort(ports.OBJECT_STATE)
    path = write(tmp_path, "s.yaml", """
real_box:
  station: !HardwareStationConfig
    arm: {lcm_url: "memq://"}
    gripper: {port: /dev/no-such-gripper}
    tactile: {port: /dev/no-such-myrio}
""")
    # The hardware builder checks the gripper's port first (test_station.py: the tactile one).
    with pytest.raises(HardwareNotReadyError, match="field 'gripper.port' '/dev/no-such-gripper'"):
        MakeStation(LoadScenario(path, "real_box"))
