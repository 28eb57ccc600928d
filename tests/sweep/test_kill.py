"""Acceptance: a sweep killed with SIGKILL and resumed gives exactly the records of an
uninterrupted run."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path


from tests import killed_runs
from tests.killed_runs import environment

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
