"""The device emulators answer as the devices do: the gripper emulator refuses requests a
2F-85 cannot take and resynchronises after noise, the myRIO emulator streams on between
runs and says when one stops and the next begins, an option the device does not use is
refused, and --write-config writes only a config of its own, saying which ports are
defaults."""

import os
import random
import time
import tracemalloc
import types

import numpy as np
import pytest
from pymodbus.framer.rtu import FramerRTU

from tegrasp_drake.commands import emulate
from tegrasp_drake.emulators.controller_clock import ControllerClock
from tegrasp_drake.emulators.modbus_request_framer import BAD_CRC, FRAMING, ModbusRequestFramer
from tegrasp_drake.emulators.myrio_emulator import (MyRioEmulator, MyRioEmulatorConfig,
                                                    TactileRecording, TactileRecordingError,
                                                    load_tactile_recording)
from tegrasp_drake.hardware.message_boundary import MessageBoundary
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tests.bad_input.probes import (SEED, assert_one_line_error, run_cli, spoiled, trial_log_with,
                                    wait_for)


def _frame(body: bytes) -> bytes:
    return body + FramerRTU.compute_CRC(body).to_bytes(2, "big")


def test_the_emulated_gripper_resynchronises_after_noise_and_malformed_requests():
    read = _frame(bytes([9, 4, 0x07, 0xD0, 0, 3]))
    write = _frame(bytes([9, 16, 0x03, 0xE8, 0, 3, 6, 9, 0, 0, 255, 255, 255]))
    bad_count = _frame(bytes([9, 16, 0x03, 0xE8, 0, 3, 200]) + bytes(6))
    bad_crc = read[:-1] + bytes([read[-1] ^ 0xFF])
    noise = random.Random(SEED).randbytes(37)
    boundary = MessageBoundary("robotiq")
    framer = ModbusRequestFramer(boundary)
    stream = [bad_count, read, noise, write, bad_crc, read]
    received = [framer.feed(chunk) for chunk in stream]
    assert received[1] == [read] and received[3] == [write] and received[5] == [read]
    assert received[0] == [] and received[4] == []
    counters = boundary.counters()
    assert counters.accepted == 3
    assert counters.rejected.get(FRAMING, 0) >= 1 and counters.rejected.get(BAD_CRC, 0) >= 1
    assert framer.skipped_bytes >= len(bad_count) + len(bad_crc)
    # Byte by byte, a request still arrives whole.
    assert [f for byte in write for f in framer.feed(bytes([byte]))] == [write]


@pytest.mark.parametrize("seed", range(SEED, SEED + 10))
def test_the_request_after_a_burst_of_noise_is_the_one_the_emulated_gripper_answers(seed):
    read = _frame(bytes([9, 4, 0x07, 0xD0, 0, 3]))
    framer = ModbusRequestFramer(MessageBoundary("robotiq"))
    noise = random.Random(seed).randbytes(4000)
    received = framer.feed(noise) + framer.feed(read)
    assert received[-1:] == [read]
    assert len(received) <= 2  # a CRC-valid request hides in 4 kB of noise once in ~300


@pytest.mark.parametrize("device, option", [
    ("jaco", ["--sync", "follow"]), ("robotiq", ["--trial", "trial.npz"]),
    ("jaco", ["--follow-gripper"]), ("myrio", ["--inject-fault", "0x0E@3"])])
def test_an_emulate_option_the_device_does_not_use_is_refused(device, option, capfd):
    code, text = run_cli(["emulate", device, *option, "--scheduling", "normal"], capfd)
    assert_one_line_error(code, text, option[0], "does not use it")


# --- notes: a replay's missing tactile messages say why; --write-config makes its folder ------

def test_write_config_makes_a_missing_folder_as_plot_out_does(tmp_path):
    from tegrasp_drake.commands.emulate import _check_config_target
    from tegrasp_drake.emulators.launcher import Emulators, WRITTEN_BY_EMULATE
    target = tmp_path / "new" / "hw.yaml"
    _check_config_target(target)  # not refused: the folder is made with the file
    Emulators(lcm_url="memq://", out=lambda text: None).write_hardware_config(target)
    assert target.read_text().startswith(WRITTEN_BY_EMULATE)


def test_write_config_through_a_file_is_still_refused(tmp_path):
    a_file = tmp_path / "file"
    a_file.write_text("")
    from tegrasp_drake.commands.emulate import _check_config_target
    with pytest.raises(SystemExit, match="is not a folder"):
        _check_config_target(a_file / "hw.yaml")


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


def test_the_myrio_emulator_refuses_gripper_requests_a_2f85_cannot_take(tmp_path):
    path = trial_log_with(tmp_path / "trial.npz",
                           gripper_command=spoiled((11, 3), 0, 1e9))
    with pytest.raises(TactileRecordingError, match=r"'gripper_command' column 0 \(rPR\)"):
        load_tactile_recording(path)
    bare = tmp_path / "bare.npz"  # a bare recording (no meta) is checked alike
    with np.load(path) as data:
        np.savez(bare, **{name: data[name] for name in
                          ("t_sa", "taxels", "t_ra", "pad_acceleration", "t_slow",
                           "gripper_command")})
    with pytest.raises(TactileRecordingError, match=r"'gripper_command' column 0 \(rPR\)"):
        load_tactile_recording(bare)


# Rule: a file is read with a bound before its end: --write-config looks at the first line
# of the file it would replace, and reads no more of it (a sparse 200 MB file here).
def test_write_config_reads_only_the_first_line_of_the_file_it_would_replace(tmp_path):
    big = tmp_path / "big.yaml"
    with open(big, "wb") as f:
        f.truncate(200_000_000)
    tracemalloc.start()
    try:
        with pytest.raises(SystemExit, match="was not written by `tegrasp emulate`"):
            emulate._check_config_target(big)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 10_000_000, f"{peak} bytes allocated to check a 200 MB file's first line"

PERIOD = 1e-3           # [s] the emulator's frame period

COMMAND_PERIOD = 0.01   # [s] the arm commands' period (100 Hz)


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
        # 50 more frames (50 ms of the 1 kHz stream), waited for: a loaded host delays them
        wait_for(lambda: reader.counters().decoder.frames > streamed + 50,
                 "stream after the stop")
        assert not said("a new run's arm commands")()
        run_commands(0.1)
        wait_for(said("a new run's arm commands: replaying the trial from its beginning"),
                 "word of the next run")


def test_write_config_says_which_ports_are_defaults_not_emulated_devices():
    """`emulate jaco --write-config` wrote the default gripper and tactile ports without a
    word; a run on that config opens them."""
    from tegrasp_drake.commands.emulate import config_written_line
    from tegrasp_drake.emulators.launcher import Emulators, hardware_config_for
    line = config_written_line(Emulators(lcm_url="memq://", out=lambda text: None), "hw.yaml")
    assert "gripper.port /dev/" in line and "tactile.port /dev/" in line
    assert "the defaults, for devices not emulated here" in line and "\n" not in line
    devices = {"gripper": {"port": "/dev/pts/7"}}  # the robotiq emulator's, as it records it
    robotiq = types.SimpleNamespace(devices=devices,
                                    hardware_config=lambda: hardware_config_for(devices))
    line = config_written_line(robotiq, "hw.yaml")
    assert "gripper.port" not in line and "tactile.port /dev/" in line
