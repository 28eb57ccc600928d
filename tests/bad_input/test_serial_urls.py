"""A device's port given as a pyserial URL is checked at load from its text, as pyserial's
handlers read it (hardware/serial_urls.py): the scheme, the host and port, each query option
and its value; spy://'s log file must never be a user's file, which pyserial would empty
as soon as the port is named."""

import serial
import pytest

from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.rig.typed_yaml import ConfigError
from tests.bad_input.probes import assert_one_line_error, one_line_of, run_cli


def _load(tmp_path, port, field="tactile"):
    config = tmp_path / "hw.yaml"
    config.write_text(f"{field}: {{port: '{port}'}}\n")
    return LoadHardwareConfig(config)


# Rule: a URL pyserial would refuse when the device starts, misread or read past is refused
# at load in one line naming the field, the URL, what is wrong and an example.
@pytest.mark.parametrize("port, words", [
    ("nope://x", "'nope://' is not one; taken: socket://, rfc2217://, loop://, spy://"),
    ("hwgrep://.*", "'hwgrep://' is not one"),
    ("socket://host", "has no port (socket://HOST:PORT)"),
    ("socket://:4001", "has no host"),
    ("socket://host:0", "has the port '0', which is not a number from 1 to 65535"),
    ("socket://host:99999", "has the port '99999', which is not a number from 1 to 65535"),
    ("rfc2217://host:x", "has the port 'x'"),
    ("socket://host:4001/x", "has a path '/x' after the port, which socket:// ignores"),
    ("socket://host:4001?logging=loud", "logging must be one of debug, info, warning, error"),
    ("socket://host:4001?nodelay", "has the option 'nodelay', which pyserial's socket:// "
                                   "does not take (it takes logging"),
    ("rfc2217://host:2217?timeout=nan", "timeout must be a number of seconds above 0"),
    ("rfc2217://host:2217?timeout=-1", "timeout must be a number of seconds above 0"),
    ("rfc2217://host:2217?poll_modem=no", "poll_modem takes no value"),
    ("rfc2217://host:2217?timeout=1&timeout=2", "gives the option timeout twice"),
    ("loop://?x", "has the option 'x', which pyserial's loop:// does not take"),
    ("loop://device", "has 'device' before its options, which loop:// ignores"),
    ("spy://", "names no device for spy:// to wrap"),
    ("spy://loop://", "spy:// wraps a device's path, not another URL"),
    ("spy:///dev/ttyUSB7?dev=/dev/pts/3", "has the option 'dev'"),
])
def test_a_pyserial_url_pyserial_would_not_read_as_written_is_refused(tmp_path, port, words):
    with pytest.raises(ConfigError) as refused:
        _load(tmp_path, port)
    message = str(refused.value)
    assert "\n" not in message and f"field 'tactile.port': {port} " in message, message
    assert words in message, message
    assert "e.g. " in message, message


@pytest.mark.parametrize("port", ["socket://192.168.1.30:4001", "socket://[::1]:4001",
                                  "socket://gripper.local:4001?logging=debug",
                                  "rfc2217://192.168.1.30:2217?timeout=2.5&poll_modem",
                                  "loop://", "loop://?logging=info", "spy:///dev/ttyUSB7?raw",
                                  "spy:///dev/ttyUSB7?file=/dev/null&color"])
def test_a_pyserial_url_pyserial_reads_as_written_is_taken(tmp_path, port):
    assert _load(tmp_path, port, "gripper").gripper.port == port


# Rule: spy://'s file= is opened for writing (emptied) by pyserial as soon as the port is
# named, before it is opened; so only a new file, an empty file, an earlier spy log or a
# character device is taken, and a user's file is refused and left whole.
def test_pyserial_empties_the_spy_file_when_the_port_is_only_named(tmp_path):
    kept = tmp_path / "notes.txt"
    kept.write_text("a user's notes\n")
    port = serial.serial_for_url(f"spy:///dev/ttyUSB7?file={kept}", do_not_open=True)
    port.formatter.output.close()  # pyserial never closes it
    assert kept.read_text() == ""  # what the check below protects against


def test_a_spy_file_that_is_a_users_file_is_refused_and_left_whole(tmp_path):
    kept = tmp_path / "notes.txt"
    kept.write_text("a user's notes\n")
    with pytest.raises(ConfigError, match="is a file that is not an earlier spy log: pyserial "
                                          "would empty it; give a new file's path"):
        _load(tmp_path, f"spy:///dev/ttyUSB7?file={kept}")
    assert kept.read_text() == "a user's notes\n"


@pytest.mark.parametrize("existing", [None, "", "000000.000 TX   0000  09 03 07 D0\n"],
                         ids=["new", "empty", "earlier-spy-log"])
def test_a_spy_file_that_is_new_empty_or_an_earlier_log_is_taken(tmp_path, existing):
    log = tmp_path / "spy.log"
    if existing is not None:
        log.write_text(existing)
    assert _load(tmp_path, f"spy:///dev/ttyUSB7?file={log}").tactile.port.endswith("spy.log")


def test_a_spy_file_in_no_folder_or_a_folder_is_refused(tmp_path):
    with pytest.raises(ConfigError, match="which is not a folder"):
        _load(tmp_path, f"spy:///dev/ttyUSB7?file={tmp_path}/none/spy.log")
    with pytest.raises(ConfigError, match="is a folder: give a file's path"):
        _load(tmp_path, f"spy:///dev/ttyUSB7?file={tmp_path}")


@pytest.mark.parametrize("gripper_port, roles", [
    ("spy:///dev/ttyUSB8?file={folder}/./spy.log", "the spy log file of each"),
    ("{folder}/spy.log", "the tactile port's spy log file, the gripper port's device"),
], ids=["two-spy-urls", "spy-file-on-the-other-port"])
def test_two_ports_naming_one_file_are_refused_naming_both_fields(tmp_path, capfd,
                                                                  gripper_port, roles):
    config = tmp_path / "hw.yaml"
    tactile = f"spy:///dev/ttyUSB7?file={tmp_path}/spy.log"
    gripper = gripper_port.format(folder=tmp_path)
    config.write_text(f"tactile: {{port: '{tactile}'}}\ngripper: {{port: '{gripper}'}}\n")
    with pytest.raises(ConfigError) as refused:
        LoadHardwareConfig(config)
    text = one_line_of(refused.value)
    assert text.startswith(f"{config}: fields 'tactile.port' ("), text
    assert "and 'gripper.port' (" in text and f"({roles}); each port needs its own: give one " \
        "of them another file" in text, text
    code, text = run_cli(["hardware", "--config", str(config)], capfd)
    assert_one_line_error(code, text, str(config), "'tactile.port'", "'gripper.port'",
                          "both name")
    assert not (tmp_path / "spy.log").exists()


def test_two_spy_urls_logging_to_their_own_files_are_taken(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text(f"tactile: {{port: 'spy:///dev/ttyUSB7?file={tmp_path}/a.log'}}\n"
                      f"gripper: {{port: 'spy:///dev/ttyUSB8?file={tmp_path}/b.log'}}\n")
    assert LoadHardwareConfig(config).gripper.port.endswith("b.log")


def test_a_spy_url_on_the_other_devices_line_is_one_serial_line(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text("tactile: {port: 'spy:///dev/ttyUSB0?raw'}\ngripper: {port: /dev/ttyUSB0}\n")
    with pytest.raises(ConfigError, match="are one serial line"):
        LoadHardwareConfig(config)


# Rule: only a plain path (or the device spy:// wraps) is looked for as a device file before
# the devices start; loop://, socket:// and rfc2217:// open no file, and go to pyserial.
@pytest.mark.parametrize("port", ["loop://", "socket://192.168.1.30:4001",
                                  "rfc2217://192.168.1.30:2217?timeout=2.5"])
def test_a_pyserial_url_is_not_looked_for_as_a_device_file(tmp_path, port):
    from tegrasp_drake.hardware.config import HardwareStationConfig
    from tegrasp_drake.hardware.station import absent_device_problem, serial_port_in_use
    config = HardwareStationConfig()
    config.gripper.port = port
    config.tactile.port = str(tmp_path / "ttyACM9")
    problem = absent_device_problem(config)
    assert problem is not None and problem.startswith("field 'tactile.port'"), problem
    assert not serial_port_in_use(port)


def test_a_spy_url_wrapping_a_device_not_there_names_that_device(tmp_path, monkeypatch):
    from tegrasp_drake.hardware.config import HardwareStationConfig
    from tegrasp_drake.hardware.station import absent_device_problem
    monkeypatch.chdir(tmp_path)  # a short port name: a message cuts one over 80 characters
    config = HardwareStationConfig()
    config.gripper.port = "spy://./ttyUSB9?raw"
    problem = absent_device_problem(config)
    assert problem.startswith("field 'gripper.port' 'spy://./ttyUSB9?raw' (the device it "
                              "wraps, './ttyUSB9'): No such file"), problem
