"""Property-based fuzzing (Hypothesis) of every parser and loader: any input gives a value
or the module's own one-line error, never another exception, and a crafted input cannot make
a reader hold more than a bound.

Inputs: scenario YAML files and `--set` assignments, sweep, transfer and sensitivity specs,
hardware configs, memorized event files and their index, trial logs (.npz), LCM run logs,
the myRIO's serial frames and the Robotiq's Modbus replies. Each comes both as raw bytes or
text and as a mutation of a well-formed example, which reaches the checks past the parser.

The examples are bounded for CI (the whole module about a minute on a loaded 2-core host);
`TEGRASP_FUZZ=long python -m pytest -p no:cacheprovider tests/test_fuzz_inputs.py` runs
50 times as many. No test here measures time (deadline=None).
"""

import dataclasses
import functools
import io
import json
import os
import pathlib
import struct
import tempfile
import tracemalloc
import types
import typing
import zipfile

import numpy as np
import numpy.lib.format as npy_format
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator, SimulatorConfig
from pydrake.systems.framework import DiagramBuilder

from tests.bad_input.probes import memorized_events, trial_log
from tegrasp_drake.events.event_file import MemorizedEventError
from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
from tegrasp_drake.events.transitions import REQUIRED_TRANSITIONS
from tegrasp_drake.hardware.config import HardwareStationConfig, LoadHardwareConfig
from tegrasp_drake.hardware.myrio.tactile_frame import (MAX_FRAME_SIZE, TactileFrameDecoder,
                                                        encode_frame)
from tegrasp_drake.rig.ranges import declared_ranges
from tegrasp_drake.rig.typed_yaml import ConfigError, apply_override
from tegrasp_drake.robotiq import registers
from tegrasp_drake.runs.hardware_log_reader import (LCM_SYNC, MESSAGE_TYPES, RunLogError,
                                                    read_run_log, scan_lcm_log)
from tegrasp_drake.scenario.scenario import LoadScenario, Scenario
from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
from tegrasp_drake.sweep.spec import SweepSpec
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
from tegrasp_drake.transfer.matrix import LoadTransferSpec

LONG = os.environ.get("TEGRASP_FUZZ") == "long"


def fuzz(examples: int):
    """Hypothesis settings: `examples` in CI, 50 times as many in the long mode."""
    return settings(max_examples=examples * (50 if LONG else 1), deadline=None,
                    derandomize=not LONG, database=None,
                    suppress_health_check=[HealthCheck.too_slow,
                                           HealthCheck.function_scoped_fixture,
                                           HealthCheck.data_too_large])


# --- strategies -------------------------------------------------------------------------------

SCALARS = (st.none() | st.booleans() | st.integers(min_value=-2**70, max_value=2**70)
           | st.floats(allow_nan=True, allow_infinity=True) | st.text(max_size=12))
YAML_VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=4)
                           | st.dictionaries(st.text(max_size=8), inner, max_size=4),
                           max_leaves=12)


def _plausible(hint):
    """Values of the schema's own type (and its neighbours), to get past the type checks."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        return st.one_of([_plausible(m) for m in typing.get_args(hint)])
    if origin in (list, tuple):
        return st.lists(_plausible(typing.get_args(hint)[0]), max_size=4)
    if hint is float:
        return st.floats(allow_nan=False, allow_infinity=False, width=32) | st.sampled_from(
            [0.0, -1.0, 1e9, -1e9, 1e-12, 1e300])
    if hint is int:
        return st.integers(min_value=-2**40, max_value=2**40) | st.sampled_from([0, -1])
    if hint is bool:
        return st.booleans()
    if hint is str:
        return st.text(max_size=12) | st.sampled_from(["", "box", "file", "linkage", "fifo"])
    if hint is type(None):
        return st.none()
    if dataclasses.is_dataclass(hint):
        return schema_shaped(hint)
    return YAML_VALUES


def schema_shaped(schema, depth: int = 0):
    """Mappings with (some of) the fields of dataclass `schema`, each a plausible value or
    any YAML value; unknown keys now and then."""
    if depth > 2:
        return YAML_VALUES
    hints = typing.get_type_hints(schema)
    optional = {f.name: (_plausible(hints[f.name]) if not dataclasses.is_dataclass(
        hints[f.name]) else schema_shaped(hints[f.name], depth + 1)) | YAML_VALUES
        for f in dataclasses.fields(schema)}
    return st.fixed_dictionaries({}, optional=optional) | st.dictionaries(
        st.text(max_size=8), YAML_VALUES, max_size=3)


def yaml_text(data) -> str:
    return yaml.safe_dump(data, allow_unicode=True)


RAW_TEXT = st.text(max_size=300) | st.binary(max_size=300).map(
    lambda b: b.decode("latin-1"))
YAML_SNIPPETS = st.lists(st.sampled_from([
    "a: &x [1, 2]\n", "b: *x\n", "c: !!python/object/apply:os.system [ls]\n", "d: {e: 1\n",
    "'\n", "f: 1\nf: 2\n", "- 1\n", "g: .nan\n", "h: !HardwareStationConfig {}\n", "\t\n",
    "i: [" * 30 + "\n", "%YAML 1.1\n---\n", "--- !!binary |\n  AAAA\n", "<<: *x\n"]),
    max_size=5).map("".join)


@pytest.fixture(scope="module")
def folder():
    with tempfile.TemporaryDirectory() as path:
        yield pathlib.Path(path)


def _file(folder, name, content) -> pathlib.Path:
    path = folder / name
    path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8",
                                                                              "surrogatepass"))
    return path


# --- configuration files ----------------------------------------------------------------------

@fuzz(60)
@given(data=st.one_of(schema_shaped(Scenario).map(yaml_text), RAW_TEXT, YAML_SNIPPETS))
def test_any_scenario_file_loads_or_is_one_config_error(data, folder):
    path = _file(folder, "scenario.yaml", "fuzz:\n" + "\n".join(
        "  " + line for line in data.splitlines()) + "\n")
    try:
        assert isinstance(LoadScenario(path, "fuzz"), Scenario)
    except ConfigError as error:
        assert "\n" not in str(error)
    path = _file(folder, "raw.yaml", data)
    try:
        LoadScenario(path, "fuzz")
    except ConfigError as error:
        assert "\n" not in str(error)


FIELD_PATHS = ["object.mass", "object.size", "object.name", "object.shape", "grasp.hold_s",
               "placement.offset", "random_seed", "controller.name", "plant_config.time_step",
               "tactile.sample_rate_hz", "disturbance.hit_force_n", "station", "gripper.model",
               "controller.matching.sa_threshold", "vibration.film.mode_frequency_hz", "object"]


@fuzz(80)
@given(key=st.sampled_from(FIELD_PATHS) | st.text(max_size=20),
       value=st.text(max_size=40) | YAML_VALUES.map(lambda v: json.dumps(v)[:60]))
def test_any_set_assignment_loads_or_is_one_config_error(key, value):
    try:
        assert isinstance(LoadScenario(name="box", overrides=[f"{key}={value}"]), Scenario)
    except ConfigError as error:
        assert "\n" not in str(error)


NUMBER_PATHS = ["object.mass", "object.friction", "grasp.hold_s", "grasp.grip_force",
                "grasp.grasp_height", "random_seed", "vibration.highpass_cutoff_hz",
                "controller.lift_load.slip_band_hz", "plant_config.stiction_tolerance",
                "simulator_config.start_time"]


@fuzz(60)
@given(key=st.sampled_from(NUMBER_PATHS), value=SCALARS)
def test_a_set_number_runs_as_given_or_is_one_config_error(key, value):
    """A scenario never runs with a value other than the one given: a null, text or a number
    out of range is refused, never replaced by a default."""
    text = yaml.safe_dump(value, default_flow_style=True).removesuffix("\n...\n").strip()
    try:
        scenario = LoadScenario(name="box", overrides=[f"{key}={text}"])
    except ConfigError as error:
        assert "\n" not in str(error)
        return
    loaded = functools.reduce(getattr, key.split("."), scenario)
    assert isinstance(value, (int, float)) and not isinstance(value, bool)
    assert loaded == value


DRAKE_FIELD_PATHS = [f"{section}.{name}" for section, cls in (
    ("plant_config", MultibodyPlantConfig), ("simulator_config", SimulatorConfig))
    for name in declared_ranges(cls)]


@fuzz(80)
@given(key=st.sampled_from(DRAKE_FIELD_PATHS),
       value=st.text(max_size=20) | YAML_VALUES.map(lambda v: json.dumps(v)[:60])
       | st.floats(width=32).map(repr))
def test_any_set_of_a_drake_setting_builds_or_is_one_config_error(key, value):
    """Drake's own config sections: a --set of any value for any of their fields gives a
    scenario Drake accepts (a plant and a simulator configured from it, no abort), or one
    ConfigError naming the field."""
    try:
        scenario = LoadScenario(name="box", overrides=[f"{key}={value}"])
    except ConfigError as error:
        assert "\n" not in str(error)
        assert f"'{key}" in str(error) or key.split(".")[0] in str(error)
        return
    builder = DiagramBuilder()
    AddMultibodyPlant(scenario.plant_config, builder)[0].Finalize()
    ApplySimulatorConfig(scenario.simulator_config, Simulator(builder.Build()))


@fuzz(40)
@given(assignment=st.text(max_size=40), data=YAML_VALUES)
def test_apply_override_changes_data_or_is_one_config_error(assignment, data):
    try:
        apply_override(data, assignment)
    except ConfigError as error:
        assert "\n" not in str(error)


@fuzz(50)
@given(data=st.one_of(schema_shaped(SweepSpec).map(yaml_text), RAW_TEXT, YAML_SNIPPETS))
def test_any_sweep_spec_loads_or_is_one_config_error(data, folder):
    try:
        assert isinstance(LoadSweepSpec(_file(folder, "spec.yaml", data)), SweepSpec)
    except ConfigError as error:
        assert "\n" not in str(error)


TRANSFER_SHAPED = st.fixed_dictionaries({}, optional={
    "worlds": st.dictionaries(st.sampled_from(["a", "b", "bad name", ""]),
                              st.fixed_dictionaries({}, optional={
                                  "scenario": st.sampled_from(["memorizing_world", "x"])
                                  | YAML_VALUES,
                                  "overrides": st.lists(st.text(max_size=20), max_size=3)
                                  | YAML_VALUES}) | YAML_VALUES, max_size=3),
    "cells": st.lists(st.lists(st.sampled_from(["a", "b", "c"]), max_size=3), max_size=3)
    | YAML_VALUES,
    "sweep": schema_shaped(SweepSpec)})


@fuzz(40)
@given(data=st.one_of(TRANSFER_SHAPED.map(yaml_text), RAW_TEXT, YAML_SNIPPETS))
def test_any_transfer_spec_loads_or_is_one_config_error(data, folder):
    try:
        LoadTransferSpec(_file(folder, "transfer.yaml", data))
    except ConfigError as error:
        assert "\n" not in str(error)


SENSITIVITY_SHAPED = st.fixed_dictionaries({}, optional={
    "parameters": st.lists(st.sampled_from(["gripper.screw_efficiency", "arm_command_latency_s",
                                            "object.size", ""]) | YAML_VALUES, max_size=3)
    | YAML_VALUES,
    "events": st.sampled_from(["each_point", "default_point", "x"]) | YAML_VALUES,
    "sweep": schema_shaped(SweepSpec)})


@fuzz(40)
@given(data=st.one_of(SENSITIVITY_SHAPED.map(yaml_text), RAW_TEXT, YAML_SNIPPETS))
def test_any_sensitivity_spec_loads_or_is_one_config_error(data, folder):
    try:
        LoadSensitivitySpec(_file(folder, "sensitivity.yaml", data))
    except ConfigError as error:
        assert "\n" not in str(error)


@fuzz(50)
@given(data=st.one_of(schema_shaped(HardwareStationConfig).map(yaml_text), RAW_TEXT,
                      YAML_SNIPPETS))
def test_any_hardware_config_loads_or_is_one_config_error(data, folder):
    try:
        assert isinstance(LoadHardwareConfig(_file(folder, "hw.yaml", data)),
                          HardwareStationConfig)
    except ConfigError as error:
        assert "\n" not in str(error)


# --- memorized events ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def events_folder(folder):
    path = folder / "events"
    save_memorized_events(path, memorized_events())
    return path


def _mutated_json(original: dict, draw_value, path: list):
    """`original` with the value at `path` (keys into nested mappings) replaced."""
    data = json.loads(json.dumps(original))
    node = data
    for key in path[:-1]:
        if not isinstance(node, dict) or key not in node:
            return data
        node = node[key]
    if isinstance(node, dict) and path:
        node[path[-1]] = draw_value
    return data


@fuzz(60)
@given(which=st.sampled_from(["index.json", "mine/reach_load.json"]),
       mode=st.sampled_from(["raw", "value", "samples"]),
       raw=st.binary(max_size=200), value=YAML_VALUES,
       key=st.sampled_from(["format", "format_version", "events", "object", "transition",
                            "sa_rate_hz", "ra_rate_hz", "samples", "window_s", "description"]),
       channel=st.sampled_from(["sa_left", "sa_right", "ra_left", "ra_right", "x"]))
def test_any_event_file_or_index_loads_or_is_one_memorized_event_error(
        which, mode, raw, value, key, channel, events_folder):
    path = events_folder / which
    original = path.read_bytes()
    try:
        if mode == "raw":
            path.write_bytes(raw)
        else:
            data = json.loads(original)
            keys = [key] if mode == "value" else ["samples", channel]
            path.write_text(json.dumps(_mutated_json(data, value, keys)))
        try:
            events = load_memorized_events(events_folder, "mine")
            assert set(events) >= set(REQUIRED_TRANSITIONS)
        except MemorizedEventError as error:
            assert "\n" not in str(error)
    finally:
        path.write_bytes(original)


# --- trial logs -----------------------------------------------------------------------------------

def _trial_log_bytes(**changes) -> bytes:
    """A well-formed trial log's bytes (trial_log of tests/bad_input/probes.py), with `changes`."""
    buffer = io.BytesIO()
    trial_log(buffer, **changes)
    return buffer.getvalue()


def _header_lie(shape, descr) -> bytes:
    """A trial log whose 'channels' header declares `shape` of `descr` over 64 bytes."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(_trial_log_bytes())) as source, \
            zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for info in source.infolist():
            if info.filename != "channels.npy":
                archive.writestr(info.filename, source.read(info))
                continue
            member = io.BytesIO()
            npy_format.write_array_header_1_0(member, {"descr": descr, "fortran_order": False,
                                                       "shape": shape})
            archive.writestr("channels.npy", member.getvalue() + bytes(64))
    return buffer.getvalue()


TRIAL_LOG_BYTES = st.one_of(
    st.binary(max_size=400),
    st.tuples(st.just(_trial_log_bytes()), st.integers(0, 5000), st.integers(0, 255)).map(
        lambda t: t[0][:t[1] % len(t[0])] + bytes([t[2]]) + t[0][t[1] % len(t[0]) + 1:]),
    st.integers(1, 200).map(lambda n: _trial_log_bytes()[:n * 25]),
    st.tuples(st.lists(st.integers(0, 2**40), min_size=0, max_size=3).map(tuple),
              st.sampled_from(["<f8", "|O", "<c16", "|b1", "<U4", "V8", "<i8"])).map(
        lambda t: _header_lie(*t)),
    st.sampled_from([_trial_log_bytes(channels=np.full((101, 4), np.nan)),
                     _trial_log_bytes(t_sa=np.zeros(11)),
                     _trial_log_bytes(t_sa=np.zeros(1), taxels=np.ones((1, 24)),
                                      true_taxels=np.ones((1, 24))),
                     _trial_log_bytes(phase=np.zeros((11, 2))),
                     _trial_log_bytes(channels=np.array(["a"] * 404).reshape(101, 4))]))


@fuzz(80)
@given(content=TRIAL_LOG_BYTES)
def test_any_trial_log_loads_or_is_one_trial_log_error_within_a_memory_bound(content, folder):
    path = _file(folder, "trial.npz", content)
    tracemalloc.start()
    try:
        load_trial_log(path)
    except TrialLogError as error:
        assert "\n" not in str(error)
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    assert peak < 64 * 2**20  # a few kB of file never costs more than this


# --- LCM run logs ---------------------------------------------------------------------------------

def _event(number, channel: bytes, data: bytes, timestamp=0) -> bytes:
    return struct.pack(">IqqII", LCM_SYNC, number, timestamp, len(channel), len(data)) + (
        channel + data)


LCM_EVENTS = st.lists(st.tuples(
    st.sampled_from([c.encode() for c in MESSAGE_TYPES]) | st.binary(max_size=8),
    st.binary(max_size=60), st.integers(-2**63, 2**63 - 1)), max_size=6)


@fuzz(80)
@given(events=LCM_EVENTS, cut=st.integers(0, 10_000), noise=st.binary(max_size=40),
       numbers=st.sampled_from(["sequential", "random"]))
def test_any_lcm_log_reads_or_is_one_run_log_error(events, cut, noise, numbers, folder):
    rng = np.random.default_rng(len(events))
    content = b"".join(_event(k if numbers == "sequential" else int(rng.integers(0, 2**62)),
                              channel, data, timestamp)
                       for k, (channel, data, timestamp) in enumerate(events))
    content = content[:cut] + noise + content[cut:]
    path = _file(folder, "run.lcmlog", content)
    scanned, damage = scan_lcm_log(path)
    assert all(isinstance(line, str) for line in damage)
    try:
        read_run_log(path)
    except RunLogError as error:
        assert "\n" not in str(error)


# --- the myRIO's serial frames -------------------------------------------------------------------

def _frame(sequence, flags):
    left = [sequence % 4096] * 12 if flags & 1 else None
    right = [4095 - sequence % 4096] * 12 if flags & 2 else None
    return encode_frame(sequence, sequence * 1000, (sequence % 100, -(sequence % 100)),
                        left, right)


@fuzz(80)
@given(chunks=st.lists(st.one_of(
    st.binary(max_size=80),
    st.tuples(st.integers(0, 70_000), st.integers(0, 3)).map(lambda t: _frame(*t)),
    st.tuples(st.integers(0, 70_000), st.integers(0, 3), st.integers(0, 40),
              st.integers(0, 255)).map(lambda t: _frame(t[0], t[1])[:t[2]] + bytes([t[3]])
                                       + _frame(t[0], t[1])[t[2] + 1:])), max_size=30))
def test_any_serial_stream_decodes_to_frames_within_a_bounded_buffer(chunks):
    decoder = TactileFrameDecoder()
    for k, chunk in enumerate(chunks):
        frames = decoder.feed(chunk, arrival_time=k * 1e-3)
        for frame in frames:
            assert np.all(np.isfinite(frame.left_counts if frame.left_counts is not None
                                      else 0))
        assert len(decoder._buffer) <= MAX_FRAME_SIZE + len(chunk)
    counters = decoder.counters
    assert counters.rejected >= 0 and counters.skipped_bytes >= 0


# --- the Robotiq's Modbus replies -------------------------------------------------------------------

class _Reply:
    def __init__(self, registers_, error):
        self.registers, self._error = registers_, error

    def isError(self):
        return self._error

    def __str__(self):
        return "an exception reply"


@fuzz(80)
@given(words=st.lists(st.integers(0, 0xFFFF), max_size=8), error=st.booleans(),
       raises=st.booleans())
def test_any_modbus_reply_is_a_status_or_a_counted_error(words, error, raises):
    from pymodbus.exceptions import ModbusIOException
    from tegrasp_drake.hardware.robotiq.modbus_client import (RobotiqModbusClient,
                                                              RobotiqModbusConfig)
    client = RobotiqModbusClient(RobotiqModbusConfig(port="/dev/null"))

    def read(*args, **kwargs):
        if raises:
            raise ModbusIOException("no reply")
        return _Reply(words, error)
    bus = types.SimpleNamespace(read_input_registers=read, read_holding_registers=read)
    sample = client._read(bus)
    if sample is None:
        assert (raises or error or len(words) != registers.REGISTER_COUNT
                or registers.status_contradiction(words) is not None)
    else:
        assert np.all(np.isfinite(sample.status))
