"""Record the taxel_aware controller's ensemble events (recording/ensemble_events.py).

    python analysis/record_ensemble_events.py LOGS_DIR [--runs 8] [--template-runs 5]
        [--workers 2] [--events events]

Runs `--runs` randomised ideal grasps of each built-in object (seeds 1_000_000 + run),
saves each log to LOGS_DIR/<object>/run<k>.npz (a log already there is reused), combines
the first `--template-runs` into the events in EVENTS/ensemble (the mean rule), and leaves
the other runs' logs for choosing the thresholds (analysis/choose_ensemble_thresholds.py),
apart from the sweeps that judge.
"""

import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

from tegrasp_drake.commands.script_output import refuse_unusable_folders, run_script, script_parser
from tegrasp_drake.rig.integer_text import integer_option
from tegrasp_drake.rig.paths import package_events_dir
from tegrasp_drake.rig.ranges import Range
from tegrasp_drake.events.events_folder import save_memorized_events
from tegrasp_drake.recording.campaign import (first_unwritten_log, run_log_path, simulate_run,
                                              unwritten_log_words)
from tegrasp_drake.recording.ensemble_events import (ENSEMBLE_FOLDER, ensemble_runs,
                                                     record_object_ensemble)
from tegrasp_drake.rig.objects import BUILTIN_OBJECTS
from tegrasp_drake.scenario.trial_log_file import LogNotWritten


def simulate(job) -> None:
    """Simulates run `k` of the object's campaign (made in the worker: a scenario holds
    pydrake configs, which do not pickle)."""
    object_name, k, runs, template_runs, log_dir = job
    run = ensemble_runs(object_name, runs, template_runs)[k]
    simulate_run(run, log_path=run_log_path(log_dir, run))
    print(f"{object_name} {run.label} done", flush=True)


def main(argv=None) -> int:
    parser = script_parser("record_ensemble_events", __doc__)
    parser.add_argument("logs", type=pathlib.Path)
    parser.add_number("--runs", type=integer_option, default=8, allowed=Range(low=1))
    parser.add_number("--template-runs", type=integer_option, default=5, allowed=Range(low=1))
    parser.add_workers()
    parser.add_argument("--events", type=pathlib.Path, default=package_events_dir())
    args = parser.parse_args(argv)
    if args.template_runs > args.runs:
        raise SystemExit(f"record_ensemble_events: error: --template-runs must be at most "
                         f"--runs ({args.runs}), got {args.template_runs}")
    refuse_unusable_folders("record_ensemble_events",
                            *(args.logs / name for name in sorted(BUILTIN_OBJECTS)),
                            args.events / ENSEMBLE_FOLDER)
    from tegrasp_drake.scenario.scenario import LoadScenario
    jobs = [(name, k, args.runs, args.template_runs, args.logs / name)
            for name in sorted(BUILTIN_OBJECTS) for k in range(args.runs)]
    with ProcessPoolExecutor(args.workers) as pool:  # the logs, in parallel
        unwritten = first_unwritten_log(pool, simulate, jobs)
    if unwritten is not None:
        print(f"record_ensemble_events: error: {unwritten_log_words(unwritten)}",
              file=sys.stderr)
        return 1
    combined, unwritten = [], None
    for name in sorted(BUILTIN_OBJECTS):
        try:
            events = record_object_ensemble(
                name, LoadScenario(name=name), args.runs, template_runs=args.template_runs,
                log_dir=args.logs / name)
        except LogNotWritten as not_written:  # the events stand; only a log is lost
            events, unwritten = not_written.result, unwritten or not_written
        combined += events.values()
    written = save_memorized_events(args.events / ENSEMBLE_FOLDER, combined)
    print(f"wrote {len(written)} files to {args.events / ENSEMBLE_FOLDER}")
    if unwritten is not None:
        print(f"record_ensemble_events: error: {unwritten_log_words(unwritten)}",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(run_script(main, "record_ensemble_events"))
