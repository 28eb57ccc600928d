"""Refused device messages the forty-first review found unreported or misnamed: the myRIO
decoder's repeated and implausible frames, and a gripper's activation refused for a reason
the error did not name. Real decoder and client classes, forged bytes on pseudo-terminals."""

import os
import select
import threading
import time
import types

import pytest

from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_frame import encode_frame
from tegrasp_drake.hardware.robotiq.modbus_client import (
    RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig)


def wait_for(predicate, what: str, timeout: float = 10.0):
    """Polls `predicate` (generously: the CI runs beside a CPU hog)."""
    deadline = time.monotonic() + timeout
    while not predicate():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.01)


def forged_tactile_stream() -> bytes:
    """Valid-CRC frames 0..19 at 1 ms; frame 20's timestamp jumps 2^31 us (implausible);
    frame 15 again (repeated); then frames 21..29, which still follow frame 19."""
    frames = [encode_frame(k, 1000 * k, (0, 0)) for k in range(20)]
    frames.append(encode_frame(20, 1000 * 20 + (1 << 31), (0, 0)))
    frames.append(encode_frame(15, 1000 * 15, (0, 0)))
    frames += [encode_frame(k, 1000 * k, (0, 0)) for k in range(21, 30)]
    return b"".join(frames)


# Rule: every frame the myRIO decoder refuses is counted under its reason in the run's
# closing summary and said once, as it happens, through the one boundary every device's
# refused messages cross (the station hands it to the run's reporter as the gripper's).
def test_refused_tactile_frames_are_summarised_and_said_once_by_reason():
    from tegrasp_drake.hardware.station import HardwareStation
    from tegrasp_drake.runs.hardware_run import format_counters
    stream = forged_tactile_stream()
    master, slave, port = open_raw_pty()
    try:
        with TactileSerialReader(port) as reader:
            os.write(master, stream)
            wait_for(lambda: reader.counters().decoder.frames == 29, "29 frames")
            counters = reader.counters()
            boundary = HardwareStation.message_boundaries(types.SimpleNamespace(
                _arm_status_boundary=None, _gripper_client=types.SimpleNamespace(boundary=None),
                _tactile_reader=reader))["tactile"]
            said = [boundary.describe(rejection) for rejection in boundary.new_rejections()]
    finally:
        os.close(master)
        os.close(slave)
    assert (counters.decoder.implausible, counters.decoder.repeated) == (1, 1)
    summary = format_counters({"gripper": RobotiqModbusClient(RobotiqModbusConfig()).counters(),
                               "tactile": counters})
    # frame 20 was refused, so 19 -> 21 also counts one dropped
    assert "tactile: 29 frames, 2 rejected (repeated 1, implausible 1), 1 dropped" in summary
    assert len(said) == 2, said
    assert said[0].startswith(f"tactile: {port}: skipped a message (implausible: sequence 20 ")
    assert said[1].startswith(f"tactile: {port}: skipped a message (repeated: sequence 15 ")


class ForgedGripper:
    """A gripper on a pty answering each Modbus RTU request with `answer(request)` -> body
    (the CRC is added). A context manager; the client opens `port`."""

    def __init__(self, answer):
        from pymodbus.framer.rtu import FramerRTU
        self._crc = FramerRTU.compute_CRC
        self._answer = answer
        self._master, self._slave, self.port = open_raw_pty()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while not self._stop.is_set():
            ready, _, _ = select.select([self._master], [], [], 0.05)
            if not ready:
                continue
            try:
                request = os.read(self._master, 256)
            except OSError:
                continue
            if len(request) >= 4:
                body = self._answer(request)
                os.write(self._master, body + self._crc(body).to_bytes(2, "big"))

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join(2.0)
        os.close(self._master)
        os.close(self._slave)


def exception_04(request: bytes) -> bytes:
    return bytes([request[0], request[1] | 0x80, 0x04])  # server device failure


def all_status_bits_set(request: bytes) -> bytes:
    if request[1] in (3, 4):
        return bytes([request[0], request[1], 6]) + b"\xff" * 6
    return request[:6]  # a write's echo


# Rule: a gripper that does not activate is reported with what it last answered, under the
# reason docs/hardware.md names (an exception response and its code; an impossible status and
# why), not as "no answer" or "gSTA did not reach 3" when it answered and reached 3.
@pytest.mark.parametrize("answer, words", [
    (exception_04, "the write of [0, 0, 0] was not accepted (the last refused: exception "
                   "response: exception code 04 to a function 16 request)"),
    (all_status_bits_set, "no status read was accepted (the last refused: impossible status: "
                          "reserved bits"),
])
def test_a_gripper_activation_failure_names_what_was_answered(answer, words):
    with ForgedGripper(answer) as gripper, RobotiqModbusClient(RobotiqModbusConfig(
            port=gripper.port, activation_timeout=0.5, request_timeout=0.5)) as client:
        with pytest.raises(RobotiqActivationError) as raised:
            client.wait_until_active(30.0)
    message = str(raised.value)
    assert "did not activate within 0.5 s: " + words in message, message
    assert "no answer" not in message and "did not reach 3" not in message, message


# Rule: a tactile stream whose frames arrive but cannot zero the pads (no taxel counts in
# them) is reported in words, what arrived and what to check, never the counters' repr.
def test_a_tactile_stream_without_counts_is_reported_in_words_when_zeroing_fails():
    from tegrasp_drake.hardware.myrio.serial_reader import zeroing_problem
    from tegrasp_drake.hardware.myrio.tactile_calibration import TactileCalibration
    from tegrasp_drake.hardware.myrio.tactile_serial_receiver import TactileSerialReceiver
    calibration = TactileCalibration(zero_samples=4)
    master, slave, port = open_raw_pty()
    try:
        with TactileSerialReader(port) as reader:
            os.write(master, b"".join(encode_frame(k, 1000 * k, (0, 0)) for k in range(50)))
            wait_for(lambda: reader.counters().decoder.frames == 50, "50 frames")
            receiver = TactileSerialReceiver(reader, calibration=calibration)
            assert not receiver.zero_before_start(time.monotonic() + 0.2)
            problem = zeroing_problem(reader.counters(), receiver.zero_samples)
    finally:
        os.close(master)
        os.close(slave)
    assert "Counters(" not in problem
    assert problem.startswith("the frames that arrived (50 frames, 0 rejected, 0 dropped, "
                              "0 restarts) did not hold 4 taxel count sequences per finger")
    assert "does the myRIO stream send the pads' counts" in problem
