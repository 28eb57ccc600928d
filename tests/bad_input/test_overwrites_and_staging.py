"""Runs replace their predecessors only when complete: a run writes into a staging folder it
commits at the end; --overwrite says what it replaced and removes only the earlier run's
own files, never a user's (a link, a folder named like staging, a non-regular file); a
second run into a folder another run holds is refused; staging left by a killed run is
removed by the next."""

import contextlib
import fcntl
import json
import logging
import os
import pathlib
import shutil
import signal
import struct
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from tegrasp_drake.commands import run_folder
from tegrasp_drake.commands.run_folder import staging_file_beside
from tegrasp_drake.events.events_folder import save_memorized_events
from tegrasp_drake.rig.files import held_folder
from tests import killed_runs
from tests.bad_input.probes import (FAKE_TRIALS, assert_one_line_error, earlier_run_of,
                                    folder_contents, memorized_events, no_recording, run_cli,
                                    transfer_out)
from tests.commands.test_run_folder import _ended_process_id


def test_an_overwritten_run_keeps_none_of_the_earlier_runs_figures(tmp_path):
    folder = earlier_run_of(tmp_path / "run", "states.png", "signals.png")
    (folder / "notes.txt").write_text("the user's own file")
    with run_folder.staged_run(folder) as stage:
        for name in ("trial.npz", "states.svg", "signals.svg"):
            (stage / name).write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz"),
                                              "figure": str(stage / "states.svg")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "notes.txt", "result.json", "signals.svg", "states.svg", "trial.npz"]
    assert (folder / "trial.npz").read_bytes() == b"new"


# --- one run per run folder -------------------------------------------------------------------

def test_a_second_run_into_a_folder_being_written_is_refused(tmp_path, monkeypatch, capfd):
    """The first run holds the folder (staged_run's flock) while it simulates; a second
    `tegrasp trial --out` into it stops with one line before it simulates, and the first
    run's files are its own."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "same").mkdir()
    with run_folder.staged_run(tmp_path / "same") as stage:
        (stage / "trial.npz").write_bytes(b"the first run's log")
        with pytest.raises(run_folder.RunFolderError, match="another run is writing there"):
            with run_folder.staged_run(tmp_path / "same"):
                pass
        code, text = run_cli(["trial", "--out", "same", "--overwrite"], capfd)
        assert_one_line_error(code, text, "--out same: another run is writing there now")
        assert (stage / "trial.npz").read_bytes() == b"the first run's log"
    with run_folder.staged_run(tmp_path / "same"):  # released when the first run ends
        pass


def test_the_staging_of_a_killed_run_is_removed_by_the_next_run(tmp_path):
    from tegrasp_drake.commands.run_folder import STAGING_PREFIX, RunFolderError, staged_run
    killed = subprocess.run(
        [sys.executable, "-c", "import os, signal, sys\n"
         "from tegrasp_drake.commands.run_folder import staged_run\n"
         "with staged_run(sys.argv[1]):\n    os.kill(os.getpid(), signal.SIGKILL)\n",
         str(tmp_path)], env=killed_runs.environment(), timeout=300)
    assert killed.returncode == -signal.SIGKILL
    (left,) = tmp_path.glob(f"{STAGING_PREFIX}*")
    with staged_run(tmp_path) as stage:
        assert not left.exists() and stage.is_dir()
        with pytest.raises(RunFolderError, match="another run is writing there now"):
            with staged_run(tmp_path):
                pass
        assert stage.is_dir()  # a live run's staging is never touched
    assert not list(tmp_path.glob(f"{STAGING_PREFIX}*"))


def _processes_naming(path: pathlib.Path) -> list[int]:
    """The ids of the processes whose command line names `path` (Linux's /proc)."""
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        try:
            if entry.name.isdigit() and str(path).encode() in (entry / "cmdline").read_bytes():
                found.append(int(entry.name))
        except OSError:
            continue
    return found


def _wait_until(condition, what: str, timeout_s: float = 120.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not condition():
        assert time.monotonic() < deadline, what
        time.sleep(0.05)


# Rule: a run killed past its handlers (SIGKILL) leaves nothing running and nothing for ever:
# its staging log is removed by the next run logging to the same --log, a live run's is left
# alone.
@pytest.mark.slow
@pytest.mark.skipif(not pathlib.Path("/proc/self/cmdline").exists(), reason="no /proc")
def test_a_killed_hardware_runs_staging_log_is_removed_by_the_next_run(tmp_path,
                                                                       ideal_grasp_log):
    from tegrasp_drake.emulators.emulator_process import EmulatedDevices
    from tegrasp_drake.hardware.config import hardware_config_to_yaml
    trial = ideal_grasp_log("box").save(tmp_path / "box.npz")
    logs = tmp_path / "logs"
    url = f"udpm://239.255.76.67:{7500 + (os.getpid() * 7) % 100}?ttl=0"
    command = [sys.executable, "-m", "tegrasp_drake", "hardware", "--config",
               str(tmp_path / "hw.yaml"), "--scenario-name", "box", "--controller",
               "heuristic", "--config-set", "scheduling=normal"]
    with EmulatedDevices(lcm_url=url, trial=trial, scheduling="normal") as devices:
        (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(devices.config))
        run = subprocess.Popen([*command, "--log", str(logs / "run.lcmlog")],
                               env=killed_runs.environment(), stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        staging = logs / f".run.lcmlog.{run.pid}.staging"
        try:
            _wait_until(lambda: staging.exists() and staging.stat().st_size > 0,
                        "the run never logged")
        finally:
            run.kill()  # SIGKILL, the run alone (as the OOM killer does)
            run.wait()
    assert run.returncode == -signal.SIGKILL and staging.exists()
    _wait_until(lambda: not _processes_naming(staging), "the run's lcm-logger outlived it")
    live = logs / f".run.lcmlog.{os.getpid()}.staging"  # a run still going
    live.write_bytes(b"being written")
    done = subprocess.run([*command, "--log", str(logs / "run.lcmlog"),
                           "--config-set", "tactile.port=/dev/no_such_port",
                           "--config-set", "ready_timeout=1.5"],
                          env=killed_runs.environment(), capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 1, done.stderr  # the devices did not come up: quickly done
    assert sorted(path.name for path in logs.iterdir()) == [live.name]


# Rule: `--overwrite` replaces the earlier run in the folder wherever that folder has been
# moved or copied to: its files are known by their names (result.json, trial.npz, the
# figures' STEM.FORMAT), not by the absolute paths its result.json recorded; the user's own
# files stay.
@pytest.mark.parametrize("how", ["moved", "copied"])
def test_an_overwrite_into_a_moved_or_copied_run_folder_replaces_the_earlier_run(tmp_path, how):
    from tegrasp_drake.commands import run_folder
    written = earlier_run_of(tmp_path / "written", "states.png", "signals.png",
                             "contact_ra.png")
    (written / "mynotes.txt").write_text("the user's own file")
    folder = tmp_path / "elsewhere"
    (shutil.move if how == "moved" else shutil.copytree)(written, folder)
    with run_folder.staged_run(folder) as stage:
        for name in ("trial.npz", "states.svg", "signals.svg"):
            (stage / name).write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz"),
                                              "figure": str(stage / "states.svg"),
                                              "signals_figure": str(stage / "signals.svg")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "mynotes.txt", "result.json", "signals.svg", "states.svg", "trial.npz"]
    if how == "copied":  # the folder it was copied from is not touched
        assert sorted(p.name for p in written.iterdir()) == [
            "contact_ra.png", "mynotes.txt", "result.json", "signals.png", "states.png",
            "trial.npz"]


# Rule: a result.json is no list of files to delete: a file of the folder it names stays,
# whatever the key, the replay an earlier --html wrote too (a file the user named, which may
# be theirs by now).
def test_an_overwrite_deletes_no_file_the_earlier_result_names(tmp_path):
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    for name in ("trial.npz", "thesis.tex", "notes.html", "replay.html"):
        (folder / name).write_bytes(b"earlier")
    (folder / "result.json").write_text(json.dumps(
        {"log": str(folder / "trial.npz"), "figure": str(folder / "thesis.tex"),
         "signals_figure": str(folder / "notes.html"),
         run_folder.REPLAY_KEY: str(folder / "replay.html")}))
    with run_folder.staged_run(folder) as stage:
        (stage / "trial.npz").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "notes.html", "replay.html", "result.json", "thesis.tex", "trial.npz"]


# Rule: what an --overwrite replaces or removes of the earlier run is said under -v (INFO),
# each file by name.
def test_an_overwrite_says_what_it_replaced_and_removed(tmp_path, caplog):
    from tegrasp_drake.commands import run_folder
    folder = earlier_run_of(tmp_path / "run", "states.png")
    (folder / "notes.txt").write_bytes(b"earlier")
    with caplog.at_level(logging.INFO, logger=run_folder.__name__):
        with run_folder.staged_run(folder) as stage:
            (stage / "trial.npz").write_bytes(b"new")
            run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    said = "\n".join(record.getMessage() for record in caplog.records)
    assert "replaced the earlier run's result.json, trial.npz" in said, said
    assert "removed the earlier run's states.png" in said, said
    assert "notes.txt" not in said, said


@contextlib.contextmanager
def _held(folder):
    """The output folder held as another run's process holds it (a flock on the folder)."""
    folder.mkdir(parents=True, exist_ok=True)
    lock = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        yield
    finally:
        os.close(lock)


# Rule: another run writing into the --out folder is an error outside the run (exit 1, one
# "tegrasp: error:" line naming the folder), not a refused spec (exit 2).
def test_a_sweep_into_a_folder_another_run_holds_is_an_error_outside_the_run(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n")
    out = tmp_path / "out"
    with _held(out):
        code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--no-progress",
                              "--trial-function", "tests.fake_trials:fake_trial"], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(out), "another")
    assert not (out / "trials").exists()


def one_cell_study_spec(tmp_path, command):
    """A `tegrasp transfer` or `tegrasp sensitivity` spec of one cell, in tmp_path."""
    if command == "transfer":
        return transfer_out(tmp_path)[0]
    spec = tmp_path / "s.yaml"
    spec.write_text("parameters: [gripper.position_loop_hz]\nsweep: {controllers: "
                    "[memorized], attempts: 1, objects: [box], grid: [[0.0, 0.0]]}\n")
    return spec


# Rule: a transfer or a sensitivity study holds its whole --out (the sweep runner's lock)
# before it records or writes anything, so a second run into the folder is refused at once
# (exit 1), not after recording every world's events again beside the first.
@pytest.mark.parametrize("command", ["transfer", "sensitivity"])
def test_a_second_study_into_a_held_out_is_refused_before_anything(tmp_path, capfd,
                                                                   monkeypatch, command):
    spec = one_cell_study_spec(tmp_path, command)
    no_recording(monkeypatch)
    out = tmp_path / "out"
    with _held(out):
        before = folder_contents(out)
        code, text = run_cli([command, str(spec), "--out", str(out), "--workers", "1",
                              "--no-progress", *FAKE_TRIALS], capfd)
        assert folder_contents(out) == before
    assert code == 1, text
    assert_one_line_error(code, text, "tegrasp: error:", str(out), "another")
    assert not (out / "cells").exists()


# Rule: what is in the place of a run's own file is a regular file, or the run is refused
# before it simulates (a FIFO, a device link, a folder there is no earlier run's file).
@pytest.mark.parametrize("make", [
    lambda path: __import__("os").mkfifo(path),
    lambda path: path.symlink_to("/dev/zero"),
    lambda path: path.mkdir(),
], ids=["fifo", "device-link", "folder"])
def test_an_overwrite_over_a_run_file_that_is_no_regular_file_is_refused(tmp_path, capfd,
                                                                         monkeypatch, make):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    out = tmp_path / "o"
    out.mkdir()
    make(out / "result.json")
    code, text = run_cli(["trial", "--set", "random_seed=600", "--out", str(out),
                          "--overwrite"], capfd)
    assert code == 1 and "result.json" in text and "remove it yourself" in text, text
    assert len(text.strip().splitlines()) == 1, text


# Rule: a hardware --log that names a file which is not an LCM log (a trial's result.json) is
# said to be one, with or without --overwrite, never "already holds a run's log", and stays.
@pytest.mark.parametrize("overwrite", [[], ["--overwrite"]])
def test_a_hardware_log_naming_a_file_that_is_no_lcm_log_is_said_so_and_kept(
        tmp_path, capfd, monkeypatch, overwrite):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "base").mkdir()
    (tmp_path / "base" / "result.json").write_text('{"held": true, "controller": "memorized"}\n')
    before = folder_contents(tmp_path)
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "base/result.json",
                          "--duration", "5", *overwrite], capfd)
    assert code == 1, text
    assert_one_line_error(code, text, "base/result.json exists and is not an LCM log",
                          "give another --log, or remove it yourself")
    assert "already holds" not in text, text
    assert folder_contents(tmp_path) == before


# Rule: --overwrite replaces an LCM log only when it is an earlier run's (its result beside
# it names it): an LCM log of the user's (lcm-logger's, no run's result beside it) is said to
# be one before the devices are asked for, with or without --overwrite, and stays.
@pytest.mark.parametrize("overwrite", [[], ["--overwrite"]])
@pytest.mark.parametrize("result", [None, '{"transitions": [], "faults": [], "log": '
                                          '"other.lcmlog", "device_counters": {}}\n'],
                         ids=["no-result", "result-of-another-log"])
def test_a_hardware_log_naming_a_users_lcm_log_is_said_so_and_kept(
        tmp_path, capfd, monkeypatch, overwrite, result):
    from tegrasp_drake.hardware.config import HardwareStationConfig, hardware_config_to_yaml
    monkeypatch.chdir(tmp_path)
    (tmp_path / "hw.yaml").write_text(hardware_config_to_yaml(HardwareStationConfig()))
    (tmp_path / "mine.lcmlog").write_bytes(LCM_LOG_START + b"my own recording of the bus")
    if result is not None:
        (tmp_path / "mine.result.json").write_text(result)
    before = folder_contents(tmp_path)
    code, text = run_cli(["hardware", "--config", "hw.yaml", "--log", "mine.lcmlog",
                          "--duration", "5", *overwrite], capfd)
    assert_one_line_error(code, text, "--log mine.lcmlog exists and is an LCM log of no "
                          "earlier run (no mine.result.json beside it names it",
                          "give another --log, or remove it yourself")
    assert folder_contents(tmp_path) == before


# Rule: a run removes only the staging folders a run left (named as mkdtemp names them,
# holding nothing but a run's own files), never a folder of the user's with that prefix.
def test_a_run_keeps_a_users_folder_named_like_a_staging_folder(tmp_path):
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    mine = {".staging-mydata": "thesis.txt", ".staging-x": "notes.txt",
            ".staging-abcd1234": "notes.txt"}
    for name, file in mine.items():
        (folder / name).mkdir()
        (folder / name / file).write_text("the user's")
    left = folder / ".staging-k2j4h5g6"
    left.mkdir()
    (left / "trial.npz").write_bytes(b"a killed run's")
    (left / "states.png").write_bytes(b"a killed run's")
    with run_folder.staged_run(folder):
        pass
    for name, file in mine.items():
        assert (folder / name / file).read_text() == "the user's"
    assert not left.exists()


# Rule: an --overwrite leaves the replay an earlier --html wrote into the folder (a file the
# user named, and may have replaced with their own since).
def test_an_overwrite_keeps_the_earlier_replay_html(tmp_path):
    import json
    from tegrasp_drake.commands import run_folder
    folder = tmp_path / "run"
    folder.mkdir()
    (folder / "trial.npz").write_bytes(b"earlier")
    (folder / "notes.html").write_text("<html>my own notes</html>")
    (folder / "result.json").write_text(json.dumps(
        {run_folder.REPLAY_KEY: str(folder / "notes.html")}))
    with run_folder.staged_run(folder) as stage:
        (stage / "trial.npz").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert (folder / "notes.html").read_text() == "<html>my own notes</html>"


# Rule: a symbolic link under a run file's name (a figure, trial.npz, result.json) is the
# user's: a run writes its files itself, never a link. The trial is refused before it
# simulates, as for a FIFO there, and the link stays (--overwrite removed it as "the earlier
# run's" figure when the new run wrote another format).
@pytest.mark.parametrize("name", ["avoid.svg", "trial.npz"])
def test_a_link_under_a_run_files_name_refuses_the_trial_and_stays(tmp_path, capfd,
                                                                  monkeypatch, name):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    folder, precious = tmp_path / "ow", tmp_path / "precious.svg"
    folder.mkdir()
    precious.write_text("<svg/>")
    (folder / name).symlink_to(precious)
    code, text = run_cli(["trial", "--set", "random_seed=633", "--out", str(folder),
                          "--overwrite"], capfd)
    assert code == 1, text
    assert f"{name} is a symbolic link" in text and text.count("\n") == 0, text
    assert (folder / name).is_symlink() and precious.read_text() == "<svg/>"


# Rule: a file under a figure's name (any format: a run replaces its own format's and removes
# the others') that no run of this tool wrote is the user's: a trial into that folder is
# refused before it simulates, with or without --overwrite, naming the file, and the file
# stays. A run's own figure is one its result.json lists that starts as its format does: the
# user's notes saved as states.png are not, nor the user's own picture the run never listed
# (both were replaced, or removed as "the earlier run's").
USERS_PICTURE = b"\x89PNG\r\n\x1a\n the user's own picture"


@pytest.mark.parametrize("name, content, overwrite, earlier", [
    ("states.png", b"earlier", True, True),  # listed by result.json, but not a figure
    ("avoid.png", USERS_PICTURE, True, True),  # a PNG, but the earlier run never wrote it
    ("signals.svg", b"<svg>my drawing</svg>", True, True),  # removed as the other format
    ("states.png", USERS_PICTURE, False, False),  # an existing folder that holds no run
    ("contact_ra.pdf", b"earlier", False, False)])
def test_a_users_file_under_a_figures_name_refuses_the_trial_and_stays(
        tmp_path, capfd, monkeypatch, name, content, overwrite, earlier):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    folder = tmp_path / "ow"
    if earlier:
        earlier_run_of(folder, "states.png", "signals.png")
    folder.mkdir(exist_ok=True)
    (folder / name).write_bytes(content)
    before = folder_contents(folder)
    code, text = run_cli(["trial", "--set", "random_seed=633", "--out", str(folder)]
                         + ["--overwrite"] * overwrite, capfd)
    assert code == 1, text
    assert text.count("\n") == 0 and f"{name} is not a figure" in text, text
    assert "move it" in text and "another --out" in text, text
    assert folder_contents(folder) == before


def test_demo_refuses_a_users_file_under_a_figures_name_in_its_own_folder(
        tmp_path, capfd, monkeypatch):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    monkeypatch.chdir(tmp_path)
    folder = earlier_run_of(tmp_path / "out" / "demo", "states.png")
    (folder / "avoid.svg").write_bytes(b"earlier")
    code, text = run_cli(["demo"], capfd)
    assert code == 1 and "avoid.svg is not a figure" in text, text
    assert (folder / "avoid.svg").read_bytes() == b"earlier"


def test_a_commit_removes_no_file_under_a_figures_name_the_earlier_run_did_not_write(tmp_path):
    folder = earlier_run_of(tmp_path / "run", "states.png")
    (folder / "avoid.png").write_bytes(USERS_PICTURE)
    (folder / "signals.pdf").write_bytes(b"earlier")
    with run_folder.staged_run(folder) as stage:
        (stage / "trial.npz").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {"log": str(stage / "trial.npz")})
    assert sorted(p.name for p in folder.iterdir()) == [
        "avoid.png", "result.json", "signals.pdf", "trial.npz"]
    assert (folder / "avoid.png").read_bytes() == USERS_PICTURE


# Rule: an --overwrite replaces the earlier run's real figures, of its format and the others.
@pytest.mark.parametrize("figure_format", ["png", "svg"])
def test_an_overwrite_replaces_the_earlier_runs_own_figures(tmp_path, figure_format):
    folder = earlier_run_of(tmp_path / "run", "states.png", "signals.png", "avoid.png")
    assert run_folder.choose_run_folder(str(folder), default="unused", replace_default=False,
                                        overwrite=True) == folder
    with run_folder.staged_run(folder) as stage:
        for stem in ("states", "signals"):
            (stage / f"{stem}.{figure_format}").write_bytes(b"new")
        run_folder.commit_run(stage, folder, {})
    assert sorted(p.name for p in folder.iterdir()) == [
        "result.json", f"signals.{figure_format}", f"states.{figure_format}"]


# Rule: every command that writes a run into a folder takes one lock, the folder's own: a
# sweep into the folder a trial is writing is refused at once, and the reverse (the sweep held
# D/.sweep.lock, the trial the folder itself: both ran, and the lock file stayed in the trial's
# run folder).
_HOLD = ("import sys\n"
         "from tegrasp_drake.commands.run_folder import claimed_run_folder\n"
         "with claimed_run_folder(sys.argv[1]):\n"
         "    print('held', flush=True)\n"
         "    sys.stdin.read()\n")

_CLAIM = ("import sys\n"
          "from tegrasp_drake.commands.run_folder import RunFolderError, claimed_run_folder\n"
          "try:\n"
          "    with claimed_run_folder(sys.argv[1]):\n"
          "        print('claimed')\n"
          "except RunFolderError as e:\n"
          "    print(e)\n")


def test_a_trial_and_a_sweep_exclude_each_other_on_one_folder(tmp_path):
    from tegrasp_drake.rig.files import UserPathError
    from tegrasp_drake.sweep.runner import hold_output_folder
    folder = tmp_path / "D"
    folder.mkdir()
    trial = subprocess.Popen([sys.executable, "-c", _HOLD, str(folder)], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, text=True)
    try:
        assert trial.stdout.readline() == "held\n"  # a trial's run holds the folder
        with pytest.raises(UserPathError, match="another run .* is writing there now"):
            with hold_output_folder(folder):
                pass
    finally:
        trial.communicate("", timeout=600)
    with hold_output_folder(folder):  # a sweep holds it: a trial's run is refused
        claim = subprocess.run([sys.executable, "-c", _CLAIM, str(folder)],
                               capture_output=True, text=True, timeout=600)
    assert "another run is writing there now" in claim.stdout, claim.stdout + claim.stderr
    assert list(folder.iterdir()) == []  # no lock file left behind

LCM_LOG_START = struct.pack(">I", 0xEDA1DA01)  # an LCM log's first event's sync word


def _write_all(files: dict) -> None:
    for path, data in files.items():
        path.write_bytes(data)


# Rule: a hardware run's log staging removes the killed runs' staging logs of that --log
# alone, and only those holding an LCM log (or nothing, or the start of a sync word).
def test_a_log_staging_removes_the_same_logs_leftovers_and_keeps_the_users_files(tmp_path):
    dead = _ended_process_id()
    users = {tmp_path / f".txt.lcmlog.{dead}.staging": b"not a log",
             tmp_path / f".other.lcmlog.{dead}.staging": LCM_LOG_START + b"another log",
             tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": b"not a log either"}
    left = {tmp_path / f".kill.lcmlog.{dead}.staging": LCM_LOG_START + b"events",
            tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": b"",
            tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging": LCM_LOG_START[:2]}
    live = tmp_path / f".kill.lcmlog.{os.getppid()}.staging"
    _write_all({**users, **left, live: LCM_LOG_START})
    link = tmp_path / f".kill.lcmlog.{_ended_process_id()}.staging"
    link.symlink_to(tmp_path / f".txt.lcmlog.{dead}.staging")
    staging_file_beside(tmp_path / "kill.lcmlog", LCM_LOG_START)
    assert all(path.read_bytes() == data for path, data in users.items())
    assert link.is_symlink() and live.exists()
    assert not any(path.exists() for path in left)


# Rule: saving events removes the ended writers' staging files of the files it writes (JSON),
# and nothing else of the events folder's.
def test_saving_events_keeps_the_users_files_named_like_staging_files(tmp_path):
    dead = _ended_process_id()
    (tmp_path / "mine").mkdir()
    users = {tmp_path / f".notes.txt.{dead}.staging": b"{my notes}",
             tmp_path / "mine" / f".photo.json.{dead}.staging": b"{\"a\": 1}",
             tmp_path / f".index.json.abcd1234.{dead}.staging": b"not JSON"}
    left = {tmp_path / f".index.json.k2j4h5g6.{dead}.staging": b"{\"format\"",
            tmp_path / "mine" / f".reach_load.json.x_y0z9w8.{dead}.staging": b""}
    _write_all({**users, **left})
    save_memorized_events(tmp_path, memorized_events())
    assert all(path.read_bytes() == data for path, data in users.items())
    assert not any(path.exists() for path in left)


def test_record_events_into_a_folder_another_recording_holds_is_refused_at_once(tmp_path,
                                                                                capfd):
    """Two record-events into one folder: the second replaced the first's events when both
    saved; now it is refused before it simulates, as a second run into an --out is."""
    events = tmp_path / "events"
    events.mkdir()
    with held_folder(events):  # the first recording, still running
        code, text = run_cli(["record-events", "--object", "box", "--set", "random_seed=620",
                              "--events", str(events), "-q"], capfd)
    assert_one_line_error(code, text, f"--events {events}: another run is recording events "
                                      "there now")
    assert list(events.iterdir()) == []


def _edited_earlier_log(folder):
    """The earlier run's trial.npz with one taxel changed by hand (its checksum kept)."""
    from tests.trial_log_contents import read_trial_log_contents
    contents = read_trial_log_contents(folder / "trial.npz")
    contents["taxels"] = contents["taxels"] + 0.5
    np.savez_compressed(folder / "trial.npz", **contents)


def _result_edit(change):
    def edit(folder):
        data = json.loads((folder / "result.json").read_text())
        change(data)
        (folder / "result.json").write_text(json.dumps(data))
    return edit


# Rule: --overwrite replaces a run folder's trial.npz and result.json only when they are an
# earlier run's (trial.npz a trial log with its checksum, result.json a trial's result naming
# trial.npz and, beside it, that log's result): a file of the user's under one of those names
# refuses the trial or demo before it simulates, naming the file and what to do, and stays.
@pytest.mark.parametrize("spoil, name, words", [
    (lambda folder: (folder / "trial.npz").write_text("my notes"), "trial.npz",
     "is not a trial log a run wrote (is not a trial log (an .npz zip archive written by "
     "tegrasp): it starts with the bytes 6d 79 20 6e, not a zip archive's (50 4b 03 04))"),
    (_edited_earlier_log, "trial.npz", "is not a trial log a run wrote (was changed after it "
     "was written"),
    (lambda folder: np.savez(folder / "trial.npz", x=[1.0]), "trial.npz",
     "is not a trial log a run wrote (is truncated or corrupt ('x.npy' is not an array a trial "
     "log has"),
    (lambda folder: (folder / "result.json").write_text('{"my": "data"}'), "result.json",
     "is not a trial's result (field 'object' is missing"),
    (_result_edit(lambda data: data.update(log="/home/me/thesis.npz")), "result.json",
     "is a result whose log is '/home/me/thesis.npz', not a run's trial.npz"),
    (_result_edit(lambda data: data.update(hold_time_s=0.05)), "result.json",
     "is not the result of the trial.npz beside it (their 'hold_time_s' differ)"),
], ids=["notes-log", "edited-log", "other-npz", "other-json", "other-log", "other-result"])
@pytest.mark.parametrize("command", ["trial", "demo"])
def test_an_overwrite_refuses_a_users_trial_log_or_result_before_simulating(
        spoil, name, words, command, tmp_path, capfd, monkeypatch):
    from tegrasp_drake.runs import trial as trial_module
    monkeypatch.setattr(trial_module, "run_trial",
                        lambda *a, **k: pytest.fail("the trial was simulated"))
    monkeypatch.chdir(tmp_path)
    folder = earlier_run_of(tmp_path / "out" / "demo", "states.png")
    assert run_folder.foreign_run_file_problem(folder) is None  # the earlier run's own
    spoil(folder)
    before = folder_contents(folder)
    argv = ["demo"] if command == "demo" else ["trial", "--out", str(folder), "--overwrite"]
    code, text = run_cli(argv, capfd)
    assert_one_line_error(code, text, f"{name} {words}", f"a run replaces its {name}; move it "
                          "out of the folder, or give another --out")
    assert folder_contents(folder) == before


def test_a_run_written_before_logs_carried_a_checksum_is_still_an_earlier_run(tmp_path):
    """A run folder an earlier version of the package wrote (its trial.npz without meta
    'checksum') may be replaced by `tegrasp demo` or `trial --overwrite`, as a run of this
    version may; load_trial_log still refuses to read that log."""
    from tegrasp_drake.scenario.trial_log_file import TrialLogError, load_trial_log
    from tests.trial_log_contents import read_trial_log_contents
    folder = earlier_run_of(tmp_path / "out" / "demo", "states.png")
    contents = read_trial_log_contents(folder / "trial.npz")
    meta = json.loads(str(contents["meta"]))
    del meta["checksum"]
    contents["meta"] = np.array(json.dumps(meta))
    np.savez_compressed(folder / "trial.npz", **contents)
    assert run_folder.foreign_run_file_problem(folder) is None
    with pytest.raises(TrialLogError, match="written by an earlier version of the package"):
        load_trial_log(folder / "trial.npz")


# Rule: a sweep's, transfer's or sensitivity study's text report (Table I, the statistics,
# the summary, success by offset, transfer.md, sensitivity.md) replaces a file under its name
# only when that file is such a report; the user's own file there refuses the command before
# anything runs, in one line naming it, and stays; an earlier report is replaced.
@pytest.mark.parametrize("name", ["table1.md", "table1.csv", "statistics.md",
                                  "statistics.json", "summary.md", "success_by_offset.csv"])
def test_a_users_file_under_a_reports_name_refuses_the_sweep_and_stays(tmp_path, capfd, name):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / name).write_text("my own table\n")
    code, text = run_cli(["sweep", "--spec", str(spec), "--out", str(out), "--no-progress",
                          "--workers", "1", "--trial-function", "tests.fake_trials:fake_trial"],
                         capfd)
    assert_one_line_error(code, text, "tegrasp: error:", str(out), f"{name} exists and is not",
                          "move it out of the folder, or give another --out")
    assert code == 1, text
    assert (out / name).read_text() == "my own table\n"
    assert not (out / "trials").exists()


# Rule: a named pipe or a folder under a report's or a figure's name is said to be one,
# without waiting on the pipe for a writer (an open for reading would block).
@pytest.mark.parametrize("kind, words", [("fifo", "is a named pipe (FIFO) where a"),
                                         ("folder", "is a folder where a")])
def test_a_pipe_or_folder_under_a_reports_or_figures_name_is_said_at_once(tmp_path, kind,
                                                                           words):
    from tegrasp_drake.figures.figure_files import figure_replace_problem
    from tegrasp_drake.rig.report_files import report_replace_problem
    checks = {"table1.md": lambda path: report_replace_problem(path, "# Table I"),
              "states.png": figure_replace_problem}
    for name, check in checks.items():
        path = tmp_path / name
        os.mkfifo(path) if kind == "fifo" else path.mkdir()
        found = []
        checking = threading.Thread(target=lambda: found.append(check(path)), daemon=True)
        checking.start()
        checking.join(timeout=60)  # a hang guard: the check reads no byte of a pipe
        assert found and found[0].startswith(words), (name, found)


def test_a_sweeps_earlier_reports_are_replaced(tmp_path, capfd):
    spec = tmp_path / "spec.yaml"
    spec.write_text("objects: [box]\ncontrollers: [open_loop]\nattempts: 1\n")
    out = tmp_path / "out"
    arguments = ["sweep", "--spec", str(spec), "--out", str(out), "--no-progress", "--workers",
                 "1", "--trial-function", "tests.fake_trials:fake_trial"]
    for _ in range(2):
        code, text = run_cli(arguments, capfd)
        assert code == 0, text
    from tegrasp_drake.reports import report_starts
    for name, start in report_starts().items():
        assert (out / name).read_bytes().startswith(start.encode()), name


def test_write_reports_keeps_a_users_file_under_a_reports_name(tmp_path):
    from tegrasp_drake.reports import write_reports
    from tegrasp_drake.rig.files import UserPathError
    out = tmp_path / "out"
    shutil.copytree(pathlib.Path(__file__).parents[2] / "analysis" / "results_seed0" / "trials",
                    out / "trials")
    (out / "summary.md").write_text("| my | own |\n")
    with pytest.raises(UserPathError, match="summary.md exists and is not"):
        write_reports(out)
    assert (out / "summary.md").read_text() == "| my | own |\n"
    assert not (out / "table1.md").exists()


@pytest.mark.parametrize("command", ["transfer", "sensitivity"])
def test_a_users_file_under_a_studys_report_name_refuses_it_before_anything(
        tmp_path, capfd, monkeypatch, command):
    spec = one_cell_study_spec(tmp_path, command)
    no_recording(monkeypatch)
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    (out / f"{command}.md").write_text("my notes\n")
    before = folder_contents(out)
    code, text = run_cli([command, str(spec), "--out", str(out), "--workers", "1",
                          "--no-progress", *FAKE_TRIALS], capfd)
    assert_one_line_error(code, text, "tegrasp: error:", f"{command}.md exists and is not")
    assert code == 1, text
    assert folder_contents(out) == before
    assert (out / f"{command}.md").read_text() == "my notes\n"
