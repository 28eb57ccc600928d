"""Integers written as text are read by one reader everywhere (YAML files, --set, sweep specs,
JSON, integer options): a 5000-digit integer is refused by its length without being
echoed, a fraction is told the field takes whole numbers and the advice is followed to a
valid input, YAML 1.1's base-60 and other forms are text, a leading zero is decimal and 0x
hexadecimal, and a quoted number is text in Drake's config sections too."""

import dataclasses
import types
import typing

import pytest

import tegrasp_drake as T
from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.rig.ranges import Range, range_of
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tests.bad_input.probes import assert_one_line_error, refusal, run_cli

DIGITS_5000 = "9" * 5000


# --- 1. integers beyond any setting's range: one bounded reader ------------------------------

def test_a_5000_digit_set_value_is_a_one_line_error_naming_the_field(capfd):
    code, text = run_cli(["trial", "--set", f"object.mass={DIGITS_5000}"], capfd)
    assert_one_line_error(code, text, "field 'object.mass'", "5000 digits")
    assert len(text) < 600  # the value is not echoed whole


def test_a_5000_digit_seed_in_a_scenario_file_names_the_file_and_the_field(tmp_path, capfd):
    scenario = tmp_path / "s.yaml"
    scenario.write_text(f"x:\n  object: {{name: box}}\n  random_seed: {'7' * 5000}\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "x"], capfd)
    assert_one_line_error(code, text, str(scenario), "random_seed", "5000 digits")


def test_a_5000_digit_attempts_in_a_sweep_spec_is_refused_before_any_trial(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [box]\ncontrollers: [open_loop]\nattempts: {DIGITS_5000}\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--trial-function", "tests.fake_trials:fake_trial"], capfd)
    assert_one_line_error(code, text, "attempts", "5000 digits")
    assert not (tmp_path / "out" / "trials").exists()


def test_a_5000_digit_integer_option_is_a_usage_error_that_does_not_echo_it(tmp_path, capfd):
    code, text = run_cli(["sweep", "--workers", DIGITS_5000, "--out", str(tmp_path)], capfd)
    assert code == 2 and "--workers" in text and "5000 digits" in text
    assert "Traceback" not in text and len(text) < 2000


def test_a_logged_scenario_with_a_5000_digit_integer_is_a_config_error():
    from tegrasp_drake.scenario.scenario import scenario_from_yaml
    with pytest.raises(ConfigError, match="random_seed.*5000 digits"):
        scenario_from_yaml(f"random_seed: {'7' * 5000}\n", "the log's scenario")


# Rule: a Python int handed to the API (a field of a config, a scenario changed after loading)
# meets the same bound as integer text: beyond a float's range it is refused naming the field,
# in the readers' words, never Python's "int too large to convert to float".
BEYOND_FLOAT = 10 ** 400


def _public_configs() -> list[type]:
    """The public dataclasses that build from their defaults alone."""
    def has_default(field) -> bool:
        return (field.default is not dataclasses.MISSING
                or field.default_factory is not dataclasses.MISSING)
    return [cls for cls in (getattr(T, name) for name in T.__all__)
            if isinstance(cls, type) and dataclasses.is_dataclass(cls)
            and all(has_default(field) for field in dataclasses.fields(cls))]


def _beyond_float(hint, length: int):
    """A value of type `hint` holding BEYOND_FLOAT (in each list, `length` of them), or None
    for a type that holds no number where a value can be made (a mapping of names)."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        made = [_beyond_float(m, length) for m in typing.get_args(hint) if m is not type(None)]
        return next((value for value in made if value is not None), None)
    if origin in (list, tuple):
        item = _beyond_float(typing.get_args(hint)[0], length)
        return None if item is None else [item] * length
    return BEYOND_FLOAT if hint in (int, float) else None


def _beyond_float_fields(cls) -> list[tuple[str, object]]:
    """(name, a value holding BEYOND_FLOAT) of each number field of `cls` with a range."""
    hints, fields = typing.get_type_hints(cls), []
    for field in dataclasses.fields(cls):
        if isinstance(range_of(field), Range):
            value = _beyond_float(hints[field.name], range_of(field).length or 2)
            if value is not None:
                fields.append((field.name, value))
    return fields


@pytest.mark.parametrize("cls", _public_configs(), ids=lambda cls: cls.__name__)
def test_every_public_config_refuses_an_int_beyond_a_float_naming_the_field(cls):
    for name, value in _beyond_float_fields(cls):
        refusal(lambda: cls(**{name: value}), f"{cls.__name__}: field '{name}",
                "401 digits, beyond the range of any setting")


@pytest.mark.parametrize("field, value, named", [
    ("random_seed", BEYOND_FLOAT, "random_seed"),
    ("object.mass", BEYOND_FLOAT, "object.mass"),
    ("placement.offset", [BEYOND_FLOAT, 0.0], "placement.offset[0]"),
    ("controller.contact_force_n", -BEYOND_FLOAT, "controller.contact_force_n"),
], ids=["random_seed", "object.mass", "placement.offset", "controller.contact_force_n"])
@pytest.mark.parametrize("function", ["grasp_plan", "MakeGraspDiagram"])
def test_a_scenario_changed_to_an_int_beyond_a_float_is_refused_naming_the_field(
        function, field, value, named):
    scenario = LoadScenario(name="box")
    *owners, name = field.split(".")
    owner = scenario
    for part in owners:
        owner = getattr(owner, part)
    setattr(owner, name, value)
    refusal(lambda: getattr(T, function)(scenario), f"{function}:", f"field '{named}'",
            "401 digits")


def test_a_5000_digit_int_in_a_text_field_is_refused_without_being_written_out():
    from tegrasp_drake.rig.objects import ObjectConfig
    with pytest.raises(TypeError, match="field 'name' must be str, got int <an integer of 5001 "
                                        "digits>"):
        ObjectConfig(name=10 ** 5000)


# --- 4. an integer field's advice is digits ------------------------------------------------------

def _first_error(load) -> str:
    try:
        load()
    except ConfigError as e:
        return str(e)
    return ""


def test_the_advice_for_attempts_written_as_text_is_followed_to_a_valid_spec(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text('objects: [box]\ncontrollers: [open_loop]\nattempts: "3"\n')
    error = _first_error(lambda: LoadSweepSpec(spec))
    assert "field 'attempts' must be an integer" in error and "write 3," in error
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 3\n")
    assert LoadSweepSpec(spec).attempts == 3


def test_the_advice_for_a_seed_written_as_text_is_followed_to_a_valid_scenario(tmp_path):
    scenario = tmp_path / "s.yaml"
    scenario.write_text('x:\n  object: {name: box}\n  random_seed: "5"\n')
    error = _first_error(lambda: LoadScenario(scenario, "x"))
    assert "random_seed" in error and "write 5," in error
    scenario.write_text("x:\n  object: {name: box}\n  random_seed: 5\n")
    assert LoadScenario(scenario, "x").random_seed == 5


def test_the_advice_for_a_device_id_written_as_text_is_followed_past_its_type(tmp_path):
    config = tmp_path / "hw.yaml"
    config.write_text('gripper: {device_id: "9"}\n')
    error = _first_error(lambda: LoadHardwareConfig(config))
    assert "device_id" in error and "write 9," in error
    config.write_text("gripper: {device_id: 9}\n")
    assert "device_id" not in _first_error(lambda: LoadHardwareConfig(config))


def test_an_integer_field_given_a_fraction_as_text_is_told_it_takes_whole_numbers(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text('objects: [box]\ncontrollers: [open_loop]\nattempts: "2.5"\n')
    error = _first_error(lambda: LoadSweepSpec(spec))
    assert "whole numbers" in error and "2.5" in error and "write 2.5" not in error


# Rule: every YAML the package reads (scenario files, --set values, sweep, sensitivity and
# transfer specs) reads numbers as YAML 1.2's core schema does (rig/core_schema_yaml.py):
# YAML 1.1's base-60, binary and `_` forms are text, refused by a numeric field in one line.
@pytest.mark.parametrize("override, field", [
    ("placement.yaw_deg=1:30", "placement.yaw_deg"),
    ("random_seed=0b101", "random_seed"),
    ("random_seed=1_000", "random_seed"),
])
def test_a_yaml_11_only_number_in_a_set_value_is_refused(override, field, capfd):
    code, text = run_cli(["trial", "--set", override], capfd)
    assert_one_line_error(code, text, f"field '{field}' must be", "YAML 1.2")


def test_a_leading_zero_is_decimal_and_0x_hexadecimal():
    from tegrasp_drake.scenario.scenario import LoadScenario
    assert LoadScenario(name="box", overrides=["random_seed=017"]).random_seed == 17
    assert LoadScenario(name="box", overrides=["random_seed=0x10"]).random_seed == 16


def test_a_scenario_file_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "s.yaml").write_text("s:\n  placement: {yaw_deg: 1:30}\n")
    code, text = run_cli(["trial", "--scenario", str(tmp_path / "s.yaml"),
                          "--scenario-name", "s", "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "field 'placement.yaw_deg' must be a finite number")


def test_a_sweep_spec_reads_base_60_as_text(tmp_path, capfd):
    (tmp_path / "spec.yaml").write_text("objects: [box]\nattempts: 1:00\n")
    code, text = run_cli(["sweep", "--spec", str(tmp_path / "spec.yaml"), "--workers", "1",
                          "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "attempts", "1:00")
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())


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
    refusal(lambda: LoadScenario(overrides=[assignment]), f"field '{field}'", words)
    LoadScenario(overrides=[assignment.replace("'", "").replace("!!str ", "")])


def test_a_5000_digit_lcm_url_in_a_hardware_config_names_the_file_and_the_field(tmp_path, capfd):
    config = tmp_path / "hw.yaml"
    config.write_text(f"arm: {{lcm_url: {DIGITS_5000}}}\n")
    code, text = run_cli(["hardware", "--config", str(config), "--controller", "heuristic"], capfd)
    assert_one_line_error(code, text, str(config), "field 'arm.lcm_url'", "5000 digits")
