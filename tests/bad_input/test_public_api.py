"""The Python API checks what it is given: every public function and class checks every
argument (types, ranges, folders that must exist, the items of lists, the fields of
dataclasses) at the call and names the wrong one; value classes such as transitions and
results refuse fields no run makes; the API's ranges are the command line's."""

import dataclasses
import enum
import inspect
import os
import typing

import numpy as np
import pytest

import tegrasp_drake
import tegrasp_drake as T
from tegrasp_drake.rig.api_boundary import Folder
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.sweep.spec import SweepSpec
from tests.bad_input.probes import refusal


# --- the public API's boundary -------------------------------------------------------------------

PUBLIC_FUNCTIONS = [name for name in tegrasp_drake.__all__
                    if callable(getattr(tegrasp_drake, name))
                    and not isinstance(getattr(tegrasp_drake, name), type)]


@pytest.mark.parametrize("name", PUBLIC_FUNCTIONS)
def test_every_public_function_checks_every_argument(name):
    import inspect
    import typing
    function = getattr(tegrasp_drake, name)
    assert getattr(function, "__checked_arguments__", False), f"{name} lacks @public_api"
    hints = typing.get_type_hints(function)
    unannotated = [p for p in inspect.signature(function).parameters if p not in hints]
    assert not unannotated, f"{name}: annotate {unannotated} (typing.Any if any value goes)"


@pytest.mark.parametrize("call, words", [
    (lambda: tegrasp_drake.LoadScenario(name=None),
     "LoadScenario: argument 'name' must be str, got None"),
    (lambda: tegrasp_drake.LoadScenario(overrides="object.mass=1"),
     "argument 'overrides' must be a sequence of str (not a single string)"),
    (lambda: tegrasp_drake.LoadScenario(overrides=[b"object.mass=0.1"]),
     "LoadScenario: argument 'overrides[0]' must be str, got bytes b'object.mass=0.1'"),
    (lambda: tegrasp_drake.LoadHardwareConfig("hw.yaml", overrides=["a=1", b"x=1"]),
     "LoadHardwareConfig: argument 'overrides[1]' must be str, got bytes b'x=1'"),
    (lambda: tegrasp_drake.LoadSweepSpec("s.yaml", builtin_objects=[b"box"]),
     "LoadSweepSpec: argument 'builtin_objects[0]' must be str, got bytes b'box'"),
    (lambda: tegrasp_drake.MakeStation(None), "MakeStation: argument 'scenario' must be Scenario"),
    (lambda: tegrasp_drake.run_trial("box"), "run_trial: argument 'scenario' must be Scenario"),
    (lambda: tegrasp_drake.load_trial_log(None), "load_trial_log: argument 'path' must be str"),
    (lambda: tegrasp_drake.load_memorized_events("events", 5),
     "argument 'object_name' must be str, got int 5"),
    (lambda: tegrasp_drake.write_reports("out", "memorized/box/m00/a0"),
     "argument 'trial_ids' must be a sequence of str"),
    # a mapping where its items belong: its values when they are the items, not "a string"
    (lambda: tegrasp_drake.save_memorized_events("evs", tegrasp_drake.load_memorized_events(
        package_events_dir(), "box")), "argument 'events' must be an iterable of "
     "MemorizedEvent (not a mapping: give its values, list(d.values())), got dict"),
    (lambda: tegrasp_drake.LoadScenario(overrides={"object.mass": 1}),
     "argument 'overrides' must be a sequence of str (not a mapping), got dict"),
    (lambda: tegrasp_drake.write_reports("out", 5),
     "argument 'trial_ids' must be a sequence of str or None, got int 5"),
])
def test_a_wrong_argument_is_named_at_the_call(call, words):
    with pytest.raises(TypeError) as error:
        call()
    assert words in str(error.value)



def _probed_arguments(kind):
    """(function name, argument) of every public function whose argument takes no `kind`:
    "none" (None), "text" (a list, a sequence or a collection: a single string), "config"
    (a config class of the package: another config class)."""
    import collections.abc
    import types

    def members(hint):
        hint = getattr(hint, "__origin__", hint) if typing.get_origin(hint) is typing.Annotated \
            else hint
        if typing.get_origin(hint) in (typing.Union, types.UnionType):
            return [m for member in typing.get_args(hint) for m in members(member)]
        return [hint]
    collections_ = (list, tuple, collections.abc.Sequence, collections.abc.Collection,
                    collections.abc.Iterable)
    rows = []
    for name in PUBLIC_FUNCTIONS:
        function = getattr(tegrasp_drake, name)
        hints = typing.get_type_hints(function, include_extras=True)
        for argument, parameter in inspect.signature(function).parameters.items():
            if parameter.kind in (parameter.VAR_POSITIONAL, parameter.VAR_KEYWORD):
                continue
            hint_members = members(hints[argument])
            if any(m in (type(None), None, typing.Any, object) for m in hint_members):
                if kind == "none":
                    continue
            if kind == "none":
                rows.append((name, argument))
            elif kind == "text" and any(typing.get_origin(m) in collections_
                                        for m in hint_members) and str not in hint_members:
                rows.append((name, argument))
            elif kind == "config" and any(isinstance(m, type) and dataclasses.is_dataclass(m)
                                          and m is not SweepSpec for m in hint_members):
                rows.append((name, argument))
    return rows


# Rule: a public function given None, a single string for a list or a config of another
# class says, in one line, the function, the argument, what it must be and what was given in
# the user's words: "got None" (not "NoneType None"), "got str 'box'", "got a SweepSpec"
# (not the config's repr, which runs for lines).
@pytest.mark.parametrize("name, argument", _probed_arguments("none"))
def test_every_public_function_given_none_says_got_none(name, argument):
    with pytest.raises(TypeError) as raised:
        getattr(tegrasp_drake, name).bind_now(**{argument: None})
    message = str(raised.value)
    assert message.startswith(f"{name}: argument '{argument}' must be "), message
    assert message.endswith(", got None") and "\n" not in message, message


@pytest.mark.parametrize("name, argument", _probed_arguments("text"))
def test_every_public_function_given_one_string_for_a_list_names_it(name, argument):
    with pytest.raises(TypeError) as raised:
        getattr(tegrasp_drake, name).bind_now(**{argument: "box"})
    message = str(raised.value)
    assert message.startswith(f"{name}: argument '{argument}' must be "), message
    assert "(not a single string)" in message and message.endswith(", got str 'box'"), message


@pytest.mark.parametrize("name, argument", _probed_arguments("config"))
def test_every_public_function_given_another_config_names_its_class(name, argument):
    with pytest.raises(TypeError) as raised:
        getattr(tegrasp_drake, name).bind_now(**{argument: SweepSpec()})
    message = str(raised.value)
    assert message.startswith(f"{name}: argument '{argument}' must be "), message
    assert message.endswith(", got a SweepSpec") and "\n" not in message, message


def test_a_public_dataclass_given_none_for_a_field_says_got_none():
    with pytest.raises(TypeError, match=r"^Scenario: field 'random_seed' must be int, got None$"):
        T.Scenario(random_seed=None)
    with pytest.raises(TypeError, match=r"^Scenario: field 'object' must be an ObjectConfig "
                       r"\(e\.g\. ObjectConfig\(\.\.\.\)\), not its fields as a mapping or a "
                       r"name, got a SweepSpec$"):
        T.Scenario(object=SweepSpec())

PUBLIC_DATACLASSES = [name for name in tegrasp_drake.__all__
                      if dataclasses.is_dataclass(getattr(tegrasp_drake, name))]


@pytest.mark.parametrize("name", PUBLIC_DATACLASSES)
def test_every_public_dataclass_checks_its_collections(name):
    cls = getattr(tegrasp_drake, name)
    assert getattr(cls.__init__, "__checked_arguments__", False), f"{name} lacks @public_dataclass"


def test_a_public_function_checks_the_items_of_a_list(tmp_path):
    with pytest.raises(TypeError, match=r"save_memorized_events: argument 'events\[0\]' must "
                                        "be MemorizedEvent, got str 'not an event'"):
        tegrasp_drake.save_memorized_events(tmp_path, ["not an event"])
    assert not (tmp_path / "index.json").exists()


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


# --- 7. public classes check their constructors' arguments ---------------------------------------

PUBLIC_CLASSES = [name for name in tegrasp_drake.__all__
                  if inspect.isclass(getattr(tegrasp_drake, name))
                  and not issubclass(getattr(tegrasp_drake, name), (BaseException, enum.Enum))]


@pytest.mark.parametrize("name", PUBLIC_CLASSES)
def test_every_public_class_checks_its_constructors_arguments(name):
    cls = getattr(tegrasp_drake, name)
    assert getattr(cls.__init__, "__checked_arguments__", False), (
        f"{name}: decorate its __init__ with @public_api"
        + ("" if not dataclasses.is_dataclass(cls) else " (or the class with @public_dataclass)"))


def test_a_window_normalizer_given_text_for_its_config_names_the_argument():
    with pytest.raises(TypeError, match="WindowNormalizer: argument 'config' must be "
                                        "WindowNormalizerConfig or None, got str 'fast'"):
        tegrasp_drake.WindowNormalizer(config="fast")


# Rule: a system's mapping argument is checked at construction: a missing or unknown key is
# named beside the keys expected, a wrong value by its key, with what was given and what must be.
@pytest.mark.parametrize("states, words", [
    ({"x": np.zeros(5)}, "WindowNormalizer: argument 'window_states' has unknown key 'x' and "
     "lacks keys 'sa', 'ra'; give one initial state per rate group of the config, keyed "
     "'sa', 'ra'"),
    ({"sa": np.zeros(200)}, "WindowNormalizer: argument 'window_states' lacks key 'ra'; give "
     "one initial state per rate group of the config, keyed 'sa', 'ra'"),
    ({"sa": np.zeros((2, 3)), "ra": np.zeros(2000)},
     "WindowNormalizer: argument 'window_states['sa']' must be a 1-D array (an empty window of "
     "122 zeros, then the subclass's own state), got a 2-D array of shape (2, 3)"),
    ({"sa": np.zeros(200), "ra": np.zeros(7)}, "WindowNormalizer: argument "
     "'window_states['ra']' must start with an empty window of 1202 zeros, got 7 numbers"),
    ({"sa": np.r_[np.zeros(5), np.nan, np.zeros(200)], "ra": np.zeros(2000)},
     "WindowNormalizer: argument 'window_states['sa']' must start with an empty window of 122 "
     "zeros, got nan at entry 5"),
    ({"sa": np.array(["0"] * 200), "ra": np.zeros(2000)}, "WindowNormalizer: argument "
     "'window_states['sa']' must be an array of numbers, got an array of dtype <U1"),
    ({"sa": "zeros", "ra": np.zeros(2000)},
     "WindowNormalizer: argument 'window_states['sa']' must be ndarray, got str 'zeros'"),
])
def test_a_window_normalizers_initial_states_are_checked_at_construction(states, words):
    with pytest.raises((TypeError, ValueError)) as refused:
        tegrasp_drake.WindowNormalizer(window_states=states)
    assert str(refused.value) == words


def test_public_dataclasses_check_scalar_field_types_at_construction():
    import numpy as np
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(TypeError, match="TrialResult: field 'hold_success' must be bool, got str"):
        TrialResult(hold_success="yes")
    with pytest.raises(TypeError, match="ObjectConfig: field 'mass' must be"):
        ObjectConfig(mass="heavy")
    assert TrialResult(hold_success=np.bool_(True), seed=np.int64(3), hold_time_s=3).seed == 3


# Rule: a public dataclass given a keyword that is not its field says so in one line, as
# the scenario and `--set` do: a removed field with what replaced it (the same words), a
# moved one with its path now, a misspelt one with the closest field; never Python's
# "unexpected keyword argument".
def test_a_public_dataclass_given_a_removed_moved_or_misspelt_field_names_it():
    from tegrasp_drake.control.controller_config import GraspControllerConfig
    from tegrasp_drake.simulation.sim_robotiq_driver import GripperDriverConfig, REMOVED_FIELDS
    calls = [
        (lambda: GripperDriverConfig(driver_position_gain=1),
         "GripperDriverConfig: field 'driver_position_gain' was removed: "
         f"{REMOVED_FIELDS['driver_position_gain']}; leave it out"),
        (lambda: GripperDriverConfig(stal_speed=0.01),
         "GripperDriverConfig has no field 'stal_speed': did you mean 'stall_speed'?"),
        (lambda: GraspControllerConfig(re_reach_enabled=True),
         "GraspControllerConfig has no field 're_reach_enabled': it is now 're_reach.enabled'"),
    ]
    for call, words in calls:
        with pytest.raises(TypeError) as refused:
            call()
        assert str(refused.value) == words
    with pytest.raises(ConfigError) as scenario:
        LoadScenario(overrides=["gripper.driver_position_gain=1"])
    assert REMOVED_FIELDS["driver_position_gain"] in str(scenario.value)
    with pytest.raises(AttributeError, match="field 'driver_damping_gain' was removed"):
        GripperDriverConfig().driver_damping_gain = 1.0


# Rule: a public function's number takes the range its command-line or scenario twin takes,
# from the same declaration.
def test_the_api_rates_noise_and_duration_share_the_command_lines_ranges():
    from tegrasp_drake.commands.hardware import MAX_DURATION_S
    from tegrasp_drake.control.grasp_controller import RA_NOISE_RANGE, SAMPLE_RATE_RANGE
    from tegrasp_drake.rig.ranges import HARDWARE_RUN_DURATION, field_range
    from tegrasp_drake.simulation.pad_vibration_sensor import VibrationSensorConfig
    from tegrasp_drake.simulation.tactile_pads import TactileSensorConfig
    assert SAMPLE_RATE_RANGE == field_range(TactileSensorConfig, "sample_rate_hz")
    assert SAMPLE_RATE_RANGE == field_range(VibrationSensorConfig, "sample_rate_hz")
    assert RA_NOISE_RANGE == field_range(VibrationSensorConfig, "noise_std_mps2")
    assert MAX_DURATION_S == HARDWARE_RUN_DURATION.high


# Rule: the public value classes check their fields' types when built, as the guide says.
def test_the_public_value_classes_refuse_fields_of_the_wrong_type():
    refusal(lambda: T.Transition(t=1.0, from_mode="Reach", to_mode="Load", trigger="timer",
                                  reason="x"), "Transition", "'from_mode'", "Mode")
    refusal(lambda: T.TrialLog(*([None] * 13), meta={}), "TrialLog", "'t_sa'")
    refusal(lambda: T.TrialResult(final_mode="Done"), "TrialResult", "'final_mode'")
    refusal(lambda: T.TrialResult(transitions=({"t": 1.0},)), "transitions[0]", "Transition")


# Rule: the sweep API's records, reports and folders are bounded as the CLI's are: a
# hand-edited record is one line, trial ids that name no record are refused, an empty
# folder argument is not the current folder.
def test_sweep_records_reports_and_folders_at_the_api(tmp_path, monkeypatch):
    from tests.fake_trials import fake_trial
    record = {"status": "ok", "result": fake_trial({"pair_id": "p", "seed": 600,
                                                    "well_placed": True,
                                                    "controller": "memorized"})}
    assert T.record_result(record).hold_success in (True, False)
    for transitions in ([{"t": "soon"}], "Reach", [None]):
        record["result"]["transitions"] = transitions
        with pytest.raises(ValueError, match="not a trial result's JSON form") as refused:
            T.record_result(record)
        assert "\n" not in str(refused.value)
    spec = T.SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                       attempts=1)
    summary = T.run_sweep(spec, fake_trial, tmp_path / "sweep", workers=1, progress=False)
    assert summary.ran == 1
    with pytest.raises(ValueError, match="'trial_ids' names no trial recorded"):
        T.write_reports(tmp_path / "sweep", trial_ids=["nope"])
    assert T.write_reports(tmp_path / "sweep", trial_ids=list(summary.trial_ids))
    monkeypatch.chdir(tmp_path)
    for empty in ("", " "):
        with pytest.raises(OSError, match="is empty; give a folder"):
            T.run_sweep(spec, fake_trial, empty, workers=1, progress=False)
    assert not (tmp_path / "trials").exists()


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
    refusal(lambda: getattr(T, function)(_changed(field, value)), f"{function}:",
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


# Every public function's folder declarations hold at its call: a folder argument declared
# to exist (Folder(exists=True)) is refused, naming the argument, when it does not.
def _existing_folder_arguments():
    import inspect
    import typing
    import tegrasp_drake as T
    from tegrasp_drake.rig.api_boundary import Folder
    for name in T.__all__:
        function = getattr(T, name)
        if not callable(function) or inspect.isclass(function):
            continue
        hints = typing.get_type_hints(inspect.unwrap(function), include_extras=True)
        for argument, hint in hints.items():
            if any(isinstance(m, Folder) and m.exists for m in getattr(hint, "__metadata__", ())):
                yield name, argument


@pytest.mark.parametrize("name, argument", list(_existing_folder_arguments()))
def test_every_folder_declared_to_exist_is_checked_at_the_call(tmp_path, name, argument):
    import tegrasp_drake as T
    from tegrasp_drake.rig.files import UserPathError
    with pytest.raises(UserPathError, match=f"argument '{argument}'.*does not exist"):
        getattr(T, name).bind_now(**{argument: tmp_path / "missing"})


# Rule: a timeline entry leaves one mode for another (no rule's `then` keeps its mode).
def test_a_transition_that_keeps_its_mode_is_refused():
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    with pytest.raises(ConfigError, match="Transition: field 'to_mode' must differ from "
                                          "'from_mode'"):
        Transition(t=1.0, from_mode=Mode.LOAD, to_mode=Mode.LOAD, trigger=Trigger.TIMER,
                   reason="x")


# Rule: without sim_time_s, a time of a result is still bounded by the longest run a trial
# can last (the longest grasp script plus the time for corrections).
# (A latency far below zero meets the stricter rule first: no detection is earlier than its
# physical event by more than the false-trigger margin.)
@pytest.mark.parametrize("field, value, words", [
    ("detection_latency_s", {"reach_load": 1e300}, "the longest run a trial can last"),
    ("detection_latency_s", {"reach_load": -1e300}, "at least -0.01 s"),
    ("physical_events", {"hit": 1e300}, "the longest run a trial can last"),
])
def test_a_result_time_longer_than_any_run_is_refused_without_sim_time(field, value, words):
    from tegrasp_drake.scenario.trial_result import TrialResult
    key = next(iter(value))
    with pytest.raises(ConfigError, match=f"TrialResult: field '{field}.{key}' must be .*"
                                          f"{words}"):
        TrialResult(**{field: value})


def test_a_result_time_within_the_longest_run_is_accepted_without_sim_time():
    from tegrasp_drake.scenario.trial_result import TrialResult
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    detected = Transition(1.0, Mode.REACH, Mode.LOAD, Trigger.MEMORIZED_EVENT, "Reach-Load event")
    result = TrialResult(transitions=(detected,), final_mode=Mode.LOAD,
                         detection_latency_s={"reach_load": 0.2},
                         physical_events={"reach_load": 0.8, "hit": 9.0})
    assert result.detection_latency_s == {"reach_load": 0.2}


def test_a_simulated_time_longer_than_any_run_is_refused():
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ConfigError, match="TrialResult: field 'sim_time_s' must be at most .*"
                                          "the longest run a trial can last"):
        TrialResult(sim_time_s=1e300, detection_latency_s={"reach_load": 1e299})


# Rule: a result's fields are checked for their types before the relations that read them
# (a mapping where a Transition belongs, with sim_time_s set, was an AttributeError).
def test_a_result_with_a_mapping_for_a_transition_names_the_field():
    from tegrasp_drake.scenario.trial_result import TrialResult
    with pytest.raises(ConfigError, match=r"TrialResult: field 'transitions\[0\]'"):
        TrialResult(transitions=({"t": 1.0},), sim_time_s=10.0)


def test_a_transition_built_in_python_with_a_code_of_no_rule_is_refused():
    """The JSON reader refused it; a Transition built by hand (the API) did not."""
    from tegrasp_drake.control.grasp_modes import Mode, Transition, Trigger
    from tegrasp_drake.rig.typed_yaml import ConfigError
    with pytest.raises(ConfigError, match="names no rule"):
        Transition(t=1.0, from_mode=Mode.REACH, to_mode=Mode.LOAD,
                   trigger=Trigger.MEMORIZED_EVENT, reason="", code="bogus_rule")
    Transition(t=1.0, from_mode=Mode.REACH, to_mode=Mode.LOAD,
               trigger=Trigger.MEMORIZED_EVENT, reason="", code="reach_event")


@pytest.mark.parametrize("field, value", [("grid", np.array([[0.0, 0.0]])),
                                          ("objects", np.array(["box"]))])
def test_a_numpy_array_in_a_list_field_is_refused_naming_it(field, value):
    with pytest.raises(TypeError, match=f"SweepSpec: field '{field}' must be a list or tuple, "
                                        f"got numpy.ndarray; give {field}={field}.tolist()"):
        SweepSpec(**{field: value})


# Rule: a NumPy number of any real dtype is the number it holds, wherever the API takes a
# number (a config's field, a changed scenario, a function's argument), and is kept as a
# Python number; a NaN or an infinity is said to be not finite before any range or relation
# judges it; an array where a list belongs is refused saying a list is wanted.
@pytest.mark.parametrize("value", [np.float32(0.2), np.int64(1), np.float16(0.5), np.uint8(1),
                                   np.float64(0.2)], ids=repr)
def test_a_numpy_number_for_a_changed_scenario_field_is_the_number_it_holds(value):
    scenario = LoadScenario(name="box")
    scenario.object.mass = value
    scenario.object.size = [np.float32(0.045), np.float32(0.045), np.float32(0.11)]
    T.grasp_plan(scenario)
    assert type(scenario.object.mass) in (int, float) and scenario.object.mass == value.item()
    assert all(type(size) is float for size in scenario.object.size)


@pytest.mark.parametrize("field, value, named", [
    ("mass", np.float64("nan"), "object.mass"),
    ("mass", np.float32("-inf"), "object.mass"),
    ("friction", float("nan"), "object.friction"),
    ("size", [float("nan"), 0.04, 0.1], "object.size[0]"),
])
def test_a_nan_or_infinite_number_for_a_changed_scenario_field_is_said_not_finite(
        field, value, named):
    scenario = LoadScenario(name="box")
    setattr(scenario.object, field, value)
    message = refusal(lambda: T.grasp_plan(scenario), f"field '{named}' must be a finite number")
    assert "positive" not in message


def test_a_nan_force_is_said_not_finite_rather_than_too_large():
    scenario = LoadScenario(name="box")
    scenario.disturbance.hit_force_n = [float("nan"), 0.0, 0.0]
    refusal(lambda: T.grasp_plan(scenario),
            "field 'disturbance.hit_force_n[0]' must be a finite number")


@pytest.mark.parametrize("field", ["size", "color"])
def test_a_numpy_array_for_a_changed_scenario_list_field_is_refused_saying_a_list_is_wanted(
        field):
    scenario = LoadScenario(name="box")
    setattr(scenario.object, field, np.array(getattr(scenario.object, field)))
    refusal(lambda: T.grasp_plan(scenario), "grasp_plan: argument 'scenario'",
            f"field 'object.{field}' must be a list or tuple, got numpy.ndarray; "
            f"give {field}={field}.tolist()")


def test_numpy_numbers_in_event_thresholds_and_a_sweep_grid_are_numbers():
    from tegrasp_drake.events.event_matcher import check_matcher_config
    check_matcher_config(T.EventMatcherConfig(
        event_thresholds={"reach_load": (np.float32(0.5), np.float64(0.4))}))
    spec = SweepSpec(grid=[[np.float32(0.01), 0.0]], objects=["box"],
                     controllers=["open_loop"])
    assert spec.grid[0][0] == np.float32(0.01)


def test_a_result_built_from_numpy_numbers_holds_python_numbers():
    import json
    result = T.TrialResult(seed=np.int64(3), hold_success=np.bool_(True),
                           hold_time_s=np.float32(3))
    assert (type(result.seed), type(result.hold_success), type(result.hold_time_s)) == (
        int, bool, float)
    json.dumps([result.seed, result.hold_success, result.hold_time_s])


def test_a_numpy_number_given_to_a_public_function_is_passed_on_as_a_python_number():
    from tegrasp_drake.rig.api_boundary import public_api

    @public_api
    def takes(count: int, scale: float, offsets: list[float]):
        return count, scale, offsets

    count, scale, offsets = takes(np.int64(2), np.float32(0.5), [np.float32(0.25), 1.0])
    assert (type(count), type(scale), [type(o) for o in offsets]) == (int, float,
                                                                       [float, float])


# Rule: a wrong name or folder given to a public function is named with the function and
# the argument, as the command line names its option.
def test_an_unknown_controller_name_names_with_controller_and_its_argument():
    scenario = T.LoadScenario(name="box")
    with pytest.raises(ValueError, match="with_controller: argument 'name' must be one of "
                                         "'memorized', .* got 'nosuch'"):
        T.with_controller(scenario, "nosuch")


@pytest.mark.parametrize("name", ["load_controller_events", "load_corrective_events"])
def test_an_events_folder_that_is_a_file_is_named_as_a_file(tmp_path, name):
    from tegrasp_drake.rig.files import UserPathError
    scenario = T.LoadScenario(name="box")
    file = tmp_path / "events.json"
    file.write_text("{}")
    with pytest.raises(UserPathError, match=f"{name}: argument 'events_dir': .* is a file, "
                                            "not a folder"):
        getattr(T, name)(scenario, events_dir=file)


@pytest.mark.parametrize("field, index", [("object.size", 0), ("disturbance.hit_force_n", 1)])
def test_a_numpy_number_put_into_a_list_field_in_place_is_kept_as_the_number_it_holds(
        field, index):
    import json
    scenario = LoadScenario(name="box")
    section, name = field.split(".")
    values = getattr(getattr(scenario, section), name)
    values[index] = np.float32(values[index])
    T.grasp_plan(scenario)
    assert type(values[index]) is float and values[index] == np.float32(values[index])
    json.dumps(values)


@pytest.mark.parametrize("build", [lambda: T.ObjectConfig(mass="heavy"),
                                   lambda: T.Scenario(random_seed="x"),
                                   lambda: T.ObjectConfig(size="abc"),
                                   lambda: T.ObjectConfig(size=None)])
def test_a_config_fields_wrong_type_is_one_error_type(build):
    """Every wrong field type of a public config is a ConfigError (as a bad value is) and a
    TypeError: `except ConfigError` catches them all, not only some."""
    with pytest.raises(ConfigError) as refused:
        build()
    assert isinstance(refused.value, TypeError), refused.value


# Rule: an empty file name given to the public API is refused naming the argument, in the
# words of the command line's refusal of an empty file option ("is empty; give ..."), never
# read as "not given" (LoadScenario's built-in file) nor as the current folder; checked at
# the API boundary, before the function runs.
_EMPTY_FILE_NAME_CALLS = {
    ("LoadScenario", "filename"): lambda: T.LoadScenario(filename=""),
    ("LoadHardwareConfig", "filename"): lambda: T.LoadHardwareConfig(""),
    ("LoadSweepSpec", "path"): lambda: T.LoadSweepSpec(""),
    ("load_memorized_events", "events_dir"): lambda: T.load_memorized_events("", "box"),
    ("load_trial_log", "path"): lambda: T.load_trial_log(""),
    ("run_on_hardware", "log_path"): lambda: T.run_on_hardware(LoadScenario(), log_path=""),
    ("run_on_hardware", "events_dir"): lambda: T.run_on_hardware(LoadScenario(), events_dir=""),
}


@pytest.mark.parametrize("function, argument", sorted(_EMPTY_FILE_NAME_CALLS))
def test_an_empty_file_name_is_refused_naming_its_argument(tmp_path, monkeypatch, function,
                                                           argument):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(OSError) as refused:
        _EMPTY_FILE_NAME_CALLS[function, argument]()
    text = str(refused.value)
    what = "a folder" if argument.endswith("_dir") else "a file"
    assert text.startswith(f"{function}: argument '{argument}': '' is empty; give {what}"), text
    assert "\n" not in text
    assert list(tmp_path.iterdir()) == []


def _takes_a_path(hint) -> bool:
    if typing.get_origin(hint) is typing.Annotated:
        return _takes_a_path(typing.get_args(hint)[0])
    return hint is os.PathLike or any(_takes_a_path(h) for h in typing.get_args(hint))


def test_every_public_file_name_argument_is_checked_for_the_empty_name():
    """Every public function's PathLike argument is a Folder (Folder.problem refuses an
    empty name) or one of the file names tested above."""
    unchecked = []
    for name in tegrasp_drake.__all__:
        function = getattr(tegrasp_drake, name)
        if inspect.isclass(function) or not callable(function):
            continue
        hints = typing.get_type_hints(inspect.unwrap(function), include_extras=True)
        for argument, hint in hints.items():
            folder = typing.get_origin(hint) is typing.Annotated and any(
                isinstance(c, Folder) for c in typing.get_args(hint)[1:])
            if argument != "return" and _takes_a_path(hint) and not folder \
                    and (name, argument) not in _EMPTY_FILE_NAME_CALLS:
                unchecked.append((name, argument))
    assert unchecked == []


# Rule: a file or folder name given to the public API that holds a NUL byte (which no
# operating system takes in a path) is refused at the API boundary in one line naming the
# argument and the byte's position, never Python's bare "embedded null byte" from deep in
# a reader; every PathLike argument of every public function is checked (the set below is
# compared with the signatures).
def _nul_calls(path) -> dict:
    from tests.fake_trials import fake_trial
    spec = T.SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                       attempts=1)
    return {
        ("LoadScenario", "filename"): lambda: T.LoadScenario(filename=path),
        ("LoadHardwareConfig", "filename"): lambda: T.LoadHardwareConfig(path),
        ("LoadSweepSpec", "path"): lambda: T.LoadSweepSpec(path),
        ("load_trial_log", "path"): lambda: T.load_trial_log(path),
        ("load_memorized_events", "events_dir"): lambda: T.load_memorized_events(path, "box"),
        ("load_controller_events", "events_dir"):
            lambda: T.load_controller_events(LoadScenario(), path),
        ("load_corrective_events", "events_dir"):
            lambda: T.load_corrective_events(LoadScenario(), path),
        ("load_records", "out_dir"): lambda: T.load_records(path),
        ("write_reports", "out_dir"): lambda: T.write_reports(path),
        ("save_memorized_events", "events_dir"): lambda: T.save_memorized_events(path, []),
        ("run_sweep", "out_dir"):
            lambda: T.run_sweep(spec, fake_trial, path, workers=1, progress=False),
        ("run_trial_from_spec", "events_dir"): lambda: T.run_trial_from_spec({}, events_dir=path),
        ("run_trial_from_spec", "log_dir"): lambda: T.run_trial_from_spec({}, log_dir=path),
        ("run_on_hardware", "log_path"): lambda: T.run_on_hardware(LoadScenario(), log_path=path),
        ("run_on_hardware", "events_dir"):
            lambda: T.run_on_hardware(LoadScenario(), events_dir=path),
    }


@pytest.mark.parametrize("function, argument", sorted(_nul_calls("")))
@pytest.mark.parametrize("as_path", [False, True])
def test_a_file_name_holding_a_nul_byte_is_refused_naming_its_argument_and_position(
        tmp_path, monkeypatch, function, argument, as_path):
    import pathlib
    monkeypatch.chdir(tmp_path)
    path = "ok/a\0b" if not as_path else pathlib.Path("ok/a\0b")
    with pytest.raises(OSError) as refused:
        _nul_calls(path)[function, argument]()
    text = str(refused.value)
    assert text.startswith(f"{function}: argument '{argument}' holds a NUL byte at "
                           "position 4 "), text
    assert "remove it" in text and "\n" not in text and "\0" not in text
    assert list(tmp_path.iterdir()) == []


def test_every_public_file_name_argument_is_checked_for_a_nul_byte():
    """The calls above cover every PathLike argument of every public function."""
    taken = set()
    for name in tegrasp_drake.__all__:
        function = getattr(tegrasp_drake, name)
        if inspect.isclass(function) or not callable(function):
            continue
        hints = typing.get_type_hints(inspect.unwrap(function), include_extras=True)
        taken |= {(name, argument) for argument, hint in hints.items()
                  if argument != "return" and _takes_a_path(hint)}
    assert taken == set(_nul_calls(""))
