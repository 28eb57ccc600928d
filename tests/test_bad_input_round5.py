"""Bad inputs a fifth hostile tester found, each re-run through the entry point it reached and
tested at the one place its discipline lives:

- an integer written as text (rig/integer_text.py): every typed reader (YAML files, --set,
  sweep specs, JSON, integer options) reads it with one bound, a float's range, decided from
  the text's length; an integer field's type error advises digits, not 3.0;
- a file a run will write (rig/files.replace_problem): a folder in a sweep record's or an
  events file's place is refused before the trials or the recording run, and a reader names
  what is there (folder, FIFO) instead of "missing";
- a folder named by the environment (rig/paths.user_events_dir): a path through a file is
  refused naming the variable;
- a public class's constructor (rig/api_boundary.public_api): its arguments' types, by name.
"""

import dataclasses
import enum
import inspect
import os

import pytest

import tegrasp_drake
from tegrasp_drake.events import event_file, events_folder
from tegrasp_drake.hardware.config import LoadHardwareConfig
from tegrasp_drake.rig import paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.sweep.spec_file import LoadSweepSpec
from tests.test_bad_input import assert_one_line_error, folder_contents, run_cli

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


# --- 2. a folder in place of a sweep record ------------------------------------------------------

def test_a_folder_in_place_of_a_sweep_record_is_refused_before_the_trial_runs(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n"
                    "grid: [[0.0, 0.0]]\n")
    argv = ["sweep", "--spec", str(spec), "--out", str(tmp_path / "out"), "--workers", "1",
            "--no-progress", "--trial-function", "tests.fake_trials:fake_trial"]
    assert run_cli(argv, capfd)[0] == 0
    record = next((tmp_path / "out" / "trials").glob("*.json"))
    record.unlink()
    record.mkdir()
    (record / "mine.txt").write_text("kept")
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, str(record), "is a folder", "nothing was run")
    assert (record / "mine.txt").read_text() == "kept"


# --- 3. record-events checks its destination before simulating; readers name what is there ---

@pytest.fixture
def no_simulation(monkeypatch):
    """Fails a test whose command reaches the (minutes long) recording."""
    from tegrasp_drake.recording import paper_events

    def simulated(*args, **kwargs):
        raise AssertionError("record-events simulated before checking its destination")
    monkeypatch.setattr(paper_events, "record_events", simulated)


@pytest.mark.parametrize("damage, words", [
    (lambda ev: (ev / "index.json").mkdir(), "is a folder"),
    (lambda ev: (ev / "index.json").write_text('{"format": "tegrasp.memorized_event_index", '),
     "is not valid JSON"),
    (lambda ev: (ev / "box").write_text("a file where the box's folder belongs"),
     "is not a folder"),
])
def test_record_events_refuses_a_destination_it_could_not_save_into_before_simulating(
        damage, words, tmp_path, capfd, no_simulation):
    events = tmp_path / "ev"
    events.mkdir()
    damage(events)
    before = folder_contents(events)
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}", words, "nothing was recorded")
    assert folder_contents(events) == before


@pytest.mark.parametrize("make, words", [
    (lambda path: path.mkdir(), "is a folder, not a file"),
    (lambda path: os.mkfifo(path), "is a named pipe (FIFO)"),
    (lambda path: path.symlink_to("/dev/zero"), "is a device"),
])
def test_an_index_that_is_not_a_file_is_named_for_what_it_is(make, words, tmp_path):
    make(tmp_path / event_file.INDEX_FILE)
    with pytest.raises(event_file.MemorizedEventError) as refused:
        event_file.read_index(tmp_path)
    assert words in str(refused.value) and "missing" not in str(refused.value)
    with pytest.raises(event_file.MemorizedEventError, match=words.split(" (")[0]):
        events_folder.find_memorized_events([tmp_path], "box")


def test_an_index_that_does_not_exist_is_still_missing(tmp_path):
    with pytest.raises(event_file.MemorizedEventError, match="file is missing"):
        event_file.read_index(tmp_path)


# --- 6. an events folder named through a file ---------------------------------------------------

def test_an_events_variable_through_a_file_is_refused_naming_it(tmp_path, monkeypatch, capfd):
    a_file = tmp_path / "hostname"
    a_file.write_text("not a folder\n")
    monkeypatch.setenv(paths.EVENTS_ENV, str(a_file / "x"))
    code, text = run_cli(["trial", "--out", str(tmp_path / "out")], capfd)
    assert_one_line_error(code, text, paths.EVENTS_ENV, str(a_file))
    assert not (tmp_path / "out").exists()


def test_a_data_home_through_a_file_is_refused_naming_it(tmp_path, monkeypatch):
    a_file = tmp_path / "data"
    a_file.write_text("not a folder\n")
    monkeypatch.delenv(paths.EVENTS_ENV, raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(a_file))
    with pytest.raises(OSError, match="XDG_DATA_HOME"):
        paths.user_events_dir()


def test_an_events_variable_not_there_yet_is_the_folder_to_make(tmp_path, monkeypatch):
    monkeypatch.setenv(paths.EVENTS_ENV, str(tmp_path / "new" / "events"))
    assert paths.user_events_dir() == tmp_path / "new" / "events"


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


def test_a_log_that_stops_is_reported_once_by_the_run_and_named_by_its_closing_error():
    from types import SimpleNamespace

    from tegrasp_drake.runs.hardware_run import RunReporter
    station = SimpleNamespace(GetOutputPort=lambda name: SimpleNamespace(Eval=lambda c: []),
                              GetMyContextFromRoot=lambda context: context)
    lines = []
    reporter = RunReporter(diagram=None, station=station,
                           grasp=SimpleNamespace(transitions=lambda context: []),
                           drake_lcm=SimpleNamespace(Publish=lambda channel, data: None),
                           out=lines.append, log_problem=lambda: "the LCM log x stopped")
    reporter(SimpleNamespace(get_time=lambda: 1.0))
    assert reporter.log_fault == "the LCM log x stopped"  # the closing error's words
    assert len(lines) == 1 and "FAULT" in lines[0] and "log x" not in lines[0]
