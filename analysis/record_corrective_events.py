"""Record the memorized corrective events (recording/corrective_events.py).

    python analysis/record_corrective_events.py LOGS_DIR [--object box] [--workers 2]
        [--events events]

Simulates each of CORRECTIVE_RUNS on the object as an open-loop grasp, only as long as its
situation needs (a hit run to the end of the script's Hold, a slip run to the end of its
Lift), saves each log to LOGS_DIR/<object>/<label>.npz (a log already there is reused),
and writes the mean of the template runs of each corrective transition to
EVENTS/corrective/. The held-out runs' logs are for analysis/choose_corrective_thresholds.py.
"""

import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

from tegrasp_drake.commands.script_output import refuse_unusable_folders, run_script, script_parser
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.events.events_folder import save_memorized_events
from tegrasp_drake.events.transitions import CORRECTIVE_TRANSITIONS
from tegrasp_drake.recording.campaign import (first_unwritten_log, run_log_path, simulate_run,
                                              unwritten_log_words)
from tegrasp_drake.recording.corrective_events import (
    CORRECTIVE_FOLDER, CORRECTIVE_RUNS, campaign_run, record_corrective_events)
from tegrasp_drake.scenario.trial_log_file import LogNotWritten


def log_path(logs: pathlib.Path, object_name: str, run) -> pathlib.Path:
    """Where the log of corrective run `run` of `object_name` is kept under `logs`."""
    return run_log_path(logs / object_name, run)


def simulate(job) -> None:
    object_name, run, logs = job
    simulate_run(campaign_run(object_name, run), log_path=log_path(logs, object_name, run))
    print(f"{object_name} '{run.label}' done", flush=True)


def main(argv=None) -> int:
    parser = script_parser("record_corrective_events", __doc__)
    parser.add_argument("logs", type=pathlib.Path)
    parser.add_argument("--object", default="box")
    parser.add_workers()
    parser.add_argument("--events", type=pathlib.Path, default=package_events_dir())
    args = parser.parse_args(argv)
    refuse_unusable_folders("record_corrective_events", args.logs / args.object,
                            args.events / CORRECTIVE_FOLDER)
    with ProcessPoolExecutor(args.workers) as pool:  # the logs, in parallel
        unwritten = first_unwritten_log(pool, simulate, [(args.object, run, args.logs)
                                                         for run in CORRECTIVE_RUNS])
    if unwritten is not None:
        print(f"record_corrective_events: error: {unwritten_log_words(unwritten)}",
              file=sys.stderr)
        return 1
    events, unwritten = [], None
    for transition in CORRECTIVE_TRANSITIONS:
        try:
            events.append(record_corrective_events(args.object, transition,
                                                   log_dir=args.logs / args.object))
        except LogNotWritten as not_written:  # the event stands; only a log is lost
            events.append(not_written.result)
            unwritten = unwritten or not_written
    written = save_memorized_events(args.events / CORRECTIVE_FOLDER, events,
                                    required=CORRECTIVE_TRANSITIONS)
    print(f"wrote {len(written)} files to {args.events / CORRECTIVE_FOLDER}")
    if unwritten is not None:
        print(f"record_corrective_events: error: {unwritten_log_words(unwritten)}",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "record_corrective_events"))
