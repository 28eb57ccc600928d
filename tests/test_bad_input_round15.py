"""Bad inputs the fifteenth review found, one test per rule."""

import sys

import pytest

from tegrasp_drake import cli


# Rule: a setting a command cannot use stops it before it does any work. `--scheduler` is
# checked whole (its address, the Dask extra, whether the scheduler answers) by the runner
# arguments' check that sweep, transfer and sensitivity share, so transfer and sensitivity
# refuse it before recording any world's events, as sweep refuses it before any trial.
@pytest.mark.parametrize("command, spec", [
    ("transfer", "analysis/transfer_matrix.yaml"),
    ("sensitivity", "analysis/sensitivity.yaml"),
])
@pytest.mark.parametrize("cause, words", [("no extra", "tegrasp-drake[dask]"),
                                          ("no answer", "cannot reach the Dask scheduler")])
def test_a_scheduler_that_cannot_work_is_refused_before_any_event_is_recorded(
        tmp_path, monkeypatch, capsys, command, spec, cause, words):
    from tegrasp_drake.sweep import runner
    from tegrasp_drake.transfer import matrix

    def no_recording(*args, **kwargs):
        raise AssertionError("events recorded before --scheduler was checked")

    monkeypatch.setattr(matrix, "record_world_events", no_recording)
    if cause == "no extra":
        monkeypatch.setitem(sys.modules, "distributed", None)  # as if it were not installed
    else:
        pytest.importorskip("distributed", reason="the optional 'dask' extra is not installed")
        monkeypatch.setattr(runner, "DASK_CONNECT_TIMEOUT_S", 1.0)
    code = cli.main([command, spec, "--workers", "1", "--no-progress",
                     "--scheduler", "tcp://127.0.0.1:1", "--out", str(tmp_path / "out")])
    error = capsys.readouterr().err
    assert code == 1, error  # an option's value: bad input
    assert error.count("\n") == 1 and words in error, error
    assert not (tmp_path / "out").exists()


# Rule: a Modbus request whose quantity is outside its function's range, or whose byte count
# contradicts its quantity, gets the exception response the protocol prescribes (Modbus
# Application Protocol V1.1b3, 6.4 and 6.12: function | 0x80, exception code 03), from the
# emulated 2F-85's request framer, over its pseudo-terminal as a driver sees it; not a reply
# of "function 0", not silence. A valid request after them is still answered.
def _crc(body: bytes) -> bytes:
    from pymodbus.framer.rtu import FramerRTU
    return body + FramerRTU.compute_CRC(body).to_bytes(2, "big")


def _reply(port_fd: int, request: bytes, timeout_s: float = 2.0) -> bytes:
    import os
    import select
    import time
    os.write(port_fd, request)
    reply, end = b"", time.monotonic() + timeout_s
    while time.monotonic() < end:
        ready, _, _ = select.select([port_fd], [], [], 0.1)
        if ready:
            reply += os.read(port_fd, 256)
        elif reply:  # a pause after bytes: the reply is whole
            break
    return reply


@pytest.mark.parametrize("request_body", [
    bytes([9, 4, 0x07, 0xD0, 0x7F, 0xFF]),               # read 0x7FFF input registers
    bytes([9, 4, 0x07, 0xD0, 0, 0]),                     # read 0 input registers
    bytes([9, 4, 0x07, 0xD0, 0, 0x7E]),                  # read 0x7E: one past the most
    bytes([9, 16, 0x03, 0xE8, 0, 0, 0]),                 # write 0 registers
    bytes([9, 16, 0x03, 0xE8, 0, 3, 4, 9, 0, 0, 255]),   # 3 registers in 4 bytes
])
def test_a_request_with_a_quantity_out_of_range_gets_exception_03(request_body):
    import os
    import tty
    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator
    with RobotiqEmulator() as emulator:
        fd = os.open(emulator.port, os.O_RDWR | os.O_NOCTTY)
        try:
            tty.setraw(fd)
            function = request_body[1]
            assert _reply(fd, _crc(request_body)) == _crc(bytes([9, function | 0x80, 0x03]))
            status = _reply(fd, _crc(bytes([9, 4, 0x07, 0xD0, 0, 3])))
            assert status[:3] == bytes([9, 4, 6]), status.hex()
        finally:
            os.close(fd)


# Rule: an event file holds its fields and nothing else: an unknown key in it or in its
# `samples` (a forged extra channel) is refused naming the key, as a duplicate channel or a
# window of the wrong length is, rather than ignored.
@pytest.mark.parametrize("where, key, words", [
    ("samples", "extra", "field 'samples.extra' is not a channel"),
    ("file", "sa_rate", "field 'sa_rate' is not a field of an event file"),
])
def test_an_event_file_with_an_unknown_key_is_refused_naming_it(tmp_path, where, key, words):
    import json
    import shutil
    from tegrasp_drake.events.event_file import MemorizedEventError, read_memorized_event
    path = tmp_path / "reach_load.json"
    shutil.copy("events/box/reach_load.json", path)
    data = json.loads(path.read_text())
    (data["samples"] if where == "samples" else data)[key] = [0.0, 0.0, 0.0]
    path.write_text(json.dumps(data))
    with pytest.raises(MemorizedEventError) as refused:
        read_memorized_event(path)
    message = str(refused.value)
    assert "\n" not in message and str(path) in message and words in message, message


def test_every_committed_event_file_still_loads():
    import pathlib
    from tegrasp_drake.events.event_file import read_memorized_event
    files = [path for path in pathlib.Path("events").glob("**/*.json")
             if path.name != "index.json"]
    assert len(files) >= 40
    for path in files:
        assert read_memorized_event(path).object_name == path.parent.name


# Rule: one path rule for an output file: what --overwrite could never replace (a device, a
# folder) is refused as such first; only a regular file is said to hold an earlier run.
def test_a_device_as_the_hardware_log_is_refused_as_a_device(tmp_path, monkeypatch, capfd):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    from tests.test_bad_input import run_cli
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "/dev/null"], capfd)
    assert code == 1 and "\n" not in text.strip(), text
    assert "--log /dev/null is a device, not a file" in text and "overwrite" not in text, text


# Rule: a command that talks over LCM to another process (the emulators to `tegrasp
# hardware`, `tegrasp hardware` to the arm's driver) refuses a bus that exists inside one
# process (memq://) in one line, before it starts anything; library code may still run both
# ends in one process on it.
@pytest.mark.parametrize("argv, words", [
    (["emulate", "jaco", "--lcm-url", "memq://", "--scheduling", "normal"],
     ["--lcm-url 'memq://'", "no other process can reach"]),
    (["hardware", "--config", "hw.yaml", "--config-set", "arm.lcm_url=memq://"],
     ["hw.yaml: field 'arm.lcm_url'", "no other process can reach"]),
])
def test_an_in_process_lcm_bus_is_refused_by_the_commands(tmp_path, monkeypatch, capfd, argv,
                                                          words):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    from tests.test_bad_input import run_cli
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    code, text = run_cli(argv, capfd)
    assert code == 1 and "\n" not in text.strip(), text
    for word in words:
        assert word in text, text


# Rule: `-v` makes a command log its main steps at INFO through the package's logging, as
# `trial` does: for a sweep (and the sweeps of transfer and sensitivity), what it read from
# --out, what it will run and on what, and what it wrote.
def test_a_verbose_sweep_logs_what_it_read_ran_and_wrote(tmp_path, capfd, caplog):
    from tests.test_bad_input import run_cli
    out = tmp_path / "out"
    code, text = run_cli(["sweep", "-v", "--objects", "box", "--controllers", "heuristic",
                          "--attempts", "1", "--workers", "1", "--out", str(out),
                          "--trial-function", "tests.fake_trials:fake_trial", "--no-progress"],
                         capfd)
    assert code == 0, text
    info = [record.getMessage() for record in caplog.records  # pytest holds the log
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any(f"0 records read from {out}" in line for line in info), info
    assert any("running" in line and "processes:1" in line for line in info), info
    assert any("wrote" in line and str(out) in line for line in info), info


def test_a_verbose_plot_logs_what_it_read_and_wrote(tmp_path, capfd, caplog):
    from tests.test_bad_input import run_cli
    out = tmp_path / "events.png"
    code, text = run_cli(["plot", "events", "-v", "--events", "events", "--out", str(out)],
                         capfd)
    assert code == 0, text
    info = [record.getMessage() for record in caplog.records
            if record.levelname == "INFO" and record.name.startswith("tegrasp_drake")]
    assert any("reading events" in line and str(out) in line for line in info), info
    assert any(f"wrote {out}" in line for line in info), info
