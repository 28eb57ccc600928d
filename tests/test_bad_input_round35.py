"""An emulated myRIO that streams on after a run stops and replays again for the next one; a
tactile port that sends no valid frame named in words; two devices on one serial port
refused."""

import os
import time

import numpy as np
import pytest

from tegrasp_drake.emulators.controller_clock import ControllerClock
from tegrasp_drake.emulators.myrio_emulator import (
    MyRioEmulator, MyRioEmulatorConfig, TactileRecording)
from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tests.test_bad_input import assert_one_line_error, run_cli

PERIOD = 1e-3           # [s] the emulator's frame period
COMMAND_PERIOD = 0.01   # [s] the arm commands' period (100 Hz)
HANG_GUARD_S = 30.0     # a guard against a hang on a busy host, not a criterion


def ramp_trial() -> TactileRecording:
    """1 s of pad forces rising from 0 to 10 N (each sample names its time)."""
    t = np.arange(0.0, 1.0, PERIOD)
    forces = 10.0 * t[:, None] * np.ones((1, 12))
    return TactileRecording(t, forces, forces, t, np.zeros((len(t), 3)), np.zeros(len(t)))


def command_for(clock: ControllerClock, seconds: float):
    """A controller run's commands for `seconds` of Context time from 0, at its real rate."""
    for n in range(int(round(seconds / COMMAND_PERIOD)) + 1):
        clock.on_command(int(round(n * COMMAND_PERIOD * 1e6)))
        time.sleep(COMMAND_PERIOD)


def frames_after(emulator, when: float):
    return [f for f in emulator.sent() if f.write_time > when]


def wait_for(condition, what):
    deadline = time.monotonic() + HANG_GUARD_S
    while not condition():
        assert time.monotonic() < deadline, f"no {what} within {HANG_GUARD_S} s"
        time.sleep(0.01)


# Rule: the emulated myRIO keeps streaming when the arm commands stop (holding the sample the
# replay reached), and the next run's commands replay the trial again from its beginning
# (a run that ended mid-replay left the pty silent: the next run found no frame in 10 s).
def test_the_myrio_streams_on_after_a_run_stops_and_replays_for_the_next():
    clock = ControllerClock()
    config = MyRioEmulatorConfig(start_on_trigger=True, hold_at_end=True, lead_in=0.0)
    with MyRioEmulator(ramp_trial(), config, trial_clock=clock) as emulator, \
            TactileSerialReader(emulator.port):
        emulator.start_trial()
        command_for(clock, 0.3)  # the first run stops mid-replay
        stopped = time.monotonic()
        time.sleep(1.5)  # well past the clock's idle time (0.5 s)
        quiet_end = time.monotonic()
        held = [f for f in frames_after(emulator, stopped + 1.0) if f.write_time < quiet_end]
        # A myRIO streams 500 frames in that 0.5 s; at a tenth of that rate it still streams.
        assert len(held) > 50, f"{len(held)} frames in the 0.5 s after the run went idle"
        reached = max(f.trial_time for f in emulator.sent() if f.write_time < stopped)
        held_times = {f.trial_time for f in held}
        assert len(held_times) == 1, "the held frames do not hold one sample"
        assert held_times.pop() == pytest.approx(reached, abs=0.02)

        second = time.monotonic()
        command_for(clock, 0.2)  # the next run: its Context time starts at 0 again
        replayed = [f.trial_time for f in frames_after(emulator, second)]
        assert min(replayed) < 0.02, "the next run's replay did not start from the beginning"
        assert max(replayed) > 0.1, "the next run's replay did not advance"
        assert emulator.counters().restarts == 1


# Rule: after the arm commands' silence (IDLE_AFTER), a command stamped no later than the last
# is the next run's first: the clock counts from it again. A later stamp after a pause, and an
# earlier stamp without one, stay in the same run.
def test_the_controller_clock_begins_a_new_run_when_commands_resume_from_an_earlier_time():
    now = [100.0]
    clock = ControllerClock(now=lambda: now[0])
    for n in range(31):  # 0.3 s of a run
        clock.on_command(n * 10_000)
        now[0] += COMMAND_PERIOD
    assert not clock.idle() and clock.run == 0
    clock.on_command(290_000)  # a late duplicate at once: the same run
    assert clock.run == 0
    now[0] += 1.0
    assert clock.idle()
    clock.on_command(310_000)  # a pause, then later commands: the same run
    assert clock.run == 0 and clock() == pytest.approx(0.31, abs=0.011)
    now[0] += 1.0
    clock.on_command(0)  # the next run's first command
    assert clock.run == 1 and not clock.idle()
    assert clock() == pytest.approx(0.0, abs=0.011)
    now[0] += COMMAND_PERIOD
    clock.on_command(10_000)
    assert clock() == pytest.approx(0.01, abs=0.011)


def reader_counters_after(write: bytes):
    """The counters of a reader on a pty the other end of which wrote `write`."""
    master, slave, port = open_raw_pty()
    try:
        with TactileSerialReader(port) as reader:
            if write:
                os.write(master, write)
            wait_for(lambda: reader.counters().bytes_read >= len(write), "bytes read")
            time.sleep(0.1)
            return reader.counters()
    finally:
        os.close(master)
        os.close(slave)


# Rule: a tactile port that sent no valid frame is reported in words (what arrived, what to
# check), never as the counters' Python repr.
def test_a_silent_tactile_port_is_reported_in_words():
    from tegrasp_drake.hardware.myrio.serial_reader import no_valid_frame_problem
    problem = no_valid_frame_problem(reader_counters_after(b""))
    assert "Counters(" not in problem
    assert "not one byte arrived" in problem and "streaming on that port" in problem


def test_a_tactile_port_sending_other_bytes_is_reported_in_words():
    from tegrasp_drake.hardware.myrio.serial_reader import no_valid_frame_problem
    modbus = bytes([9, 3, 7, 208, 0, 3, 4, 14]) * 20  # a Robotiq's Modbus RTU, not frames
    problem = no_valid_frame_problem(reader_counters_after(modbus))
    assert "Counters(" not in problem
    assert f"{len(modbus)} bytes arrived but none made a valid myRIO frame" in problem
    assert "another device's port" in problem


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
        config.write_text(f"ready_timeout: 1.0\nscheduling: normal\ngripper: {{port: {port}}}\n"
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


# Rule: `tegrasp emulate` says when a run's arm commands stop (the myRIO streams on, holding)
# and when the next run's begin (its replay starts from the beginning), instead of staying
# silent at "ready" while the stream has stopped.
def test_the_emulated_myrio_says_when_a_run_stops_and_the_next_begins(tmp_path):
    import lcm
    from tegrasp_drake.emulators.launcher import Emulators
    from tegrasp_drake.hardware.jaco.jaco_lcm import JACO_COMMAND_CHANNEL, make_jaco_command
    from tegrasp_drake.scenario.scenario import LoadScenario
    from tegrasp_drake.emulators.myrio_emulator import save_tactile_recording

    url = f"udpm://239.255.76.67:{8600 + os.getpid() % 400}?ttl=0"
    trial = save_tactile_recording(tmp_path / "trial.npz", ramp_trial())
    bus, lines = lcm.LCM(url), []

    def run_commands(seconds):
        for n in range(int(round(seconds / COMMAND_PERIOD)) + 1):
            command = make_jaco_command(n * COMMAND_PERIOD * 1e6, [0.0] * 6, [0.0] * 6)
            bus.publish(JACO_COMMAND_CHANNEL, command.encode())
            time.sleep(COMMAND_PERIOD)

    def said(words):
        return lambda: any(words in line for line in lines)

    with Emulators(lcm_url=url, out=lines.append).start(
            ("myrio",), LoadScenario(name="box"), trial=trial, sync="follow") as emulators, \
            TactileSerialReader(emulators.devices["tactile"]["port"]) as reader:
        run_commands(0.2)
        wait_for(said("the arm commands stopped: streaming on"), "word of the stop")
        streamed = reader.counters().decoder.frames
        time.sleep(0.5)
        assert reader.counters().decoder.frames > streamed + 50
        assert not said("a new run's arm commands")()
        run_commands(0.1)
        wait_for(said("a new run's arm commands: replaying the trial from its beginning"),
                 "word of the next run")
