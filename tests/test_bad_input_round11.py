"""Bad inputs the eleventh review found, one test per rule: each stops with one line that
names the input and what to do, a non-zero exit, and nothing lost."""

import ast
import errno
import io
import pathlib
import re
import sys

import pytest

import tegrasp_drake
import tegrasp_drake as T
from tegrasp_drake.commands import output_streams
from tegrasp_drake.commands.progress import SimulatedTimeBar
from tegrasp_drake.hardware.robotiq.modbus_client import (RobotiqActivationError,
                                                          RobotiqModbusClient,
                                                          RobotiqModbusConfig)
from tegrasp_drake.rig.ranges import field_range
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.runs.ideal_grasp import run_ideal_grasp
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
from tegrasp_drake.simulation.station import ArmDriverConfig, initial_arm_positions
from tegrasp_drake.sweep.spec import RandomisationConfig, SweepSpec, validate_spec
from tests.cheap_contact import CHEAP_CONTACT
from tests.test_bad_input import assert_one_line_error, run_probe
from tests.test_bad_input_round10 import _refused
from tests.test_bad_input_round2 import _trial_log_with


_BOX = scenario_to_yaml(LoadScenario(name="box"))


# Rule: every metadata field of a trial log that a reader uses has one declared form
# (trial_log_file.META_FIELDS), checked when the log is read: a number where names belong,
# a map of times that holds text, a result that is not one, is refused naming the file and
# the field; a log without the scenario the figures need is refused as such.
@pytest.mark.parametrize("meta, words", [
    ({"phases": [1, 2, 3]}, "meta 'phases' must be a non-empty list of names"),
    ({"controller": 5}, "meta 'controller' must be a controller name, one of memorized"),
    ({"scenario": 5}, "meta 'scenario' must be the scenario's YAML text"),
    ({"campaign_run": ["a"]}, "meta 'campaign_run' must be"),
    ({"events": 5}, "meta 'events' must map event names to times [s]"),
    ({"events": {"reach_load": "soon"}}, "meta 'events' must map event names to times [s]"),
    ({"result": [1]}, "meta 'result' must be a trial result's JSON form"),
    ({"result": {"final_mode": 3}, "scenario": _BOX}, "'result' is not a trial result's JSON form"),
    ({}, "its metadata has no 'scenario'"),
])
def test_a_trial_log_metadata_field_of_the_wrong_form_is_refused_naming_it(
        meta, words, tmp_path, monkeypatch, capfd):
    make = lambda folder: _trial_log_with(folder / "t.npz", meta)  # noqa: E731
    before, _, code, text = run_probe(make, ["plot", "trial", "t.npz", "--out", "x.png"],
                                      tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, "trial log 't.npz'", words)
    assert not (tmp_path / "x.png").exists()


# Rule: every number a message shows is written by rig.number_text (or a format spec), so
# none prints 3.997943786001997 where the others print 3.99794. Each message f-string of the
# package (raised, printed, an error's text) is read, and a value with a unit in its name
# (period_s, rate_hz, timeout, ...) or computed by arithmetic must not be formatted bare.
_UNIT_NAME = re.compile(r"(_s|_hz|_m|_n|_mps2|_rad|_mm|_kg|timeout|time_step|period|rate)$")
_MESSAGE_CALLS = ("print", "SystemExit", "warn")


def _message_fstrings(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.Raise) and node.exc is not None:
            yield node.exc
        elif isinstance(node, ast.Call):
            name = getattr(node.func, "id", None) or getattr(node.func, "attr", "")
            if name in _MESSAGE_CALLS or name.endswith("Error"):
                yield node


def _bare_float(value: ast.expr) -> bool:
    """Whether `value` is a number that needs rounding: a name with a unit, or a division."""
    if isinstance(value, ast.BinOp):
        return (isinstance(value.op, ast.Div) or _bare_float(value.left)
                or _bare_float(value.right))
    name = getattr(value, "attr", None) or getattr(value, "id", "")
    return bool(_UNIT_NAME.search(name))


def test_every_number_a_message_shows_is_rounded_by_one_formatter():
    package = pathlib.Path(tegrasp_drake.__file__).parent
    bare = set()  # a raised error's call is walked twice
    for path in sorted(package.rglob("*.py")):
        source = path.read_text()
        for message in _message_fstrings(ast.parse(source)):
            for part in ast.walk(message):
                if (isinstance(part, ast.FormattedValue) and part.format_spec is None
                        and part.conversion == -1 and _bare_float(part.value)):
                    bare.add(f"{path.relative_to(package)}:{part.lineno}: "
                             f"{ast.get_source_segment(source, part.value)}")
    assert not bare, sorted(bare)


def test_a_gripper_that_does_not_activate_says_so_with_a_rounded_time():
    client = RobotiqModbusClient(RobotiqModbusConfig(port="/dev/tegrasp-no-such-port"))
    with pytest.raises(RobotiqActivationError) as refused:
        client.wait_until_active(0.0123456789)  # never started: it waits out the timeout
    assert "not active after 0.0123457 s" in str(refused.value), refused.value


# Rule: a field with a declared range is checked by that declaration alone: a sweep spec's
# number below its range and one above it are refused in the same words (the Range's), not
# by a hand-written check beside it with other words.
@pytest.mark.parametrize("owner, field", [
    ("spec", "attempts"), ("spec", "base_seed"),
    ("randomisation", "placement_xy_bound_m"), ("randomisation", "placement_yaw_bound_deg"),
    ("randomisation", "friction_scale_bound"), ("randomisation", "mass_scale_bound"),
])
def test_a_sweep_spec_field_is_refused_in_its_declared_range_words(owner, field):
    owner_class = SweepSpec if owner == "spec" else RandomisationConfig
    declared = field_range(owner_class, field)
    ends = (declared.low - 1, None if declared.high is None else declared.high + 1)
    for value in (end for end in ends if end is not None):
        value = type(getattr(owner_class(), field))(value)
        if owner == "spec":
            spec = SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                             **{field: value})
            where = field
        else:
            spec = SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                             randomisation=RandomisationConfig(**{field: value}))
            where = f"randomisation.{field}"
        _refused(lambda: validate_spec(spec), f"field '{where}' {declared.words(value)}")


# Rule: the progress bar is decoration: a terminal that refuses it (hung up: EIO; closed)
# while Drake's monitor draws it stops the bar, not the simulation; a refused write is
# remembered for the command's end (output_streams), as every failed write is.
class _RefusingTerminal(io.StringIO):
    """A terminal that takes the first `accepted` writes, then refuses with `error`."""

    def __init__(self, error: Exception, accepted: int = 0):
        super().__init__()
        self._error, self._accepted = error, accepted

    def isatty(self):
        return True

    def write(self, text):
        if self._accepted <= 0:
            raise self._error
        self._accepted -= 1
        return super().write(text)


@pytest.mark.parametrize("error, remembered", [
    (OSError(errno.EIO, "Input/output error"), True),  # a terminal hung up
    (OSError(errno.ENOSPC, "No space left on device"), True),
    (ValueError("I/O operation on closed file."), False),
    (BrokenPipeError(errno.EPIPE, "Broken pipe"), False),  # the command line ends quietly
])
@pytest.mark.parametrize("accepted", [0, 3])  # refused at the first draw, or mid-run
def test_a_progress_bar_that_cannot_be_drawn_does_not_stop_the_simulation(
        error, remembered, accepted, monkeypatch):
    scenario = LoadScenario(name="box", overrides=list(CHEAP_CONTACT))
    monkeypatch.setattr(sys, "stderr", _RefusingTerminal(error, accepted))
    with output_streams.guarded_output():  # as the command line runs: the bar on its stderr
        with SimulatedTimeBar("ideal grasp", enabled=True) as progress:
            log, _ = run_ideal_grasp(scenario, duration=1.1, progress=progress)
        failures = output_streams.unwritable_output()
    assert log.t_ra[-1] > 1.09  # the whole 1.1 s simulated (5 draws of the bar)
    assert (failures is not None) == remembered, failures
    if remembered:
        assert failures[0] == output_streams.STANDARD_ERROR


# Rule: a choice of controller (`--controller`, LoadScenario(controller=...)) replaces the
# scenario's controller tag and drops the other controllers' settings only after the section
# as written is checked: its form (a mapping, a known tag) and each setting against the
# controller that has it, type and range, as a load without the choice checks them.
@pytest.mark.parametrize("text, overrides, words", [
    ("default: {object: {name: box}, controller: memorized}\n", [],
     "field 'controller' must be a mapping of fields, got str 'memorized'"),
    ("default: {object: {name: box}, controller: !Bogus {}}\n", [],
     "field 'controller': unknown tag !Bogus"),
    ("default: {}\n", ["controller.matching.sa_threshold=abc"],
     "field 'controller.matching.sa_threshold' must be a finite number"),
    ("default: {}\n", ["controller.re_reach.max_re_reaches=-1"],
     "field 'controller.re_reach.max_re_reaches' must be zero or positive"),
    ("default: {}\n", ["controller.update_period_s=0.0"],
     "field 'controller.update_period_s' must be positive"),
])
def test_a_choice_of_controller_checks_the_controller_section_as_written(
        tmp_path, text, overrides, words):
    path = tmp_path / "s.yaml"
    path.write_text(text)
    for controller in ("open_loop", "heuristic"):
        _refused(lambda: LoadScenario(path, overrides=overrides, controller=controller),
                 str(path), words)
    ignored = []
    LoadScenario(overrides=["controller.matching.sa_threshold=0.5"], controller="heuristic",
                 on_ignored=ignored.extend)  # a good setting of another controller: dropped
    assert ignored == ["matching.sa_threshold"]


# Rule: a setting a solver decides (the arm's start, reached by inverse kinematics) is
# checked with the others when the scenario is loaded: out of reach, it is refused naming
# the field, before anything is built; a builder given one says the same.
def test_a_start_the_arm_cannot_reach_is_refused_naming_the_field():
    unreachable = "arm.initial_gripper_xyz=[0.69, 0.0, -0.5]"  # 0.5 m under the table
    _refused(lambda: LoadScenario(overrides=[unreachable]), "field 'arm.initial_gripper_xyz'",
             "must be a point the JACO2 reaches")
    arm = ArmDriverConfig(initial_gripper_xyz=[0.69, 0.0, -0.5])
    _refused(lambda: initial_arm_positions(arm), "field 'arm.initial_gripper_xyz'")
    assert initial_arm_positions(ArmDriverConfig()).shape == (6,)


# Rule: a config class says what relates its fields (Scenario.check_relations: validate), and
# the public API checks it on every argument of that class (rig/api_boundary.RELATIONS_CHECK),
# so a scenario changed after loading is refused by any public function, not only builders.
def _changed(field: str, value) -> T.Scenario:
    scenario = LoadScenario(overrides=["random_seed=632"])
    owner, name = field.split(".")
    setattr(getattr(scenario, owner), name, value)
    return scenario


@pytest.mark.parametrize("field, value, words", [
    ("object.size", [1.0], "must hold 3 positive sizes"),
    ("gripper.model", "bogus", "must be one of 'linkage', 'prismatic'"),
])
@pytest.mark.parametrize("function", ["grasp_plan", "scenario_to_yaml", "sample_rates_hz"])
def test_a_public_function_refuses_a_scenario_changed_out_of_its_relations(
        function, field, value, words):
    _refused(lambda: getattr(T, function)(_changed(field, value)), f"{function}:",
             f"field '{field}'", words)


def test_every_public_function_that_takes_a_scenario_checks_its_arguments():
    import inspect
    import typing
    takes_scenario = []
    for name in T.__all__:
        function = getattr(T, name)
        if not inspect.isfunction(function):
            continue
        hints = typing.get_type_hints(getattr(function, "__wrapped__", function))
        if any(T.Scenario in (hint, *typing.get_args(hint)) for hint in hints.values()):
            takes_scenario.append(name)
            assert getattr(function, "__checked_arguments__", False), name
    assert {"grasp_plan", "MakeGraspDiagram", "run_trial"} <= set(takes_scenario)
    assert hasattr(T.Scenario, "check_relations")


# Rule: every configuration file the package reads is refused without a field (empty,
# comments only, `{}`, null), as the sweep spec and the hardware config already were: the
# sensitivity and transfer specs too, which otherwise started the whole study.
@pytest.mark.parametrize("text", ["", "# my study\n", "{}\n", "~\n"])
@pytest.mark.parametrize("loader, what", [
    ("tegrasp_drake.sensitivity.study:LoadSensitivitySpec", "the sensitivity spec"),
    ("tegrasp_drake.transfer.matrix:LoadTransferSpec", "the transfer spec"),
    ("tegrasp_drake.sweep.spec_file:LoadSweepSpec", "the sweep spec"),
    ("tegrasp_drake.hardware.config:LoadHardwareConfig", "the hardware config"),
])
def test_a_configuration_file_without_a_field_is_refused(tmp_path, text, loader, what):
    import importlib
    module, name = loader.split(":")
    path = tmp_path / "config.yaml"
    path.write_text(text)
    _refused(lambda: getattr(importlib.import_module(module), name)(path), str(path),
             f"{what} is empty (no fields)")


# Rule: a quoted number is text in every section, Drake's config structs too (whose own
# loader would read '0.5' as 0.5): a numeric or true/false field of SimulatorConfig or
# MultibodyPlantConfig refuses text as a field of ours does.
@pytest.mark.parametrize("assignment, words", [
    ("simulator_config.accuracy='0.5'", "must be a finite number, got str '0.5'"),
    ("simulator_config.accuracy=!!str 0.5", "must be a finite number, got str '0.5'"),
    ("simulator_config.max_step_size='0.01'", "must be a finite number"),
    ("simulator_config.target_realtime_rate='1'", "must be a finite number"),
    ("plant_config.sap_near_rigid_threshold='1.0'", "must be a finite number"),
    ("simulator_config.publish_every_time_step='true'", "must be true or false"),
])
def test_a_quoted_number_is_text_in_drakes_config_sections_too(assignment, words):
    field = assignment.split("=")[0]
    _refused(lambda: LoadScenario(overrides=[assignment]), f"field '{field}'", words)
    LoadScenario(overrides=[assignment.replace("'", "").replace("!!str ", "")])


# Rule: an object's name given to a public function names a folder, as a scenario's
# object.name does: record_events declares OBJECT_NAME on its argument, checked at the call,
# so '' or '../x' is refused before an ideal grasp is simulated (load_memorized_events says
# so in its own words, with what to record instead).
@pytest.mark.parametrize("name", ["", "../x", "a b"])
def test_an_object_name_argument_is_refused_unless_it_names_a_folder(tmp_path, name):
    scenario = LoadScenario(overrides=["random_seed=633"])
    with pytest.raises(ValueError, match="argument 'object_name' must be letters, digits"):
        T.record_events(name, scenario)  # at once: no ideal grasp simulated


# Rule: the arguments a command binds to a public function for later calls (a sweep's trial
# function, called in its workers) are checked when bound (api_boundary.bound_arguments), so
# a missing --events folder is one line before any trial, not an error record per trial.
def test_a_sweep_with_a_missing_events_folder_stops_before_any_trial(tmp_path, monkeypatch,
                                                                     capfd):
    argv = ["sweep", "--objects", "box", "--controllers", "open_loop", "--base-seed", "640",
            "--attempts", "1", "--workers", "1", "--out", "sw", "--events", "missing",
            "--no-progress"]
    _, _, code, text = run_probe(None, argv, tmp_path, monkeypatch, capfd)
    assert_one_line_error(code, text, "--events missing: does not exist; give an existing folder")
    assert not (tmp_path / "sw" / "trials").exists()


# Rule: an object's name is bounded where it is declared (rig/objects.OBJECT_NAME_PATTERN):
# it names a folder and is part of file names, so 300 characters are refused at load, not
# after minutes of simulation when the folder cannot be made.
def test_an_object_name_longer_than_a_folder_name_should_be_is_refused_at_load():
    own = ["object.shape=box", "object.size=[0.04, 0.04, 0.1]", "object.mass=0.1",
           "object.friction=0.5"]
    with pytest.raises(ConfigError) as refused:  # its --set echoes make it long: no _refused
        LoadScenario(overrides=["object.name=" + "a" * 300, *own])
    assert "\n" not in str(refused.value)
    assert "field 'object.name'" in str(refused.value)
    assert "at most 64 characters" in str(refused.value)
    assert LoadScenario(overrides=["object.name=" + "a" * 64, *own]).object.name == "a" * 64
    with pytest.raises(ValueError, match="at most 64 characters"):
        T.record_events("a" * 65, LoadScenario(overrides=["random_seed=633"]))
