"""Bad inputs a third hostile tester found, each tested as the class it belongs to, at the
one place its discipline lives: silent acceptance (a duplicate JSON key, an event listed
twice, an empty path, a period below the plant's step, a log's damaged scenario, a scenario
for the devices given to a simulation, a calibration file not read at load), a raw exception
instead of one line (a figure that cannot be written, a Ctrl-C that Drake wrapped, a public
function given the wrong items), a hang (a FIFO calibration, an interrupted sweep waiting for
its trial), a late refusal (an output that cannot be made, --html naming the run folder) and
an unsafe message (a control character quoted raw)."""

import dataclasses
import json
import os
import pathlib
import shutil
import signal

import pytest

import tegrasp_drake
from tests.test_bad_input import assert_one_line_error, run_cli
from tegrasp_drake import cli
from tegrasp_drake.events.event_file import MemorizedEventError, read_index
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.hardware.myrio.tactile_calibration import LoadTactileCalibration
from tegrasp_drake.rig import files, paths
from tegrasp_drake.rig.typed_yaml import ConfigError
from tegrasp_drake.scenario.scenario import LoadScenario, scenario_from_yaml, scenario_to_yaml


def _events_copy(tmp_path) -> pathlib.Path:
    folder = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), folder,
                    ignore=shutil.ignore_patterns("prismatic", "ensemble", "corrective"))
    return folder


# --- 1. silent acceptance, silent defaults ---------------------------------------------------

def test_the_one_json_reader_refuses_a_duplicate_key():
    with pytest.raises(files.DuplicateKeyError, match="key 'format_version' appears twice"):
        files.load_json('{"format_version": 3, "format_version": 2}')
    assert files.load_json('{"a": {"b": 1}, "b": 2}') == {"a": {"b": 1}, "b": 2}


def test_an_event_file_with_a_duplicate_key_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    path = folder / "box" / "reach_load.json"
    path.write_text(path.read_text().replace('"format":', '"format_version": 2,\n "format":', 1))
    with pytest.raises(MemorizedEventError, match="reach_load.json: key 'format_version' appears"):
        tegrasp_drake.load_memorized_events(folder, "box")


def test_an_index_listing_an_event_twice_is_refused(tmp_path):
    folder = _events_copy(tmp_path)
    index = json.loads((folder / "index.json").read_text())
    index["events"].append(dict(index["events"][0]))
    (folder / "index.json").write_text(json.dumps(index))
    with pytest.raises(MemorizedEventError, match="both list the box reach_load event"):
        read_index(folder)


def test_an_events_variable_naming_a_file_is_refused(tmp_path, monkeypatch, capfd):
    not_a_folder = tmp_path / "events.txt"
    not_a_folder.write_text("")
    monkeypatch.setenv(paths.EVENTS_ENV, str(not_a_folder))
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, "TEGRASP_EVENTS_DIR", "is not a folder")
    assert not (tmp_path / "x.png").exists()


# Arguments a command needs before the path option under test.
_POSITIONALS = {"plot": ["events"], "transfer": ["spec.yaml"], "sensitivity": ["spec.yaml"],
                "replay": ["run.lcmlog"],
                "emulate": ["myrio"]}


def _path_options():
    parser = cli.build_parser()
    commands = next(a for a in parser._actions if hasattr(a, "choices") and a.choices)
    return [(name, action.option_strings[0]) for name, command in commands.choices.items()
            for action in command._actions
            if action.dest in cli.PATH_ARGUMENTS and action.option_strings]


@pytest.mark.parametrize("command, option", _path_options())
def test_every_empty_path_option_is_refused(command, option, capfd):
    code, text = run_cli([command, *_POSITIONALS.get(command, []), option, ""], capfd)
    assert code == 2 and f"{option} '' is empty" in text and "Traceback" not in text


def test_a_log_given_to_plot_events_is_refused(tmp_path, capfd):
    code, text = run_cli(["plot", "events", "trial.npz", "--out", str(tmp_path / "x.png")],
                         capfd)
    assert_one_line_error(code, text, "takes no LOG", "--events DIR")


def test_records_of_a_file_or_of_no_folder_are_refused(tmp_path):
    log = tmp_path / "trial.npz"
    log.write_bytes(b"PK")
    with pytest.raises(files.UserPathError, match="'out_dir'.*is a file, not a folder"):
        tegrasp_drake.load_records(log)
    with pytest.raises(files.UserPathError, match="'out_dir'.*does not exist"):
        tegrasp_drake.load_records(tmp_path / "not yet")
    assert tegrasp_drake.load_records(tmp_path).records == {}


def test_a_sweep_spec_refuses_a_string_for_a_list():
    with pytest.raises(TypeError, match="SweepSpec: field 'objects' must be a collection"):
        tegrasp_drake.SweepSpec(objects="box")
    assert tegrasp_drake.SweepSpec(objects=["box"]).objects == ["box"]


PUBLIC_DATACLASSES = [name for name in tegrasp_drake.__all__
                      if dataclasses.is_dataclass(getattr(tegrasp_drake, name))]


@pytest.mark.parametrize("name", PUBLIC_DATACLASSES)
def test_every_public_dataclass_checks_its_collections(name):
    cls = getattr(tegrasp_drake, name)
    assert getattr(cls.__init__, "__checked_arguments__", False), f"{name} lacks @public_dataclass"


@pytest.mark.parametrize("assignment", ["controller.update_period_s=0.000000001",
                                        "arm.control_period_s=0.0001",
                                        "disturbance.hit_duration_s=0.0005"])
def test_a_time_shorter_than_the_plant_step_is_refused(assignment):
    field = assignment.split("=")[0]
    with pytest.raises(ConfigError, match=f"field '{field}' must be at least the simulation's "
                                          r"time step plant_config.time_step = 0.001 s"):
        LoadScenario(overrides=[assignment])


def test_a_logged_scenario_is_checked_as_a_loaded_one():
    text = scenario_to_yaml(LoadScenario(name="box"))
    assert scenario_from_yaml(text).object.mass > 0
    damaged = text.replace("mass: 0.15", "mass: .nan", 1)
    assert damaged != text
    with pytest.raises(ConfigError, match="run log 'x': field 'object.mass' must be a finite"):
        scenario_from_yaml(damaged, "run log 'x'")


# Rule: a logged scenario is walked field by field as a loaded one is (check_fields): a section
# corrupt bytes made a scalar is named, never an AssertionError inside Drake's loader.
def test_a_logged_scenario_whose_section_is_text_names_the_field():
    with pytest.raises(ConfigError, match="run log 'x': field 'object' must be a mapping"):
        scenario_from_yaml("object: name-box\n", "run log 'x'")


def test_a_trial_refuses_a_scenario_for_the_devices(tmp_path, capfd):
    scenario = tmp_path / "scenarios.yaml"
    scenario.write_text("mine:\n  station: !HardwareStationConfig {ready_timeout: 1.0}\n")
    code, text = run_cli(["trial", "--scenario", str(scenario), "--scenario-name", "mine",
                          "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, "!HardwareStationConfig", "tegrasp hardware")
    assert not (tmp_path / "run").exists()


def _fifo(path):
    os.mkfifo(path)


@pytest.mark.parametrize("make, words", [
    (None, "it does not exist"),
    (_fifo, "is a named pipe (FIFO)"),
    (lambda path: path.write_text("- 1\n- 2\n"), "must be a mapping of fields"),
    (lambda path: path.write_text("left: {gain: [.nan]}\n"), "must be a finite number"),
])
def test_the_hardware_config_reads_its_calibration_file_at_load(make, words, tmp_path):
    calibration = tmp_path / "pads.yaml"
    if make:
        make(calibration)
    config = HardwareStationConfig()
    config.tactile.calibration_file = str(calibration)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(config))
    with pytest.raises(ConfigError, match="field 'tactile.calibration_file': .*pads.yaml") as e:
        tegrasp_drake.LoadHardwareConfig(tmp_path / "hw.yaml")
    assert words in str(e.value)


# --- 2. one line, not a raw exception --------------------------------------------------------

def test_a_figure_that_cannot_be_written_is_one_line(tmp_path, capfd):
    out = tmp_path / ("a" * 300 + ".png")  # longer than a file name may be
    code, text = run_cli(["plot", "events", "--out", str(out)], capfd)
    # refused before the figure is drawn, by the check every output file gets
    assert_one_line_error(code, text, "--out", "File name too long")
    assert code == cli.EXIT_ERROR and list(tmp_path.iterdir()) == []


def test_a_figure_on_a_full_disk_is_one_line_and_the_old_one_kept(tmp_path):
    import errno
    from tegrasp_drake.figures.figure_files import new_figure, save_figure
    old = tmp_path / "fig.png"
    old.write_bytes(b"the earlier figure")
    figure = new_figure(2, 2)

    def disk_full(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    figure.savefig = disk_full
    with pytest.raises(files.UserPathError, match="cannot write the figure .*fig.png: No space"):
        save_figure(figure, old)
    assert old.read_bytes() == b"the earlier figure" and len(list(tmp_path.iterdir())) == 1


def test_a_public_function_checks_the_items_of_a_list(tmp_path):
    with pytest.raises(TypeError, match="save_memorized_events: argument 'events' must be an "
                                        "iterable of MemorizedEvent"):
        tegrasp_drake.save_memorized_events(tmp_path, ["not an event"])
    assert not (tmp_path / "index.json").exists()


def test_a_calibration_device_is_refused_in_one_line():
    with pytest.raises(ConfigError, match="/dev/zero: more than"):
        LoadTactileCalibration("/dev/zero")


def test_an_interrupt_that_drake_wrapped_is_reported_as_an_interrupt(monkeypatch, capfd):
    from tegrasp_drake.commands import plot

    def interrupted_inside_a_calc(args):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            for _ in range(10_000_000):  # the handler runs between two bytecodes
                pass
        except KeyboardInterrupt:  # as pybind11 turns it into its own error
            raise TypeError("SetFromVector(): incompatible function arguments") from None
        return 0

    monkeypatch.setattr(plot, "run", interrupted_inside_a_calc)
    code, text = run_cli(["plot", "events"], capfd)
    assert code == 128 + signal.SIGINT and "interrupted (SIGINT)" in text
    assert "internal error" not in text
    assert files.interrupt_received() == "SIGINT"
    monkeypatch.undo()
    code, text = run_cli(["plot", "events", "extra"], capfd)  # the next run starts clean
    assert "interrupted" not in text and files.interrupt_received() is None


# --- 3. no hang ------------------------------------------------------------------------------

def test_a_fifo_calibration_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "pads.yaml")  # no writer: an open() for reading would block
    with pytest.raises(ConfigError, match="is a named pipe"):
        LoadTactileCalibration(str(tmp_path / "pads.yaml"))


def test_an_interrupted_sweep_abandons_its_running_trial(tmp_path):
    from tests.fake_trials import stuck_fake_trial
    from tegrasp_drake.sweep.runner import _run_on_process_pool
    marker = str(tmp_path / "second")
    outcomes = _run_on_process_pool(stuck_fake_trial, [{"trial_id": "first"},
                                                       {"trial_id": "second",
                                                        "marker": marker}], 1)
    assert next(outcomes)[0] == "first"
    while not os.path.exists(marker + ".started"):  # the long trial is running
        os.sched_yield()
    outcomes.close()  # what Ctrl-C does to the sweep's loop
    assert not os.path.exists(marker + ".finished")  # abandoned, not waited for
    worker = int(pathlib.Path(marker + ".started").read_text())
    with pytest.raises(ProcessLookupError):
        os.kill(worker, 0)


# --- 4. refused before the work --------------------------------------------------------------

def test_an_output_folder_that_cannot_be_made_is_refused_up_front():
    assert "not writable" in files.folder_problem("/proc/tegrasp-test/events")


def test_html_naming_the_run_folder_is_refused_up_front(tmp_path, capfd):
    out = tmp_path / "run"
    code, text = run_cli(["trial", "--out", str(out), "--html", str(out)], capfd)
    assert_one_line_error(code, text, "--html", "is the run's folder")
    assert not out.exists()


# --- 5. safe messages ------------------------------------------------------------------------

@pytest.mark.parametrize("character", ["\x1b", "\x07", "\x9b", "\u2028", "\r", "\n"])
def test_an_error_never_quotes_a_control_character_raw(character):
    quoted = files.one_line(f"a{character}[2Jb")
    assert quoted.isprintable() and character not in quoted


def test_a_set_value_with_an_escape_is_quoted_safely(capfd):
    code, text = run_cli(["trial", "--set", "object.name=a\x1b[2Jb"], capfd)
    assert code != 0 and "\x1b" not in text and "\\x1b[2Jb" in text
    code, text = run_cli(["trial", "--controller", "x\x1b[2J"], capfd)  # argparse's words
    assert code == 2 and "\x1b" not in text and "\\x1b[2J" in text
