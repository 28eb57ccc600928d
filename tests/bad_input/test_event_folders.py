"""Where memorized events are read from and saved to: --events, TEGRASP_EVENTS_DIR and
XDG_DATA_HOME name a folder (or one to make); a file, a missing index, a folder without
events or a destination that cannot be saved into is named by its option or variable before
anything records or runs; saving replaces an object's events all or nothing."""

import os

import pytest

from tegrasp_drake.events import event_file, events_folder
from tegrasp_drake.events.events_folder import save_memorized_events
from tegrasp_drake.rig import files, paths
from tests.bad_input.probes import (assert_one_line_error, denied_for, edit_json,
                                    folder_contents, memorized_events, run_cli, run_probe)


def test_the_corrective_events_are_read_from_the_events_folder_given(events_copy, capfd):
    edit_json(events_copy / "corrective" / "box" / "hold_avoid.json",
          lambda data: data["samples"].update(ra_left=[0.0] * len(data["samples"]["ra_left"])))
    code, text = run_cli(["trial", "--events", str(events_copy), "--set",
                          "controller.memorized_corrective.events=[hold_avoid]"], capfd)
    assert_one_line_error(code, text, str(events_copy / "corrective"),
                          "channels ['ra_left'] are zero throughout the window")


def test_a_failed_staging_leaves_the_old_events_whole(tmp_path, monkeypatch):
    old = memorized_events(seed=1)
    save_memorized_events(tmp_path, old)
    before = folder_contents(tmp_path)
    from tegrasp_drake.events import events_folder
    real_stage, calls = events_folder.staged_file, []

    def stage_until_the_disk_is_full(path, data, **options):
        calls.append(path)
        if len(calls) == 3:
            raise OSError(28, "No space left on device")
        return real_stage(path, data, **options)
    monkeypatch.setattr(events_folder, "staged_file", stage_until_the_disk_is_full)
    with pytest.raises(OSError):
        save_memorized_events(tmp_path, memorized_events(seed=2))
    assert folder_contents(tmp_path) == before


def test_record_events_does_not_record_another_object_under_an_objects_name(tmp_path,
                                                                          capfd):
    (tmp_path / "events").mkdir()
    code, text = run_cli(["record-events", "--object", "thin_cylinder", "--set",
                          "object.name=box", "--events", str(tmp_path / "events")], capfd)
    assert_one_line_error(code, text, "--object thin_cylinder", "would record the object 'box'")
    code, text = run_cli(["record-events", "--object", "thin_cylinder", "--scenario-name",
                          "box", "--events", str(tmp_path / "events")], capfd)
    assert_one_line_error(code, text, "give one or the other")
    assert list((tmp_path / "events").iterdir()) == []


def test_record_events_with_object_and_set_records_that_object_with_the_setting():
    import argparse
    from tegrasp_drake.commands.record_events import _scenarios_to_record
    args = argparse.Namespace(object=["thin_cylinder"], scenario=None, scenario_name=None,
                              overrides=["random_seed=603"])
    (name, scenario), = _scenarios_to_record(args)
    assert name == "thin_cylinder" and scenario.object.name == "thin_cylinder"
    assert scenario.random_seed == 603


def test_an_events_variable_naming_a_file_is_refused(tmp_path, monkeypatch, capfd):
    not_a_folder = tmp_path / "events.txt"
    not_a_folder.write_text("")
    monkeypatch.setenv(paths.EVENTS_ENV, str(not_a_folder))
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, "TEGRASP_EVENTS_DIR", "is not a folder")
    assert not (tmp_path / "x.png").exists()


# Rule: the folder TEGRASP_EVENTS_DIR names holds events, or nothing yet; one of other files
# (a mistyped path) is refused as `--events` there is, not passed over for the package's.
def test_an_events_variable_naming_a_folder_of_other_files_is_refused(tmp_path, monkeypatch,
                                                                     capfd):
    from tegrasp_drake.commands.events_option import check_events_folder
    folder = tmp_path / "etc"
    folder.mkdir()
    monkeypatch.setenv(paths.EVENTS_ENV, str(folder))
    (folder / ".hidden").write_text("")
    check_events_folder(None)  # empty but for a hidden file: no events recorded yet
    (folder / "hosts").write_text("127.0.0.1 localhost\n")
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "x.png")], capfd)
    assert_one_line_error(code, text, f"TEGRASP_EVENTS_DIR='{folder}': {folder} is not an "
                          "events folder: it holds no index.json but other files (e.g. "
                          "'hosts'); point it at your events folder")
    assert not (tmp_path / "x.png").exists()
    (folder / "ensemble").mkdir()
    (folder / "ensemble" / "index.json").write_text("[]")
    check_events_folder(None)  # events in a subfolder: an events folder


# --- 3. record-events checks its destination before simulating; readers name what is there ---

@pytest.fixture
def no_simulation(monkeypatch):
    """Fails a test whose command reaches the (minutes long) recording."""
    from tegrasp_drake.recording import paper_events

    def simulated(*args, **kwargs):
        raise AssertionError("record-events simulated before checking its destination")
    monkeypatch.setattr(paper_events, "record_events", simulated)


# Rule: record-events refuses, before it simulates, a destination it could not save into,
# and a folder that holds another command's run (as --out refuses one command's folder to
# another): the events would mix with the run's files.
@pytest.mark.parametrize("make, words, refusal", [
    (lambda ev: (ev / "index.json").mkdir(), "is a folder", "nothing was recorded"),
    (lambda ev: (ev / "index.json").write_text('{"format": "tegrasp.memorized_event_index", '),
     "is not valid JSON", "nothing was recorded"),
    (lambda ev: (ev / "box").write_text("a file where the box's folder belongs"),
     "is not a folder", "nothing was recorded"),
    (lambda run: (run / "result.json").write_text("{}"), "`tegrasp trial` run (result.json)",
     "not a run's folder"),
    (lambda run: (run / "trial.npz").write_bytes(b"PK"), "`tegrasp trial` run (trial.npz)",
     "not a run's folder"),
    (lambda run: (run / "trials").mkdir(), "`tegrasp sweep` run (trials)", "not a run's folder"),
    (lambda run: (run / "points.json").write_text("{}"), "`tegrasp sensitivity` run",
     "not a run's folder"),
], ids=["index-folder", "index-truncated", "object-file", "result", "log", "sweep",
        "sensitivity"])
def test_record_events_refuses_a_destination_before_simulating(make, words, refusal, tmp_path,
                                                               capfd, no_simulation):
    events = tmp_path / "ev"
    events.mkdir()
    make(events)
    before = folder_contents(events)
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}", words, refusal)
    assert folder_contents(events) == before



# Rule: a recording replaces only files it wrote: a file at one of an object's event paths
# (any transition: a save removes the object's event files it does not write again) that is
# not a memorized event's file, a text file named like one, is the user's; record-events
# refuses before it simulates, naming the file, and the file stays (it was replaced).
@pytest.mark.parametrize("name, content", [
    ("reach_load.json", "my notes on the box's first contact\n"),
    ("hold_avoid.json", '{"format": "my.own.format", "notes": []}\n'),
    ("lift_hold.json", "")], ids=["text", "other-json", "empty"])
def test_record_events_refuses_a_users_file_at_an_event_files_path(name, content, tmp_path,
                                                                   capfd, no_simulation):
    events = tmp_path / "ev"
    save_memorized_events(events, memorized_events("box"))
    (events / "box" / name).write_text(content)
    before = folder_contents(events)
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}", str(events / "box" / name),
                          "is not a 'tegrasp.memorized_event' file", "move it",
                          "nothing was recorded")
    assert folder_contents(events) == before


def test_a_save_replaces_its_own_event_files_and_keeps_the_users(tmp_path):
    """A save over an earlier recording replaces the object's event files (a damaged one too,
    which re-recording remakes) and leaves a file of the user's beside them."""
    events = tmp_path / "ev"
    save_memorized_events(events, memorized_events("box", seed=1))
    damaged = events / "box" / "load_lift.json"
    damaged.write_text(damaged.read_text()[:300])  # past its "format" field, cut
    (events / "box" / "notes.json").write_text("[]")
    save_memorized_events(events, memorized_events("box", seed=2))
    assert (events / "box" / "notes.json").read_text() == "[]"
    loaded = events_folder.load_memorized_events(events, "box")
    assert set(loaded) >= {"reach_load", "load_lift", "place_unload"}


def test_save_memorized_events_refuses_a_users_file_at_an_event_files_path(tmp_path):
    events = tmp_path / "ev"
    (events / "mine").mkdir(parents=True)
    (events / "mine" / "place_unload.json").write_text("my notes")
    with pytest.raises(events_folder.EventsDestinationError, match="place_unload.json is not"):
        save_memorized_events(events, memorized_events("mine"))
    assert (events / "mine" / "place_unload.json").read_text() == "my notes"
    with pytest.raises(events_folder.EventsDestinationError, match="index.json is not"):
        (events / "index.json").write_text("my index")
        (events / "mine" / "place_unload.json").unlink()
        save_memorized_events(events, memorized_events("mine"), keep_other_objects=False)
    assert (events / "index.json").read_text() == "my index"


@pytest.mark.parametrize("exists", [True, False], ids=["folder", "new folder"])
def test_record_events_refuses_a_full_disk_before_simulating(exists, tmp_path, monkeypatch,
                                                             capfd, no_simulation):
    from tests.runs.test_hardware_output_safety import disk_with_free_bytes
    events = tmp_path / "ev"
    if exists:
        events.mkdir()
    disk_with_free_bytes(monkeypatch, 40_960)
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}", "40 kB free", "nothing was recorded")
    assert not events.exists() or folder_contents(events) == {}

# Rule: an events folder is told from a run's by its index.json, not by its folders'
# names: an object may be called what a sweep's or a transfer's folder is.
@pytest.mark.parametrize("object_name", ["trials", "cells", "events"])
def test_an_events_folder_holding_an_object_named_like_a_runs_folder_is_an_events_folder(
        object_name, tmp_path, capfd):
    from tegrasp_drake.commands.run_folder import other_run_problem
    events = tmp_path / "ev"
    save_memorized_events(events, memorized_events(object_name))
    assert other_run_problem(events, "record-events") is None
    before = folder_contents(events)
    code, text = run_cli(["sweep", "--out", str(events), "--dry-run"], capfd)
    assert_one_line_error(code, text, f"--out {events}", "memorized events (index.json)")
    assert folder_contents(events) == before


def test_an_events_variable_naming_a_runs_folder_is_refused(tmp_path, monkeypatch, capfd,
                                                            no_simulation):
    (tmp_path / "result.json").write_text("{}")
    monkeypatch.setenv(paths.EVENTS_ENV, str(tmp_path))
    code, text = run_cli(["record-events", "--object", "box"], capfd)
    assert_one_line_error(code, text, paths.EVENTS_ENV, "`tegrasp trial` run (result.json)")


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


# Rule: a save of nothing is refused, as the command line never makes one.
def test_saving_no_events_is_refused(tmp_path):
    from tegrasp_drake import save_memorized_events
    with pytest.raises(ValueError, match="no events given; there is nothing to save"):
        save_memorized_events(tmp_path / "ev", [])
    assert not (tmp_path / "ev").exists()


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


# Rule: an --events folder given is checked whether or not the command's controllers read
# events: a folder of other files is refused (one line, exit 1), never ignored in silence.
@pytest.mark.parametrize("controllers", ["open_loop", "heuristic"])
def test_an_events_folder_of_other_files_is_refused_for_controllers_without_events(
        tmp_path, capfd, controllers):
    other = tmp_path / "etc"
    other.mkdir()
    (other / "adduser.conf").write_text("# not an event\n")
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", controllers,
                          "--attempts", "1", "--dry-run", "--out", str(tmp_path / "sw"),
                          "--events", str(other)], capfd)
    assert_one_line_error(code, text, f"--events {other} is not an events folder")
    assert code == 1 and "sweep plan" not in text
    assert not (tmp_path / "sw").exists()


def test_trial_checks_a_given_events_folder_for_a_controller_without_events(tmp_path):
    from tegrasp_drake.commands.scenario_args import controller_events
    from tegrasp_drake.scenario import LoadScenario
    (tmp_path / "notes.txt").write_text("mine\n")
    with pytest.raises(files.UserPathError, match="is not an events folder"):
        controller_events(LoadScenario(controller="open_loop"), tmp_path)
    assert controller_events(LoadScenario(controller="open_loop"), None) is None


# Rule: a command's refusal names its option, not the function argument it is bound to
# (`--events`, not run_trial_from_spec's events_dir), before any trial runs.
@pytest.mark.parametrize("controller", ["open_loop", "memorized"])
def test_tegrasp_sweep_names_its_events_option(tmp_path, capfd, controller):
    missing = tmp_path / "MISSING"
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", controller,
                          "--base-seed", "640", "--attempts", "1", "--workers", "1",
                          "--out", str(tmp_path / "sw"), "--events", str(missing)], capfd)
    assert code == 1, text
    assert f"--events {missing}" in text and "events_dir" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert not (tmp_path / "sw").exists()


# Rule: a refusal names what the user set: events recorded into the user's folder that an
# environment variable chose (no --events) are refused naming that variable, before
# anything is simulated.
@pytest.mark.parametrize("variable, value", [("XDG_DATA_HOME", "/proc/x"),
                                             ("TEGRASP_EVENTS_DIR", "/proc/x/events")])
def test_an_unusable_events_folder_from_the_environment_is_named_by_its_variable(
        variable, value, monkeypatch, capfd):
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    monkeypatch.setenv(variable, value)
    code, text = run_cli(["record-events", "--set", "random_seed=642", "--ensemble-runs", "0"],
                         capfd)
    assert code == 1, text
    assert f"{variable}=" in text and "--events" not in text.split(";")[0], text
    assert len(text.strip().splitlines()) == 1, text


# Rule: a relative XDG_DATA_HOME is invalid (XDG Base Directory spec) and ignored, with a
# warning, not a folder below wherever the command runs.
def test_a_relative_xdg_data_home_is_ignored(monkeypatch, tmp_path, caplog):
    monkeypatch.delenv(paths.EVENTS_ENV, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("XDG_DATA_HOME", "relative/dir")
    monkeypatch.setattr(paths, "_IGNORED_DATA_HOMES", set())  # warned once per process
    assert paths.user_events_dir() == tmp_path / "home" / ".local" / "share" / "tegrasp" / (
        "events")
    assert "relative/dir" in caplog.text and "not an absolute path" in caplog.text


# Rule: that warning reaches stderr as the package's other warnings do, in one line
# `tegrasp: warning: ...`, not in the log's `WARNING tegrasp_drake.rig.paths: ...` form.
def test_a_relative_xdg_data_home_is_warned_in_the_packages_form(monkeypatch, tmp_path,
                                                                  caplog):
    from tegrasp_drake.commands.verbosity import CommandLogFormatter
    monkeypatch.delenv(paths.EVENTS_ENV, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    monkeypatch.setenv("XDG_DATA_HOME", "relative/dir")
    monkeypatch.setattr(paths, "_IGNORED_DATA_HOMES", set())  # warned once per process
    paths.user_events_dir()
    (record,) = [r for r in caplog.records if r.name == paths.__name__]
    line = CommandLogFormatter().format(record)
    assert line.startswith("tegrasp: warning: XDG_DATA_HOME='relative/dir'"), line
    assert len(line.splitlines()) == 1, line


# Rule: an events folder the user named that does not exist is refused whatever the
# controllers (a typo would otherwise go unnoticed), a dry run's too, by --events or the
# variable.
@pytest.mark.parametrize("by_variable", [False, True], ids=["--events", "TEGRASP_EVENTS_DIR"])
def test_a_missing_events_folder_is_refused_when_no_controller_reads_events(
        tmp_path, monkeypatch, capfd, by_variable):
    missing = str(tmp_path / "no_such_folder")
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    if by_variable:
        monkeypatch.setenv("TEGRASP_EVENTS_DIR", missing)
    code, text = run_cli(["sweep", "--dry-run", "--objects", "box", "--controllers",
                          "open_loop", "--attempts", "1", "--out", str(tmp_path / "sw"),
                          *([] if by_variable else ["--events", missing])], capfd)
    assert_one_line_error(code, text, f"{missing} does not exist" if by_variable
                          else f"--events {missing}: does not exist")
    assert code == 1


def test_an_events_folder_that_is_a_symlink_loop_is_named_as_one(tmp_path, monkeypatch, capfd):
    """A loop is no missing folder: it is said as --scenario says it."""
    loop = tmp_path / "loop"
    loop.symlink_to(loop.name)
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    code, text = run_cli(["sweep", "--dry-run", "--objects", "box", "--controllers",
                          "open_loop", "--attempts", "1", "--out", str(tmp_path / "sw"),
                          "--events", str(loop)], capfd)
    assert_one_line_error(code, text, f"--events {loop}", "it is a symbolic-link loop")
    assert "does not exist" not in text


# Rule: the environment variable naming the events folder (TEGRASP_EVENTS_DIR) is refused by
# every command that reads events when the folder it names does not exist, as --events is, in
# one line naming the variable; never the package's events in silence. XDG_DATA_HOME is every
# application's: a folder it names may not be made yet (no events recorded).
@pytest.mark.parametrize("variable", ["TEGRASP_EVENTS_DIR"])
@pytest.mark.parametrize("command", [
    ["plot", "events"],
    ["trial", "--set", "random_seed=641"],  # the memorized controller reads its events
], ids=["plot-events", "trial"])
def test_an_events_variable_naming_no_folder_is_refused(variable, command, tmp_path,
                                                        monkeypatch, no_simulation, capfd):
    missing = tmp_path / "no_such_folder"
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    monkeypatch.setenv(variable, str(missing))
    code, text = run_cli([*command, "--out", str(tmp_path / "out.png" if command[0] == "plot"
                                                 else tmp_path / "run")], capfd)
    assert code == 1 and "internal error" not in text, text
    assert len(text.strip().splitlines()) == 1, text
    assert f"{variable}=" in text and f"{missing} does not exist" in text, text


@pytest.mark.parametrize("data_home", ["made", "not_made_yet"])
def test_a_data_folder_without_events_yet_reads_the_packages(data_home, tmp_path, monkeypatch,
                                                             capfd):
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    # no tegrasp/events in it (none recorded), or the folder itself not made yet
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path if data_home == "made"
                                            else tmp_path / "share"))
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "events.png")], capfd)
    assert code == 0 and (tmp_path / "events.png").is_file(), text


# Rule: an events folder missing a file a trial needs is bad input (exit 1, one line naming
# the file), as a missing --events folder is; exit 2 is kept for a refused sweep spec.
def test_a_sweep_events_folder_missing_a_file_exits_1(tmp_path, capfd):
    import shutil
    from tegrasp_drake.rig import paths
    events = tmp_path / "events"
    shutil.copytree(paths.package_events_dir(), events)
    (events / "box" / "load_lift.json").unlink()
    code, text = run_cli(["sweep", "--objects", "box", "--controllers", "memorized",
                          "--base-seed", "640", "--attempts", "1", "--workers", "1",
                          "--out", str(tmp_path / "sw"), "--events", str(events)], capfd)
    assert code == 1, text
    assert "load_lift.json" in text and len(text.strip().splitlines()) == 1, text
    assert "Traceback" not in text and not (tmp_path / "sw").exists(), text


@pytest.mark.parametrize("command", [["trial"], ["plot", "events"],
                                     ["replay", "run.lcmlog"], ["sweep", "--dry-run"]])
@pytest.mark.parametrize("kind", ["file", "pipe"])
def test_events_that_are_not_a_folder_are_said_so_by_every_command(command, kind, tmp_path,
                                                                   monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    events = tmp_path / "events"
    if kind == "file":
        events.write_text("")
    else:
        os.mkfifo(events)
    code, text = run_cli(command + ["--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}: is a ",
                          "not a folder; give a folder of memorized events")


# Rule: the user's events folder chosen by TEGRASP_EVENTS_DIR or XDG_DATA_HOME is read with the
# checks --events gets: only a folder with nothing at its index path is passed over (no events
# saved there yet); an index that is a pipe, a folder or a looping symlink is refused by name,
# never skipped in silence for the package's events.
_UNREADABLE_INDEXES = [
    (lambda path: os.mkfifo(path), "is a named pipe (FIFO)"),
    (lambda path: path.symlink_to(path.name), "it is a symbolic-link loop"),
    (lambda path: path.mkdir(), "is a folder, not a file"),
]


def _user_events_folder_with(make, variable, tmp_path, monkeypatch):
    monkeypatch.delenv("TEGRASP_EVENTS_DIR", raising=False)
    if variable == "TEGRASP_EVENTS_DIR":
        folder = tmp_path / "events"
        monkeypatch.setenv(variable, str(folder))
    else:
        folder = tmp_path / "share" / "tegrasp" / "events"
        monkeypatch.setenv(variable, str(tmp_path / "share"))
    folder.mkdir(parents=True)
    make(folder / event_file.INDEX_FILE)
    return folder


@pytest.mark.parametrize("variable", ["TEGRASP_EVENTS_DIR", "XDG_DATA_HOME"])
@pytest.mark.parametrize("make, words", _UNREADABLE_INDEXES)
def test_an_unreadable_index_in_the_users_events_folder_is_refused_by_plot_events(
        make, words, variable, tmp_path, monkeypatch, capfd):
    folder = _user_events_folder_with(make, variable, tmp_path, monkeypatch)
    code, text = run_cli(["plot", "events", "--out", str(tmp_path / "events.png")], capfd)
    assert_one_line_error(code, text, str(folder / event_file.INDEX_FILE), words)
    assert code == 1 and not (tmp_path / "events.png").exists(), text


@pytest.mark.parametrize("variable", ["TEGRASP_EVENTS_DIR", "XDG_DATA_HOME"])
@pytest.mark.parametrize("command", [["trial"], ["sweep", "--dry-run"]])
def test_an_unreadable_index_in_the_users_events_folder_is_refused_by_every_reader(
        command, variable, tmp_path, monkeypatch, capfd):
    make, words = _UNREADABLE_INDEXES[0]
    folder = _user_events_folder_with(make, variable, tmp_path, monkeypatch)
    code, text = run_cli([*command, "--out", str(tmp_path / "run")], capfd)
    assert_one_line_error(code, text, str(folder / event_file.INDEX_FILE), words)
    assert code == 1, text
    with pytest.raises(event_file.MemorizedEventError, match=words.split(" (")[0]):
        events_folder.events_folder_of(paths.events_search_path(), "box")  # `tegrasp hardware`


# Rule: a path (a variable's or an argument's) holding a byte that is not UTF-8 is shown as
# that byte (`x\xff`), through echo.shown and every error line, never as Python's `\udcff`.
@pytest.mark.parametrize("given", ["variable", "argument"])
def test_a_path_that_is_not_utf8_is_shown_by_its_bytes(given, tmp_path, monkeypatch, capfd):
    folder = os.fsdecode(os.fsencode(tmp_path) + b"/x\xff")
    shown = f"{tmp_path}/x\\xff"
    argv = ["plot", "events", "--out", str(tmp_path / "x.png")]
    if given == "variable":
        monkeypatch.setenv(paths.EVENTS_ENV, folder)
        words = (f"TEGRASP_EVENTS_DIR='{shown}': {shown} does not exist; point it at your "
                 "events folder")
    else:
        argv += ["--events", folder]
        words = f"--events {shown}: does not exist; give an existing folder"
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, words)
    assert "\\udc" not in text


# --- 7. one check of a folder's contents for its readers and its writers ----------------------

def _documents(tmp_path):
    """A folder of the user's own files: no events folder."""
    folder = tmp_path / "documents"
    (folder / "letters").mkdir(parents=True)
    (folder / "tax-return.txt").write_text("mine\n")
    (folder / "letters" / "to-ann.txt").write_text("dear Ann\n")
    return folder


# Rule: a folder that holds no index but other files (the user's documents, /etc) is not an
# events folder: record-events refuses it before it simulates, save_memorized_events before it
# writes, and every reader says it is no events folder (not that its index "is missing").
def test_record_events_refuses_a_folder_of_other_files_before_simulating(tmp_path, capfd,
                                                                          no_simulation):
    folder = _documents(tmp_path)
    before = folder_contents(folder)
    code, text = run_cli(["record-events", "--object", "box", "--events", str(folder)], capfd)
    assert_one_line_error(code, text, f"--events {folder}: {folder} is not an events folder: "
                          "it holds no index.json but other files (e.g. 'tax-return.txt'); "
                          "give a new or empty folder", "nothing was recorded")
    assert folder_contents(folder) == before


def test_save_memorized_events_refuses_a_folder_of_other_files(tmp_path):
    folder = _documents(tmp_path)
    before = folder_contents(folder)
    with pytest.raises(events_folder.EventsDestinationError, match="is not an events folder"):
        save_memorized_events(folder, memorized_events("mine"))
    assert folder_contents(folder) == before


@pytest.mark.parametrize("argv, out", [(["plot", "events"], "x.png"), (["trial"], "run")],
                         ids=["plot", "trial"])
def test_readers_say_a_folder_of_other_files_is_not_an_events_folder(argv, out, tmp_path,
                                                                     capfd):
    folder = _documents(tmp_path)
    code, text = run_cli([*argv, "--events", str(folder), "--out", str(tmp_path / out)], capfd)
    assert_one_line_error(code, text, f"{folder} is not an events folder: it holds no "
                          "index.json but other files", "give the folder `tegrasp "
                          "record-events` wrote")
    assert "missing" not in text
    with pytest.raises(event_file.MemorizedEventError, match="is not an events folder"):
        events_folder.find_memorized_events([folder], "box")


def _stopped_recording(events, object_name="mine", index=False):
    """What a recording of `object_name` killed between its event files' renames and its index
    leaves: the object's event files, no index entry (`index`: other objects' index kept)."""
    if index:
        save_memorized_events(events, memorized_events("other"))
    staging = tmp = events.parent / "staging"
    save_memorized_events(tmp, memorized_events(object_name))
    (events / object_name).mkdir(parents=True)
    for path in (staging / object_name).iterdir():
        path.rename(events / object_name / path.name)
    return events


# Rule: what a stopped recording left (an object's event files without their index entry) is
# refused by its readers, saying to record the object again and how, never read as "no
# events" (nor passed over for the package's); recording into it again makes it whole.
@pytest.mark.parametrize("index", [False, True], ids=["no-index", "index-without-it"])
def test_a_stopped_recordings_event_files_are_refused_and_recorded_again(index, tmp_path):
    events = _stopped_recording(tmp_path / "ev", index=index)
    again = (f"record them again with --events {events}: Remake it with `tegrasp "
             "record-events` and the options that describe 'mine'")
    with pytest.raises(event_file.MemorizedEventError) as refused:
        events_folder.load_memorized_events(events, "mine")
    assert "recording stopped before it wrote" in str(refused.value)
    assert again in str(refused.value) and "\n" not in str(refused.value)
    with pytest.raises(event_file.MemorizedEventError, match="recording stopped before"):
        events_folder.find_memorized_events([events, tmp_path / "package"], "mine")
    events_folder.check_events_destination(events, ["mine"])  # a writer takes it
    save_memorized_events(events, memorized_events("mine", seed=3))
    assert set(events_folder.load_memorized_events(events, "mine")) >= {"reach_load"}


def test_a_folder_that_cannot_be_made_in_says_so_and_what_to_do(capfd, no_simulation):
    code, text = run_cli(["record-events", "--object", "box", "--events", "/proc"], capfd)
    assert_one_line_error(code, text, "--events /proc: /proc cannot be written in: making a "
                          "folder there failed", "give a folder you can write")
    assert "not writable (No such file" not in text


# Rule: an object's events folder this user cannot write in (another user's), whose files the
# recording replaces, is refused before record-events simulates, and by save_memorized_events
# before it writes: the one check (check_events_destination) both ask.
def test_an_object_folder_that_cannot_be_written_is_refused_before_simulating(
        tmp_path, capfd, monkeypatch, no_simulation):
    events = tmp_path / "ev"
    save_memorized_events(events, memorized_events("box", seed=3))
    before = folder_contents(events)
    access = files.os.access  # root ignores modes: the folder's owner's refusal is said here
    monkeypatch.setattr(files.os, "access", lambda path, mode, **kw: (
        False if str(path) == str(events / "box") else access(path, mode, **kw)))
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_line_error(code, text, f"--events {events}: {events / 'box'} is not writable",
                          "give an events folder you can write", "nothing was recorded")
    with pytest.raises(events_folder.EventsDestinationError, match="box is not writable"):
        save_memorized_events(events, memorized_events("box", seed=4))
    assert folder_contents(events) == before


# Rule: an index this user cannot look at (its folder may be listed but not searched) or
# read is said as one that cannot be read, with what to do; never as "no index.json", as a
# folder of other files, or with the advice to record the events again.
def test_an_index_that_cannot_be_read_is_said_so_not_absent_or_to_be_remade(
        tmp_path, capfd, monkeypatch):
    events = tmp_path / "ev"
    save_memorized_events(events, memorized_events("box", seed=3))
    index = events / "index.json"
    monkeypatch.setattr(os, "lstat", denied_for([index], os.lstat))
    monkeypatch.setattr(os, "open", denied_for([index], os.open))
    assert event_file.has_index(events)
    with pytest.raises(event_file.MemorizedEventError) as refused:
        events_folder.find_memorized_events([events], "box")
    assert f"{index}: cannot be read (Permission denied)" in str(refused.value)
    assert "Remake" not in str(refused.value) and "no index.json" not in str(refused.value)
    code, text = run_cli(["plot", "events", "--events", str(events),
                          "--out", str(tmp_path / "e.png")], capfd)
    assert_one_line_error(code, text, "cannot be read (Permission denied)", "readable")
    assert "Remake" not in text and not (tmp_path / "e.png").exists()
