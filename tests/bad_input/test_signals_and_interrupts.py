"""Signals sent to a running `tegrasp`: Ctrl-C, SIGTERM and SIGHUP stop a command with the
one interruption line and the signal's exit code, remove the run's staging, abandon a
sweep's running trial and leave replaced events all new; a second signal during the
cleanup of the first, or one while pydrake is imported, is no traceback."""

import contextlib
import os
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from tegrasp_drake import cli
from tegrasp_drake.commands import run_folder
from tegrasp_drake.events.events_folder import load_memorized_events, save_memorized_events
from tegrasp_drake.rig import files
from tests import killed_runs
from tests.bad_input.probes import (assert_one_interruption_line, memorized_events,
                                    parser_of_one_command, run_cli)
from tests.killed_runs import default_signal_dispositions


@pytest.fixture
def python_sigint_handler():
    """Python's own Ctrl-C handler for the test, whatever an earlier test in this process
    left installed (the emulator and hardware tests install their own)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_ctrl_c_while_events_are_replaced_leaves_them_all_new(tmp_path, monkeypatch,
                                                              python_sigint_handler):
    """Probe 8: the SIGINT comes during the renames; it is held until the index is in."""
    save_memorized_events(tmp_path, memorized_events(seed=1))
    real_replace, interrupted = os.replace, []

    def replace_then_interrupt(source, target):
        if not interrupted:
            interrupted.append(target)
            os.kill(os.getpid(), signal.SIGINT)
        real_replace(source, target)
    monkeypatch.setattr(os, "replace", replace_then_interrupt)
    new = memorized_events(seed=2)
    with pytest.raises(KeyboardInterrupt):
        save_memorized_events(tmp_path, new)
    monkeypatch.setattr(os, "replace", real_replace)
    loaded = load_memorized_events(tmp_path, "mine")
    for event in new:
        np.testing.assert_array_equal(loaded[event.transition].sa, event.sa)
    assert not list(tmp_path.rglob("*.tmp"))


@pytest.mark.parametrize("signal_number", [signal.SIGTERM, signal.SIGHUP])
def test_sigterm_and_sighup_remove_a_runs_staging_folder(signal_number, tmp_path):
    # The signal's default disposition, as a terminal's process has it (a suite started
    # under nohup inherits SIGHUP ignored, which termination_interrupts leaves alone).
    inherited = signal.signal(signal_number, signal.SIG_DFL)
    try:
        with pytest.raises(KeyboardInterrupt, match=signal.Signals(signal_number).name):
            with files.termination_interrupts():
                with run_folder.staged_run(tmp_path) as stage:
                    (stage / "trial.npz").write_bytes(b"half a log")
                    os.kill(os.getpid(), signal_number)
        assert list(tmp_path.iterdir()) == []
        assert signal.getsignal(signal_number) == signal.SIG_DFL
    finally:
        signal.signal(signal_number, inherited)


def test_cli_main_reports_a_sigterm_as_an_interruption(monkeypatch, capfd):
    from tegrasp_drake.commands import plot

    def terminated(args):
        os.kill(os.getpid(), signal.SIGTERM)
    monkeypatch.setattr(plot, "run", terminated)
    code, text = run_cli(["plot", "table1", "nowhere"], capfd)
    assert code == 128 + signal.SIGTERM
    assert text.strip() == ("tegrasp: interrupted (SIGTERM); the run's unfinished files were "
                            "removed")


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


# Rule: every catchable terminating signal stops a run as Ctrl-C does (its staging removed);
# a run killed past its handlers leaves a staging folder the next run into its folder removes.
@pytest.mark.parametrize("name", ["SIGQUIT", "SIGUSR1", "SIGUSR2", "SIGALRM"])
def test_a_terminating_signal_removes_the_runs_staging(name, tmp_path, monkeypatch, capfd):
    from tegrasp_drake.commands.run_folder import STAGING_PREFIX, staged_run

    def stage_and_signal(args):
        with staged_run(tmp_path):
            os.kill(os.getpid(), signal.Signals[name])
            raise AssertionError("the signal did not stop the run")

    monkeypatch.setattr(cli, "build_parser", lambda: parser_of_one_command(stage_and_signal))
    code, text = run_cli(["say"], capfd)
    assert code == 128 + signal.Signals[name].value
    assert text.strip() == f"tegrasp: interrupted ({name}); the run's unfinished files were removed"
    assert not list(tmp_path.glob(f"{STAGING_PREFIX}*"))


# The wrapped calls, chosen by the variable SIGNALS_AT. "staging": SIGHUP as the run's
# staging folder is made and SIGTERM as it is removed (the second signal during the first's
# cleanup), then SIGINT and SIGTERM at the interpreter's exit. "import": SIGTERM as
# pydrake.common, a C++ module, imports its first Python module (inside the C++
# initialisation that catches a KeyboardInterrupt). "exec": SIGTERM inside code run by
# exec() of a string (as scipy imports numpy) while the run's folder is made.
_SITECUSTOMIZE = """
import atexit, importlib.abc, os, pathlib, shutil, signal, sys, tempfile

def send(number):
    os.kill(os.getpid(), number)

where = os.environ.pop("SIGNALS_AT", "")
if where == "staging":
    made, removed = tempfile.mkdtemp, shutil.rmtree

    def mkdtemp(*args, **kwargs):
        folder = made(*args, **kwargs)
        if os.path.basename(folder).startswith(".staging-"):
            send(signal.SIGHUP)
        return folder

    def rmtree(path, *args, **kwargs):
        if os.path.basename(str(path)).startswith(".staging-"):
            send(signal.SIGTERM)
        return removed(path, *args, **kwargs)

    tempfile.mkdtemp, shutil.rmtree = mkdtemp, rmtree
    atexit.register(lambda: (send(signal.SIGINT), send(signal.SIGTERM)))
elif where == "import":
    class SignalAtPydrake(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.startswith("pydrake.common.") and not getattr(self, "sent", False):
                self.sent = True
                send(signal.SIGTERM)
            return None

    sys.meta_path.insert(0, SignalAtPydrake())
elif where == "exec":
    mkdir = pathlib.Path.mkdir

    def signalled_mkdir(self, *args, **kwargs):
        if self.name == "run":
            exec("send(signal.SIGTERM)", {"send": send, "signal": signal})
        return mkdir(self, *args, **kwargs)

    pathlib.Path.mkdir = signalled_mkdir
"""


def _run_signalled(where, tmp_path, *arguments):
    """(exit code, stderr) of `python -m tegrasp_drake ARGUMENTS` signalled at `where`."""
    hooks = tmp_path / "hooks"
    hooks.mkdir()
    (hooks / "sitecustomize.py").write_text(_SITECUSTOMIZE)
    environment = killed_runs.environment()
    environment.update(PYTHONPATH=f"{hooks}:{environment['PYTHONPATH']}", SIGNALS_AT=where,
                       PYTHONUTF8="1")
    finished = subprocess.run([sys.executable, "-m", "tegrasp_drake", *arguments],
                              env=environment, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True, timeout=600,
                              preexec_fn=default_signal_dispositions)
    return finished.returncode, finished.stderr


# Rule: the first termination signal is taken once; more while it is handled, or while the
# interpreter exits, neither print a traceback nor change the exit code nor keep a file.
def test_a_second_signal_during_the_cleanup_of_the_first_is_not_a_traceback(tmp_path):
    code, text = _run_signalled("staging", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    assert_one_interruption_line(code, text, "SIGHUP")
    assert not (tmp_path / "run").exists()  # the staging folder removed, and the folder made for it


# Rule: a signal during pydrake's import is acted on once the import returned: the one line,
# not pydrake's own report of a KeyboardInterrupt in its initialisation.
def test_a_signal_while_pydrake_is_imported_is_the_one_interruption_line(tmp_path):
    code, text = _run_signalled("import", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    assert_one_interruption_line(code, text, "SIGTERM")
    assert not (tmp_path / "run").exists()


# Rule: the exit code is the signal's even when its KeyboardInterrupt passed through code
# that exec() ran from a string (CPython then ends a `python -m` process by SIGINT).
def test_an_interrupt_raised_inside_exec_keeps_the_signals_exit_code(tmp_path):
    code, text = _run_signalled("exec", tmp_path, "trial", "--set", "random_seed=629",
                                "--out", str(tmp_path / "run"))
    assert_one_interruption_line(code, text, "SIGTERM")
    assert not (tmp_path / "run").exists()


def test_a_hangup_sent_to_a_sweeps_process_group_is_one_line(tmp_path):
    """A terminal that closes sends SIGHUP to the whole process group, the pool's helper
    processes too; multiprocessing's resource tracker died of it and, relaunched during the
    clean-up, printed a traceback for each semaphore it had not seen."""
    started = tmp_path / "started"
    started.mkdir()
    process = subprocess.Popen(
        [sys.executable, "-m", "tegrasp_drake", "sweep", "--objects", "box", "--controllers",
         "open_loop", "--attempts", "2", "--workers", "2", "--out", str(tmp_path / "out"),
         "--trial-function", "tests.fake_trials:started_fake_trial", "--no-progress"],
        env={**killed_runs.environment(), "FAKE_TRIALS_STARTED": str(started)},
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=default_signal_dispositions)
    try:
        deadline = time.monotonic() + 300.0
        while len(list(started.iterdir())) < 2:  # both workers are in a trial
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.1)
        os.killpg(process.pid, signal.SIGHUP)
        _, err = process.communicate(timeout=300)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
    assert_one_interruption_line(process.returncode, err, "SIGHUP")
    assert "resource_tracker" not in err and "leak" not in err, err


# Rule: a record-events stopped before it saved (SIGTERM, Ctrl-C, an error) removes the events
# folder it made, and its parents it made, while they are empty; a folder the user had stays.
def _recording_that_gets(signal_number):
    def record(*args, **kwargs):
        os.kill(os.getpid(), signal_number)
        raise AssertionError("the signal did not stop the recording")
    return record


@pytest.mark.parametrize("signal_number", [signal.SIGTERM, signal.SIGINT])
def test_an_interrupted_record_events_removes_the_empty_folder_it_made(
        signal_number, tmp_path, monkeypatch, capfd, python_sigint_handler):
    from tegrasp_drake.recording import paper_events
    monkeypatch.setattr(paper_events, "record_events", _recording_that_gets(signal_number))
    events = tmp_path / "new" / "ev"
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_interruption_line(code, text, signal.Signals(signal_number).name)
    assert list(tmp_path.iterdir()) == []


def test_a_failed_record_events_removes_the_empty_folder_it_made(tmp_path, monkeypatch,
                                                                 capfd):
    from tegrasp_drake.recording import paper_events

    def failed(*args, **kwargs):
        raise paper_events.RecordEventsError("no first contact")
    monkeypatch.setattr(paper_events, "record_events", failed)
    code, text = run_cli(["record-events", "--object", "box", "--events",
                          str(tmp_path / "ev")], capfd)
    assert code == 1 and "no first contact" in text
    assert list(tmp_path.iterdir()) == []


def test_an_interrupted_record_events_keeps_the_users_empty_folder(tmp_path, monkeypatch,
                                                                   capfd):
    from tegrasp_drake.recording import paper_events
    monkeypatch.setattr(paper_events, "record_events", _recording_that_gets(signal.SIGTERM))
    events = tmp_path / "ev"
    events.mkdir()
    code, text = run_cli(["record-events", "--object", "box", "--events", str(events)], capfd)
    assert_one_interruption_line(code, text, "SIGTERM")
    assert events.is_dir() and list(events.iterdir()) == []


@pytest.mark.parametrize("name", ["SIGTERM", "SIGINT", "SIGHUP"])
def test_emulate_stopped_by_a_signal_ends_with_128_plus_its_number(name, tmp_path):
    lcm_url = f"udpm://239.255.76.67:{7900 + os.getpid() % 500}?ttl=0"
    with subprocess.Popen([sys.executable, "-m", "tegrasp_drake", "emulate", "robotiq",
                           "--lcm-url", lcm_url], cwd=tmp_path, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          preexec_fn=default_signal_dispositions) as emulator:
        try:
            lines = []
            while not lines or lines[-1].strip() != "ready":  # up: its handlers are in place
                lines.append(emulator.stdout.readline())
                assert lines[-1], "".join(lines) + emulator.stderr.read()
            emulator.send_signal(getattr(signal, name))
            said, err = emulator.communicate(timeout=120)
        finally:
            if emulator.poll() is None:
                emulator.kill()
    assert said.strip().splitlines()[-1] == "stopped", said
    assert_one_interruption_line(emulator.returncode, err, name)
