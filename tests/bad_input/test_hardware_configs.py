"""The hardware config and its companions are checked at load, before any device is opened:
empty or short values, missing fields, calibration files (a device, a pipe, ranges), two
devices on one serial port, scheduling, watchdog timeouts within two device updates, joint
limits, a duration past the command line's cap, and a scenario for the devices given to a
simulation."""

import os
import re

import pytest

import tegrasp_drake
import tegrasp_drake as T
from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.config import (HardwareStationConfig, LoadHardwareConfig,
                                           hardware_config_to_yaml, validate_hardware_config,
                                           watchdog_timeouts_problem)
from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import assert_one_line_error, refusal, run_cli


# --- hardware configs -------------------------------------------------------------------

@pytest.mark.parametrize("text, expected", [
    ("- arm\n- gripper\n", "must be a mapping of HardwareStationConfig fields"),
    ("watchdog: {tactile_timeout: .nan}\n", "field 'watchdog.tactile_timeout' must be a finite"),
    ("ready_timeout: -5\n", "field 'ready_timeout' must lie in [1.13333, 600] s"),
    ("tactile: {max_backlog: -3}\n", "field 'tactile.max_backlog' must be zero or a positive"),
    ("watchdog: {arm_timeout: 0}\n", "field 'watchdog.arm_timeout' must lie in (0.02, 10] s"),
    ("arm: {lcm_url: 'udpm://239.255.76.67:99999?ttl=0'}\n",
     "field 'arm.lcm_url' has the port '99999', which is not a number from 1 to 65535"),
    ("arm: {lcm_url: garbage}\n", "field 'arm.lcm_url' does not parse as an LCM URL: it "
                                  "names no provider (PROVIDER://ADDRESS)"),
    ("arm: {lcm_url: 'nope://'}\n", "field 'arm.lcm_url' is not an LCM bus URL"),
    ("watchdog: {arm_timeout: 0.05\n", "not valid YAML"),
    ("scheduling: deadline\n", "field 'scheduling' must be one of 'fifo', 'nice', 'normal'"),
])
def test_a_bad_hardware_config_is_named_before_any_device_is_opened(text, expected, tmp_path,
                                                                     capfd):
    config = tmp_path / "hw.yaml"
    config.write_text(text)
    code, output = run_cli(["hardware", "--config", str(config), "--controller", "heuristic"],
                           capfd)
    assert_one_line_error(code, output, str(config), expected)


@pytest.mark.parametrize("duration", ["-5", "0", "1e7"])
def test_a_hardware_duration_out_of_range_is_bad_input(duration, tmp_path, capfd):
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--duration", duration], capfd)
    assert code == 1 and "--duration" in text and "Traceback" not in text


@pytest.mark.parametrize("duration", ["nan", "inf"])
def test_a_hardware_duration_that_is_no_number_is_a_usage_error(duration, tmp_path, capfd):
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--duration", duration], capfd)
    assert code == 2 and "--duration" in text and "not a number" in text
    assert "Traceback" not in text


def test_a_trial_refuses_a_scenario_for_the_devices(tmp_path, capfd):
    scenario = tmp_path / "scenarios.yaml"
    scenario.write_text("mine:\n  station: !HardwareStationConfig {ready_timeout: 1.5}\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine",
                          "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, "!HardwareStationConfig", "tegrasp hardware")
    assert not (tmp_path / "run").exists()


def _fifo(path):
    os.mkfifo(path)


@pytest.mark.parametrize("make, words", [
    (None, "it does not exist"),
    (_fifo, "is a named pipe (FIFO)"),
    (lambda path: path.write_text("- 1\n- 2\n"), "must be a mapping of fields"),
    (lambda path: path.write_text("left: {gain: [.nan]}\n"), "must be a finite number"),
])
def test_the_hardware_config_reads_its_calibration_file_at_load(make, words, tmp_path):
    calibration = tmp_path / "pads.yaml"
    if make:
        make(calibration)
    config = HardwareStationConfig()
    config.tactile.calibration_file = str(calibration)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(config))
    with pytest.raises(ConfigError, match="field 'tactile.calibration_file': .*pads.yaml") as e:
        tegrasp_drake.LoadHardwareConfig(tmp_path / "hw.yaml")
    assert words in str(e.value)


def test_a_calibration_device_is_refused_in_one_line():
    with pytest.raises(ConfigError, match="/dev/zero.*is a device, not a file"):
        LoadTactileCalibration("/dev/zero")


# --- 3. no hang ------------------------------------------------------------------------------

def test_a_fifo_calibration_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "pads.yaml")  # no writer: an open() for reading would block
    with pytest.raises(ConfigError, match="is a named pipe"):
        LoadTactileCalibration(str(tmp_path / "pads.yaml"))


def test_a_hardware_run_longer_than_the_command_lines_cap_is_refused():
    from tegrasp_drake import LoadScenario, run_on_hardware
    with pytest.raises(ValueError, match=r"duration.*must lie in \(0, 600\] s"):
        run_on_hardware(LoadScenario(name="box"), duration=1e9)


# Rule: a configuration file without a field (empty, comments only, `{}`, its own tag alone)
# is a mistake, not a request for every default: the hardware config as scenario files and
# specs. (Another kind's tag alone is refused as that: tests/test_yaml_top_level.py.)
@pytest.mark.parametrize("text", ["", "# my robot\n", "{{}}\n", "!{kind} {{}}\n"])
def test_a_hardware_config_without_fields_is_refused(tmp_path, text):
    path = tmp_path / "hardware.yaml"
    path.write_text(text.format(kind="HardwareStationConfig"))
    refusal(lambda: T.LoadHardwareConfig(path), str(path), "is empty")
    spec = tmp_path / "spec.yaml"
    spec.write_text(text.format(kind="SweepSpec"))
    refusal(lambda: T.LoadSweepSpec(spec), str(spec), "is empty")


# Rule: a file tagged as the simulated station is not an empty hardware config: it is said
# to be the other station, with the tag `tegrasp hardware` needs and where it runs instead.
@pytest.mark.parametrize("text", ["!SimulatedStationConfig {}\n",
                                  "!SimulatedStationConfig {time_step: 0.001}\n"])
def test_a_simulated_station_given_as_hardware_config_is_named(tmp_path, capfd, text):
    config = tmp_path / "hw.yaml"
    config.write_text(text)
    code, output = run_cli(["hardware", "--config", str(config), "--duration", "1"], capfd)
    assert code == 1, output
    assert_one_line_error(code, output, f"{config}: the file is a !SimulatedStationConfig, a "
                          "simulated station", "needs a !HardwareStationConfig (or untagged "
                          "hardware fields", "runs with `tegrasp trial`")
    assert "empty" not in output, output


# Rule: an empty text or list is a value only where the field declares what empty means
# (unset_fields) or where its default is itself empty; a field whose default is filled (an
# LCM bus, a port, the joints that wrap) refuses an empty one naming the field, rather than
# run on LCM's default bus or no device (rig/ranges.check_ranges, at load and at a public
# function). A list of a fixed length (one value per joint) holds that many in every config.
@pytest.mark.parametrize("text, field, words", [
    ("arm: {tracker: {continuous_joints: []}}\n", "arm.tracker.continuous_joints", "is empty"),
    ("arm: {tracker: {continuous_joints: [true]}}\n", "arm.tracker.continuous_joints",
     "must hold 6"),
    ('arm: {lcm_url: ""}\n', "arm.lcm_url", "is empty"),
    ("arm: {lcm_url: ''}\n", "arm.lcm_url", "is empty"),
    ('gripper: {port: ""}\n', "gripper.port", "is empty"),
    ("gripper: {port: ''}\n", "gripper.port", "is empty"),
    ('tactile: {port: ""}\n', "tactile.port", "is empty"),
    ("tactile: {port: ''}\n", "tactile.port", "is empty"),
])
def test_a_hardware_config_refuses_an_empty_or_short_value(tmp_path, text, field, words):
    path = tmp_path / "hardware.yaml"
    path.write_text(text)
    refusal(lambda: T.LoadHardwareConfig(path), str(path), f"field '{field}' {words}")


# Rule: two devices configured on one serial port (the same name, or one line through a
# symlink) are refused by the config check, naming both fields and the file, before any
# device is opened (the tactile reader took the gripper's answers; the run blamed the gripper).
@pytest.mark.parametrize("through_symlink", [False, True], ids=["same-name", "symlink"])
def test_two_devices_on_one_serial_port_are_refused(through_symlink, tmp_path, capfd):
    master, slave, port = open_raw_pty()  # a serial line no device answers on
    try:
        tactile = port
        if through_symlink:
            tactile = str(tmp_path / "ttyMYRIO")
            os.symlink(port, tactile)
        config = tmp_path / "hw.yaml"
        config.write_text(f"ready_timeout: 1.5\nscheduling: normal\ngripper: {{port: {port}}}\n"
                          f"tactile: {{port: {tactile}}}\n")
        code, output = run_cli(["hardware", "--config", str(config), "--set",
                                "random_seed=620"], capfd)
    finally:
        os.close(master)
        os.close(slave)
    assert_one_line_error(code, output, str(config), "'tactile.port'", "'gripper.port'",
                          "are one serial line")


def test_distinct_serial_ports_are_accepted(tmp_path):
    first, second = open_raw_pty(), open_raw_pty()
    try:
        config = tmp_path / "hw.yaml"
        config.write_text(f"gripper: {{port: {first[2]}}}\ntactile: {{port: {second[2]}}}\n")
        loaded = LoadHardwareConfig(config)
    finally:
        for master, slave, _ in (first, second):
            os.close(master)
            os.close(slave)
    assert (loaded.gripper.port, loaded.tactile.port) == (first[2], second[2])


# Rule: a tactile calibration file's gains, offsets and piezo offset lie in their declared
# ranges, each pad's lists 12 long, named in one line.
@pytest.mark.parametrize("body, field", [
    ("left: {gain: [-1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, 1.0e-3, "
     "1.0e-3, 1.0e-3, 1.0e-3]}", "left.gain[0]"),
    ("left: {gain: [1.0e-3]}", "left.gain"),
    ("right: {offset: [70000, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]}", "right.offset[0]"),
    ("left: {piezo_offset: 50.0}", "left.piezo_offset"),
    ("right: {piezo_gain: 1.0e+30}", "right.piezo_gain"),
    ("left: {piezo_gain: 0.253}", "left.piezo_gain"),
    ("left: {piezo_gain: -253.0}", "left.piezo_gain"),
    ("zero_samples: -1", "zero_samples"),
    ("zero_samples: 1000000000", "zero_samples"),
    ("piezo_volts_per_count: 0.0", "piezo_volts_per_count"),
    ("piezo_volts_per_count: 10.0", "piezo_volts_per_count"),
])
def test_a_tactile_calibration_out_of_its_ranges_is_refused(tmp_path, body, field):
    from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
    from tegrasp_drake.rig.typed_yaml import ConfigError
    path = tmp_path / "calibration.yaml"
    path.write_text(body + "\n")
    with pytest.raises(ConfigError, match=f"field '{re.escape(field)}'"):
        LoadTactileCalibration(str(path))


# Rule: a builder given a config checks its choices as the loader does, not only its ranges
# (scheduling='rr' went on to open the devices).
@pytest.mark.parametrize("mutate", [False, True], ids=["built", "changed-after"])
def test_a_hardware_config_with_an_unknown_scheduling_is_refused_by_the_builder(mutate):
    from tegrasp_drake import MakeHardwareStation
    from tegrasp_drake.hardware.config import HardwareStationConfig
    with pytest.raises(ConfigError, match="field 'scheduling' must be one of 'fifo', 'nice', "
                                          "'normal', got str 'rr'"):
        if mutate:
            config = HardwareStationConfig()
            config.scheduling = "rr"
        else:
            config = HardwareStationConfig(scheduling="rr")
        MakeHardwareStation(config)


@pytest.mark.parametrize("flags, joint", [("[true,true,false,true,true,true]", 2),
                                          ("[true,false,true,true,true,true]", 3)])
def test_a_limited_joint_marked_continuous_is_refused_in_both_configs(tmp_path, flags, joint):
    """The tracker wraps a continuous joint's error into [-pi, pi): on the JACO2's joints 2
    and 3, which have stops, that drives an error past half a turn through the stop."""
    from tegrasp_drake.hardware.config import LoadHardwareConfig
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    words = f"marks joint {joint} continuous, but the JACO2's joint {joint} turns only"
    with pytest.raises(ConfigError, match=words):
        LoadScenario(name="box", overrides=[f"arm.tracker.continuous_joints={flags}"])
    config = tmp_path / "hardware.yaml"
    config.write_text(f"arm: {{tracker: {{continuous_joints: {flags}}}}}\n")
    with pytest.raises(ConfigError, match="field 'arm.tracker.continuous_joints' " + words):
        LoadHardwareConfig(config)


@pytest.mark.parametrize("device, least", [("arm", "0.02"), ("gripper", "0.06"),
                                           ("tactile", "0.002")])
def test_a_watchdog_timeout_within_two_device_updates_is_refused(device, least):
    config = HardwareStationConfig()
    assert watchdog_timeouts_problem(config) is None  # the defaults
    setattr(config.watchdog, f"{device}_timeout", 1e-9)
    problem = watchdog_timeouts_problem(config)
    assert f"field 'watchdog.{device}_timeout'" in problem
    assert f"give more than {least} s" in problem


# Rule: one unanswered Modbus request (gripper.request_timeout) and two reads after it must
# not trip the gripper's watchdog, as two of its read periods must not.
def test_a_gripper_request_timeout_the_watchdog_cannot_wait_out_is_refused(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text("gripper: {request_timeout: 0.5}\nwatchdog: {gripper_timeout: 0.1}\n")
    with pytest.raises(ConfigError, match=re.escape(
            "field 'watchdog.gripper_timeout' is 0.1 s, not longer than one unanswered request "
            "(field 'gripper.request_timeout', 0.5 s)")) as refused:
        LoadHardwareConfig(config)
    assert "give more than 0.51 s" in str(refused.value)
    assert "or a shorter 'gripper.request_timeout'" in str(refused.value)
    config.write_text("gripper: {request_timeout: 0.5}\nwatchdog: {gripper_timeout: 0.6}\n")
    assert LoadHardwareConfig(config).watchdog.gripper_timeout == 0.6


# Rule: at a slow gripper.baudrate a request must be given the time its frames take on the
# wire, and the watchdog the time between reads that the wire allows (1200 baud: a read and
# a write take 0.47 s, past the 50 ms request timeout and the 100 ms watchdog).
@pytest.mark.parametrize("body, words", [
    ("gripper: {baudrate: 1200}\n", "field 'gripper.request_timeout' is 0.05 s, not longer "
     "than a command write and its answer take at 1200 baud (0.25 s on the wire)"),
    ("gripper: {baudrate: 9600}\n", "field 'watchdog.gripper_timeout' is 0.1 s, not longer "
     "than one unanswered request (field 'gripper.request_timeout', 0.05 s) and then 2 of the "
     "gripper's reads (0.0583333 s each), so the watchdog would stop the run on the first "
     "lost answer: give more than 0.166667 s"),
])
def test_a_gripper_baudrate_too_slow_for_its_timeouts_is_refused(tmp_path, body, words):
    config = tmp_path / "hw.yaml"
    config.write_text(body)
    with pytest.raises(ConfigError, match=re.escape(words)):
        LoadHardwareConfig(config)


def test_a_slow_gripper_baudrate_with_timeouts_to_match_is_taken(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text("gripper: {baudrate: 1200, request_timeout: 0.3}\n"
                      "watchdog: {gripper_timeout: 1.3}\n")
    assert LoadHardwareConfig(config).gripper.baudrate == 1200


def test_a_config_with_such_a_timeout_is_one_line(tmp_path, capfd):
    config = tmp_path / "hw.yaml"
    config.write_text("arm: {lcm_url: 'udpm://239.255.76.67:7667?ttl=0'}\n"
                      "gripper: {port: /dev/null}\ntactile: {port: /dev/zero}\n"
                      "watchdog: {arm_timeout: 1.0e-9}\n")
    code, text = run_cli(["hardware", "--config", str(config)], capfd)
    assert_one_line_error(code, text, "field 'watchdog.arm_timeout' must lie in (0.02, 10] s")


# Rule: every number of a hardware config has a declared range whose ends its device's timing
# gives (a staleness timeout below the myRIO's frame period, a ready timeout below the
# 2F-85's activation, a watchdog timeout below two of a device's updates cannot work), with
# the reason said, checked at load and where MakeHardwareStation is handed a config.
def test_every_hardware_config_number_declares_a_range_with_its_reason():
    import dataclasses
    import typing

    from tegrasp_drake.rig.ranges import range_of
    missing = []

    def walk(cls, prefix=""):
        hints = typing.get_type_hints(cls)
        for field in dataclasses.fields(cls):
            hint = hints[field.name]
            if dataclasses.is_dataclass(hint):
                walk(hint, f"{prefix}{field.name}.")
            elif hint in (int, float) or typing.get_args(hint) in ((int,), (float,)):
                declared = range_of(field)
                if (declared is None or declared.low is None or declared.high is None
                        or not (declared.why or declared.below)):
                    missing.append(prefix + field.name)
    walk(HardwareStationConfig)
    assert missing == []


@pytest.mark.parametrize("body, words", [
    ("tactile: {stale_timeout: 1.0e-9}\n",
     "field 'tactile.stale_timeout' must lie in [0.002, 10] s (at least 2 of the myRIO's"),
    ("ready_timeout: 1.0e-300\n",
     "field 'ready_timeout' must lie in [1.13333, 600] s (at least the 2F-85's fastest "
     "activation"),
    ("gripper: {activation_timeout: 0.1}\n", "field 'gripper.activation_timeout' must lie in "
                                             "[1.13333, 60] s"),
    ("gripper: {request_timeout: 1.0e-9}\n", "field 'gripper.request_timeout' must lie in "
                                             "(0.00260417, 10] s"),
    ("gripper: {command_refresh_period: 1.0e-9}\n",
     "field 'gripper.command_refresh_period' must lie in [0.005, 10] s"),
    ("watchdog: {tactile_timeout: 0.001}\n", "field 'watchdog.tactile_timeout' must lie in "
                                             "(0.002, 10] s"),
    ("tactile: {baudrate: 9600}\n", "field 'tactile.baudrate' must lie in [232174, 12000000]"),
    ("tactile: {max_backlog: 100000}\n", "field 'tactile.max_backlog' must lie in [0, 500]"),
])
def test_a_device_timing_no_device_can_meet_is_refused_at_load(tmp_path, body, words):
    config = tmp_path / "hw.yaml"
    config.write_text(body)
    with pytest.raises(ConfigError) as raised:
        LoadHardwareConfig(config)
    assert words in str(raised.value) and "\n" not in str(raised.value), str(raised.value)


@pytest.mark.parametrize("section, field, value, words", [
    ("tactile", "stale_timeout", 1e-9, "field 'tactile.stale_timeout' must lie in [0.002"),
    (None, "ready_timeout", 1e-300, "field 'ready_timeout' must lie in [1.13333"),
    ("gripper", "baudrate", 9600, "field 'watchdog.gripper_timeout' is 0.1 s, not longer"),
])
def test_a_device_timing_set_after_loading_is_refused_by_the_builder(section, field, value,
                                                                     words):
    from tegrasp_drake import MakeHardwareStation
    config = HardwareStationConfig()
    setattr(getattr(config, section) if section else config, field, value)
    with pytest.raises(ConfigError) as raised:
        MakeHardwareStation(config)
    assert str(raised.value).startswith("MakeHardwareStation: config: " + words), \
        str(raised.value)


# Rule: a serial port field naming something that is not a terminal device (a folder, a
# file, /dev/null, which takes every command and never answers) is refused when the config
# is checked, naming the field and the path, before any device is waited for; a
# pseudo-terminal (the emulators' /dev/pts/N) and a port not there yet are taken.
@pytest.mark.parametrize("field", ["gripper.port", "tactile.port"])
@pytest.mark.parametrize("port, words", [
    ("/tmp", "/tmp is a folder, not a serial device"),
    ("/etc/passwd", "/etc/passwd is a file, not a serial device"),
    ("/dev/null", "/dev/null is a character device but not a terminal"),
])
def test_a_serial_port_that_is_no_terminal_is_refused_naming_the_field(
        tmp_path, capfd, field, port, words):
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", str(config), "--config-set",
                          f"{field}={port}", "--log", str(tmp_path / "run.lcmlog")], capfd)
    assert code == 1
    assert_one_line_error(code, text, f"field '{field}': {words}", "give the device's serial port")


def test_a_pseudo_terminal_and_a_port_not_there_yet_are_taken(tmp_path):
    master, slave, port = open_raw_pty()
    try:
        config = LoadHardwareConfig(_written_default_config(tmp_path), overrides=[
            f"gripper.port={port}", "tactile.port=/dev/ttyACM-not-plugged-in"])
    finally:
        os.close(master), os.close(slave)
    assert config.gripper.port == port


def _written_default_config(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    return config


# Rule: a text field (a port, a file name, a name) holding a control character is refused at
# load naming the field, in files, --config-set/--set and the Python API alike: a NUL would
# reach the operating system's path functions as a ValueError (exit 70).
@pytest.mark.parametrize("body, field", [
    ('gripper: {port: "/dev/pts/\\0"}\n', "gripper.port"),
    ('tactile: {port: "/dev/x\\0"}\n', "tactile.port"),
    ('tactile: {calibration_file: "/tmp/x\\0y"}\n', "tactile.calibration_file"),
    ('tactile: {port: "/dev/x\\e[2J"}\n', "tactile.port"),
])
def test_a_control_character_in_a_hardware_config_is_refused_naming_the_field(
        tmp_path, body, field):
    path = tmp_path / "hw.yaml"
    path.write_text(body)
    message = refusal(lambda: LoadHardwareConfig(path), str(path), f"field '{field}' holds",
                      "printable characters only")
    assert "\x00" not in message and "\x1b" not in message


def _hardware_with_config_set(tmp_path, capfd, assignment):
    """(config path, exit code, output) of `tegrasp hardware` on the default config with one
    --config-set."""
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", str(config), "--config-set", assignment,
                          "--log", str(tmp_path / "run.lcmlog")], capfd)
    return config, code, text


def test_a_nul_in_a_config_set_port_is_bad_input(tmp_path, capfd):
    _, code, text = _hardware_with_config_set(tmp_path, capfd, 'tactile.port="/dev/x\\0"')
    assert_one_line_error(code, text, "field 'tactile.port' holds a NUL")
    assert code == 1


@pytest.mark.parametrize("assignment, words", [
    ("ready_timeout=-5", "field 'ready_timeout' must lie in [1.13333, 600] s"),
    ("watchdog.arm_timeout=0", "field 'watchdog.arm_timeout' must lie in (0.02, 10] s"),
    ("tactile.max_backlog=many", "field 'tactile.max_backlog'"),
])
def test_a_config_set_value_wrong_for_its_field_is_named_as_the_option(tmp_path, capfd,
                                                                       assignment, words):
    config, code, text = _hardware_with_config_set(tmp_path, capfd, assignment)
    assert_one_line_error(code, text, f"{config} --config-set {assignment}: {words}")
    assert code == 1


def test_a_config_set_value_that_is_not_yaml_is_named_as_the_option(tmp_path, capfd):
    _, code, text = _hardware_with_config_set(tmp_path, capfd, "tactile.port=[unclosed")
    assert_one_line_error(code, text, "--config-set 'tactile.port=[unclosed': not valid YAML",
                          "e.g. tactile.port='a: b'")


def test_a_nul_in_a_port_set_from_python_is_refused_by_the_builder():
    from tegrasp_drake.hardware.station import MakeHardwareStation
    config = HardwareStationConfig()
    config.gripper.port = "/dev/pts/\0"
    with pytest.raises(ConfigError) as refused:  # before any device is opened
        MakeHardwareStation(config)
    assert "argument 'config': field 'gripper.port' holds a NUL" in str(refused.value)


# Rule: a file a field names may be any file the user can read (the hardware command may run
# with privileges): one that is no calibration is refused by what it is and its size, never
# by its content (a first line, a key, a token of a YAML error).
@pytest.mark.parametrize("content, words", [
    ("root:$6$secretsalt$secrethash:20228:0:99999:7:::\ndaemon:*:20228::::::\n",
     "2 of its 2 top-level keys are not one of"),
    ("secret words on a line\nmore secret words\n", "got text of"),
    ("- secret\n- words\n", "got a list of 2 items"),
    ("secret: [unclosed\n", "are refused as YAML"),
    ("secret: 1\nsecret: 2\n", "are refused as YAML"),
])
def test_a_file_that_is_no_calibration_is_refused_without_its_content(tmp_path, capfd, content,
                                                                        words):
    (tmp_path / "private").write_text(content)
    message = refusal(lambda: LoadTactileCalibration(tmp_path / "private"), words)
    assert "secret" not in message.replace(str(tmp_path), ""), message
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", str(config), "--config-set",
                          f"tactile.calibration_file={tmp_path / 'private'}",
                          "--log", str(tmp_path / "run.lcmlog")], capfd)
    assert_one_line_error(code, text, "field 'tactile.calibration_file'", words)
    assert code == 1 and "secret" not in text.replace(str(tmp_path), "")


@pytest.mark.parametrize("content, where", [
    ("left:\n  gain: [1.0e-3]\n  offset: [unclosed\n", "line 4, column 1"),
    ("left: {}\nright: {}\nleft: {}\n", "line 3, column 1"),
])
def test_a_calibration_that_is_not_yaml_is_refused_saying_where_without_its_content(
        tmp_path, content, where):
    (tmp_path / "private").write_text(content.replace("left", "secret_left"))
    message = refusal(lambda: LoadTactileCalibration(tmp_path / "private"),
                      f"{tmp_path / 'private'}: {where}: is not a tactile calibration")
    assert "secret" not in message.replace(str(tmp_path), ""), message


@pytest.mark.parametrize("field", ["lcm_url", "port"])
def test_a_huge_integer_in_a_hardware_config_text_field_is_named(field):
    config = HardwareStationConfig()
    device = config.arm if field == "lcm_url" else config.tactile
    setattr(device, field, 10 ** 5000)
    with pytest.raises(ConfigError, match=rf"api: field '\w+\.{field}' must be a string, got "
                                          r"int <an integer of 5001 digits>"):
        validate_hardware_config(config, "api")


@pytest.mark.parametrize("absent", ["gripper", "tactile"])
def test_a_serial_device_not_plugged_in_names_its_config_field(absent, tmp_path, capfd):
    """One line: the config file's field, the port, the OS's reason once, what to do; exit 1
    (a device that did not come up). Either serial device, the other on a line that is there."""
    master, slave, there = open_raw_pty()
    try:
        ports = {"gripper": there, "tactile": there}
        ports[absent] = "/dev/ttyNOPE"
        config = tmp_path / "hw.yaml"
        config.write_text("".join(f"{device}: {{port: {port}}}\n"
                                  for device, port in ports.items()))
        code, text = run_cli(["hardware", "--config", str(config), "--controller", "heuristic",
                              "--log", str(tmp_path / "run.lcmlog"), "--duration", "0.5"],
                             capfd)
    finally:
        os.close(master)
        os.close(slave)
    assert code == 1, text
    error = [line for line in text.splitlines() if "error" in line]
    assert len(error) == 1 and "Traceback" not in text, text
    assert error[0] == (f"tegrasp: error: {config}: field '{absent}.port' '/dev/ttyNOPE': No "
                        f"such file or directory: plug in the "
                        + ("Robotiq 2F-85's USB-RS485 adapter" if absent == "gripper"
                           else "myRIO's serial line")
                        + f", or give its port in {absent}.port; `tegrasp emulate all "
                        "--write-config FILE` writes a config of emulated devices to try "
                        "without hardware"), text
    assert "Errno" not in text, text


@pytest.mark.parametrize("existing", ["", "runs"])
def test_a_refused_hardware_run_leaves_no_folder_it_made_for_its_log(existing, tmp_path, capfd):
    """--log deep/a/b/run.lcmlog refused (a device not plugged in): the folders made for the
    log are removed again; one that was there before stays."""
    config = tmp_path / "hw.yaml"
    config.write_text("gripper: {port: /dev/ttyNOPE}\ntactile: {port: /dev/ttyNOPE2}\n")
    base = tmp_path / "out"
    if existing:
        (base / existing).mkdir(parents=True)
    log = base / (existing or "deep") / "a" / "b" / "run.lcmlog"
    code, text = run_cli(["hardware", "--config", str(config), "--controller", "heuristic",
                          "--log", str(log), "--duration", "0.5"], capfd)
    assert code == 1 and "field 'gripper.port' '/dev/ttyNOPE'" in text, text
    left = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_dir())
    assert left == (["out", "out/runs"] if existing else []), left


# Rule: a file's top-level tag is its class's own or none: another (a typo, a config of another
# kind) is refused, not dropped without a word.
def test_a_hardware_config_or_calibration_tagged_as_another_class_is_refused(tmp_path):
    path = tmp_path / "hw.yaml"
    path.write_text("!SweepSpec\narm: {lcm_url: 'udpm://239.255.76.67:7667?ttl=0'}\n")
    refusal(lambda: LoadHardwareConfig(path), f"{path}: the file is tagged !SweepSpec, but it "
            "is read as a HardwareStationConfig; tag it !HardwareStationConfig or remove")
    path.write_text("!HardwareStationConfig\narm: {lcm_url: 'udpm://239.255.76.67:7667?ttl=0'}\n")
    assert LoadHardwareConfig(path).arm.lcm_url == "udpm://239.255.76.67:7667?ttl=0"
    calibration = tmp_path / "pads.yaml"
    calibration.write_text("!Calibration\nzero_samples: 100\n")
    refusal(lambda: LoadTactileCalibration(str(calibration)), "the file is tagged !Calibration, "
            "but it is read as a TactileCalibration")
    calibration.write_text("!TactileCalibration\nzero_samples: 100\n")
    assert LoadTactileCalibration(str(calibration)).zero_samples == 100
