"""Sweep specs are checked at load: an empty spec or mapping, a string for a list, fields
outside their declared ranges, objects that cannot run, user objects the spec does not run,
overrides of a swept setting, and a trial spec that is not one are refused in one line
naming the field, before any trial runs."""

import pytest

import tegrasp_drake
from tegrasp_drake.rig.ranges import field_range
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.sweep.spec import RandomisationConfig, SweepSpec, validate_spec
from tests.bad_input.probes import (SEED, assert_one_line_error, deny_reading, one_line_of,
                                    refusal, run_cli)


# --- sweep specs ------------------------------------------------------------------------

@pytest.mark.parametrize("definition, expected", [
    ("{shape: box, size: [0.04, 0.09, 0.1], mass: 0.1, friction: 0.5}",
     "field 'user_objects.crate.size': makes the object 90.0 mm wide"),
    ("{shape: box, size: [0.2, 0.04, 0.1], mass: 0.1, friction: 0.5}",
     "field 'user_objects.crate.size': makes the object 200.0 mm deep along the approach, "
     "more than the 85.0 mm"),
    ("{shape: cylinder, size: [0.04, 0.1], mass: 0.1}",
     "field 'user_objects.crate.friction': is missing"),
    ("{shape: cylinder, size_m: [0.04, 0.1], mass_kg: 0.1, friction_coefficient: 0.5}",
     "field 'user_objects.crate.size_m': is the old name of the field: rename size_m to "
     "size, mass_kg to mass, friction_coefficient to friction"),
])
def test_a_sweep_spec_whose_objects_cannot_run_is_refused_at_load(definition, expected,
                                                                  tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [crate]\nuser_objects:\n  crate: {definition}\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                          "--no-progress"], capfd)
    assert code == 2, text
    assert_one_line_error(code, text, str(spec), expected)
    assert not (tmp_path / "out" / "trials").exists()


def test_an_empty_sweep_spec_is_refused_not_run_as_the_paper_experiment(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "sw")], capfd)
    assert_one_line_error(code, text, str(spec), "the sweep spec is empty")
    assert not (tmp_path / "sw").exists()


def test_a_sweep_spec_refuses_a_string_for_a_list():
    with pytest.raises(TypeError, match="SweepSpec: field 'objects' must be a collection"):
        tegrasp_drake.SweepSpec(objects="box")
    assert tegrasp_drake.SweepSpec(objects=["box"]).objects == ["box"]


@pytest.mark.parametrize("trial, words", [
    ({}, "lacks trial_id"),
    ({"object": "teapot", "controller": "open_loop", "seed": SEED}, "object='teapot'"),
])
def test_a_trial_spec_that_is_not_one_names_its_keys(trial, words):
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.run_trial_from_spec(trial)
    assert "argument 'trial'" in one_line_of(refused.value) and words in str(refused.value)


def test_a_sweep_spec_that_is_an_empty_mapping_is_refused_like_an_empty_file(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    for text in ("", "{}\n"):
        (tmp_path / "spec.yaml").write_text(text)
        with pytest.raises(ConfigError, match="the sweep spec is empty"):
            LoadSweepSpec(tmp_path / "spec.yaml")


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
        refusal(lambda: validate_spec(spec), f"field '{where}' {declared.words(value)}")


# Rule: a sweep spec's `user_objects` entry that `objects` does not name is refused, naming it
# and saying to add it to `objects`, wherever a spec is checked (the file's reader, a
# SweepSpec built in Python, the command line); not dropped while the default objects run.
# A command line's `--objects` chooses the objects to run: the spec's other definitions are
# then the user's choice not to run them.
MUG = "{mug: {shape: cylinder, size: [0.04, 0.1], mass: 0.3, friction: 0.5}}"


@pytest.mark.parametrize("text", [f"user_objects: {MUG}\n",
                                  f"objects: [box]\nuser_objects: {MUG}\n"])
def test_a_user_object_the_spec_does_not_run_is_refused(tmp_path, capfd, text):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sweep import LoadSweepSpec
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError, match=r"user_objects\.mug.*add it to 'objects'"):
        LoadSweepSpec(spec)
    code, error = run_cli(["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"),
                           "--workers", "1", "--base-seed", "640", "--no-progress"], capfd)
    assert_one_line_error(code, error, "user_objects.mug", "objects")
    assert not (tmp_path / "out").exists()


def test_a_user_object_a_python_spec_does_not_run_is_refused():
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.rig.objects import ObjectConfig
    from tegrasp_drake.sweep import SweepSpec, expand_trials
    mug = ObjectConfig(name="mug", shape="cylinder", size=[0.04, 0.1], mass=0.3, friction=0.5)
    with pytest.raises(ConfigError, match=r"user_objects\.mug"):
        expand_trials(SweepSpec(objects=("box",), user_objects={"mug": mug}))


def test_objects_chosen_on_the_command_line_leave_the_other_definitions_unrun(tmp_path):
    import argparse
    from tegrasp_drake.commands.sweep import spec_from_arguments
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [box, mug]\nuser_objects: {MUG}\n")
    args = argparse.Namespace(spec=str(spec), objects=["box"], controllers=None, attempts=None,
                              base_seed=None, overrides=None, confirm_trials=None)
    assert spec_from_arguments(args).objects == ("box",)


@pytest.mark.parametrize("override", ["gripper={pad_friction: 1.0}", "gripper.pad_friction=1.0",
                                      " gripper.pad_friction =1.0"])
def test_a_sweep_override_of_a_swept_setting_or_its_section_is_refused(tmp_path, override):
    """A study whose every point ran the override's value would say its parameter changes
    nothing."""
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.pad_friction]\n"
                    "sweep: {objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], "
                    f"attempts: 1, base_seed: 640, scenario_overrides: ['{override}']}}\n")
    with pytest.raises(ConfigError, match=r"scenario_overrides\[0\].*gripper.pad_friction"):
        LoadSensitivitySpec(spec)


# Rule: a name listed twice is named, with what to do, in words that read right for each list.
@pytest.mark.parametrize("text, words", [
    ("objects: [box, thin_cylinder, box]\n",
     "field 'objects': lists 'box' twice; list each object once"),
    ("controllers: [memorized, memorized]\n",
     "field 'controllers': lists 'memorized' twice; list each controller once"),
])
def test_a_sweep_spec_listing_a_name_twice_names_it(tmp_path, text, words):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.sweep import LoadSweepSpec
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError) as refused:
        LoadSweepSpec(spec)
    assert str(refused.value) == f"{spec}: {words}"


# A marker in the grid's range that the placement jitter carries out of placement.offset's is
# refused when the spec is loaded, naming the spec, its grid entry and the largest marker
# allowed; not when the first trial that draws the jitter is built.
@pytest.mark.parametrize("grid, entry", [
    ("[[0.2, 0]]", "field 'grid[0]': marker [0.2, 0.0] m"),
    ("[[0.0, 0.0], [0.1, -0.199]]", "field 'grid[1]': marker [0.1, -0.199] m"),
])
def test_a_marker_the_jitter_carries_out_of_range_is_refused_at_load(tmp_path, capfd, grid,
                                                                     entry):
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"objects: [box]\ncontrollers: [memorized]\ngrid: {grid}\nattempts: 1\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--dry-run",
                          "--out", str(tmp_path / "out")], capfd)
    assert code == 2, text
    assert_one_line_error(code, text, f"{spec}: {entry}", "+-0.002 m of placement jitter",
                          "[-0.2, 0.2] m", "give markers within +-0.198 m")
    assert "trial" not in text, text
    spec.write_text("objects: [box]\ncontrollers: [memorized]\ngrid: [[0.198, -0.198]]\n"
                    "attempts: 1\n")
    assert run_cli(["sweep", "--spec", str(spec), "--dry-run",
                    "--out", str(tmp_path / "out")], capfd)[0] == 0


@pytest.mark.parametrize("kind", ["sweep", "sensitivity"])
def test_a_sweep_override_out_of_range_names_its_entry_not_the_scenario_file(tmp_path, kind):
    """The sweep spec's scenario_overrides[i] (a sensitivity spec's sweep's too), not the
    built-in scenario file the override is applied to."""
    from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    sweep = ("{objects: [box], controllers: [memorized], grid: [[0.0, 0.0]], attempts: 1, "
             "scenario_overrides: [grasp.hold_s=2.0, grasp.grip_force=5000.0]}")
    spec = tmp_path / "s.yaml"
    if kind == "sweep":
        spec.write_text(f"{sweep[1:-1]}\n".replace("], ", "]\n").replace("1, ", "1\n"))
        load, where = LoadSweepSpec, f"{spec}: "
    else:
        spec.write_text(f"parameters: [gripper.pad_friction]\nsweep: {sweep}\n")
        load, where = LoadSensitivitySpec, f"{spec} [sweep]: "
    with pytest.raises(ConfigError) as refused:
        load(spec)
    text = one_line_of(refused.value)
    assert text.startswith(where + "field 'scenario_overrides[1]' 'grasp.grip_force=5000.0': "
                           "field 'grasp.grip_force' must lie in [20, 235] N"), text
    assert text.endswith("got 5000.0; correct the entry, or drop it"), text
    assert "scenarios.yaml" not in text, text


# Rule: a list of KEY=VALUE settings (a sweep's scenario_overrides, a transfer world's
# overrides) is called that in its errors, with an example that runs, never "a list of names".
@pytest.mark.parametrize("text, field, got", [
    ("scenario_overrides: {object: {mass: 10}}\n", "scenario_overrides",
     "got dict {'object': {'mass': 10}}"),
    ("scenario_overrides: 3\n", "scenario_overrides", "got int 3"),
])
def test_scenario_overrides_that_are_no_list_are_called_settings_with_an_example(
        tmp_path, capfd, text, field, got):
    spec = tmp_path / "spec.yaml"
    spec.write_text(text)
    code, output = run_cli(["sweep", "--spec", str(spec), "--dry-run",
                            "--out", str(tmp_path / "out")], capfd)
    assert_one_line_error(code, output, f"{spec}: field '{field}' must be a list of KEY=VALUE "
                          f"settings, {got}", f"{field}: [grasp.grip_force=50.0]")
    assert "names" not in output, output
    assert not (tmp_path / "out").exists()
    example = tmp_path / "example.yaml"  # the example the error gives loads
    example.write_text(f"objects: [box]\n{field}: [grasp.grip_force=50.0]\n")
    assert tegrasp_drake.LoadSweepSpec(example).scenario_overrides == ("grasp.grip_force=50.0",)


def test_a_scenario_override_that_is_no_text_is_called_a_setting(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text("scenario_overrides: [{object: {mass: 1}}]\n")
    refusal(lambda: tegrasp_drake.LoadSweepSpec(spec), str(spec),
            "field 'scenario_overrides[0]' must be a KEY=VALUE setting (as --set), got dict",
            "scenario_overrides: [grasp.grip_force=50.0]")


def test_a_transfer_world_override_that_is_no_list_is_called_settings(tmp_path):
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "transfer.yaml"
    spec.write_text("worlds: {ideal: {scenario: memorizing_world, overrides: {grasp: 1}}}\n"
                    "cells: [[ideal, ideal]]\n")
    refusal(lambda: LoadTransferSpec(spec), str(spec), "field 'worlds.ideal.overrides' must "
            "be a list of KEY=VALUE settings, got dict", "overrides: [grasp.grip_force=50.0]")


@pytest.mark.parametrize("kind, text, where", [
    ("sweep", "objects: [box]\nscenario_overrides: [grasp.hold_s=2, grasp.grip_force=50, "
     "grasp.hold_s=3]\n", "field 'scenario_overrides'"),
    ("sensitivity", "parameters: [gripper.pad_friction]\nsweep: {objects: [box], "
     "scenario_overrides: [grasp.hold_s=2, grasp.grip_force=50, grasp.hold_s=3]}\n",
     "[sweep]: field 'scenario_overrides'"),
    ("transfer", "worlds:\n  a: {scenario: memorizing_world, overrides: [grasp.hold_s=2, "
     "grasp.grip_force=50, grasp.hold_s=3]}\ncells: [[a, a]]\nsweep: {objects: [box], "
     "controllers: [memorized], grid: [[0.0, 0.0]], attempts: 1}\n",
     "field 'worlds.a.overrides'"),
])
def test_a_spec_list_setting_one_key_twice_is_refused(tmp_path, kind, text, where):
    """Neither value silently wins, as for --set given twice and a repeated YAML key."""
    from tegrasp_drake.sensitivity.study import LoadSensitivitySpec
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    load = {"sweep": LoadSweepSpec, "sensitivity": LoadSensitivitySpec,
            "transfer": LoadTransferSpec}[kind]
    spec = tmp_path / "s.yaml"
    spec.write_text(text)
    with pytest.raises(ConfigError) as refused:
        load(spec)
    assert one_line_of(refused.value) == (
        f"{spec}{' ' if where.startswith('[') else ': '}{where} sets grasp.hold_s twice "
        "('grasp.hold_s=2' at [0], then 'grasp.hold_s=3' at [2]); set it once")


def test_a_spec_list_repeating_one_setting_and_a_world_refining_its_preset_load(tmp_path):
    from tegrasp_drake.sweep.spec_file import LoadSweepSpec
    from tegrasp_drake.transfer.matrix import LoadTransferSpec
    spec = tmp_path / "s.yaml"
    spec.write_text("objects: [box]\nscenario_overrides: [grasp.hold_s=2, grasp.hold_s=2]\n")
    assert LoadSweepSpec(spec).scenario_overrides == ("grasp.hold_s=2", "grasp.hold_s=2")
    # a world's override of a field its preset sets refines the preset: not "twice"
    spec.write_text("worlds:\n  a: {scenario: memorizing_world, overrides: "
                    "[gripper.model=linkage]}\ncells: [[a, a]]\nsweep: {objects: [box], "
                    "controllers: [memorized], grid: [[0.0, 0.0]], attempts: 1}\n")
    transfer = LoadTransferSpec(spec)
    assert transfer.worlds["a"].overrides == ("gripper.model=linkage",)
    # its cell's sweep (the preset's gripper.model, then the override) expands and runs so
    from tegrasp_drake.sweep.spec import expand_trials
    from tegrasp_drake.sweep.trial_function import scenario_from_trial_spec
    from tegrasp_drake.transfer.matrix import running_sweep
    (trial,) = expand_trials(running_sweep(transfer, "a"))
    assert scenario_from_trial_spec(trial.to_dict()).gripper.model == "linkage"


def test_a_list_setting_one_key_twice_is_refused_by_the_api_too(tmp_path):
    """LoadScenario's overrides, and a SweepSpec built in code (validate_spec, run_sweep), in
    the words a spec file's scenario_overrides are refused with."""
    from tegrasp_drake.sweep.runner import run_sweep
    from tegrasp_drake.sweep.trial_function import run_trial_from_spec
    twice = "sets grasp.grip_force twice ('grasp.grip_force=30.0' at [0], then " \
            "'grasp.grip_force=60.0' at [1]); set it once"
    settings = ("grasp.grip_force=30.0", "grasp.grip_force=60.0")
    with pytest.raises(ConfigError) as refused:
        tegrasp_drake.LoadScenario(overrides=list(settings))
    assert one_line_of(refused.value) == f"LoadScenario: argument 'overrides' {twice}"
    spec = SweepSpec(objects=("box",), controllers=("open_loop",), grid=((0.0, 0.0),),
                     attempts=1, scenario_overrides=settings)
    with pytest.raises(ConfigError) as refused:
        validate_spec(spec, "api")
    assert one_line_of(refused.value) == f"api: field 'scenario_overrides' {twice}"
    with pytest.raises(ConfigError, match=r"field 'scenario_overrides' sets grasp.grip_force "):
        run_sweep(spec, run_trial_from_spec, tmp_path / "out", progress=False)
    assert not (tmp_path / "out").exists()
    assert tegrasp_drake.LoadScenario(overrides=[settings[0]] * 2).grasp.grip_force == 30.0


# Rule: a configuration file that is not there to read (missing, a folder) is a file that
# cannot be read, exit 1 for a sweep, transfer or sensitivity spec as for a scenario file or a
# hardware config (docs/user-guide.md, "Exit codes": exit 2 is a spec refused for what it
# holds).
@pytest.mark.parametrize("command, what", [
    (["sweep", "--spec"], "the sweep spec"), (["transfer"], "the transfer spec"),
    (["sensitivity"], "the sensitivity spec"), (["trial", "--scenario"], "the scenario file"),
    (["hardware", "--config"], "the hardware config"),
], ids=["sweep", "transfer", "sensitivity", "scenario", "hardware"])
@pytest.mark.parametrize("given, words", [
    ("missing.yaml", "it does not exist"), ("folder", "it is a folder; give a file"),
], ids=["missing", "folder"])
def test_a_configuration_file_that_is_not_there_exits_1(command, what, given, words, tmp_path,
                                                       capfd):
    (tmp_path / "folder").mkdir()
    path = tmp_path / given
    code, text = run_cli([*command, str(path)], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"{path}: cannot read {what}: {words}")


# Rule: a spec file this user cannot read (another user's: simulated, as root ignores modes) is
# a file that cannot be read, exit 1 as an unreadable --scenario is; exit 2 is for a spec
# refused for what it holds.
@pytest.mark.parametrize("command", [
    ["sweep", "--spec"], ["transfer"], ["sensitivity"]], ids=["sweep", "transfer", "sensitivity"])
def test_a_spec_that_cannot_be_read_exits_1(command, tmp_path, capfd, monkeypatch):
    from tegrasp_drake.rig import typed_yaml
    spec = tmp_path / "sp.yaml"
    spec.write_text("objects: [box]\n")
    deny_reading(monkeypatch, typed_yaml, "read_bounded", spec)
    code, text = run_cli([*command, str(spec), "--out", str(tmp_path / "o"), "--workers", "1"],
                         capfd)
    assert code == 1, text
    assert_one_line_error(code, text, f"{spec}: cannot read the", "Permission denied; ask its "
                          "owner to make it readable, or give a file you can read")
    assert not (tmp_path / "o").exists()
