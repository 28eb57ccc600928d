"""Commands killed mid-run, as a job scheduler or the OOM killer kills them (no tests here):
the kill-and-resume tests of the sweep and of the studies built on it share this."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

TESTS = Path(__file__).resolve().parent
REPOSITORY = TESTS.parent


def environment() -> dict:
    """This process's environment with the checkout and tests/ first on PYTHONPATH (the
    fake trial functions live in tests/)."""
    paths = [str(REPOSITORY), str(TESTS), os.environ.get("PYTHONPATH", "")]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in paths if p)}


def default_signal_dispositions():
    """A Popen preexec_fn: the child's termination signals as a terminal's shell leaves them.
    A suite run under `nohup` (or by a runner that ignores SIGHUP) would pass its SIG_IGN on
    through fork and exec, which tegrasp honours (docs/user-guide.md, "Exit codes"), and a
    SIGHUP a test sends would never arrive."""
    for number in (signal.SIGHUP, signal.SIGTERM, signal.SIGINT):
        signal.signal(number, signal.SIG_DFL)


def kill_after_some_records(command, record_files, minimum: int, timeout_s: float,
                            signal_number: int = signal.SIGKILL,
                            signal_dispositions=default_signal_dispositions):
    """Starts `command` in its own process group and SIGKILLs the group (the parent and its
    workers) once `record_files()` lists `minimum` records; waits until the whole group is
    gone (its folder lock released with it). Returns (records at the kill, return code).
    Another `signal_number` (SIGTERM, SIGHUP) goes to the parent alone, as `kill PID` sends it,
    and the parent is left to stop as it does on it. `signal_dispositions` sets the child's
    before it runs the command (a Popen preexec_fn): by default, a terminal's."""
    process = subprocess.Popen(command, env=environment(), stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True,
                               preexec_fn=signal_dispositions)
    deadline = time.monotonic() + timeout_s
    try:
        while len(record_files()) < minimum:
            assert process.poll() is None, "the command ended before it could be killed"
            assert time.monotonic() < deadline, "no records appeared in time"
            time.sleep(0.005)
        if signal_number == signal.SIGKILL:
            os.killpg(process.pid, signal.SIGKILL)
        else:
            os.kill(process.pid, signal_number)
        count = len(record_files())
        process.wait(timeout=timeout_s)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait(timeout=timeout_s)
    while time.monotonic() < deadline:
        try:
            os.killpg(process.pid, 0)
        except ProcessLookupError:
            break
        time.sleep(0.01)
    return count, process.returncode


def killed_before_rename(statements: str, timeout_s: float = 120) -> None:
    """Runs the Python `statements` in a child process that its first os.replace SIGKILLs, as
    the OOM killer or a power cut ends a writer between writing its temporary file and renaming
    it onto the target: no handler runs, so what the writer staged stays behind."""
    prelude = ("import os, signal\n"
               "os.replace = lambda *names, **options: os.kill(os.getpid(), signal.SIGKILL)\n")
    process = subprocess.run([sys.executable, "-c", prelude + statements], env=environment(),
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             timeout=timeout_s)  # a bound on a hang, not a measure of speed
    assert process.returncode == -signal.SIGKILL, process.stderr.decode(errors="replace")
