"""`tegrasp hardware` keeps an earlier run's output whole: one run at a time per --log, a
disk too full for a log refused before the devices come up, a failed run's files kept beside
(not over) the earlier run's, a log removed mid-run reported as a fault with the result still
written; and one run at a time per serial device."""

import json
import os

import pytest

from tegrasp_drake import cli
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.runs import hardware_run
from tests.runs.earlier_hardware_run import EARLIER_LOG, EARLIER_RESULT


@pytest.fixture
def earlier_run(tmp_path, monkeypatch):
    """A hardware config (devices that are not there) and an earlier run's log and result."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "run.lcmlog").write_bytes(EARLIER_LOG)
    (tmp_path / "run.result.json").write_text(EARLIER_RESULT)
    return tmp_path


HARDWARE_TO = ["hardware", "--config", "hw.yaml", "--config-set", "scheduling=normal",
               "--controller", "heuristic", "--overwrite", "--log"]
HARDWARE = HARDWARE_TO + ["run.lcmlog"]


def ended_run(staged_bytes=b"this run's log", *, log_fault=None, remove=None):
    """A run_on_hardware standing in for the devices: it writes `staged_bytes` to the log it is
    given (or removes `remove` as a user would mid-run) and ends with `log_fault`."""
    def run(scenario, *, log_path, **kwargs):
        if staged_bytes is not None:
            log_path.write_bytes(staged_bytes)
        if remove is not None:
            import shutil
            shutil.rmtree(remove)
        return hardware_run.HardwareRunResult(
            transitions=[], faults=(), sim_time=1.0, wall_time=1.0, log_path=log_path,
            log_messages=0, device_counters={}, log_fault=log_fault)
    return run


def test_a_second_run_on_a_log_another_run_writes_is_refused(earlier_run):
    from tegrasp_drake.rig.files import held_file
    with held_file(earlier_run / "run.lcmlog"):  # the first run
        with pytest.raises(SystemExit) as refused:
            cli.main(HARDWARE)
    message = str(refused.value.code)
    assert "another tegrasp hardware run is writing it" in message and "\n" not in message
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG


def disk_with_free_bytes(monkeypatch, free: int):
    """The free-space probe (rig.files.free_bytes's shutil.disk_usage) reporting `free`."""
    import shutil
    import types
    monkeypatch.setattr(shutil, "disk_usage", lambda path: types.SimpleNamespace(
        total=10**12, used=10**12 - free, free=free))


def test_a_log_on_a_disk_too_full_for_it_is_refused_before_the_devices(earlier_run,
                                                                       monkeypatch):
    disk_with_free_bytes(monkeypatch, 40_960)
    monkeypatch.setattr(hardware_run, "run_on_hardware", lambda *a, **k: pytest.fail(
        "the devices came up"))
    with pytest.raises(SystemExit) as refused:
        cli.main(HARDWARE)
    assert "40 kB free" in str(refused.value.code) and "1 MB" in str(refused.value.code)
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG


def test_a_failed_run_keeps_the_earlier_runs_log_and_result(earlier_run, monkeypatch, capfd):
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run(
        log_fault="the LCM log stopped: the disk holding it has less than 1 MB free"))
    assert cli.main(HARDWARE) == 2
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG
    assert (earlier_run / "run.result.json").read_text() == EARLIER_RESULT
    failed = earlier_run / "run.failed.lcmlog"
    assert failed.read_bytes() == b"this run's log"
    result = json.loads((earlier_run / "run.failed.result.json").read_text())
    assert result["log"] == failed.name and result["log_fault"]
    err = capfd.readouterr().err
    assert "run.lcmlog and run.result.json are kept" in err


FAULT = "the LCM log stopped: the disk holding it has less than 1 MB free"


def test_a_failed_run_replaces_the_earlier_failed_runs_pair_and_names_it(earlier_run,
                                                                         monkeypatch, capfd):
    """Failed runs do not pile up beside --log: the newest failed pair replaces the one
    before, which the stderr line names; the run that did not fail stays."""
    (earlier_run / "run.failed.lcmlog").write_bytes(EARLIER_LOG)
    (earlier_run / "run.failed.result.json").write_text(EARLIER_FAILED_RESULT)
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run(log_fault=FAULT))
    assert cli.main(HARDWARE) == 2
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG
    assert (earlier_run / "run.failed.lcmlog").read_bytes() == b"this run's log"
    assert sorted(path.name for path in earlier_run.iterdir()) == [
        "hw.yaml", "run.failed.lcmlog", "run.failed.result.json", "run.lcmlog",
        "run.result.json"]
    line = [line for line in capfd.readouterr().err.splitlines() if "the run failed" in line]
    assert len(line) == 1
    assert ("they replace the earlier failed run's run.failed.lcmlog and "
            "run.failed.result.json") in line[0]


EARLIER_FAILED_RESULT = EARLIER_RESULT.replace('"run.lcmlog"', '"run.failed.lcmlog"')


@pytest.mark.parametrize("name, contents, words", [
    ("run.failed.lcmlog", b"my notes\n", "is not an LCM log"),
    ("run.failed.lcmlog", EARLIER_LOG, "is an LCM log of no earlier run"),  # lcm-logger's
    ("run.failed.result.json", b'{"mine": 1}\n', "is not a hardware run's result"),
])
def test_a_users_file_where_a_failed_run_would_go_is_refused_before_the_devices(
        earlier_run, monkeypatch, name, contents, words):
    """--overwrite replaces there only an earlier failed run's pair: a file of the user's
    there is refused before the devices come up, naming it, and kept."""
    (earlier_run / name).write_bytes(contents)
    monkeypatch.setattr(hardware_run, "run_on_hardware", lambda *a, **k: pytest.fail(
        "the devices came up"))
    with pytest.raises(SystemExit) as refused:
        cli.main(HARDWARE)
    message = str(refused.value.code)
    assert "\n" not in message and f"--log run.lcmlog: {name}, where a run that fails" in message
    assert words in message and "move it away, or give another --log" in message, message
    assert (earlier_run / name).read_bytes() == contents
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG


def test_failed_runs_of_an_earlier_version_are_left_and_said(earlier_run, monkeypatch,
                                                              capfd):
    older = [earlier_run / f"run.failed-{pid}.lcmlog" for pid in (4242, 4243)]
    for path in older:
        path.write_bytes(b"an earlier version's failed run")
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run(log_fault=FAULT))
    assert cli.main(HARDWARE) == 2
    assert all(path.read_bytes() == b"an earlier version's failed run" for path in older)
    err = capfd.readouterr().err
    assert "2 earlier failed runs kept beside it by an earlier version (run.failed-4242" in err


def test_a_failed_run_of_a_log_without_a_suffix_keeps_the_earlier_result(tmp_path,
                                                                          monkeypatch):
    """LOG.failed's result would be named as LOG's own (the stem is LOG): it gets .lcmlog."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "run").write_bytes(EARLIER_LOG)
    earlier_result = EARLIER_RESULT.replace('"run.lcmlog"', '"run"')  # the run's log: run
    (tmp_path / "run.result.json").write_text(earlier_result)
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run(log_fault=FAULT))
    assert cli.main(HARDWARE_TO + ["run"]) == 2
    assert (tmp_path / "run.result.json").read_text() == earlier_result
    assert (tmp_path / "run.failed.lcmlog").read_bytes() == b"this run's log"
    assert (tmp_path / "run.failed.result.json").exists()


def test_a_folder_where_a_failed_run_would_go_is_refused_before_the_devices(earlier_run,
                                                                            monkeypatch):
    (earlier_run / "run.failed.lcmlog").mkdir()
    monkeypatch.setattr(hardware_run, "run_on_hardware", lambda *a, **k: pytest.fail(
        "the devices came up"))
    with pytest.raises(SystemExit) as refused:
        cli.main(HARDWARE)
    assert "run.failed.lcmlog" in str(refused.value.code)
    assert "\n" not in str(refused.value.code)


def test_a_run_that_ends_well_replaces_the_earlier_runs_log_and_result(earlier_run,
                                                                       monkeypatch):
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run())
    assert cli.main(HARDWARE) == 0
    assert (earlier_run / "run.lcmlog").read_bytes() == b"this run's log"
    assert json.loads((earlier_run / "run.result.json").read_text())["log"] == "run.lcmlog"
    assert not list(earlier_run.glob(".*"))  # no lock or staging file left


def test_a_log_folder_removed_mid_run_is_a_fault_and_the_result_is_still_written(
        earlier_run, monkeypatch, capfd):
    (earlier_run / "logs").mkdir()
    monkeypatch.setattr(hardware_run, "run_on_hardware", ended_run(
        None, remove=earlier_run / "logs",
        log_fault="the LCM log stopped: it was removed during the run"))
    code = cli.main(HARDWARE_TO + ["logs/run.lcmlog"])
    captured = capfd.readouterr()
    assert code == 2, captured
    result = json.loads((earlier_run / "logs" / "run.result.json").read_text())
    assert result["log"] is None and "removed" in result["log_fault"]
    assert "no log" in captured.out and "removed during the run" in captured.err


def test_a_serial_port_another_run_reads_cannot_be_opened_by_a_second(tmp_path):
    import serial
    from tegrasp_drake.emulators.null_modem import open_raw_pty
    from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
    from tegrasp_drake.hardware.station import serial_port_in_use
    master, slave, port = open_raw_pty()
    try:
        assert not serial_port_in_use(port)
        with TactileSerialReader(port):  # the first run's
            assert serial_port_in_use(port)
            with pytest.raises(serial.SerialException):
                TactileSerialReader(port).start()
        assert not serial_port_in_use(port)
    finally:
        os.close(master)
        os.close(slave)


@pytest.mark.parametrize("text, code", [("14@3", 14), ("0x0E@3", 14), ("0X0e@3", 14)])
def test_an_injected_fault_code_is_hexadecimal_with_0x_or_decimal(text, code):
    from tegrasp_drake.commands.emulate import _parse_fault
    assert _parse_fault(text).code == code


@pytest.mark.parametrize("text", ["0b1110@3", "0o16@3", "1_4@3"])
def test_an_injected_fault_code_in_another_notation_is_refused_naming_both(text):
    import argparse
    from tegrasp_drake.commands.emulate import fault_option
    with pytest.raises(argparse.ArgumentTypeError) as refused:
        fault_option(text)
    assert "hexadecimal with 0x or decimal" in str(refused.value)


def test_another_controllers_arm_commands_are_heard_before_a_run():
    import threading
    import time
    import lcm
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL
    from tegrasp_drake.runs.hardware_run import arm_commands_heard
    url = f"udpm://239.255.76.122:{7722 + os.getpid() % 50}?ttl=0"  # loopback only
    assert arm_commands_heard(url) == 0
    stop = threading.Event()

    def other_controller():  # publishes at the JACO2 driver's 100 Hz
        bus = lcm.LCM(url)
        while not stop.is_set():
            bus.publish(JACO_COMMAND_CHANNEL, b"a command")
            time.sleep(0.01)
    thread = threading.Thread(target=other_controller, daemon=True)
    thread.start()
    try:
        assert arm_commands_heard(url) > 0
    finally:
        stop.set()
        thread.join()


def broken_off_run(staged_bytes: bytes):
    """A run_on_hardware that records `staged_bytes` (an LCM log's start) and is then
    interrupted, as by Ctrl-C."""
    def run(scenario, *, log_path, **kwargs):
        log_path.write_bytes(staged_bytes)
        raise KeyboardInterrupt
    return run


# Rule: a run that breaks off keeps what its log recorded as LOG.incomplete.lcmlog, the newest
# such run's only (as the failed pair): the next one replaces it and says so, so that they
# do not pile up; the earlier run's LOG and result stay, and a completed run's log under that
# name (its result beside it) is never replaced.
def test_only_the_newest_unfinished_runs_log_is_kept_and_the_replaced_one_named(
        earlier_run, monkeypatch, capfd):
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    for k in (1, 2):
        monkeypatch.setattr(hardware_run, "run_on_hardware",
                            broken_off_run(LCM_LOG_START + b"run %d" % k))
        assert cli.main(HARDWARE) == 130
        said = capfd.readouterr().err
        kept = earlier_run / "run.incomplete.lcmlog"
        assert f"what its log recorded is in {kept.name}" in said, said
        assert ("replaces the earlier unfinished run's log" in said) == (k == 2), said
    assert kept.read_bytes() == LCM_LOG_START + b"run 2"
    assert sorted(path.name for path in earlier_run.iterdir()) == [
        "hw.yaml", "run.incomplete.lcmlog", "run.lcmlog", "run.result.json"]
    assert (earlier_run / "run.lcmlog").read_bytes() == EARLIER_LOG


def test_a_completed_log_named_as_an_unfinished_ones_is_never_replaced(earlier_run,
                                                                      monkeypatch, capfd):
    from tegrasp_drake.runs.hardware_log_reader import LCM_LOG_START
    completed = earlier_run / "run.incomplete.lcmlog"  # a user's --log, with its result
    completed.write_bytes(LCM_LOG_START + b"a completed run")
    (earlier_run / "run.incomplete.result.json").write_text('{"completed": true}\n')
    monkeypatch.setattr(hardware_run, "run_on_hardware",
                        broken_off_run(LCM_LOG_START + b"half a run"))
    assert cli.main(HARDWARE) == 130
    said = capfd.readouterr().err
    assert completed.read_bytes() == LCM_LOG_START + b"a completed run"
    kept = earlier_run / f"run.incomplete-{os.getpid()}.lcmlog"
    assert kept.read_bytes() == LCM_LOG_START + b"half a run" and kept.name in said, said
