"""`tegrasp` with the events recording replaced by the package's memorized events, and a kill
at a chosen point of it (no tests here): the transfer kill-and-resume tests run this as a
child process, so that the claim (what a killed events stage leaves, what a rerun redoes) is
tested without simulating ideal grasps.

    python -m fake_recording CALLS_FILE KILL -- ARGV...

CALLS_FILE gets a line per object recorded. KILL: `none`; `SIGNAL@record:N`, the signal sent
to this process while the Nth object is recorded (from 1); `SIGNAL@commit:N`, the signal sent
at the Nth rename of a staged events file onto its target (SIGKILL: past every handler, as
the OOM killer does)."""

import os
import signal
import sys

from tegrasp_drake import cli
from tegrasp_drake.events import events_folder
from tegrasp_drake.events.events_folder import load_memorized_events
from tegrasp_drake.recording import paper_events
from tegrasp_drake.rig import paths


def _kill_at(kill: str):
    """(signal, where, n) of KILL, or None."""
    if kill == "none":
        return None
    name, point = kill.split("@")
    where, n = point.split(":")
    return signal.Signals[name], where, int(n)


def main(calls_file: str, kill: str, argv: list[str]) -> int:
    planned = _kill_at(kill)
    counts = {"record": 0, "commit": 0}

    def count(where):
        counts[where] += 1
        if planned and planned[1] == where and planned[2] == counts[where]:
            os.kill(os.getpid(), planned[0])

    def recorded_events(object_name, scenario=None, *, progress=None):
        with open(calls_file, "a", encoding="utf-8") as calls:
            calls.write(object_name + "\n")
        count("record")
        return load_memorized_events(paths.package_events_dir(), object_name)

    class _CountedOs:
        """os, with each replace counted (events_folder commits staged files with it)."""

        def __getattr__(self, name):
            return getattr(os, name)

        @staticmethod
        def replace(source, target):
            count("commit")
            os.replace(source, target)

    paper_events.record_events = recorded_events
    events_folder.os = _CountedOs()
    return cli.main(argv)


if __name__ == "__main__":
    separator = sys.argv.index("--")
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[separator + 1:]))
