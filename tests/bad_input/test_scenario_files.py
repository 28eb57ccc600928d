"""Scenario files and --set values as YAML and JSON: one safe reader refuses syntax errors,
binary files, duplicate or merged keys, YAML 1.1 booleans, nesting too deep, nulls and empty
values the user gave, a YAML tag where no variant is chosen, a key past YAML's 1024
characters, in one line naming the file and field; a built-in name given as a file, a file
without a field, or a stored scenario read back are named for what they are."""

import pytest

import tegrasp_drake as T
from tegrasp_drake.rig import files
from tegrasp_drake.scenario.scenario import LoadScenario
from tests.bad_input.probes import assert_one_line_error, one_error_line, refusal, run_cli


# --- scenario values ----------------------------------------------------------------------

@pytest.mark.parametrize("overrides, expected", [
    (["object.friction=0"], "field 'object.friction' must be positive"),
    (["object.mass=0"], "field 'object.mass' must be positive"),
    (["object.mass=.nan"], "field 'object.mass' must be a finite number, got float nan"),
    (["object.mass=.inf"], "field 'object.mass' must be a finite number, got float inf"),
    (["object.friction=.inf"], "field 'object.friction' must be a finite number"),
    (["controller.matching.sa_threshold=.nan"], "field 'controller.matching.sa_threshold' must be a finite"),
    (["controller.matching.ra_threshold=2"], "field 'controller.matching.ra_threshold' must lie in [-1, 1]"),
    (["gripper.position_loop_hz=10"], "field 'gripper.position_loop_hz' must lie in [40, 150]"),
    (["gripper.screw_efficiency=0.9"], "field 'gripper.screw_efficiency' must lie in [0.2, 0.5]"),
    (["controller.matching.ra_envelope_hz=-1"], "field 'controller.matching.ra_envelope_hz' must be 0 (no RA"),
    (["controller.matching.ra_envelope_hz=500"], "between 0 and half the RA rate (500 Hz), got 500"),
    (["controller.matching.ra_noise_floor_sigmas=5.39", "controller.matching.ra_noise_quiet_s=3"],
     "field 'controller.matching.ra_noise_quiet_s' must end with the approach, by grasp.settle_s + "
     "grasp.reach_s = 2.8 s"),
    (["placement.offset=[.nan,0]"], "field 'placement.offset[0]' must be a finite number"),
    (["placement.yaw_deg=.nan"], "field 'placement.yaw_deg' must be a finite number"),
    (["plant_config.time_step=.nan"], "field 'plant_config.time_step' must be a finite"),
    (["controller.event_object_may_differ=[colour]"],
     "field 'controller.event_object_may_differ[0]' must name a field"),
])
def test_a_bad_scenario_value_is_named_and_nothing_runs(overrides, expected, capfd):
    argv = ["trial", "--controller", "memorized"]
    for assignment in overrides:
        argv += ["--set", assignment]
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, expected, f"--set {overrides[0]}")


@pytest.mark.parametrize("overrides, expected", [
    (["object.mass=150 g"], "field 'object.mass' must be a finite number, got str '150 g' (the "
                            "field is in kg and takes a bare number: write 0.15)"),
    (["placement.offset=[0, 15mm]"], "field 'placement.offset[1]' must be a finite number, got "
                                     "str '15mm' (the field is in m and takes a bare number: "
                                     "write 0.015)"),
    (["grasp.grip_force=25 N"], "(the field is in N and takes a bare number: write 25)"),
    (["object.mass=5 lb"], "(the field is in kg: write the number in kg, without a unit)"),
])
def test_a_number_written_with_its_unit_is_told_the_fields_unit(overrides, expected):
    with pytest.raises(T.ConfigError) as error:
        LoadScenario(overrides=overrides)
    assert expected in str(error.value)


def test_a_yaml_syntax_error_in_a_scenario_file_is_named(tmp_path, capfd):
    scenario = tmp_path / "bad.yaml"
    scenario.write_text("mine:\n  object: {name: box\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), "not valid YAML: line 3, column 1: "
                          "expected ',' or '}'")


@pytest.mark.parametrize("text, where", [("mine:\n\tobject: {name: box}\n", "line 2, column 1"),
                                         ("mine:\n  object: {mass:\t0.1}\n", "line 2")])
def test_a_tab_in_a_scenario_file_is_told_to_be_spaces(tmp_path, capfd, text, where):
    """Not PyYAML's "found character '\\t' that cannot start any token"."""
    scenario = tmp_path / "tabs.yaml"
    scenario.write_text(text)
    code, said = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, said, str(scenario), f"not valid YAML: {where}",
                          "a tab where YAML takes only spaces (it never indents with tabs); "
                          "use spaces")
    assert "cannot start any token" not in said


@pytest.mark.parametrize("command", [["record-events"], ["trial"]])
def test_a_built_in_scenario_name_given_as_its_file_says_use_scenario_name(command, capfd):
    code, text = run_cli([*command, "--scenario", "memorizing_world"], capfd)
    assert_one_line_error(code, text, "'memorizing_world' is a built-in scenario",
                          "--scenario-name memorizing_world")


def test_a_binary_scenario_file_is_one_line(tmp_path, capfd):
    scenario = tmp_path / "binary.yaml"
    scenario.write_bytes(b"mine:\n  object: \xff\xfe\x00\x01\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), "not UTF-8 text")


def test_a_colour_on_a_built_in_object_is_honoured():
    scenario = LoadScenario(overrides=["object.color=[0.1,0.2,0.3,1.0]"])
    assert scenario.object.color == [0.1, 0.2, 0.3, 1.0]
    assert scenario.object.mass == LoadScenario().object.mass  # the rest is the built-in's


# --- 1. silent acceptance, silent defaults ---------------------------------------------------

def test_the_one_json_reader_refuses_a_duplicate_key():
    with pytest.raises(files.DuplicateKeyError, match="key 'format_version' appears twice"):
        files.load_json('{"format_version": 3, "format_version": 2}')
    assert files.load_json('{"a": {"b": 1}, "b": 2}') == {"a": {"b": 1}, "b": 2}


def test_the_json_reader_refuses_what_json_has_not():
    for text in ('{"a": NaN}', '{"a": Infinity}', '{"a": -Infinity}', '[' + "1" * 400 + ']'):
        with pytest.raises(files.JsonValueError):
            files.load_json(text)
    assert files.load_json('{"a": 1e300, "b": 12}') == {"a": 1e300, "b": 12}


@pytest.mark.parametrize("assignment", ["object.size=[]", "object.shape=''", "object.color=[]",
                                        "object.file=''"])
def test_an_empty_value_the_user_gives_is_refused_not_read_as_unset(assignment):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    field = assignment.split("=")[0]
    with pytest.raises(ConfigError, match=f"field '{field}' is empty: give a value, or leave"):
        LoadScenario(name="box", overrides=[assignment])


def test_a_stored_scenario_reads_back_as_a_scenario_file(tmp_path):
    from tegrasp_drake.scenario.scenario import LoadScenario, scenario_to_yaml
    stored = scenario_to_yaml(LoadScenario(name="box"))
    assert "file:" not in stored  # empty "not set" fields are left out of the text
    path = tmp_path / "s.yaml"
    path.write_text("x:\n" + "".join(f"  {line}\n" for line in stored.splitlines()))
    assert LoadScenario(path, name="x").object.size == LoadScenario(name="box").object.size


def test_a_null_scenario_entry_is_refused_naming_it(tmp_path, capfd):
    path = tmp_path / "s.yaml"
    path.write_text("x:\n")
    code, text = run_cli(["trial", "--scenario", str(path), "--scenario-name", "x",
                          "--out", str(tmp_path / "o")], capfd)
    assert code == 1
    errors = one_error_line(text)
    assert len(errors) == 1 and "scenario 'x' is empty" in errors[0], text


# Rule: a file that holds no scenario (a password file, another program's settings) is
# refused without its keys shown, only counted; a scenario file with the name misspelt still
# lists its scenarios.
def test_a_file_of_no_scenarios_is_refused_without_listing_its_keys(tmp_path, capfd):
    path = tmp_path / "s.yaml"
    path.write_text("db_password: hunter2\napi_token: abc\n")
    code, text = run_cli(["trial", "--scenario", str(path), "--out", str(tmp_path / "o")],
                         capfd)
    assert_one_line_error(code, text, "no scenario named 'default'", "2 top-level key(s)")
    assert code == 1 and "db_password" not in text and "hunter2" not in text
    assert not (tmp_path / "o").exists()


def test_a_misspelt_scenario_name_lists_the_files_scenarios(tmp_path, capfd):
    path = tmp_path / "s.yaml"
    path.write_text("mine: {}\ntheirs: {object: {name: box}}\n")
    code, text = run_cli(["trial", "--scenario", str(path), "--scenario-name", "mnie",
                          "--out", str(tmp_path / "o")], capfd)
    assert_one_line_error(code, text, "no scenario named 'mnie' (scenarios: mine, theirs); "
                                      "did you mean 'mine'?")


def test_a_file_of_many_scenarios_lists_them_whole_up_to_thirty(tmp_path, capfd):
    """The built-in file's eleven names are listed whole, not cut mid-name; a file of more
    than thirty counts the rest."""
    code, text = run_cli(["trial", "--scenario-name", "nonesuch"], capfd)
    assert_one_line_error(code, text, "sweep_grade)")
    path = tmp_path / "many.yaml"
    path.write_text("".join(f"scene_{k}: {{}}\n" for k in range(35)))
    code, text = run_cli(["trial", "--scenario", str(path), "--scenario-name", "nonesuch"],
                         capfd)
    assert_one_line_error(code, text, "scene_29, and 5 more)")


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
    refusal(lambda: getattr(importlib.import_module(module), name)(path), str(path),
             f"{what} is empty (no fields)")


# Rule: the field an empty spec's refusal gives as an example is one the spec takes (the
# sensitivity spec's names a real uncertain parameter, not a literal that drifted).
@pytest.mark.parametrize("loader", ["tegrasp_drake.sensitivity.study:LoadSensitivitySpec",
                                    "tegrasp_drake.sweep.spec_file:LoadSweepSpec"])
def test_the_example_an_empty_spec_is_refused_with_loads(tmp_path, loader):
    import importlib
    import re
    load = getattr(importlib.import_module(loader.split(":")[0]), loader.split(":")[1])
    path = tmp_path / "spec.yaml"
    path.write_text("")
    with pytest.raises(T.ConfigError) as refused:
        load(path)
    example = re.search(r"e\.g\. (\w+: \[[^\]]*\])", str(refused.value))
    assert example, refused.value
    path.write_text(example.group(1) + "\n")
    load(path)


def test_an_empty_value_is_kept_where_the_field_declares_what_empty_means(tmp_path):
    path = tmp_path / "hardware.yaml"
    path.write_text('tactile: {port: /dev/ttyACM0, calibration_file: ""}\n')
    assert T.LoadHardwareConfig(path).tactile.calibration_file == ""
    refusal(lambda: T.LoadScenario(name="box", overrides=["object.shape=''"]),
             "'object.shape'")
    assert T.LoadScenario(name="box", overrides=[
        "controller.event_object_may_differ=[]"]).controller.event_object_may_differ == []


# Rule: values are read as YAML 1.2 reads them (rig/core_schema_yaml.py): `yes`, `no`, `on`
# and `off` (any case) are text, which a true/false setting refuses saying to write true or
# false, in a file and in --set alike; a text setting keeps them as text.
@pytest.mark.parametrize("word", ["yes", "no", "on", "off", "Yes", "OFF", "y", "N"])
def test_a_yaml_11_boolean_word_is_refused_for_a_true_false_setting(tmp_path, word):
    path = tmp_path / "s.yaml"
    path.write_text(f"default: {{arm: {{tracker: {{continuous_joints: "
                    f"[{word}, false, false, true, true, true]}}}}}}\n")
    refusal(lambda: T.LoadScenario(path), "'arm.tracker.continuous_joints[0]'",
             "write true or false")
    setting = f"vibration.film.impact_enabled={word}"
    refusal(lambda: T.LoadScenario(name="box", overrides=[setting]),
             "'vibration.film.impact_enabled'", "write true or false")


def test_true_and_false_are_still_read_and_a_text_setting_keeps_yes_as_text():
    scenario = T.LoadScenario(name="box", overrides=["vibration.film.impact_enabled=False",
                                                     "object.name=yes", "object.shape=box",
                                                     "object.size=[0.04,0.04,0.1]",
                                                     "object.mass=0.1", "object.friction=0.5"])
    assert scenario.vibration.film.impact_enabled is False and scenario.object.name == "yes"


# Rule: a duplicate key is refused naming both lines, a merge key '<<' too (the first
# merge's values were dropped without a word); one '<<' with a list of mappings merges both.
def test_two_merge_keys_in_one_mapping_are_refused(tmp_path):
    from tegrasp_drake.rig.typed_yaml import ConfigError
    from tegrasp_drake.scenario.scenario import LoadScenario
    twice = tmp_path / "twice.yaml"
    twice.write_text("default:\n  object: {name: box}\nother:\n  <<: {random_seed: 681}\n"
                     "  <<: {random_seed: 682}\n")
    with pytest.raises(ConfigError, match="key '<<' appears twice.*list of them"):
        LoadScenario(str(twice), "other")
    listed = tmp_path / "listed.yaml"
    listed.write_text("default:\n  object: {name: box}\nother:\n"
                      "  <<: [{random_seed: 681}, {object: {name: thin_cylinder}}]\n")
    scenario = LoadScenario(str(listed), "other")
    assert scenario.random_seed == 681 and scenario.object.name == "thin_cylinder"


@pytest.mark.parametrize("entry, expected", [
    ("  object: !ObjectConfig {mass: 0.1}\n",
     "field 'object': a YAML tag (!ObjectConfig) is not allowed here; remove it"),
    ("  object: !Nonsense {mass: 0.1}\n",
     "field 'object': a YAML tag (!Nonsense) is not allowed here; remove it"),
    ("  object: {mass: !Nonsense {a: 1}}\n",
     "field 'object.mass': a YAML tag (!Nonsense) is not allowed here; remove it"),
    ("  plant_config: !Nonsense {time_step: 0.001}\n",
     "field 'plant_config': a YAML tag (!Nonsense) is not allowed here; remove it"),
])
def test_a_yaml_tag_where_no_variant_is_chosen_is_refused_naming_its_field(entry, expected,
                                                                            tmp_path, capfd):
    scenario = tmp_path / "tagged.yaml"
    scenario.write_text("mine:\n" + entry)
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), expected)
    assert "unknown field" not in text


def test_a_yaml_tag_still_chooses_the_controller(tmp_path):
    scenario = tmp_path / "tagged.yaml"
    scenario.write_text("mine:\n  controller: !TaxelAwareControllerConfig {}\n")
    assert LoadScenario(scenario, "mine").controller.name == "taxel_aware"


@pytest.mark.parametrize("entry, length", [
    ("  " + "k" * 500_000 + ": 1\n", 500_000),
    ("  object: {mass: 0.1, " + "k" * 2000 + ": 1}\n", 2000),
    ("  - " + "k" * 1025 + ": 1\n", 1025),
])
def test_a_key_past_yamls_1024_characters_is_named_by_its_length(entry, length, tmp_path,
                                                                  capfd):
    scenario = tmp_path / "long_key.yaml"
    scenario.write_text("mine:\n" + entry)
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario), f"line 2: a key of {length} characters; "
                          "keys are at most 1024 characters")
    assert len(text) < 400, text


def test_a_key_of_1024_characters_is_read(tmp_path, capfd):
    scenario = tmp_path / "long_key.yaml"
    scenario.write_text("mine:\n  " + "k" * 1024 + ": 1\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, "unknown field")


def test_yaml_nested_too_deeply_says_the_limit_and_what_to_give(tmp_path, capfd):
    scenario = tmp_path / "deep.yaml"
    scenario.write_text("mine: " + "[" * 5000 + "]" * 5000 + "\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, "nests deeper than Python's recursion limit",
                          "give a flat mapping of its fields")


# --- committed scenarios ------------------------------------------------------------------

# Rule: every scenario the repository ships or commits loads: the named scenarios, and each
# stored scenario text (a memorized event's and an events index entry's, the package's events
# and the studies' under analysis/), those written before a key was removed included.
REPOSITORY = files.pathlib.Path(__file__).resolve().parents[2]


def _stored_scenario_texts():
    """[(file, k), text] of each scenario text in the repository's JSON files: a 'scenario'
    field of several lines (the YAML record-events stores; a one-line one, an ensemble's or a
    template's, names what made the event, events/FORMAT.md)."""
    texts = []
    for path in sorted(REPOSITORY.glob("[!.]*/**/*.json")):
        raw = path.read_text()
        if '"scenario": "' not in raw:
            continue
        data = files.load_json(raw)
        entries = data.get("events", []) if path.name == "index.json" else [data]
        texts += [((str(path.relative_to(REPOSITORY)), k), entry["scenario"])
                  for k, entry in enumerate(entries)
                  if isinstance(entry.get("scenario"), str) and "\n" in entry["scenario"]]
    return texts


def test_every_committed_scenario_text_loads():
    from tegrasp_drake.scenario.scenario import scenario_from_yaml
    texts = _stored_scenario_texts()
    studies = [where for where, _ in texts if where[0].startswith("analysis/results_transfer")]
    # the studies': 9 events in each of 4 folders, in its own file and its folder's index
    assert len(studies) == 72 and len(texts) > len(studies)
    for (path, k), text in texts:
        scenario_from_yaml(text, f"{path} [{k}]")


def test_every_named_scenario_loads():
    import yaml
    names = yaml.safe_load((REPOSITORY / "tegrasp_drake" / "scenarios" / "scenarios.yaml")
                           .read_text())
    assert "default" in names
    for name in names:
        assert LoadScenario(name=name).object.name


def test_a_stored_scenario_is_read_without_the_removed_driver_gains():
    from tegrasp_drake.scenario.scenario import scenario_from_yaml
    stored = ("gripper:\n  model: linkage\n  driver_position_gain: 1000.0\n"
              "  driver_damping_gain: 1.0\n")
    assert scenario_from_yaml(stored).gripper.model == "linkage"


def test_a_scenario_file_naming_a_removed_driver_gain_says_what_replaced_it(tmp_path, capfd):
    scenario = tmp_path / "old.yaml"
    scenario.write_text("mine:\n  gripper:\n    driver_position_gain: 1000.0\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine"],
                         capfd)
    assert_one_line_error(code, text, str(scenario),
                          "'gripper.driver_position_gain' was removed",
                          "gripper.position_loop_hz", "delete it")


# Rule: a controller section's YAML tag and its name select the controller together or not
# at all: neither silently wins, in a file, a --set or a stored scenario; --controller still
# replaces the controller a section selects.
@pytest.mark.parametrize("entry, tag, name", [
    ("  controller: !HeuristicControllerConfig {name: memorized}\n",
     "!HeuristicControllerConfig", "memorized"),
    ("  controller: !TaxelAwareControllerConfig {name: open_loop}\n",
     "!TaxelAwareControllerConfig", "open_loop"),
])
def test_a_controller_tag_and_name_that_disagree_are_refused_naming_both(entry, tag, name,
                                                                        tmp_path, capfd):
    scenario = tmp_path / "tagged.yaml"
    scenario.write_text("mine:\n" + entry)
    message = refusal(lambda: LoadScenario(scenario, "mine"), "field 'controller'", tag,
                      f"'{name}'", "select different controllers")
    assert str(scenario) in message
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine",
                          "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, tag, f"'{name}'")
    assert code == 1


def test_a_set_controller_whose_tag_and_name_disagree_is_refused(tmp_path, capfd):
    assignment = "controller=!HeuristicControllerConfig {name: open_loop}"
    refusal(lambda: LoadScenario(overrides=[assignment]), "!HeuristicControllerConfig",
            "'open_loop'", "select different controllers")
    code, text = run_cli(["trial", "--set", assignment, "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, "!HeuristicControllerConfig", "'open_loop'")
    assert code == 1


def test_a_controller_tag_and_name_that_agree_load_and_a_choice_replaces_them(tmp_path):
    scenario = tmp_path / "tagged.yaml"
    scenario.write_text("mine:\n  controller: !HeuristicControllerConfig {name: heuristic}\n"
                        "other:\n  controller: !HeuristicControllerConfig {}\n")
    assert LoadScenario(scenario, "mine").controller.name == "heuristic"
    assert LoadScenario(scenario, "other", controller="memorized").controller.name == (
        "memorized")
