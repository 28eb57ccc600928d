"""Where a run's files go: a named folder that holds a run is refused unless --overwrite,
`tegrasp trial` without --out keeps every run in a new folder, `tegrasp demo` replaces its
own; result.json is written whole; a hardware run's result goes beside its log."""

import dataclasses
import json
import os
import threading

import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands.run_folder import (RESULT_FILE, RunFolderError, choose_run_folder,
                                               commit_run, other_run_problem,
                                               result_path_beside_log, run_owners, staged_run,
                                               write_result)
from tegrasp_drake.runs.hardware_run import HardwareRunResult
from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
from tegrasp_drake.hardware.device_fault import DeviceFault
from tegrasp_drake.hardware.myrio.serial_reader import TactileReaderCounters
from tegrasp_drake.hardware.myrio.tactile_frame import TactileDecoderCounters
from tegrasp_drake.hardware.robotiq.modbus_client import RobotiqModbusCounters
from tests.bad_input.probes import earlier_run_file
from tests.runs.earlier_hardware_run import EARLIER_LOG, EARLIER_RESULT


def earlier_run(folder, name="trial.npz"):
    """`folder` holding `name` of an earlier run as the run wrote it (earlier_run_file)."""
    return earlier_run_file(folder, name)


@pytest.mark.parametrize("command", ["trial", "demo"])
@pytest.mark.parametrize("left", ["trial.npz", RESULT_FILE])
def test_a_named_folder_that_holds_a_run_is_refused_before_simulating(tmp_path, capsys,
                                                                       command, left):
    folder = earlier_run(tmp_path / "run", left)
    before = (folder / left).read_bytes()
    with pytest.raises(SystemExit) as exit_info:
        cli.main([command, "--out", str(folder)])
    message = str(exit_info.value.code)
    assert message.startswith("tegrasp: error: ") and "\n" not in message
    assert str(folder) in message and "--overwrite" in message and left in message
    assert (folder / left).read_bytes() == before
    assert capsys.readouterr().out == ""


def test_overwrite_allows_the_named_folder_and_keeps_its_old_run_until_the_new_one_commits(
        tmp_path):
    folder = earlier_run(earlier_run(tmp_path / "run", RESULT_FILE))
    before = (folder / RESULT_FILE).read_bytes()
    assert choose_run_folder(str(folder), default="unused", replace_default=False,
                             overwrite=True) == folder
    assert (folder / RESULT_FILE).read_bytes() == before  # kept until the commit
    with staged_run(folder) as stage:
        (stage / "trial.npz").write_text("the new run")
        result = commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert result["log"] == str(folder / "trial.npz")
    assert (folder / "trial.npz").read_text() == "the new run"
    assert json.loads((folder / RESULT_FILE).read_text())["log"] == result["log"]
    assert sorted(p.name for p in folder.iterdir()) == [RESULT_FILE, "trial.npz"]


def test_a_run_interrupted_before_its_commit_leaves_the_earlier_run_whole(tmp_path):
    folder = earlier_run(earlier_run(tmp_path / "run", RESULT_FILE))
    before = (folder / "trial.npz").read_bytes()
    with pytest.raises(KeyboardInterrupt):
        with staged_run(folder) as stage:
            (stage / "trial.npz").write_text("half a new run")
            raise KeyboardInterrupt
    assert sorted(p.name for p in folder.iterdir()) == [RESULT_FILE, "trial.npz"]
    assert (folder / "trial.npz").read_bytes() == before


def test_two_runs_without_out_claim_different_folders(tmp_path):
    """A folder counts as taken from the moment it is claimed."""
    default = tmp_path / "out" / "trial"
    first = choose_run_folder(None, default=str(default), replace_default=False,
                              overwrite=False)
    second = choose_run_folder(None, default=str(default), replace_default=False,
                               overwrite=False)
    assert first == default and second == tmp_path / "out" / "trial-2"


def test_an_empty_named_folder_is_used(tmp_path):
    (tmp_path / "run").mkdir()
    assert choose_run_folder(str(tmp_path / "run"), default="unused", replace_default=False,
                             overwrite=False) == tmp_path / "run"


def test_trial_without_out_takes_the_next_free_numbered_folder(tmp_path):
    default = tmp_path / "out" / "trial"
    earlier_run(default)
    before = (default / "trial.npz").read_bytes()
    earlier_run(tmp_path / "out" / "trial-2", RESULT_FILE)
    chosen = choose_run_folder(None, default=str(default), replace_default=False,
                               overwrite=False)
    assert chosen == tmp_path / "out" / "trial-3" and chosen.is_dir()
    assert (default / "trial.npz").read_bytes() == before


def test_demo_without_out_replaces_its_own_folder(tmp_path):
    default = earlier_run(earlier_run(tmp_path / "out" / "demo"), RESULT_FILE)
    assert choose_run_folder(None, default=str(default), replace_default=True,
                             overwrite=False) == default


def test_result_json_holds_the_result_whole(tmp_path):
    result = {"hold_success": True, "transitions": [{"t": 3.5, "from": "Reach"}]}
    path = write_result(tmp_path / RESULT_FILE, result)
    assert json.loads(path.read_text()) == result
    assert [p.name for p in tmp_path.iterdir()] == [RESULT_FILE]  # no temporary file left


# The hardware tests below run in their folder and name their files relative to it: an
# error cuts a path to about 80 characters, which a worker's temporary folder can pass.
def test_hardware_refuses_an_existing_log_before_connecting(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    log = tmp_path / "run.lcmlog"
    log.write_bytes(EARLIER_LOG)
    (tmp_path / "run.result.json").write_text(EARLIER_RESULT)  # the run's, naming its log
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["hardware", "--config", "hw.yaml", "--log", "run.lcmlog"])
    message = str(exit_info.value.code)
    assert message.startswith("tegrasp: error: run.lcmlog ")
    assert "--overwrite" in message and log.read_bytes() == EARLIER_LOG
    assert result_path_beside_log(log) == tmp_path / "run.result.json"


LCM_EVENT = bytes.fromhex("EDA1DA01") + bytes(24)  # an LCM log's first event's head


@pytest.mark.parametrize("log_bytes, result_text, blamed", [
    (b"PK\x03\x04 a trial.npz copied here", None, "run.lcmlog exists and is not an LCM log"),
    (LCM_EVENT, '{"mine": true}', "run.result.json exists and is not a hardware run's result"),
    (LCM_EVENT, "my notes", "run.result.json exists and is not valid JSON"),
])
def test_hardware_overwrite_replaces_only_a_runs_log_and_result(log_bytes, result_text, blamed,
                                                                 tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    log, result = tmp_path / "run.lcmlog", tmp_path / "run.result.json"
    log.write_bytes(log_bytes)
    if result_text is not None:
        result.write_text(result_text)
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["hardware", "--config", "hw.yaml", "--log", "run.lcmlog", "--overwrite"])
    message = str(exit_info.value.code)
    assert message.startswith("tegrasp: error: --log ") and "\n" not in message
    assert blamed in message and "remove it yourself" in message
    assert log.read_bytes() == log_bytes
    assert result_text is None or result.read_text() == result_text


def test_a_hardware_result_is_json(tmp_path):
    fault = DeviceFault(device="gripper", kind="DEVICE_FAULT", description="overcurrent",
                        code=0x0E, since_sim_time=3.2, since_wall_time=1.7e9)
    result = HardwareRunResult(
        transitions=[{"t": 3.4, "from": "Load", "to": "Failed", "trigger": "fault"}],
        faults=(fault,), sim_time=3.9, wall_time=4.0, log_path=tmp_path / "run.lcmlog",
        log_messages=1200,
        device_counters={"gripper": RobotiqModbusCounters(reads=300),
                         "tactile": TactileReaderCounters(TactileDecoderCounters(frames=400))})
    data = json.loads(write_result(tmp_path / "run.result.json", result.as_dict()).read_text())
    assert data["faults"] == [dataclasses.asdict(fault)]
    assert data["device_counters"]["tactile"]["decoder"]["frames"] == 400
    assert data["transitions"][0]["to"] == "Failed"
    assert data["realtime_rate"] == pytest.approx(3.9 / 4.0)
    assert data["log"] == str(tmp_path / "run.lcmlog")


def test_demo_replaces_its_default_folder_and_trial_keeps_its_runs():
    demo = cli.build_parser().parse_args(["demo"])
    trial = cli.build_parser().parse_args(["trial"])
    assert (demo.out, demo.default_out, demo.replace_default_out) == (None, "out/demo", True)
    assert (trial.out, trial.default_out, trial.replace_default_out) == (None, "out/trial", False)


def test_hardware_keeps_an_earlier_result_when_its_log_is_gone(tmp_path, monkeypatch):
    """A result beside the log, with no log, stops the run before anything is deleted; the
    message names it and --overwrite."""
    monkeypatch.chdir(tmp_path)
    config = tmp_path / "hw.yaml"
    config.write_text(hardware_config_to_yaml(HardwareStationConfig()))
    result = tmp_path / "run.result.json"
    result.write_text(EARLIER_RESULT)
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["hardware", "--config", "hw.yaml", "--log", "run.lcmlog"])
    assert "run.result.json" in str(exit_info.value.code)
    assert "--overwrite" in str(exit_info.value.code)
    assert result.read_text() == EARLIER_RESULT


def _ended_process_id() -> int:
    """The id of a process that has ended (and been reaped)."""
    import subprocess
    import sys
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def test_a_staging_file_of_an_ended_process_is_removed_and_a_live_ones_kept(tmp_path):
    from tegrasp_drake.commands.run_folder import staging_file_beside
    import os
    ended = tmp_path / f".run.lcmlog.{_ended_process_id()}.staging"
    live = tmp_path / f".run.lcmlog.{os.getppid()}.staging"
    users = [tmp_path / "run.lcmlog", tmp_path / ".notes.1x.staging", tmp_path / "a.staging"]
    for path in (ended, live, *users):
        path.write_bytes(b"data")
    staged = staging_file_beside(tmp_path / "run.lcmlog", b"data")
    assert staged == tmp_path / f".run.lcmlog.{os.getpid()}.staging"
    assert not ended.exists() and live.exists() and all(path.exists() for path in users)


def test_a_folder_another_run_holds_keeps_its_staging_files_for_the_next_run(tmp_path):
    from tegrasp_drake.commands.run_folder import claimed_run_folder, remove_stale_staging_files
    ended = tmp_path / f".run.lcmlog.{_ended_process_id()}.staging"
    ended.write_bytes(b"data")
    with claimed_run_folder(tmp_path):  # a trial writing there
        assert remove_stale_staging_files(tmp_path / "run.lcmlog", b"data") == []
        assert ended.exists()
    assert remove_stale_staging_files(tmp_path / "run.lcmlog", b"data") == [ended]
    assert not ended.exists()


def test_overwriting_a_run_whose_result_json_is_a_fifo_commits_without_reading_it(tmp_path):
    folder = earlier_run(tmp_path / "run")
    os.mkfifo(folder / RESULT_FILE)  # no writer: a plain read of it would wait for one forever
    with staged_run(folder) as stage:
        (stage / "trial.npz").write_text("the new run")
        committing = threading.Thread(target=commit_run, daemon=True,
                                      args=(stage, folder, {"log": str(stage / "trial.npz")}))
        committing.start()
        committing.join(timeout=60)  # a bound on a hang, not a measure of speed
        waited = committing.is_alive()
        if waited:  # a writer's open and close ends the blocked read, so the test ends
            os.close(os.open(folder / RESULT_FILE, os.O_WRONLY | os.O_NONBLOCK))
            committing.join()
    assert not waited, "the commit waited on the FIFO in result.json's place"
    assert json.loads((folder / RESULT_FILE).read_text())["log"] == str(folder / "trial.npz")


def test_a_run_killed_writing_a_figure_leaves_a_staging_folder_the_next_run_removes(tmp_path):
    from tests.killed_runs import killed_before_rename
    from tegrasp_drake.commands.run_folder import STAGING_PREFIX, staged_run
    killed_before_rename(
        "from tegrasp_drake.commands.run_folder import staged_run\n"
        "from tegrasp_drake.figures.figure_files import new_figure, save_figure\n"
        f"with staged_run({str(tmp_path)!r}) as stage:\n"
        "    save_figure(new_figure(2, 1), stage / 'states.png')\n")
    (left,) = tmp_path.glob(f"{STAGING_PREFIX}*")
    assert [path.name.startswith(".states.") for path in left.iterdir()] == [True]
    with staged_run(tmp_path):
        assert not left.exists()


def _other_runs(tmp_path):
    """{command: its run's top-level entry}, each made in its own folder under tmp_path."""
    entries = {"trial": "result.json", "sweep": "trials", "transfer": "cells",
               "sensitivity": "points.json"}
    folders = {}
    for command, entry in entries.items():
        folder = tmp_path / f"{command}_run"
        folder.mkdir()
        if "." in entry:
            (folder / entry).write_text("{}")
        else:
            (folder / entry).mkdir()
        folders[command] = folder
    return folders


TRANSFER_SPEC = "worlds: {a: {scenario: memorizing_world}}\ncells: [[a, a]]\n"


def _run_into(command, folder, tmp_path, capsys) -> tuple[int, list[str]]:
    """(exit code, stderr lines) of `tegrasp COMMAND ... --out FOLDER` (a sweep of fake
    trials; transfer and sensitivity of a one-cell spec)."""
    spec = tmp_path / "spec.yaml"
    spec.write_text(TRANSFER_SPEC if command == "transfer" else
                    "parameters: [object.friction]\nsweep: {objects: [box], attempts: 1}\n")
    arguments = {"transfer": [str(spec)], "sensitivity": [str(spec)],
                 "sweep": ["--objects", "box", "--attempts", "1", "--trial-function",
                           "tests.fake_trials:fake_trial", "--no-progress"],
                 "trial": []}[command]
    try:
        code = cli.main([command, *arguments, "--out", str(folder)])
        return code, capsys.readouterr().err.strip().splitlines()
    except SystemExit as exit_:  # trial's refusals end the process with their line
        return 1, [str(exit_.code)]


@pytest.mark.parametrize("command, into", [
    ("transfer", "trial"), ("transfer", "sweep"), ("transfer", "sensitivity"),
    ("sweep", "trial"), ("sweep", "transfer"), ("sensitivity", "trial"),
    ("sensitivity", "sweep"), ("trial", "sweep"), ("trial", "transfer")])
def test_a_run_into_a_folder_holding_another_commands_run_is_refused(command, into, tmp_path,
                                                                     capsys):
    folder = _other_runs(tmp_path)[into]
    before = sorted(path.name for path in folder.iterdir())
    code, lines = _run_into(command, folder, tmp_path, capsys)
    assert code == 1
    assert len(lines) == 1 and f"holds a `tegrasp {into}` run" in lines[0], lines
    assert sorted(path.name for path in folder.iterdir()) == before


@pytest.mark.parametrize("command", ["trial", "sweep", "transfer", "sensitivity"])
def test_a_run_into_an_events_folder_is_refused(command, tmp_path, capsys):
    events = tmp_path / "events"
    events.mkdir()
    (events / "index.json").write_text("{}")
    code, lines = _run_into(command, events, tmp_path, capsys)
    assert code == 1
    assert len(lines) == 1 and "holds memorized events (index.json)" in lines[0], lines
    assert sorted(path.name for path in events.iterdir()) == ["index.json"]


# The default folder a run replaces (demo's out/demo) is checked for another command's run
# as an --out given is: a sweep's run there is refused, not written into.
def test_demo_without_out_refuses_a_default_folder_holding_another_commands_run(tmp_path):
    default = tmp_path / "out" / "demo"
    (default / "trials").mkdir(parents=True)
    with pytest.raises(RunFolderError) as refused:
        choose_run_folder(None, default=str(default), replace_default=True, overwrite=False)
    assert str(refused.value) == (f"the default --out {default} holds a `tegrasp sweep` run "
                                  "(trials); give trial a folder of its own (not a run's "
                                  "folder)")
    assert sorted(path.name for path in default.iterdir()) == ["trials"]


# A folder holding several runs' entries is refused for each foreign one, not only when the
# first owner asked is foreign: a sweep's trials beside a trial's result.json.
@pytest.mark.parametrize("command, foreign", [("sweep", "trial"), ("trial", "sweep")])
def test_a_folder_of_mixed_runs_is_refused_for_any_foreign_owner(command, foreign, tmp_path):
    folder = tmp_path / "mixed"
    (folder / "trials").mkdir(parents=True)
    (folder / RESULT_FILE).write_text("{}")
    assert run_owners(folder) == [("sweep", "trials"), ("trial", RESULT_FILE)]
    problem = other_run_problem(folder, command)
    assert problem is not None and f"holds a `tegrasp {foreign}` run" in problem, problem


def test_an_events_folder_holding_an_object_named_like_a_runs_entry_has_one_owner(tmp_path):
    (tmp_path / "trials").mkdir()  # an object's events, called `trials`
    (tmp_path / "index.json").write_text("{}")
    assert run_owners(tmp_path) == [("record-events", "index.json")]


def _sweep_logs_into(logs, out, capsys) -> tuple[int, list[str]]:
    code = cli.main(["sweep", "--objects", "box", "--attempts", "1", "--trial-function",
                     "tests.fake_trials:fake_trial", "--no-progress", "--dry-run",
                     "--out", str(out), "--logs", str(logs)])
    return code, capsys.readouterr().err.strip().splitlines()


@pytest.mark.parametrize("where", ["events", "trial run", "sweep run", "out", "out/trials",
                                   "out/trials/below"])
def test_sweep_logs_of_their_own_folder_only(where, tmp_path, capsys):
    out = tmp_path / "out"
    folders = _other_runs(tmp_path)
    events = tmp_path / "events"
    events.mkdir()
    (events / "index.json").write_text("{}")
    logs = {"events": events, "trial run": folders["trial"], "sweep run": folders["sweep"],
            "out": out, "out/trials": out / "trials",
            "out/trials/below": out / "trials" / "below"}[where]
    code, lines = _sweep_logs_into(logs, out, capsys)
    assert code == 1 and len(lines) == 1 and lines[0].count("--logs") == 1, lines
    assert "give the trials' logs a folder of their own" in lines[0]
    assert not (out / "trials" / "below").exists()


def test_sweep_logs_beside_the_out_folder_are_taken(tmp_path, capsys):
    code, lines = _sweep_logs_into(tmp_path / "logs", tmp_path / "out", capsys)
    assert code == 0, lines
