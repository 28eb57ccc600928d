"""A hardware run's LCM log read by `tegrasp replay`: every channel the reader decodes is
checked on its own. A TEGRASP_FAULT the station never reports (a device or kind it has not,
a code no such fault carries, a description that is no line of words, a time before the run
or "since" after the report), a TEGRASP_GRIPPER with registers outside the 2F-85's bytes or
a status arrival time not finite, a KINOVA_JACO_COMMAND the arm refuses are skipped and
counted as damage (exit code 3); a value echoed from a log is cut and escaped."""

import inspect

import pytest
from drake import lcmt_jaco_command

from tegrasp_drake import cli
from tegrasp_drake.events import save_memorized_events
from tegrasp_drake.hardware.device_log_messages import (FAULT_CHANNEL, GRIPPER_CHANNEL,
                                                        TRANSITION_CHANNEL)
from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL, make_jaco_command
from tegrasp_drake.lcmtypes import (lcmt_tegrasp_fault, lcmt_tegrasp_gripper,
                                    lcmt_tegrasp_transition)
from tegrasp_drake.runs.hardware_log_reader import read_run_log
from tests.bad_input.test_lcm_logs import HOME, ZEROS, forged_transition, write_log
from tests.runs.test_hardware_log_reader import EVENTS

FORGED_AT = 1500  # the tactile tick [ms] after which a forged message is logged
# [chars] a damage line's words besides the echoed values: well under a kilobyte
DAMAGE_LINE_CHARS = 600


def fault(**fields) -> lcmt_tegrasp_fault:
    """A fault as hardware_run.fault_message writes one (the gripper silent, reported at
    1.5 s, when it is logged), with `fields` changed."""
    message = lcmt_tegrasp_fault()
    message.utime, message.since_utime = 1_500_000, 1_400_000
    message.since_wall_utime = 1_796_070_992_580_719
    message.device, message.kind, message.code = "gripper", "silent", -1
    message.description = "no new data for more than 100 ms"
    for name, value in fields.items():
        setattr(message, name, value)
    return message


def gripper(**fields) -> lcmt_tegrasp_gripper:
    """A TEGRASP_GRIPPER as GripperStatusSender writes one (at 1.5 s), `fields` changed."""
    message = lcmt_tegrasp_gripper()
    message.utime, message.status_arrival_s = 1_500_000, 12345.678
    message.command, message.status = [230, 255, 150], [1, 1, 3, 2, 0, 230, 228, 0]
    for name, value in fields.items():
        setattr(message, name, value)
    return message


def command(position=HOME) -> lcmt_jaco_command:
    return make_jaco_command(1_500_000, position, ZEROS)


def _read(tmp_path, channel, message):
    """The log (write_log's run) with `message` forged on `channel` after FORGED_AT, read."""
    return read_run_log(write_log(tmp_path / "run.lcmlog", forged_at=FORGED_AT,
                                  forged=[(channel, message.encode())]))


def _skipped(log, channel, wrong):
    """Checks `log` has one damage line, skipping the one forged message on `channel` for
    `wrong`, no longer than DAMAGE_LINE_CHARS; returns it."""
    assert len(log.damage) == 1, log.damage
    (words,) = log.damage
    assert words.startswith(f"1 message(s) on {channel} {wrong}"), words
    assert words.endswith("; skipped") and len(words) < DAMAGE_LINE_CHARS, words
    return words


def test_a_fault_the_station_reports_is_kept_and_no_damage(tmp_path):
    log = _read(tmp_path, FAULT_CHANNEL, fault())
    assert not log.damage, log.damage
    assert [(f.device, f.kind, f.code) for f in log.faults] == [("gripper", "silent", -1)]
    device = _read(tmp_path, FAULT_CHANNEL, fault(kind="device", code=0x0E,
                                                  description="overcurrent triggered"))
    assert not device.damage and [f.code for f in device.faults] == [0x0E], device.damage


NO_FAULT = "are no fault the station reports (the first: "


# Rule: a TEGRASP_FAULT is hardware_run.fault_message of a DeviceFault: its device, kind and
# code those device_fault and the gFLT register define, its description words on one line,
# its times within the run; any other is skipped and counted, its values echoed cut.
@pytest.mark.parametrize("fields, wrong", [
    (dict(device="toaster"), NO_FAULT + "device 'toaster' is none of arm, gripper, tactile"),
    (dict(device="w" * 100_000), NO_FAULT + "device 'wwwwwwww"),
    (dict(kind="explosion", code=99999), NO_FAULT + "kind 'explosion' is none of silent, "
                                                    "device, driver, implausible"),
    (dict(kind="device", code=99999), NO_FAULT + "a device fault's code 99999 is no fault "
                                                 "code (a gFLT register byte, 1 to 255)"),
    (dict(code=7), NO_FAULT + "a silent fault's code is -1 (none), got 7"),
    (dict(description="z" * 100_000), NO_FAULT + "its description is not one printable line "
                                                 "of at most 1000 characters (words for a "
                                                 "person): got 100000 characters"),
    (dict(description="\x1b]0;pwned\x07\x1b[2J"), NO_FAULT + "its description is not one "
                                                             "printable line of at most 1000 "
                                                             "characters (words for a person)"
                                                             ": got '\\x1b' at character 0"),
    (dict(utime=-5), NO_FAULT + "utime -5 us is before the run's start (Context time 0)"),
    (dict(since_utime=10**15), NO_FAULT + "since 1000000000 s is not between the run's start "
                                          "and the report at 1.5 s"),
    (dict(utime=3_000_000_000, since_utime=0), "lie outside the run's tactile stream's time "
                                               "span"),
    (dict(utime=100_000, since_utime=0), "carry a time more than 1 s from the run's when they "
                                         "were logged (the first: gripper silent at 0.1 s, "
                                         "logged at 1.5 s"),
])
def test_a_fault_the_station_never_reports_is_skipped_and_said(tmp_path, fields, wrong):
    log = _read(tmp_path, FAULT_CHANNEL, fault(**fields))
    assert log.faults == []
    words = _skipped(log, FAULT_CHANNEL, wrong)
    assert "\x1b" not in words and "w" * 100 not in words and "z" * 100 not in words


# Rule: a TEGRASP_GRIPPER holds the 2F-85's register bytes (robotiq.units.BYTE_MAX), a host
# clock's status arrival time and a Context time; any other is skipped and counted.
@pytest.mark.parametrize("fields, wrong", [
    (dict(command=[999, -5, 999], status=[999] * 8),
     "hold registers outside the 2F-85's bytes, 0 to 255 (the first: command (999, -5, 999), "
     "status (999, 999, 999, 999, 999, 999, 999, 999)"),
    (dict(status=[1, 1, 3, 2, 0, 230, 256, 0]), "hold registers outside the 2F-85's bytes"),
    (dict(status_arrival_s=float("nan")), "hold a status arrival time (the host's "
                                          "time.monotonic()) that is not finite or negative "
                                          "(the first: status_arrival_s nan"),
    (dict(status_arrival_s=-1.0), "hold a status arrival time"),
    (dict(utime=-5), "carry a negative time (utime) (the first: utime -5 us"),
])
def test_a_gripper_message_with_impossible_values_is_skipped_and_said(tmp_path, fields, wrong):
    log = _read(tmp_path, GRIPPER_CHANNEL, gripper(**fields))
    assert log.gripper == []
    _skipped(log, GRIPPER_CHANNEL, wrong)


def test_a_gripper_message_of_the_2f85s_bytes_is_kept(tmp_path):
    log = _read(tmp_path, GRIPPER_CHANNEL, gripper(command=[0, 0, 0], status=[255] * 8))
    assert not log.damage and len(log.gripper) == 1, log.damage


# Rule: a KINOVA_JACO_COMMAND the arm's boundary refuses (check_jaco_command) is refused
# again, as a status the live run refuses is.
def test_an_arm_command_the_arm_refuses_is_skipped_and_said(tmp_path):
    log = _read(tmp_path, JACO_COMMAND_CHANNEL, command([float("nan")] * 6))
    assert log.arm_commands == []
    _skipped(log, JACO_COMMAND_CHANNEL, "are commands the live run refuses (not finite 1; ")
    kept = _read(tmp_path, JACO_COMMAND_CHANNEL, command())
    assert not kept.damage and len(kept.arm_commands) == 1, kept.damage


# Rule: a transition's value that no controller has is echoed cut, not whole.
@pytest.mark.parametrize("from_mode, trigger", [("Reach", "x" * 100_000),
                                                ("\x1b[2J" + "y" * 100_000, "timer")])
def test_a_transitions_long_value_is_echoed_cut(tmp_path, from_mode, trigger):
    message = lcmt_tegrasp_transition.decode(
        forged_transition(1_500_000, from_mode, "Load"))
    message.trigger = trigger
    log = _read(tmp_path, TRANSITION_CHANNEL, message)
    words = _skipped(log, TRANSITION_CHANNEL, "are no transition a controller makes (the "
                                              "first: ")
    assert "(100000 characters)" in words or "(100004 characters)" in words, words
    assert "\x1b" not in words


def _replay(path, events, capfd, *options):
    code = cli.main(["replay", str(path), "--events", str(events), *options])
    out, err = capfd.readouterr()
    assert "Traceback" not in err
    return code, out, err


@pytest.fixture(scope="module")
def events(tmp_path_factory):
    folder = tmp_path_factory.mktemp("events") / "events"
    save_memorized_events(folder, EVENTS.values())
    return folder


def test_replay_of_forged_faults_exits_3_and_no_escape_reaches_the_terminal(
        tmp_path, events, capfd):
    path = write_log(tmp_path / "run.lcmlog", forged_at=FORGED_AT, forged=[
        (FAULT_CHANNEL, fault(description="\x1b]0;pwned\x07\x1b[2J").encode()),
        (FAULT_CHANNEL, fault(description="z" * 100_000).encode())])
    for options in ((), ("--json",)):
        code, out, err = _replay(path, events, capfd, *options)
        assert code == 3 and "damaged log" in err, err
        assert "2 message(s) on TEGRASP_FAULT are no fault" in err, err
        assert "\x1b" not in out + err and "\x07" not in out + err
        assert len(out) < 10_000 and len(err) < 2_000, (len(out), len(err))


def test_replay_prints_a_faults_description_cut_and_exits_0(tmp_path, events, capfd):
    words = "the gripper driver could not activate the 2F-85 " * 8  # 384 characters
    path = write_log(tmp_path / "run.lcmlog", forged_at=FORGED_AT, forged=[
        (FAULT_CHANNEL, fault(kind="driver", description=words.strip()).encode())])
    code, out, err = _replay(path, events, capfd)
    assert code == 0 and not err, err
    (line,) = [line for line in out.splitlines() if "] FAULT " in line]
    assert line.startswith("  [   1.500 s] FAULT gripper: driver: the gripper driver could "
                           "not activate"), line
    assert "(383 characters) (since 1.400 s)" in line and len(line) < 160, line


def test_replay_of_a_100_kb_trigger_echoes_it_cut(tmp_path, events, capfd):
    message = lcmt_tegrasp_transition.decode(
        forged_transition(1_500_000, "Reach", "Load"))
    message.trigger = "x" * 100_000
    path = write_log(tmp_path / "run.lcmlog", forged_at=FORGED_AT,
                     forged=[(TRANSITION_CHANNEL, message.encode())])
    for options in ((), ("--json",)):
        code, out, err = _replay(path, events, capfd, *options)
        assert code == 3 and "(100000 characters)" in err, err
        assert len(out) < 10_000 and len(err) < 2_000, (len(out), len(err))


def test_every_device_a_fault_names_is_one_device_fault_declares():
    from tegrasp_drake.hardware.device_fault import DEVICES
    from tegrasp_drake.hardware.robotiq.robotiq_driver import RobotiqDriver
    from tegrasp_drake.hardware.watchdog import DEFAULT_TIMEOUTS
    assert set(DEFAULT_TIMEOUTS) <= set(DEVICES)
    assert inspect.signature(RobotiqDriver).parameters["device"].default in DEVICES


def test_replay_prints_a_long_channel_name_cut(tmp_path, events, capfd):
    """lcm-logger records any channel (up to 256 printable characters); the summary's
    message counts name it cut."""
    path = write_log(tmp_path / "run.lcmlog", forged_at=FORGED_AT, forged=[("C" * 250, b"x")])
    code, out, err = _replay(path, events, capfd)
    assert code == 0 and not err, err
    (line,) = [line for line in out.splitlines() if line.startswith("messages: ")]
    assert "C" * 100 not in line and "(250 characters) 1" in line, line
