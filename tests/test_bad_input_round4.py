"""Bad inputs a fourth hostile tester found, each re-run through the entry point it reached
and tested as the class it belongs to, at the one place its discipline lives:

- a device's message (hardware/message_boundary.py): a malformed status or command, a
  Modbus answer of another function or size, a malformed Modbus request, is counted by
  reason and skipped; the last good value is kept; the run goes on;
- a public function's argument (rig/api_boundary.py): its range, its choices and its
  folder are declared beside it and checked at the call, before anything is written;
- a file (rig/files.load_json, the trial log's array rules, object.file) and the command
  line (an empty value, an option the device does not use)."""

import json
import math
import os
import pathlib
import random
import shutil
import typing

import numpy as np
import pytest
from drake import lcmt_jaco_command, lcmt_jaco_status
from pydrake.lcm import DrakeLcm
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import LcmInterfaceSystem
from pydrake.systems.primitives import ConstantVectorSource
from pymodbus.framer.rtu import FramerRTU
from pymodbus.pdu import ExceptionResponse
from pymodbus.pdu.register_message import (ReadHoldingRegistersResponse,
                                           ReadInputRegistersResponse,
                                           WriteMultipleRegistersResponse)

import tegrasp_drake
from tegrasp_drake.emulators.controller_clock import command_boundary
from tests.test_bad_input import assert_one_line_error, folder_contents, run_cli
from tegrasp_drake.emulators.jaco_arm_emulator import MakeJacoArmEmulator
from tegrasp_drake.emulators.modbus_request_framer import (BAD_CRC, FRAMING,
                                                           ModbusRequestFramer)
from tegrasp_drake.emulators.myrio_emulator import (TactileRecordingError,
                                                    load_tactile_recording)
from tegrasp_drake.events.event_file import MemorizedEventError
from tegrasp_drake.hardware.jaco.jaco_lcm import (
    JACO_COMMAND_CHANNEL, JACO_MAX_JOINT_SPEED, JACO_STATUS_CHANNEL, NOT_FINITE, TOO_FAST,
    WRONG_JOINT_COUNT, check_jaco_status, make_jaco_command, make_jaco_status)
from tegrasp_drake.hardware.jaco.jaco_lcm_interface import AddJacoLcmDriver
from tegrasp_drake.hardware.lcm_boundary import TOO_SHORT, TRUNCATED, WRONG_TYPE, decode_lcm
from tegrasp_drake.hardware.message_boundary import (UNDECODABLE, MessageBoundary,
                                                     RejectedMessage)
from tegrasp_drake.hardware.robotiq.modbus_client import (
    EXCEPTION_RESPONSE, WRONG_ECHO, WRONG_FUNCTION, WRONG_REGISTER_COUNT, check_answer)
from tegrasp_drake.rig import files, paths
from tegrasp_drake.rig.api_boundary import Folder
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.trial_log_file import ARRAY_FIELDS, TrialLog, load_trial_log
from tegrasp_drake.simulation.station import initial_arm_positions

SEED = 604
Q = [0.1, 2.8, 0.9, -0.4, 0.5, -0.6]  # [rad] inside the JACO2's joint ranges
ZERO = [0.0] * 6


def _one_line(error) -> str:
    text = str(error)
    assert "\n" not in text and text.strip(), text
    return text


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
    """{reason: bytes} of the malformed statuses the hostile pass published."""
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
        _one_line(refused.value)
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


# --- 2. the public API: declared ranges, choices and folders, checked before any write --------

@pytest.mark.parametrize("call, argument", [
    (lambda s: tegrasp_drake.run_ideal_grasp(s, duration=-1.0), "duration"),
    (lambda s: tegrasp_drake.run_ideal_grasp(s, duration=math.nan), "duration"),
    (lambda s: tegrasp_drake.run_trial(s, max_time=-1.0), "max_time"),
    (lambda s: tegrasp_drake.run_trial(s, max_time=math.nan), "max_time"),
])
def test_a_duration_out_of_range_is_refused_by_name_never_by_drake(call, argument):
    scenario = tegrasp_drake.LoadScenario(name="box", overrides=[f"random_seed={SEED}"])
    with pytest.raises(ValueError) as refused:  # not SystemExit from Drake's AdvanceTo
        call(scenario)
    assert f"argument '{argument}'" in _one_line(refused.value)


def test_records_of_a_folder_that_does_not_exist_are_an_error(tmp_path):
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.load_records(tmp_path / "nonexistent")


def test_reports_into_a_folder_that_does_not_exist_are_refused_and_make_nothing(tmp_path):
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.write_reports(tmp_path / "nonexistent" / "dir")
    assert not (tmp_path / "nonexistent").exists()


def test_a_wrong_figure_format_is_refused_before_any_report_is_written(tmp_path):
    (tmp_path / "trials").mkdir()
    before = folder_contents(tmp_path)
    with pytest.raises(ValueError) as refused:
        tegrasp_drake.write_reports(tmp_path, figure_format="bmp")
    assert "argument 'figure_format'" in _one_line(refused.value)
    assert folder_contents(tmp_path) == before


@pytest.mark.parametrize("call", [
    lambda file: tegrasp_drake.run_sweep(
        tegrasp_drake.SweepSpec(objects=("box",), controllers=("open_loop",), attempts=1,
                                grid=((0.0, 0.0),), base_seed=SEED),
        tegrasp_drake.run_trial_from_spec, file, workers=1, progress=False),
    lambda file: tegrasp_drake.save_memorized_events(file, []),
])
def test_a_file_given_as_an_output_folder_is_named_as_a_file(tmp_path, call):
    file = tmp_path / "good.npz"
    file.write_bytes(b"PK")
    with pytest.raises(files.UserPathError) as refused:
        call(file)
    assert "is a file, not a folder" in _one_line(refused.value)
    assert "good.npz" in str(refused.value)


@pytest.mark.parametrize("config, field", [
    (dict(sa_threshold=math.nan), "sa_threshold"),
    (dict(sa_threshold=2.0), "sa_threshold"),
    (dict(sa_threshold="0.9"), "sa_threshold"),
    (dict(event_thresholds={"reach_load": (math.nan, 0.5)}), "event_thresholds"),
])
def test_a_matcher_config_out_of_range_is_refused_where_it_is_used(config, field):
    events = tegrasp_drake.load_memorized_events(paths.package_events_dir(), "box")
    with pytest.raises((ConfigError, TypeError)) as refused:
        tegrasp_drake.EventMatcher(events, tegrasp_drake.EventMatcherConfig(**config))
    assert f"field '{field}" in _one_line(refused.value)


def test_events_given_as_a_list_are_named():
    with pytest.raises(TypeError) as refused:
        tegrasp_drake.EventMatcher(events=[1, 2])
    assert "EventMatcher: argument 'events' must be Mapping" in _one_line(refused.value)


@pytest.mark.parametrize("fields, field", [
    (dict(sa_rate_hz=math.inf), "sa_rate_hz"),
    (dict(window_s=-0.5), "window_s"),
    (dict(object_name=5), "object_name"),
])
def test_a_memorized_event_names_its_wrong_field(fields, field):
    arguments = dict(object_name="box", transition="reach_load", sa=np.ones((2, 54)),
                     ra=np.ones((2, 500)), sa_rate_hz=108.0, ra_rate_hz=1000.0)
    with pytest.raises((ConfigError, TypeError)) as refused:
        tegrasp_drake.MemorizedEvent(**{**arguments, **fields})
    assert f"field '{field}'" in _one_line(refused.value)


@pytest.mark.parametrize("trial, words", [
    ({}, "lacks trial_id"),
    ({"object": "teapot", "controller": "open_loop", "seed": SEED}, "object='teapot'"),
])
def test_a_trial_spec_that_is_not_one_names_its_keys(trial, words):
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.run_trial_from_spec(trial)
    assert "argument 'trial'" in _one_line(refused.value) and words in str(refused.value)


PUBLIC_FUNCTIONS = [name for name in tegrasp_drake.__all__
                    if callable(getattr(tegrasp_drake, name))
                    and not isinstance(getattr(tegrasp_drake, name), type)]


def _scalar_types(hint) -> set:
    hint = typing.get_args(hint)[0] if typing.get_origin(hint) is typing.Annotated else hint
    members = typing.get_args(hint) if typing.get_origin(hint) in (
        typing.Union, __import__("types").UnionType) else (hint,)
    return {m for m in members if m in (int, float)}


@pytest.mark.parametrize("name", PUBLIC_FUNCTIONS)
def test_every_numeric_argument_of_a_public_function_declares_its_range(name):
    hints = typing.get_type_hints(getattr(tegrasp_drake, name), include_extras=True)
    for argument, hint in hints.items():
        if argument == "return" or not _scalar_types(hint):
            continue
        metadata = getattr(hint, "__metadata__", ())
        assert any(isinstance(m, Range) for m in metadata), (
            f"{name}: annotate '{argument}' as Annotated[..., Range(...)]")


@pytest.mark.parametrize("name, argument", [
    ("load_records", "out_dir"), ("write_reports", "out_dir"), ("run_sweep", "out_dir"),
    ("save_memorized_events", "events_dir"), ("run_trial_from_spec", "log_dir"),
])
def test_every_folder_a_public_function_reads_or_writes_declares_what_it_must_be(name,
                                                                                  argument):
    hint = typing.get_type_hints(getattr(tegrasp_drake, name), include_extras=True)[argument]
    assert any(isinstance(m, Folder) for m in getattr(hint, "__metadata__", ()))


# --- 3. files and the command line -------------------------------------------------------------

def _events_copy(tmp_path) -> pathlib.Path:
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("prismatic", "ensemble", "corrective"))
    return folder


def test_an_event_sample_no_float_holds_is_refused_naming_the_file(tmp_path):
    folder = _events_copy(tmp_path)
    path = folder / "box" / "load_lift.json"
    data = json.loads(path.read_text())
    text = json.dumps(data).replace(json.dumps(data["samples"]["sa_left"][0]), "9" * 5000, 1)
    path.write_text(text)
    with pytest.raises(MemorizedEventError) as refused:
        tegrasp_drake.load_memorized_events(folder, "box")
    assert "load_lift.json" in _one_line(refused.value) and "5000 digits" in str(refused.value)


def test_an_index_holding_nan_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    index = folder / "index.json"
    index.write_text(index.read_text().replace("{", '{"x_nan": NaN, ', 1))
    with pytest.raises(MemorizedEventError) as refused:
        tegrasp_drake.load_memorized_events(folder, "box")
    assert "index.json" in _one_line(refused.value) and "NaN" in str(refused.value)


def test_the_json_reader_refuses_what_json_has_not():
    for text in ('{"a": NaN}', '{"a": Infinity}', '{"a": -Infinity}', '[' + "1" * 400 + ']'):
        with pytest.raises(files.JsonValueError):
            files.load_json(text)
    assert files.load_json('{"a": 1e300, "b": 12}') == {"a": 1e300, "b": 12}


@pytest.mark.parametrize("kind, words", [
    ("fifo", "is a named pipe"), ("folder", "is a folder"), ("device", "is a device")])
def test_an_object_file_that_is_not_a_file_says_what_it_is(tmp_path, kind, words):
    path = {"folder": tmp_path, "device": pathlib.Path("/dev/zero")}.get(kind)
    if kind == "fifo":
        path = tmp_path / "objfile.sdf"
        os.mkfifo(path)
    overrides = ["object.name=zz", "object.shape=file", "object.size=[0.05, 0.05, 0.1]",
                 f"object.file={path}", "object.mass=0.1", "object.friction=0.5"]
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.LoadScenario(name="box", overrides=overrides)
    assert "'object.file'" in _one_line(refused.value) and words in str(refused.value)
    assert "does not exist" not in str(refused.value)


def _small_trial_log(path, channels: int) -> pathlib.Path:
    n = 4
    times = np.arange(n) * 0.01
    shapes = {"taxels": 24, "true_taxels": 24, "channels": channels, "pad_acceleration": 6,
              "arm_q": 6, "arm_q_desired": 6, "gripper_command": 3, "gripper_status": 8,
              "object_state": 13}
    arrays = {name: np.zeros((n, shapes[name])) if name in shapes else times
              for name in ARRAY_FIELDS}
    arrays["phase"] = np.zeros(n)
    arrays["object_state"][:, 0] = 1.0  # the identity orientation, a unit quaternion
    for name in ("arm_q", "arm_q_desired"):  # joints 2 and 3 within the JACO2's limits
        arrays[name][:, 1:3] = [3.0, 1.0]
    return TrialLog(meta={"controller": "memorized"}, **arrays).save(path)


def test_a_trial_log_the_plots_refuse_is_not_streamed_either(tmp_path):
    path = _small_trial_log(tmp_path / "trial.npz", channels=3)
    with pytest.raises(ValueError, match="'channels' has shape"):
        load_trial_log(path)
    with pytest.raises(TactileRecordingError) as refused:
        load_tactile_recording(path)
    assert "'channels' has shape" in _one_line(refused.value)
    assert load_tactile_recording(_small_trial_log(tmp_path / "ok.npz", channels=4))


def test_an_empty_object_name_is_refused_not_taken_as_none(capfd):
    code, text = run_cli(["replay", "run.lcmlog", "--object", ""], capfd)
    assert code == 2 and "--object '' is empty" in text and "Traceback" not in text


@pytest.mark.parametrize("device, option", [
    ("jaco", ["--sync", "follow"]), ("robotiq", ["--trial", "trial.npz"]),
    ("jaco", ["--follow-gripper"]), ("myrio", ["--inject-fault", "0x0E@3"])])
def test_an_emulate_option_the_device_does_not_use_is_refused(device, option, capfd):
    code, text = run_cli(["emulate", device, *option, "--scheduling", "normal"], capfd)
    assert_one_line_error(code, text, option[0], "does not use it")
