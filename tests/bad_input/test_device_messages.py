"""Messages from the devices (arm, gripper, tactile pads) are checked at one boundary: a
malformed or impossible status, a Modbus answer to another request, LCM bytes of the wrong
size or type, a position jump faster than the fingers, a time from the far future or before
zero are counted by reason and skipped while the run keeps its last good value; a gripper
that faults or does not activate and a tactile port that sends no valid frame are said in
words."""

import math
import os
import random
import select
import threading
import time
import types

import numpy as np
import pytest
from drake import lcmt_jaco_command, lcmt_jaco_status
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import ConstantVectorSource
from pymodbus.pdu import ExceptionResponse
from pymodbus.pdu.register_message import (ReadHoldingRegistersResponse,
                                           ReadInputRegistersResponse,
                                           WriteMultipleRegistersResponse)

import tegrasp_drake
from tegrasp_drake.emulators.controller_clock import command_boundary
from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
from tegrasp_drake.emulators.null_modem import open_raw_pty
from tegrasp_drake.hardware.jaco import jaco_lcm
from tegrasp_drake.hardware.jaco.jaco_lcm import (JACO_COMMAND_CHANNEL, JACO_MAX_JOINT_SPEED,
                                                  JACO_STATUS_CHANNEL, NEGATIVE_UTIME, NOT_FINITE,
                                                  TOO_FAST, WRONG_JOINT_COUNT, check_jaco_status,
                                                  jaco_status_boundary, make_jaco_command,
                                                  make_jaco_status)
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver
from tegrasp_drake.hardware.lcm_boundary import TOO_SHORT, TRUNCATED, WRONG_TYPE, decode_lcm
from tegrasp_drake.hardware.message_boundary import MessageBoundary, RejectedMessage, UNDECODABLE
from tegrasp_drake.hardware.myrio.serial_reader import TactileSerialReader
from tegrasp_drake.hardware.myrio.tactile_frame import encode_frame
from tegrasp_drake.hardware.robotiq import modbus_client
from tegrasp_drake.hardware.robotiq.modbus_client import (EXCEPTION_RESPONSE,
                                                          RobotiqActivationError,
                                                          RobotiqModbusClient, RobotiqModbusConfig,
                                                          WRONG_ECHO, WRONG_FUNCTION,
                                                          WRONG_REGISTER_COUNT, check_answer)
from tegrasp_drake.robotiq import registers, units
from tegrasp_drake.simulation.station import initial_arm_positions
from tests.bad_input.probes import SEED, jaco_driver_on_memq, one_line_of

Q = [0.1, 2.8, 0.9, -0.4, 0.5, -0.6]  # [rad] inside the JACO2's joint ranges

ZERO = [0.0] * 6


# --- 1. device messages: one boundary, counted, skipped, the run goes on ----------------------

def _status(utime, position=Q, joints=6) -> bytes:
    message = make_jaco_status(utime, position[:6], ZERO, ZERO)
    if joints != 6:
        message.num_joints = joints
        for name in ("joint_position", "joint_velocity", "joint_torque",
                     "joint_torque_external", "joint_current"):
            setattr(message, name, [0.1] * joints)
    return message.encode()


def _bad_status_messages(rng: random.Random) -> dict:
    """{reason: bytes} of the malformed statuses published here."""
    good = _status(1)
    return {
        WRONG_TYPE: rng.randbytes(40),  # noise: no fingerprint of the type
        TOO_SHORT: b"",
        TRUNCATED: good[:30],
        WRONG_JOINT_COUNT: _status(2, joints=7),
        NOT_FINITE: _status(3, position=[math.nan] * 6),
    }


def test_every_malformed_status_is_refused_by_its_reason():
    for reason, data in _bad_status_messages(random.Random(SEED)).items():
        with pytest.raises(RejectedMessage) as refused:
            check_jaco_status(data)
        assert refused.value.reason == reason
        one_line_of(refused.value)
    wrong = make_jaco_command(5, Q, ZERO).encode()
    with pytest.raises(RejectedMessage, match="not a lcmt_jaco_status"):
        check_jaco_status(wrong)


def _driver_diagram(lcm):
    builder = DiagramBuilder()
    builder.AddSystem(LcmInterfaceSystem(lcm))
    driver = AddJacoLcmDriver(builder, lcm=lcm)
    source = builder.AddSystem(ConstantVectorSource(np.concatenate([Q, ZERO])))
    builder.Connect(source.get_output_port(),
                    driver.tracker.GetInputPort("desired_state"))
    return builder.Build(), driver


def test_a_status_stream_of_garbage_and_good_messages_keeps_the_run_counts_and_passes():
    lcm = DrakeLcm("memq://")
    diagram, driver = _driver_diagram(lcm)
    simulator = Simulator(diagram)
    simulator.Initialize()
    receiver_context = driver.status_receiver.GetMyContextFromRoot(simulator.get_context())
    rng = random.Random(SEED)
    bad = list(_bad_status_messages(rng).items())
    good_count, last_good = 0, 0.0
    expected = {}
    for k in range(60):
        if k % 3 == 0:
            utime = 10_000 * (k + 1)
            lcm.Publish(JACO_STATUS_CHANNEL, _status(utime, [q + 1e-3 * k for q in Q]))
            good_count, last_good = good_count + 1, utime * 1e-6
        else:
            reason, data = bad[rng.randrange(len(bad))]
            lcm.Publish(JACO_STATUS_CHANNEL, data)
            expected[reason] = expected.get(reason, 0) + 1
        simulator.AdvanceTo(simulator.get_context().get_time() + 0.01)
        # The receiver shows the newest good status, never a malformed one.
        time_measured = driver.status_receiver.GetOutputPort("time_measured").Eval(
            receiver_context)[0]
        assert time_measured == pytest.approx(last_good)
        position = driver.status_receiver.GetOutputPort("position_measured").Eval(
            receiver_context)
        assert np.all(np.isfinite(position))
    counters = driver.status_boundary.counters()
    assert counters.accepted == good_count
    assert counters.rejected == expected
    reasons = [r.reason for r in driver.status_boundary.new_rejections()]
    assert sorted(reasons) == sorted(expected)  # each said once
    assert driver.status_boundary.new_rejections() == []


def test_a_command_with_nan_or_absurd_speeds_never_reaches_the_emulated_arm():
    lcm = DrakeLcm("memq://")
    boundary = command_boundary("jaco")
    start = initial_arm_positions(tegrasp_drake.LoadScenario(name="box").arm)
    arm = MakeJacoArmEmulator(lcm=lcm, initial_positions=start, command_boundary=boundary)
    simulator = Simulator(arm)
    simulator.Initialize()
    context = simulator.get_context()
    three_joints = make_jaco_command(1, Q, ZERO)
    three_joints.num_joints, three_joints.joint_position = 3, Q[:3]
    three_joints.joint_velocity = ZERO[:3]
    bad = {WRONG_JOINT_COUNT: three_joints.encode(),
           NOT_FINITE: make_jaco_command(2, Q, [math.nan] * 6).encode(),
           TOO_FAST: make_jaco_command(3, Q, [1e30] * 6).encode(),
           WRONG_TYPE: _status(4), TRUNCATED: make_jaco_command(5, Q, ZERO).encode()[:40]}
    slow = [0.1, 0, 0, 0, 0, 0]  # rad/s, within the JACO2's limits
    for k in range(20):
        utime = 100_000 + 10_000 * k
        if k % 2:
            lcm.Publish(JACO_COMMAND_CHANNEL, list(bad.values())[k // 2 % len(bad)])
        else:
            lcm.Publish(JACO_COMMAND_CHANNEL, make_jaco_command(utime, start, slow).encode())
        simulator.AdvanceTo(context.get_time() + 0.01)
        velocity = arm.GetOutputPort("velocity_measured").Eval(context)
        assert np.all(np.isfinite(velocity))
        assert np.all(np.abs(velocity) <= JACO_MAX_JOINT_SPEED)
    counters = boundary.counters()
    assert counters.accepted == 10 and counters.rejected_total == 10
    assert set(counters.rejected) == set(bad)


def test_lcm_bytes_are_refused_by_size_type_and_truncation():
    with pytest.raises(RejectedMessage) as refused:
        decode_lcm(lcmt_jaco_command, b"\x01\x02")
    assert refused.value.reason == TOO_SHORT
    with pytest.raises(RejectedMessage) as refused:
        decode_lcm(lcmt_jaco_command, _status(1))
    assert refused.value.reason == WRONG_TYPE
    with pytest.raises(RejectedMessage) as refused:
        decode_lcm(lcmt_jaco_status, _status(1)[:20])
    assert refused.value.reason == TRUNCATED


def test_a_boundary_counts_an_unforeseen_decode_error_and_never_raises():
    def check(data):
        return {"a": 1}[data]  # KeyError on anything else: a check's own bug or bad bytes
    boundary = MessageBoundary("test", check)
    assert boundary.accept("a") == 1
    assert boundary.accept("b") is None and boundary.accept("c") is None
    counters = boundary.counters()
    assert counters.accepted == 1 and counters.rejected == {UNDECODABLE: 2}
    assert [r.reason for r in boundary.new_rejections()] == [UNDECODABLE]


@pytest.mark.parametrize("response, function, count, reason", [
    (ReadHoldingRegistersResponse(registers=[1, 2, 3]), 4, 3, WRONG_FUNCTION),
    (ReadInputRegistersResponse(registers=[1, 2, 3]), 16, 3, WRONG_FUNCTION),
    (ReadInputRegistersResponse(registers=[1, 2]), 4, 3, WRONG_REGISTER_COUNT),
    (ReadInputRegistersResponse(registers=[0] * 125), 4, 3, WRONG_REGISTER_COUNT),
    (WriteMultipleRegistersResponse(address=0, count=3), 16, 3, WRONG_ECHO),
    (ExceptionResponse(4, 2), 4, 3, EXCEPTION_RESPONSE),
])
def test_a_modbus_answer_to_another_request_is_refused_by_its_reason(response, function,
                                                                      count, reason):
    with pytest.raises(RejectedMessage) as refused:
        check_answer(response, function, 1000 if function == 16 else 2000, count)
    assert refused.value.reason == reason


def test_a_modbus_answer_to_the_request_is_taken():
    answer = ReadInputRegistersResponse(registers=[1, 2, 3])
    assert check_answer(answer, 4, 2000, 3) is answer
    echo = WriteMultipleRegistersResponse(address=1000, count=3)
    assert check_answer(echo, 16, 1000, 3) is echo


def test_a_gripper_that_does_not_activate_says_so_with_a_rounded_time():
    client = RobotiqModbusClient(RobotiqModbusConfig(port="/dev/tegrasp-no-such-port"))
    with pytest.raises(RobotiqActivationError) as refused:
        client.wait_until_active(0.0123456789)  # never started: it waits out the timeout
    assert "not active within 0.0123457 s" in str(refused.value), refused.value


# Rule: a gripper whose port is silent is said to be not active within the timeout the user
# configured (the station waits what is left of its ready_timeout after the arm's status,
# 2.99971 s of 3 s, but says 3 s), with what it waited for, what came, and what to check.
def test_a_silent_gripper_port_names_the_configured_timeout_and_what_to_check():
    main, follower = os.openpty()  # a port nobody answers on
    try:
        port = os.ttyname(follower)
        client = RobotiqModbusClient(RobotiqModbusConfig(port=port, device_id=9,
                                                         request_timeout=0.01))
        with client:
            with pytest.raises(RobotiqActivationError) as refused:
                client.wait_until_active(0.3, configured_s=3.0)
    finally:
        os.close(main)
        os.close(follower)
    message = str(refused.value)
    assert message.startswith(f"Robotiq 2F-85 on {port} (slave 9) not active within 3 s: "
                              "waited for its status to report activation complete (gSTA = 3, "
                              "no fault); "), message
    assert "2.9" not in message and "0.3" not in message, message
    assert message.endswith(f"Check the gripper's power, its RS-485 adapter on {port}, the "
                            "Modbus slave id (9) and the baud rate (115200); `tegrasp emulate "
                            "all` runs the station without hardware"), message
    assert "\n" not in message


# Rule: a Robotiq status whose gFLT holds a major fault (2F-85 manual: the fingers stop
# until the next activation) is a device fault, not an active gripper, whatever gSTA says;
# and the client keeps pymodbus's multi-line hex dumps of garbage replies off stderr (it
# counts those replies itself).
@pytest.mark.real_time
def test_a_gripper_reporting_a_major_fault_is_not_taken_as_active():
    import logging
    import time
    from tegrasp_drake.emulators.robotiq_emulator import RobotiqEmulator, RobotiqEmulatorConfig
    from tegrasp_drake.hardware.robotiq.modbus_client import (
        RobotiqActivationError, RobotiqModbusClient, RobotiqModbusConfig)
    logging.getLogger("pymodbus").setLevel(logging.NOTSET)
    config = RobotiqEmulatorConfig(activation_duration=1.0)
    with RobotiqEmulator(config) as emulator:
        with RobotiqModbusClient(RobotiqModbusConfig(port=emulator.port,
                                                     activation_timeout=5.0)) as client:
            assert logging.getLogger("pymodbus").level == logging.CRITICAL
            time.sleep(0.3)  # the activation writes are answered; gSTA not yet 3
            emulator.inject_fault(0x0F)  # automatic release completed
            with pytest.raises(RobotiqActivationError, match="gFLT = 0x0F"):
                client.wait_until_active(8.0)


# Rule: an arm status whose utime is impossible (negative: the arm's clock starts at 0) is
# counted under its reason and skipped; the receiver keeps the last good status. (The order
# of utime is not checked: jaco_lcm.jaco_status_boundary says why.)
def test_an_arm_status_with_a_negative_utime_is_skipped():
    lcm, driver, simulator, context = jaco_driver_on_memq(Q)
    real = [q + 0.2 for q in Q]
    forged = [2.0] * 6

    def publish(utime, position):
        lcm.Publish(JACO_STATUS_CHANNEL,
                    make_jaco_status(utime, position, ZERO, ZERO).encode())
        simulator.AdvanceTo(simulator.get_context().get_time() + 0.01)
        return (driver.status_receiver.GetOutputPort("time_measured").Eval(context)[0],
                list(driver.status_receiver.GetOutputPort("position_measured").Eval(context)))

    assert publish(20_000, real) == (pytest.approx(0.02), pytest.approx(real))
    for utime in (-2**63, -1):
        assert publish(utime, forged) == (pytest.approx(0.02), pytest.approx(real))
    assert publish(30_000, real) == (pytest.approx(0.03), pytest.approx(real))
    counters = driver.status_boundary.counters()
    assert counters.accepted == 2
    assert counters.rejected == {NEGATIVE_UTIME: 2}
    for rejection in driver.status_boundary.new_rejections():
        assert "\n" not in driver.status_boundary.describe(rejection)

Q_WIDE = [3.3, 4.5, 1.1, 2.5, 2.3, 3.9]  # [rad] inside every joint's range


# Rule: a status from the far future (utime 2^62 us, 146,000 years ahead) does not become a
# clock the arm's genuine statuses must beat: it is one sample, and the genuine stream after
# it is taken (the order of utime is not checked: jaco_lcm.jaco_status_boundary says why).
def test_an_arm_status_from_the_far_future_does_not_lock_out_the_genuine_stream():
    lcm, driver, simulator, context = jaco_driver_on_memq(Q_WIDE)

    def publish(utime):
        lcm.Publish(JACO_STATUS_CHANNEL, make_jaco_status(utime, Q_WIDE, ZERO, ZERO).encode())
        simulator.AdvanceTo(simulator.get_context().get_time() + 0.01)
        return driver.status_receiver.GetOutputPort("time_measured").Eval(context)[0]

    assert publish(6_580_000) == pytest.approx(6.58)
    assert publish(6_590_000) == pytest.approx(6.59)
    assert publish(2**62) == pytest.approx(2**62 * 1e-6)
    for utime in (6_600_000, 6_610_000, 6_620_000):
        assert publish(utime) == pytest.approx(utime * 1e-6)
    counters = driver.status_boundary.counters()
    assert counters.accepted == 6 and counters.rejected == {}


# Rule: an arm status whose joint positions, velocities or torques lie beyond the JACO2's
# physical ranges (modelgen/jaco2_dh.py) is counted and skipped, as a non-finite one is;
# one at the published limits is the arm's and is accepted.
@pytest.mark.parametrize("field, joint, value", [
    ("joint_position", 0, 1e300),   # finite, but no angle of a continuous joint
    ("joint_position", 1, np.radians(30.0)),   # joint 2 stops at 47 deg
    ("joint_position", 2, np.radians(350.0)),  # joint 3 stops at 341 deg
    ("joint_velocity", 3, -1e300),
    ("joint_velocity", 0, np.radians(90.0)),   # joint 1 turns at most 36 deg/s
    ("joint_torque", 1, 1e300),
    ("joint_torque", 5, -100.0),               # joint 6 makes at most 20 N m
])
def test_an_arm_status_beyond_the_jaco2s_ranges_is_skipped(field, joint, value):
    boundary = jaco_status_boundary()
    values = {"joint_position": list(Q_WIDE), "joint_velocity": list(ZERO),
              "joint_torque": list(ZERO)}
    values[field][joint] = value
    bad = make_jaco_status(1_000_000, values["joint_position"], values["joint_velocity"],
                           values["joint_torque"])
    assert boundary.accept(bad.encode()) is None
    assert boundary.counters().rejected == {jaco_lcm.OUT_OF_RANGE: 1}
    (rejection,) = boundary.new_rejections()
    assert f"{field}[{joint}]" in rejection.detail
    assert "\n" not in boundary.describe(rejection)
    at_limits = make_jaco_status(
        1_010_000, [0.0, np.radians(47.0), np.radians(341.0), 0.0, 0.0, 0.0],
        np.radians([36.0, -36.0, 36.0, 48.0, -48.0, 48.0]),
        [40.0, -80.0, 40.0, 20.0, -20.0, 20.0])
    assert boundary.accept(at_limits.encode()) is not None
    assert boundary.counters().rejected == {jaco_lcm.OUT_OF_RANGE: 1}


def _words(gACT=1, gGTO=1, gSTA=3, gOBJ=3, gFLT=0, gPR=100, gPO=100, gCU=0):
    status = [0.0] * units.STATUS_SIZE
    for name, value in dict(gACT=gACT, gGTO=gGTO, gSTA=gSTA, gOBJ=gOBJ, gFLT=gFLT, gPR=gPR,
                            gPO=gPO, gCU=gCU).items():
        status[units.STATUS_NAMES.index(name)] = value
    return registers.status_registers(status)


def _with_byte(words, index, value):
    """`words` with status byte `index` (0..5, first byte high) set to `value`."""
    out = list(words)
    shift = 8 if index % 2 == 0 else 0
    out[index // 2] = (out[index // 2] & ~(0xFF << shift)) | (value << shift)
    return out


class _Gripper:
    """A bus answering each status read with the next of `answers` (register lists), on a
    clock the test moves: a read takes 2 ms."""

    def __init__(self, monkeypatch):
        self.now = 0.0
        self.answers = []
        monkeypatch.setattr(modbus_client, "time",
                            types.SimpleNamespace(monotonic=lambda: self.now))
        self.bus = types.SimpleNamespace(read_input_registers=self._answer)

    def _answer(self, *args, **kwargs):
        self.now += 0.002
        return ReadInputRegistersResponse(registers=self.answers.pop(0))

    def read(self, client, words, after=0.003):
        """The sample `client` reads `after` seconds from now when the gripper sends `words`."""
        self.now += after
        self.answers.append(words)
        return client._read(self.bus)


def _client():
    return RobotiqModbusClient(RobotiqModbusConfig(port="/dev/null"))


# Rule: a 2F-85 status the manual's register map makes impossible (a reserved bit set, gSTA 2
# "not used", activation in progress or complete while gACT says reset) is counted under its
# reason and skipped; the client keeps the last good status.
@pytest.mark.parametrize("words, named", [
    (_words(gACT=0, gGTO=0, gSTA=3), "gSTA = 3 with gACT = 0"),
    (_words(gACT=0, gGTO=0, gSTA=1), "gSTA = 1 with gACT = 0"),
    (_words(gSTA=2), "gSTA = 2"),
    (_with_byte(_words(), 0, 0x02 | 0x01 | 0x08 | 0x30 | 0xC0), "reserved"),
    (_with_byte(_words(), 0, 0x04 | 0x01 | 0x08 | 0x30 | 0xC0), "reserved"),
    (_with_byte(_words(), 1, 0x80), "reserved"),
])
def test_a_status_the_register_map_makes_impossible_is_counted_and_skipped(
        monkeypatch, words, named):
    gripper, client = _Gripper(monkeypatch), _client()
    good = gripper.read(client, _words())
    assert good is not None
    assert gripper.read(client, words) is None
    assert client.latest_status() is good
    counters = client.counters()
    assert counters.rejected == {modbus_client.IMPOSSIBLE_STATUS: 1}
    assert named in counters.last_error


# The states a 2F-85 does report are taken: reset, reset with a go-to request (gGTO echoes
# rGTO, fault 0x07), activation in progress, active with each gOBJ, a major fault.
@pytest.mark.parametrize("words", [
    _words(gACT=0, gGTO=0, gSTA=0, gOBJ=0),
    _words(gACT=0, gGTO=1, gSTA=0, gOBJ=0, gFLT=units.FAULT_NOT_ACTIVATED),
    _words(gACT=1, gGTO=0, gSTA=1, gOBJ=0),
    _words(gACT=1, gGTO=0, gSTA=0, gOBJ=0, gFLT=0x0B),
    *[_words(gOBJ=obj) for obj in range(4)],
    _with_byte(_words(), 2, 0xA0),  # the high nibble is kFLT, the controller's fault
])
def test_a_status_the_register_map_allows_is_taken(monkeypatch, words):
    gripper, client = _Gripper(monkeypatch), _client()
    assert gripper.read(client, words) is not None
    assert client.counters().rejected == {}


# Rule: a gPO step between two accepted statuses farther than the 2F-85's fingers can move
# at their top speed in between is counted and skipped (the fingers crossing the whole
# stroke between two 5 ms reads); the client keeps the last good status.
def test_a_position_jump_faster_than_the_fingers_is_counted_and_skipped(monkeypatch):
    gripper, client = _Gripper(monkeypatch), _client()
    good = gripper.read(client, _words(gPO=3))
    for position in (255, 230, 255):
        assert gripper.read(client, _words(gPO=position)) is None
        assert client.latest_status() is good
    counters = client.counters()
    assert counters.rejected == {modbus_client.POSITION_JUMP: 3}
    assert "gPO" in counters.last_error and "150 mm/s" in counters.last_error


# The fingers moving at their top speed are taken, and a long silence allows the distance
# covered in it; the first status, and the first after a (re)activation (gSTA not 3: the
# fingers stroke to calibrate), have nothing to be compared with.
def test_a_position_the_fingers_can_reach_is_taken(monkeypatch):
    gripper, client = _Gripper(monkeypatch), _client()
    # [counts/s] the top speed, were the whole byte range the stroke (more counts per mm than
    # the encoder's 3..230: the fastest the counts can change)
    rate = units.SPEED_MAX_MPS / units.STROKE_M * units.BYTE_MAX
    position = 3.0
    assert gripper.read(client, _words(gPO=255)) is not None  # the first status
    assert gripper.read(client, _words(gPO=3), after=1.0) is not None  # a second later
    for _ in range(20):  # a read every 5 ms at full speed
        position += rate * 0.005
        assert gripper.read(client, _words(gPO=round(position))) is not None
    assert gripper.read(client, _words(gSTA=1, gGTO=0, gPO=40)) is not None  # reactivation
    assert gripper.read(client, _words(gPO=200)) is not None
    assert client.counters().rejected == {}


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
