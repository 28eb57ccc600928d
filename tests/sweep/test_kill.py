"""Acceptance: a sweep killed with SIGKILL, or stopped by SIGTERM or SIGHUP, and resumed gives
exactly the records of an uninterrupted run; started under `nohup`, it runs on through a
SIGHUP."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests import killed_runs
from tests.killed_runs import default_signal_dispositions, environment

# Seven sweeps of 54 paced fake trials: minutes on a busy host, so started first.
pytestmark = pytest.mark.long_file

TRIALS_TOTAL = 2 * 9 * 3  # two objects, nine markers, three attempts, one controller
TIMEOUT_S = 600  # [s] a hang guard on a busy host, not a performance criterion


def sweep_command(out_dir):
    return [sys.executable, "-m", "tegrasp_drake.commands.sweep",
            "--objects", "box", "thin_cylinder", "--controllers", "memorized",
            "--attempts", "3", "--workers", "2", "--out", str(out_dir), "--no-progress",
            "--trial-function", "tests.fake_trials:slow_fake_trial"]


def run_to_end(out_dir):
    return subprocess.run(sweep_command(out_dir), env=environment(), capture_output=True,
                          text=True, timeout=TIMEOUT_S, check=True)


def record_files(out_dir):
    folder = out_dir / "trials"
    return sorted(folder.glob("*.json")) if folder.is_dir() else []


def kill_after_some_records(out_dir, minimum):
    return killed_runs.kill_after_some_records(
        sweep_command(out_dir), lambda: record_files(out_dir), minimum, TIMEOUT_S)


def test_sigkill_then_resume_gives_the_records_of_an_uninterrupted_run(tmp_path):
    killed_dir, clean_dir = tmp_path / "killed", tmp_path / "clean"
    count, returncode = kill_after_some_records(killed_dir, minimum=4)
    assert returncode == -signal.SIGKILL
    assert 4 <= count < TRIALS_TOTAL, "the kill must land in the middle of the sweep"

    resumed = run_to_end(killed_dir)
    finished_before = int(resumed.stdout.split(", ")[1].split()[0])
    assert count <= finished_before < TRIALS_TOTAL
    assert f"{TRIALS_TOTAL - finished_before} run now" in resumed.stdout

    run_to_end(clean_dir)
    killed, clean = record_files(killed_dir), record_files(clean_dir)
    assert [p.name for p in killed] == [p.name for p in clean]
    assert len(clean) == TRIALS_TOTAL
    for a, b in zip(killed, clean):
        assert a.read_bytes() == b.read_bytes(), a.name
    assert not list((killed_dir / "trials").glob(".*"))  # no temporary file of any kind
    assert (killed_dir / "table1.csv").read_bytes() == (clean_dir / "table1.csv").read_bytes()


# Rule: SIGTERM (what `kill` and batch systems send) and SIGHUP (a closed terminal) stop a
# sweep as Ctrl-C does: the records written stay, no staging or temporary file is left, and
# the same command resumes to exactly the records of an uninterrupted run. The signal goes
# to the pid the test started, which `python -m tegrasp_drake.commands.sweep` keeps across
# its exec of the command line; the sweep starts with the signal at its default action
# (killed_runs.default_signal_dispositions), whatever the suite's own runner ignores.
@pytest.mark.parametrize("signal_number", [signal.SIGTERM, signal.SIGHUP])
def test_sigterm_or_sighup_then_resume_gives_the_records_of_an_uninterrupted_run(
        tmp_path, signal_number):
    stopped_dir, clean_dir = tmp_path / "stopped", tmp_path / "clean"
    count, returncode = killed_runs.kill_after_some_records(
        sweep_command(stopped_dir), lambda: record_files(stopped_dir), 4, TIMEOUT_S,
        signal_number)
    assert returncode == 128 + signal_number
    assert 4 <= count < TRIALS_TOTAL, "the signal must land in the middle of the sweep"
    assert not list(stopped_dir.rglob(".*")), list(stopped_dir.rglob(".*"))
    stopped = {p.name: p.read_bytes() for p in record_files(stopped_dir)}

    resumed = run_to_end(stopped_dir)
    finished_before = int(resumed.stdout.split(", ")[1].split()[0])
    assert finished_before == len(stopped)
    assert f"{TRIALS_TOTAL - finished_before} run now" in resumed.stdout
    for name, content in stopped.items():  # not run again
        assert (stopped_dir / "trials" / name).read_bytes() == content, name

    run_to_end(clean_dir)
    resumed_records, clean = record_files(stopped_dir), record_files(clean_dir)
    assert [p.name for p in resumed_records] == [p.name for p in clean]
    for a, b in zip(resumed_records, clean):
        assert a.read_bytes() == b.read_bytes(), a.name
    assert not list(stopped_dir.rglob(".*"))


def started_under_nohup():
    """A Popen preexec_fn: the child's signals as `nohup` leaves them (SIGHUP ignored)."""
    default_signal_dispositions()
    signal.signal(signal.SIGHUP, signal.SIG_IGN)


# Rule: a sweep started with SIGHUP ignored (`nohup tegrasp sweep ...`) keeps it ignored: a
# closed terminal does not stop it, and it runs to the end.
def test_a_sweep_started_under_nohup_runs_on_through_a_sighup(tmp_path):
    out_dir = tmp_path / "out"
    count, returncode = killed_runs.kill_after_some_records(
        sweep_command(out_dir), lambda: record_files(out_dir), 4, TIMEOUT_S, signal.SIGHUP,
        signal_dispositions=started_under_nohup)
    assert 4 <= count < TRIALS_TOTAL, "the signal must land in the middle of the sweep"
    assert returncode == 0
    assert len(record_files(out_dir)) == TRIALS_TOTAL
    assert not list(out_dir.rglob(".*"))


# Rule: `nohup` leaves SIGTERM at its default action, and SIGTERM stops such a sweep.
def test_sigterm_stops_a_sweep_started_under_nohup(tmp_path):
    out_dir = tmp_path / "out"
    count, returncode = killed_runs.kill_after_some_records(
        sweep_command(out_dir), lambda: record_files(out_dir), 4, TIMEOUT_S, signal.SIGTERM,
        signal_dispositions=started_under_nohup)
    assert returncode == 128 + signal.SIGTERM
    assert 4 <= count < TRIALS_TOTAL
    assert not list(out_dir.rglob(".*"))


def session_processes(session_id: int) -> set[int]:
    """The pids of the live processes of a session (the sweep started in its own)."""
    pids = set()
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[3]) == session_id and fields[0] != "Z":
                pids.add(int(entry.name))
    return pids


def test_workers_end_when_only_the_main_process_is_killed(tmp_path):
    """After SIGKILL of the sweep's main process alone, its workers (about 210 MB each)
    notice within a second and end."""
    out_dir = tmp_path / "out"
    process = subprocess.Popen(sweep_command(out_dir), env=environment(),
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               start_new_session=True)
    deadline = time.monotonic() + TIMEOUT_S
    try:
        while len(record_files(out_dir)) < 2:
            assert process.poll() is None and time.monotonic() < deadline
            time.sleep(0.01)
        others = session_processes(process.pid) - {process.pid}
        assert others, "the sweep has worker processes"
        os.kill(process.pid, signal.SIGKILL)  # the main process only
        process.wait(timeout=TIMEOUT_S)
        while session_processes(process.pid) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not session_processes(process.pid), "workers outlived the sweep"
    finally:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
